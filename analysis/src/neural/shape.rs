//! Shape fits of a unit's trial average `m(t)` (`t` = steps after the event): monotone
//! (isotonic) and unimodal (rise-then-fall) least-squares fits by pool-adjacent-violators,
//! and the spectral peak of a Hann-windowed periodogram.
//!
//! Every function takes one finite series (`[time]`); callers drop missing steps first.

use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::f64::consts::PI;

/// Least-squares non-decreasing fit of `y` (pool-adjacent-violators). Same length as `y`.
pub fn isotonic_increasing(y: &[f64]) -> Vec<f64> {
    // Blocks of (sum, count).
    let mut blocks: Vec<(f64, usize)> = Vec::with_capacity(y.len());
    for &v in y {
        blocks.push((v, 1));
        while blocks.len() >= 2 {
            let (s1, n1) = blocks[blocks.len() - 1];
            let (s0, n0) = blocks[blocks.len() - 2];
            if s0 / n0 as f64 > s1 / n1 as f64 {
                blocks.pop();
                let last = blocks.len() - 1;
                blocks[last] = (s0 + s1, n0 + n1);
            } else {
                break;
            }
        }
    }
    blocks
        .iter()
        .flat_map(|&(s, n)| std::iter::repeat_n(s / n as f64, n))
        .collect()
}

/// Least-squares non-increasing fit of `y`.
pub fn isotonic_decreasing(y: &[f64]) -> Vec<f64> {
    let neg: Vec<f64> = y.iter().map(|v| -v).collect();
    isotonic_increasing(&neg).iter().map(|v| -v).collect()
}

fn sse(y: &[f64], fit: &[f64]) -> f64 {
    y.iter().zip(fit).map(|(a, b)| (a - b).powi(2)).sum()
}

fn total_ss(y: &[f64]) -> f64 {
    let mean = y.iter().sum::<f64>() / y.len().max(1) as f64;
    y.iter().map(|v| (v - mean).powi(2)).sum()
}

/// Sampling noise of a trial average: `noise = Σ_t s²(t) / K_t`, the expected sum of
/// squares that the trial-to-trial variability adds to the average `m(t)` (`s²(t)` the
/// unbiased variance over the `K_t` trials at step `t`). Zero for a noise-free average.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AverageNoise {
    /// `Σ_t s²(t) / K_t` (activity², summed over the series' steps).
    pub sum_sq: f64,
}

/// A shape fit scored against the variance the trial average can explain.
///
/// The fraction of explainable variance explained (the noise-ceiling correction of Sahani
/// & Linden 2003 and Hsu, Borst & Theunissen 2004): with `W` steps, `N` = the average's
/// sampling noise and `df` the fit's degrees of freedom (for pool-adjacent-violators fits
/// the number of fitted levels, Meyer & Woodroofe 2000),
///
/// `R²_c = 1 − max(SS_res − N·(W − df)/W, 0) / (SS_tot − N·(W − 1)/W)`,
///
/// the residual and the total sum of squares each less what the noise contributes to them
/// in expectation. A noise-free average (`N = 0`) gives the plain `R² = 1 − SS_res/SS_tot`;
/// a noisy average of a clean shape (a histogram of a few trials' spikes) gives ≈ 1 where
/// the plain `R²` only measures the noise. `NaN` when the total is not above the noise
/// (nothing to explain).
fn explained(ss_res: f64, df: usize, ss_tot: f64, w: usize, noise: AverageNoise) -> f64 {
    let w = w as f64;
    let explainable = ss_tot - noise.sum_sq * (w - 1.0) / w;
    if explainable <= 0.0 {
        return f64::NAN;
    }
    let unexplained = (ss_res - noise.sum_sq * (w - df as f64).max(0.0) / w).max(0.0);
    (1.0 - unexplained / explainable).min(1.0)
}

/// Number of distinct levels of a pool-adjacent-violators fit (its degrees of freedom).
fn levels(fit: &[f64]) -> usize {
    1 + fit.windows(2).filter(|p| p[0] != p[1]).count()
}

/// Variance of `y` explained by its best monotone fit (either direction), with the
/// direction (`+1` rising, `−1` falling). `(NaN, 0)` for fewer than 3 points or a constant
/// series.
pub fn monotone_r2(y: &[f64]) -> (f64, i8) {
    monotone_r2_noisy(y, AverageNoise::default())
}

