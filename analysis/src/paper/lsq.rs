//! The paper's psychometric fit: least squares of `P(d) = 1 / (1 + e^{−(d − x0)/k})` to
//! averaged proportions, as `scipy.optimize.curve_fit` does it (Levenberg–Marquardt, no
//! bounds, no weights, initial guess `[AM, 1]`, at most `200·(n_params + 1) = 600`
//! function evaluations), with the notebook's failure rules and step-curve fallback.

use serde::{Deserialize, Serialize};

/// Result of the least-squares fit (the paper's BP, DL and WF).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LsqFit {
    /// Bisection point `x0` (steps).
    pub bp: f64,
    /// Slope scale `k` (steps).
    pub k: f64,
    /// Difference limen `k ln 3`.
    pub dl: f64,
    /// Weber fraction `DL / BP`.
    pub wf: f64,
    /// How the numbers were obtained.
    pub how: LsqHow,
}

/// How a [`LsqFit`] was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LsqHow {
    /// Levenberg–Marquardt converged.
    Fit,
    /// The fit did not converge and the curve is step-like: the notebook's fallback (BP and
    /// the quartile points from the first index with P ≥ q and the last with P ≤ q, as
    /// 0-based list positions, so one step below the probe durations — kept as coded).
    StepFallback,
}

fn sigmoid(z: f64) -> f64 {
    1.0 / (1.0 + (-z).exp())
}

fn ssr(d: &[f64], p: &[f64], x0: f64, k: f64) -> f64 {
    d.iter()
        .zip(p)
        .map(|(&t, &y)| (y - sigmoid((t - x0) / k)).powi(2))
        .sum()
}

/// Levenberg–Marquardt on `(x0, k)` from `start`; `None` when it has not converged within
/// 600 evaluations (scipy raises then) or left the finite numbers.
pub fn levenberg_marquardt(d: &[f64], p: &[f64], start: (f64, f64)) -> Option<(f64, f64)> {
    let (mut x0, mut k) = start;
    let mut cost = ssr(d, p, x0, k);
    let mut lambda = 1e-3;
    let mut evals = 1;
    let tol = 1.49012e-8; // scipy's ftol = xtol
    while evals < 600 {
        // Gauss–Newton system J^T J δ = −J^T r with r = model − y.
        let (mut a11, mut a12, mut a22, mut g1, mut g2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (&t, &y) in d.iter().zip(p) {
            let s = sigmoid((t - x0) / k);
            let ds = s * (1.0 - s);
            let j1 = -ds / k;
            let j2 = -ds * (t - x0) / (k * k);
            let r = s - y;
            a11 += j1 * j1;
            a12 += j1 * j2;
            a22 += j2 * j2;
            g1 += j1 * r;
            g2 += j2 * r;
        }
        loop {
            let (b11, b22) = (a11 * (1.0 + lambda), a22 * (1.0 + lambda));
            let det = b11 * b22 - a12 * a12;
            if !det.is_finite() || det.abs() < 1e-300 {
                return None;
            }
            let dx = -(b22 * g1 - a12 * g2) / det;
            let dk = -(b11 * g2 - a12 * g1) / det;
            let (nx, nk) = (x0 + dx, k + dk);
            let new = ssr(d, p, nx, nk);
            evals += 1;
            if new.is_finite() && new <= cost {
                let rel_f = if cost > 0.0 { (cost - new) / cost } else { 0.0 };
                let rel_x = (dx.powi(2) + dk.powi(2)).sqrt() / (x0.powi(2) + k.powi(2)).sqrt();
                x0 = nx;
                k = nk;
                cost = new;
                lambda = (lambda / 10.0).max(1e-12);
                if rel_f <= tol || rel_x <= tol || cost == 0.0 {
                    return (x0.is_finite() && k.is_finite()).then_some((x0, k));
                }
                break;
            }
            lambda *= 10.0;
            if lambda > 1e16 || evals >= 600 {
                // No step reduces the cost: a (local) minimum.
                return (lambda > 1e16 && x0.is_finite() && k.is_finite()).then_some((x0, k));
            }
        }
    }
    None
}

/// The notebook's fit of an averaged curve: `probes` are the durations (1 … L+4), `p` the
/// run-averaged P(long) (NaN entries dropped before fitting). `None` = "failed" (the
/// notebook's −100): BP outside the probe range, or no convergence and no step-like curve.
pub fn fit_paper(probes: &[f64], p: &[f64], short: f64, long: f64) -> Option<LsqFit> {
    let (d, y): (Vec<f64>, Vec<f64>) = probes
        .iter()
        .zip(p)
        .filter(|(_, y)| y.is_finite())
        .map(|(&a, &b)| (a, b))
        .unzip();
    if d.len() < 2 {
        return None;
    }
    let (lo, hi) = (
        d.iter().copied().fold(f64::INFINITY, f64::min),
        d.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    let am = 0.5 * (short + long);
    match levenberg_marquardt(&d, &y, (am, 1.0)) {
        Some((x0, k)) => {
            if x0 <= lo || x0 >= hi {
                return None;
            }
            let dl = k * 3f64.ln();
            Some(LsqFit {
                bp: x0,
                k,
                dl,
                wf: dl / x0,
                how: LsqHow::Fit,
            })
        }
        None => step_fallback(&y, short as usize, long as usize),
    }
}

/// The notebook's fallback for a fit that raised: step-like when the mean P over the first
/// `S` entries is ≤ 0.2 and from entry `L` on ≥ 0.8.
fn step_fallback(p: &[f64], short: usize, long: usize) -> Option<LsqFit> {
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    if p.len() <= long || mean(&p[..short.min(p.len())]) > 0.2 || mean(&p[long..]) < 0.8 {
        return None;
    }
    let point = |q: f64| -> Option<f64> {
        let first = p.iter().position(|&x| x >= q)? as f64;
        let last = p.iter().rposition(|&x| x <= q)? as f64;
        Some(0.5 * (first + last))
    };
    let bp = point(0.5)?;
    let dl = 0.5 * (point(0.75)? - point(0.25)?);
    Some(LsqFit {
        bp,
        k: dl / 3f64.ln(),
        dl,
        wf: dl / bp,
        how: LsqHow::StepFallback,
    })
}
