//! The paper's psychometric fit: least squares of `P(d) = 1 / (1 + e^{−(d − x0)/k})` to
//! averaged proportions, as `scipy.optimize.curve_fit` does it (Levenberg–Marquardt, no
//! bounds, no weights, initial guess `[AM, 1]`, at most `200·(n_params + 1) = 600`
//! function evaluations), with the notebook's failure rules and step-curve fallback.
//!
//! # Why not the `levenberg-marquardt` crate (measured 2026-11-24, again 2026-12-03)
//!
//! 2026-12-03, `benches/optimisers` (`cargo run --release --manifest-path
//! benches/optimisers/Cargo.toml`; tables in its README): on 300 synthetic curves of the
//! paper's range every solver fits 100% with the same errors, this file 2–3× faster; on the
//! 306 curves `results/paper-core` now fits, this file reproduces every committed fit and
//! the crate changes 69 decisions (analytic Jacobian) or 21 (forward differences).
//!
//! 2026-11-24 (the comparison example of that day, since replaced by the bench above):
//! it ran every curve the paper analysis of
//! `results/paper-core` fits (120: 100 runs and 20 run-averaged curves of the bisection
//! cells) and of `results/paper-switches` (10) through this solver and through the crate
//! (0.15.0, MINPACK with scipy's `ftol = xtol = 1.49012e-8`, `gtol = 0`, step bound 100, at
//! most 600 evaluations), both inside [`fit_paper_with`] so the notebook's rules are the
//! same; `scripts/lsq-scipy-reference.py` gives scipy 1.17.1's `curve_fit` outcome on the
//! same curves. Decisions (fit / step fallback / failed) on paper-core, where scipy has 67
//! fits, 19 fallbacks and 34 failures:
//!
//! | solver | as this file | as scipy | converged fits vs scipy (rel. BP, k) |
//! |---|---|---|---|
//! | this file | 120 | 117 | 63 of 67 within 1e-4; 4 within 9.4e-3, 7.6e-2 |
//! | crate, analytic Jacobian (`lmder`) | 100 | 99 | all within 2.2e-7, 7.4e-6 |
//! | crate, forward differences (`lmdif`, as scipy) | 118 | 119 | 64 within 1e-4; 3 within 6.4e-3, 6.9e-2 |
//!
//! On paper-switches all three agree with scipy on 10 of 10 except `lmder` (9). Every
//! difference is on a step-like curve: P(long) jumps between two adjacent probes, the best
//! `k` tends to 0 and the sum of squares is flat in `x0` between the probes, so whether a
//! solver stops by `xtol`/`ftol` or exhausts its 600 evaluations (scipy raises → step
//! fallback) depends on its exact path: the analytic Jacobian converges on 18 curves where
//! scipy's forward differences do not, and runs out on 3 where scipy converges; this file
//! converges on 3 curves where scipy falls back (ctrnn-reservoir125 4–8 seed 4, 4–12 seed
//! 2, 4–18 seed 3; runs the tables include), the forward-difference crate on 1 (4–8 seed
//! 4). The crate does not reproduce this file's
//! decisions (2 of 120 differ even with forward differences), so this file stays: swapping
//! would change two per-run fits of the committed paper-core tables (towards scipy's
//! outcome) — a results change to make deliberately, not in a refactor.

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
    fit_paper_with(probes, p, short, long, levenberg_marquardt)
}

/// [`fit_paper`] with another least-squares solver: `solve(d, y, start)` returns the fitted
/// `(x0, k)`, or `None` where scipy's `curve_fit` would raise (the notebook's rules —
/// BP inside the probe range, the step-curve fallback — stay the same).
pub fn fit_paper_with(
    probes: &[f64],
    p: &[f64],
    short: f64,
    long: f64,
    solve: impl FnOnce(&[f64], &[f64], (f64, f64)) -> Option<(f64, f64)>,
) -> Option<LsqFit> {
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
    match solve(&d, &y, (am, 1.0)) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_notebooks_rules_hold_around_any_solver() {
        let probes: Vec<f64> = (1..=12).map(f64::from).collect();
        // A step between probes 6 and 7 (anchors 4 and 8): first S entries 0, from L on 1.
        let p: Vec<f64> = probes.iter().map(|&d| f64::from(d > 6.0)).collect();
        // A solver that raises: the step fallback (BP at the middle of the 0-based step).
        let f = fit_paper_with(&probes, &p, 4.0, 8.0, |_, _, _| None).unwrap();
        assert_eq!((f.how, f.bp), (LsqHow::StepFallback, 5.5));
        // A solver whose BP leaves the probe range: failed.
        assert!(fit_paper_with(&probes, &p, 4.0, 8.0, |_, _, _| Some((12.0, 1.0))).is_none());
        // A converged solver inside the range: its parameters, DL = k ln 3; it starts at AM.
        let f = fit_paper_with(&probes, &p, 4.0, 8.0, |d, y, start| {
            assert_eq!((d.len(), y.len(), start), (12, 12, (6.0, 1.0)));
            Some((6.5, 2.0))
        })
        .unwrap();
        assert_eq!((f.how, f.bp, f.k), (LsqHow::Fit, 6.5, 2.0));
        assert!((f.dl - 2.0 * 3f64.ln()).abs() < 1e-12 && (f.wf - f.dl / 6.5).abs() < 1e-12);
    }
}
