//! Oscillation metrics: Welch power spectrum and inter-trial phase coherence (ITPC).
//!
//! Spectra use direct DFTs (recordings are short: tens to hundreds of steps), so no FFT
//! dependency is needed. Phases come from the analytic signal (DFT-based Hilbert transform:
//! negative frequencies zeroed, positive ones doubled).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// `(re, im)` discrete Fourier transform of `x` at all `n` frequencies (rustfft; the
/// inverse scaled by `1/n`).
fn dft(x: &[(f64, f64)], inverse: bool) -> Vec<(f64, f64)> {
    use rustfft::{FftPlanner, num_complex::Complex};
    let n = x.len();
    if n == 0 {
        return Vec::new();
    }
    let mut buf: Vec<Complex<f64>> = x.iter().map(|&(re, im)| Complex::new(re, im)).collect();
    let mut planner = FftPlanner::<f64>::new();
    let fft = if inverse {
        planner.plan_fft_inverse(n)
    } else {
        planner.plan_fft_forward(n)
    };
    fft.process(&mut buf);
    let scale = if inverse { 1.0 / n as f64 } else { 1.0 };
    buf.iter().map(|c| (c.re * scale, c.im * scale)).collect()
}

/// Instantaneous phase of `x` (radians) from its analytic signal.
pub fn analytic_phase(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    let spec = dft(&x.iter().map(|&v| (v, 0.0)).collect::<Vec<_>>(), false);
    let h: Vec<(f64, f64)> = spec
        .iter()
        .enumerate()
        .map(|(k, &(re, im))| {
            let w = if k == 0 || (n.is_multiple_of(2) && k == n / 2) {
                1.0
            } else if k < n.div_ceil(2) {
                2.0
            } else {
                0.0
            };
            (re * w, im * w)
        })
        .collect();
    dft(&h, true).iter().map(|&(re, im)| im.atan2(re)).collect()
}

/// ITPC over trials at every time step: `|mean_k exp(i φ_k(t))|` (1 = phase-locked,
/// ~1/√K for random phases). `trials` = one series per trial, equal lengths.
pub fn itpc(trials: &[Vec<f64>]) -> Vec<f64> {
    let Some(len) = trials.first().map(Vec::len) else {
        return Vec::new();
    };
    let mut re = vec![0.0; len];
    let mut im = vec![0.0; len];
    for x in trials {
        for (t, ph) in analytic_phase(x).into_iter().enumerate().take(len) {
            re[t] += ph.cos();
            im[t] += ph.sin();
        }
    }
    let k = trials.len() as f64;
    re.iter()
        .zip(&im)
        .map(|(a, b)| (a * a + b * b).sqrt() / k)
        .collect()
}

/// A power spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spectrum {
    /// Frequencies (cycles per time unit of `dt`).
    pub freqs: Vec<f64>,
    /// Power per frequency (averaged over segments).
    pub power: Vec<f64>,
    /// Frequency of the largest power above 0.
    pub peak: f64,
}

/// Welch spectrum: Hann-windowed segments of `segment` samples with 50% overlap, mean
/// periodogram; `dt` = sampling interval.
pub fn welch(x: &[f64], segment: usize, dt: f64) -> Spectrum {
    let seg = segment.clamp(4, x.len().max(4));
    let step = (seg / 2).max(1);
    let window: Vec<f64> = (0..seg)
        .map(|i| 0.5 - 0.5 * (2.0 * PI * i as f64 / (seg - 1) as f64).cos())
        .collect();
    let half = seg / 2 + 1;
    let mut power = vec![0.0; half];
    let mut count = 0.0;
    let mut start = 0;
    while start + seg <= x.len() {
        let part = &x[start..start + seg];
        let mean = part.iter().sum::<f64>() / seg as f64;
        let w: Vec<(f64, f64)> = part
            .iter()
            .zip(&window)
            .map(|(v, h)| ((v - mean) * h, 0.0))
            .collect();
        for (k, (re, im)) in dft(&w, false).into_iter().take(half).enumerate() {
            power[k] += re * re + im * im;
        }
        count += 1.0;
        start += step;
    }
    if count > 0.0 {
        power.iter_mut().for_each(|p| *p /= count);
    }
    let freqs: Vec<f64> = (0..half).map(|k| k as f64 / (seg as f64 * dt)).collect();
    let peak = (1..half)
        .max_by(|&a, &b| power[a].total_cmp(&power[b]))
        .map_or(f64::NAN, |k| freqs[k]);
    Spectrum { freqs, power, peak }
}

