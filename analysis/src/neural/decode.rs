//! Elapsed-time decoding from population activity, cross-validated over trials.
//!
//! * ridge regression of time on the population vector (with intercept, features
//!   standardised on the training folds, penalty `λ`; units constant on the training
//!   folds get no weight, and decoded times are clipped to the window);
//! * Bayesian decoder: per time bin a Gaussian per unit (mean per bin, variance pooled over
//!   bins, floored), flat prior over bins; the decoded time is the posterior mode.
//!
//! Folds are interleaved trials (`trial % folds`); samples with any NaN are skipped.

use crate::neural::Cube;
use serde::{Deserialize, Serialize};

/// Which decoder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Decoder {
    /// Ridge regression.
    Ridge,
    /// Gaussian naive-Bayes posterior mode.
    Bayes,
}

/// Decoding error vs time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DecodeResult {
    /// Decoder used.
    pub decoder: Decoder,
    /// Mean absolute error per time bin (NaN where no test sample).
    pub error_by_time: Vec<f64>,
    /// Mean absolute error over all test samples (steps).
    pub mean_abs_error: f64,
}

fn samples(cube: &Cube, trials: &[usize]) -> (Vec<Vec<f64>>, Vec<usize>) {
    let mut x = Vec::new();
    let mut y = Vec::new();
    for &k in trials {
        for t in 0..cube.time() {
            let v: Vec<f64> = (0..cube.units()).map(|i| cube.at(k, t, i)).collect();
            if v.iter().all(|a| a.is_finite()) {
                x.push(v);
                y.push(t);
            }
        }
    }
    (x, y)
}

/// Solves the symmetric positive-definite system `a x = b` (`a` row-major `[n, n]`) by a
/// Cholesky factorisation; `None` when `a` is not positive definite.
fn solve_spd(a: Vec<f64>, b: Vec<f64>, n: usize) -> Option<Vec<f64>> {
    let a = nalgebra::DMatrix::from_row_slice(n, n, &a);
    let x = a.cholesky()?.solve(&nalgebra::DVector::from_vec(b));
    Some(x.data.into())
}

/// Ridge weights `w = (ZᵀZ + λI)⁻¹ Zᵀy` from the primal `[n, n]` system (`z`: `[m, n]`
/// standardised samples, `y` centred): the cheaper form when samples outnumber units.
fn ridge_weights_primal(z: &[Vec<f64>], y: &[f64], lambda: f64) -> Option<Vec<f64>> {
    let n = z.first()?.len();
    let mut a = vec![0.0; n * n];
    let mut b = vec![0.0; n];
    for (r, &t) in z.iter().zip(y) {
        for i in 0..n {
            b[i] += r[i] * t;
            for j in 0..=i {
                a[i * n + j] += r[i] * r[j];
            }
        }
    }
    for i in 0..n {
        for j in 0..i {
            a[j * n + i] = a[i * n + j];
        }
        a[i * n + i] += lambda;
    }
    solve_spd(a, b, n)
}

/// The same ridge weights from the dual `[m, m]` system, `w = Zᵀ(ZZᵀ + λI)⁻¹y` (the
/// push-through identity `(ZᵀZ + λI)⁻¹Zᵀ = Zᵀ(ZZᵀ + λI)⁻¹`): the cheaper form when units
/// outnumber samples (a population of 1,000 oscillators recorded on a few hundred steps).
fn ridge_weights_dual(z: &[Vec<f64>], y: &[f64], lambda: f64) -> Option<Vec<f64>> {
    let n = z.first()?.len();
    let m = z.len();
    let mut k = vec![0.0; m * m];
    for s in 0..m {
        for u in 0..=s {
            let d: f64 = z[s].iter().zip(&z[u]).map(|(a, b)| a * b).sum();
            k[s * m + u] = d;
            k[u * m + s] = d;
        }
        k[s * m + s] += lambda;
    }
    let alpha = solve_spd(k, y.to_vec(), m)?;
    let mut w = vec![0.0; n];
    for (r, a) in z.iter().zip(&alpha) {
        for (wi, zi) in w.iter_mut().zip(r) {
            *wi += a * zi;
        }
    }
    Some(w)
}