/// [`monotone_r2`] of a trial average with sampling noise `noise`: the fraction of its
/// explainable variance explained (see [`AverageNoise`]).
pub fn monotone_r2_noisy(y: &[f64], noise: AverageNoise) -> (f64, i8) {
    let ss = total_ss(y);
    if y.len() < 3 || ss <= 0.0 {
        return (f64::NAN, 0);
    }
    let score = |fit: Vec<f64>| explained(sse(y, &fit), levels(&fit), ss, y.len(), noise);
    let up = score(isotonic_increasing(y));
    let down = score(isotonic_decreasing(y));
    // NaN (no explainable variance) loses to any number and keeps the rising direction.
    if up >= down || down.is_nan() {
        (up, 1)
    } else {
        (down, -1)
    }
}

/// Variance of `y` explained by its best unimodal fit: non-decreasing on `[0, c]`,
/// non-increasing on `[c+1, len)`, over every split `c` with at least one point on each
/// side. `NaN` for fewer than 3 points or a constant series.
pub fn unimodal_r2(y: &[f64]) -> f64 {
    unimodal_r2_noisy(y, AverageNoise::default())
}

/// [`unimodal_r2`] of a trial average with sampling noise `noise`: the fraction of its
/// explainable variance explained (see [`AverageNoise`]; the fit's degrees of freedom are
/// its levels on both sides plus the split).
pub fn unimodal_r2_noisy(y: &[f64], noise: AverageNoise) -> f64 {
    let ss = total_ss(y);
    if y.len() < 3 || ss <= 0.0 {
        return f64::NAN;
    }
    let (best, df) = best_unimodal(y);
    explained(best, df, ss, y.len(), noise)
}

/// Residual sum of squares and degrees of freedom of the best unimodal fit of `y`.
fn best_unimodal(y: &[f64]) -> (f64, usize) {
    (1..y.len())
        .map(|c| {
            let (rise, fall) = (isotonic_increasing(&y[..c]), isotonic_decreasing(&y[c..]));
            let res = sse(&y[..c], &rise) + sse(&y[c..], &fall);
            (res, levels(&rise) + levels(&fall) + 1)
        })
        .fold((f64::INFINITY, 0), |b, x| if x.0 < b.0 { x } else { b })
}

/// p of the unimodal fit's improvement over the best monotone fit, against the average's
/// sampling noise: the fall after a rise (or the rise before a fall) is real when the
/// residual sum of squares it removes, `ΔSS`, is more than noise with the extra degrees of
/// freedom `Δdf` would remove — `ΔSS / σ̄² ~ χ²(Δdf)` under a monotone truth, `σ̄² =
/// noise / W` the noise per step (an approximate F-type test: the fits' degrees of
/// freedom are their numbers of levels). A noise-free average gives 0 for any
/// improvement and 1 for none. 1 for fewer than 3 points.
pub fn unimodal_gain_p(y: &[f64], noise: AverageNoise) -> f64 {
    let ss = total_ss(y);
    if y.len() < 3 || ss <= 0.0 {
        return 1.0;
    }
    let (up, down) = (isotonic_increasing(y), isotonic_decreasing(y));
    let (mono_res, mono_df) = [up, down]
        .into_iter()
        .map(|f| (sse(y, &f), levels(&f)))
        .fold((f64::INFINITY, 0), |b, x| if x.0 < b.0 { x } else { b });
    let (uni_res, uni_df) = best_unimodal(y);
    let gain = mono_res - uni_res;
    if gain <= 1e-12 * ss {
        return 1.0;
    }
    let per_step = noise.sum_sq / y.len() as f64;
    if per_step <= 0.0 {
        return 0.0;
    }
    let dof = uni_df.saturating_sub(mono_df).max(1) as f64;
    ChiSquared::new(dof).map_or(1.0, |d| d.sf(gain / per_step))
}

