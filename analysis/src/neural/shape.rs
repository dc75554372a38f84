//! Shape fits of a unit's trial average `m(t)` (`t` = steps after the event): monotone
//! (isotonic) and unimodal (rise-then-fall) least-squares fits by pool-adjacent-violators,
//! and the spectral peak of a Hann-windowed periodogram.
//!
//! Every function takes one finite series (`[time]`); callers drop missing steps first.

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

/// Variance of `y` explained by its best monotone fit (either direction), with the
/// direction (`+1` rising, `−1` falling). `(NaN, 0)` for fewer than 3 points or a constant
/// series.
pub fn monotone_r2(y: &[f64]) -> (f64, i8) {
    let ss = total_ss(y);
    if y.len() < 3 || ss <= 0.0 {
        return (f64::NAN, 0);
    }
    let up = 1.0 - sse(y, &isotonic_increasing(y)) / ss;
    let down = 1.0 - sse(y, &isotonic_decreasing(y)) / ss;
    if up >= down { (up, 1) } else { (down, -1) }
}

/// Variance of `y` explained by its best unimodal fit: non-decreasing on `[0, c]`,
/// non-increasing on `[c+1, len)`, over every split `c` with at least one point on each
/// side. `NaN` for fewer than 3 points or a constant series.
pub fn unimodal_r2(y: &[f64]) -> f64 {
    let ss = total_ss(y);
    if y.len() < 3 || ss <= 0.0 {
        return f64::NAN;
    }
    let best = (1..y.len())
        .map(|c| {
            sse(&y[..c], &isotonic_increasing(&y[..c]))
                + sse(&y[c..], &isotonic_decreasing(&y[c..]))
        })
        .fold(f64::INFINITY, f64::min);
    1.0 - best / ss
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
    (0..=n / 2)
        .map(|k| {
            let (mut re, mut im) = (0.0, 0.0);
            for (j, v) in w.iter().enumerate() {
                let (s, c) = (2.0 * PI * ((k * j) % n) as f64 / n as f64).sin_cos();
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
    fn periodogram_peaks_at_the_sinusoid() {
        let x: Vec<f64> = (0..32)
            .map(|t| (2.0 * PI * 5.0 * t as f64 / 32.0).sin())
            .collect();
        assert_eq!(spectral_peak(&periodogram(&x), 2).0, 5);
    }
}