/// Autocorrelation `r(L)` of `x` for lags `0 … max_lag` (mean removed, biased estimator:
/// `Σ_t x_t x_{t+L} / Σ_t x_t²`, so `r(0) = 1`; all zeros for a constant series).
pub fn autocorrelation(x: &[f64], max_lag: usize) -> Vec<f64> {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n.max(1) as f64;
    let d: Vec<f64> = x.iter().map(|v| v - mean).collect();
    let var: f64 = d.iter().map(|v| v * v).sum();
    (0..=max_lag.min(n.saturating_sub(1)))
        .map(|lag| {
            if var <= 0.0 {
                return 0.0;
            }
            d.iter().zip(&d[lag..]).map(|(a, b)| a * b).sum::<f64>() / var
        })
        .collect()
}

/// Whether `x` (e.g. a unit's trial average over a window) repeats itself: its
/// autocorrelation falls below −0.25 and then rises again to a peak ≥ 0.4 at a lag of
/// 2 … len/2 steps — at least two cycles of a rhythm inside the window. Transients (a bump, a
/// ramp) have low-frequency spectral peaks but no second autocorrelation peak; white noise
/// of `len` samples has autocorrelations of SD ≈ 1/√len (≈ 0.16 at 40 steps), so a trough
/// and a later peak of this size are rare (< 1 in 8 noise units in the tests). Needs ≥ 8
/// samples.
pub fn is_oscillating(x: &[f64]) -> bool {
    if x.len() < 8 {
        return false;
    }
    acf_repeats(&autocorrelation(x, x.len() / 2), -0.25, 0.4)
}

/// Whether an autocorrelation `r(0 … L)` repeats itself: it falls to `trough` or below and
/// then rises again to a local peak ≥ `peak` at a lag of at least 2 ([`is_oscillating`]
/// uses −0.25 and 0.4 on a trial average).
pub fn acf_repeats(r: &[f64], trough: f64, peak: f64) -> bool {
    let mut fell = false;
    for lag in 1..r.len() {
        if r[lag] <= trough {
            fell = true;
        }
        let local_peak = lag + 1 >= r.len() || r[lag] >= r[lag + 1];
        if fell && lag >= 2 && r[lag] >= peak && r[lag] >= r[lag - 1] && local_peak {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_transform_of_a_cosine_is_two_lines_and_the_inverse_returns_the_signal() {
        // cos(2π·2·j/8): by hand, X[2] = X[6] = 8/2 = 4, every other bin 0.
        let x: Vec<(f64, f64)> = (0..8)
            .map(|j| ((2.0 * PI * 2.0 * j as f64 / 8.0).cos(), 0.0))
            .collect();
        let spec = dft(&x, false);
        for (k, &(re, im)) in spec.iter().enumerate() {
            let want = if k == 2 || k == 6 { 4.0 } else { 0.0 };
            assert!(
                (re - want).abs() < 1e-12 && im.abs() < 1e-12,
                "bin {k}: {re} {im}"
            );
        }
        let back = dft(&spec, true);
        for (a, b) in back.iter().zip(&x) {
            assert!((a.0 - b.0).abs() < 1e-12 && a.1.abs() < 1e-12);
        }
        assert!(dft(&[], false).is_empty());
    }
}