/// Hann-windowed periodogram of `y` (mean removed) at bins `k = 0 … len/2`
/// (frequency `k / len` cycles per step).
pub fn periodogram(y: &[f64]) -> Vec<f64> {
    let n = y.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let mean = y.iter().sum::<f64>() / n as f64;
    let w: Vec<f64> = y
        .iter()
        .enumerate()
        .map(|(i, v)| (v - mean) * (0.5 - 0.5 * (2.0 * PI * i as f64 / n as f64).cos()))
        .collect();
    // sin and cos of 2π·m/n, m = 0 … n − 1: every phase `k·j mod n` the sums below need.
    let twiddle: Vec<(f64, f64)> = (0..n)
        .map(|m| (2.0 * PI * m as f64 / n as f64).sin_cos())
        .collect();
    (0..=n / 2)
        .map(|k| {
            let (mut re, mut im) = (0.0, 0.0);
            for (j, v) in w.iter().enumerate() {
                let (s, c) = twiddle[(k * j) % n];
                re += v * c;
                im -= v * s;
            }
            re * re + im * im
        })
        .collect()
}

/// The largest periodogram bin at or above `min_bin` (`(bin, power)`; `(0, 0)` when no bin
/// qualifies).
pub fn spectral_peak(power: &[f64], min_bin: usize) -> (usize, f64) {
    power
        .iter()
        .enumerate()
        .skip(min_bin.max(1))
        .fold((0, 0.0), |b, (k, &p)| if p > b.1 { (k, p) } else { b })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotonic_fits_pool_violators() {
        assert_eq!(
            isotonic_increasing(&[1.0, 3.0, 2.0, 4.0]),
            [1.0, 2.5, 2.5, 4.0]
        );
        assert_eq!(isotonic_decreasing(&[3.0, 1.0, 2.0]), [3.0, 1.5, 1.5]);
        let (r2, dir) = monotone_r2(&[0.0, 1.0, 2.0, 3.0]);
        assert!((r2 - 1.0).abs() < 1e-12 && dir == 1);
    }

    #[test]
    fn a_bump_is_unimodal_but_not_monotone() {
        let bump: Vec<f64> = (0..21)
            .map(|t| (-(t as f64 - 10.0).powi(2) / 8.0).exp())
            .collect();
        assert!((unimodal_r2(&bump) - 1.0).abs() < 1e-12);
        assert!(monotone_r2(&bump).0 < 0.6);
        // Two bumps are neither.
        let two: Vec<f64> = (0..24)
            .map(|t| (2.0 * PI * t as f64 / 12.0).cos())
            .collect();
        assert!(unimodal_r2(&two) < 0.8);
    }

    #[test]
    fn the_noise_correction_discounts_exactly_the_noise_it_is_given() {
        // Noise-free: the plain R² (by hand: a rise-fall-rise of 5 points).
        let y = [0.0, 2.0, 1.0, 3.0, 4.0];
        let plain = {
            let m = 2.0;
            let ss: f64 = y.iter().map(|v| (v - m) * (v - m)).sum();
            // Isotonic fit pools 2 and 1 to 1.5: residual 0.25 + 0.25.
            1.0 - 0.5 / ss
        };
        assert!((monotone_r2_noisy(&y, AverageNoise::default()).0 - plain).abs() < 1e-12);
        // With noise N: R²_c = 1 − max(SS_res − N(W − df)/W, 0) / (SS_tot − N(W − 1)/W);
        // the fit has 4 levels (0, 1.5, 3, 4), W = 5.
        let n = AverageNoise { sum_sq: 0.5 };
        let want = 1.0 - (0.5f64 - 0.5 * 1.0 / 5.0) / (10.0 - 0.5 * 4.0 / 5.0);
        assert!((monotone_r2_noisy(&y, n).0 - want).abs() < 1e-12);
        // Noise as large as the whole variance: nothing to explain.
        assert!(unimodal_r2_noisy(&y, AverageNoise { sum_sq: 20.0 }).is_nan());
        // A bump is a real improvement over a ramp; a ramp is not.
        let bump: Vec<f64> = (0..15)
            .map(|t| (-(t as f64 - 7.0).powi(2) / 6.0).exp())
            .collect();
        let small = AverageNoise { sum_sq: 0.01 };
        assert!(unimodal_gain_p(&bump, small) < 1e-6);
        let ramp: Vec<f64> = (0..15).map(|t| t as f64).collect();
        assert_eq!(unimodal_gain_p(&ramp, small), 1.0);
    }

    #[test]
    fn periodogram_peaks_at_the_sinusoid() {
        let x: Vec<f64> = (0..32)
            .map(|t| (2.0 * PI * 5.0 * t as f64 / 32.0).sin())
            .collect();
        assert_eq!(spectral_peak(&periodogram(&x), 2).0, 5);
    }
}