fn fit_ridge(x: &[Vec<f64>], y: &[usize], lambda: f64) -> Option<impl Fn(&[f64]) -> f64> {
    let n = x.first()?.len();
    let m = x.len() as f64;
    let mean: Vec<f64> = (0..n)
        .map(|i| x.iter().map(|r| r[i]).sum::<f64>() / m)
        .collect();
    // A unit constant on the training trials carries no information there; standardising
    // it by a floored SD would turn any test value into an enormous feature (a
    // microstimulus cell silent on every training trial once gave errors of 4 × TD).
    // Such units get no weight: their standardised value is 0 on every trial.
    let sd: Vec<f64> = (0..n)
        .map(|i| {
            let v = x.iter().map(|r| (r[i] - mean[i]).powi(2)).sum::<f64>() / m;
            let sd = v.sqrt();
            if sd > 1e-9 * (1.0 + mean[i].abs()) {
                sd
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let ym = y.iter().map(|&v| v as f64).sum::<f64>() / m;
    let z: Vec<Vec<f64>> = x
        .iter()
        .map(|r| (0..n).map(|i| (r[i] - mean[i]) / sd[i]).collect())
        .collect();
    let yc: Vec<f64> = y.iter().map(|&t| t as f64 - ym).collect();
    let w = if z.len() < n {
        ridge_weights_dual(&z, &yc, lambda)?
    } else {
        ridge_weights_primal(&z, &yc, lambda)?
    };
    Some(move |v: &[f64]| ym + (0..n).map(|i| w[i] * (v[i] - mean[i]) / sd[i]).sum::<f64>())
}

fn fit_bayes(x: &[Vec<f64>], y: &[usize], bins: usize) -> Option<impl Fn(&[f64]) -> f64> {
    let n = x.first()?.len();
    let mut mu = vec![0.0; bins * n];
    let mut count = vec![0.0f64; bins];
    for (r, &t) in x.iter().zip(y) {
        count[t] += 1.0;
        for i in 0..n {
            mu[t * n + i] += r[i];
        }
    }
    for t in 0..bins {
        for i in 0..n {
            mu[t * n + i] /= count[t].max(1.0);
        }
    }
    let mut var = vec![0.0; n];
    for (r, &t) in x.iter().zip(y) {
        for i in 0..n {
            var[i] += (r[i] - mu[t * n + i]).powi(2);
        }
    }
    let spread: f64 = var.iter().sum::<f64>() / (x.len() * n) as f64;
    let floor = (1e-3 * spread).max(1e-9);
    let var: Vec<f64> = var
        .iter()
        .map(|v| (v / x.len() as f64).max(floor))
        .collect();
    Some(move |v: &[f64]| {
        let mut best = (0usize, f64::NEG_INFINITY);
        for t in 0..bins {
            if count[t] == 0.0 {
                continue;
            }
            let ll: f64 = (0..n)
                .map(|i| -(v[i] - mu[t * n + i]).powi(2) / (2.0 * var[i]))
                .sum();
            if ll > best.1 {
                best = (t, ll);
            }
        }
        best.0 as f64
    })
}

/// A fitted decoder: population vector → decoded time (steps).
type Predictor<'a> = Box<dyn Fn(&[f64]) -> f64 + 'a>;

/// Cross-validated decoding of elapsed time (bins of `cube`) with `folds` folds.
/// `lambda` is the ridge penalty (ignored by the Bayesian decoder).
pub fn decode_time(cube: &Cube, decoder: Decoder, folds: usize, lambda: f64) -> DecodeResult {
    let folds = folds.clamp(2, cube.trials().max(2));
    let mut err = vec![0.0; cube.time()];
    let mut cnt = vec![0.0; cube.time()];
    for f in 0..folds {
        let train: Vec<usize> = (0..cube.trials()).filter(|k| k % folds != f).collect();
        let test: Vec<usize> = (0..cube.trials()).filter(|k| k % folds == f).collect();
        let (xtr, ytr) = samples(cube, &train);
        let (xte, yte) = samples(cube, &test);
        if xtr.is_empty() || xte.is_empty() {
            continue;
        }
        let predict: Predictor = match decoder {
            Decoder::Ridge => match fit_ridge(&xtr, &ytr, lambda) {
                Some(p) => Box::new(p),
                None => continue,
            },
            Decoder::Bayes => match fit_bayes(&xtr, &ytr, cube.time()) {
                Some(p) => Box::new(p),
                None => continue,
            },
        };
        // The decoded elapsed time lies in the window: a linear read-out beyond it is
        // clipped to its ends.
        let last = cube.time().saturating_sub(1) as f64;
        for (v, &t) in xte.iter().zip(&yte) {
            err[t] += (predict(v).clamp(0.0, last) - t as f64).abs();
            cnt[t] += 1.0;
        }
    }
    let total: f64 = err.iter().sum();
    let n: f64 = cnt.iter().sum();
    DecodeResult {
        decoder,
        error_by_time: err
            .iter()
            .zip(&cnt)
            .map(|(e, c)| if *c > 0.0 { e / c } else { f64::NAN })
            .collect(),
        mean_abs_error: if n > 0.0 { total / n } else { f64::NAN },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn random(m: usize, n: usize, seed: u64) -> (Vec<Vec<f64>>, Vec<f64>) {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let z = (0..m)
            .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
            .collect();
        let y = (0..m).map(|_| rng.random_range(-5.0..5.0)).collect();
        (z, y)
    }

    /// `‖(ZᵀZ + λI)w − Zᵀy‖∞`, the residual of the ridge normal equations.
    fn normal_residual(z: &[Vec<f64>], y: &[f64], lambda: f64, w: &[f64]) -> f64 {
        let n = w.len();
        let zw: Vec<f64> = z
            .iter()
            .map(|r| r.iter().zip(w).map(|(a, b)| a * b).sum())
            .collect();
        (0..n)
            .map(|i| {
                let lhs: f64 =
                    z.iter().zip(&zw).map(|(r, v)| r[i] * v).sum::<f64>() + lambda * w[i];
                let rhs: f64 = z.iter().zip(y).map(|(r, t)| r[i] * t).sum();
                (lhs - rhs).abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn both_forms_solve_the_ridge_normal_equations_and_agree() {
        // More units than samples (the dual's case) and more samples than units.
        for (m, n, seed) in [(30, 80, 1), (80, 30, 2), (40, 40, 3)] {
            let (z, y) = random(m, n, seed);
            let primal = ridge_weights_primal(&z, &y, 0.5).unwrap();
            let dual = ridge_weights_dual(&z, &y, 0.5).unwrap();
            assert!(normal_residual(&z, &y, 0.5, &primal) < 1e-9, "{m}×{n}");
            assert!(normal_residual(&z, &y, 0.5, &dual) < 1e-9, "{m}×{n}");
            for (a, b) in primal.iter().zip(&dual) {
                assert!(
                    (a - b).abs() < 1e-9 * (1.0 + a.abs()),
                    "{m}×{n}: {a} vs {b}"
                );
            }
        }
    }
}
