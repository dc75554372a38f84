//! The time-locking test of the unit categories: is a unit's activity locked to the event?
//! Per-trial circular shifts (each trial rotated by its own uniform random offset within
//! its recorded steps: every trial keeps its values and its autocorrelation, the alignment
//! to the event is destroyed) against two statistics — the variance over time of the trial
//! average and the dispersion of single-trial activity centroids
//! ([`crate::neural::categories`]).

use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// Trial average of `trials` rotated by `shifts` (NaN-aware; NaN where no trial reaches).
pub(crate) fn rotated_average(trials: &[Vec<f64>], shifts: &[usize], len: usize) -> Vec<f64> {
    let mut sum = vec![0.0; len];
    let mut n = vec![0usize; len];
    for (x, &s) in trials.iter().zip(shifts) {
        // Step t reads x[(t + s) mod l]: the tail x[s..] first, then the head.
        let l = x.len();
        let s = if l > 0 { s % l } else { 0 };
        let (tail, head) = (&x[s..], &x[..s]);
        for (t, v) in tail.iter().chain(head).take(len).enumerate() {
            sum[t] += v;
            n[t] += 1;
        }
    }
    sum.iter()
        .zip(&n)
        .map(|(s, &c)| if c > 0 { s / c as f64 } else { f64::NAN })
        .collect()
}

/// Dispersion over trials of the single-trial activity centroids `c_k = Σ_t t·a_k(t) /
/// Σ_t a_k(t)`, `a_k` the trial (rotated by `shifts`, its first `len` steps) less its own
/// minimum; trials without variation are left out. `None` below two such trials.
fn centroid_dispersion(trials: &[Vec<f64>], shifts: &[usize], len: usize) -> Option<f64> {
    let centroids: Vec<f64> = trials
        .iter()
        .zip(shifts)
        .filter_map(|(x, &s)| {
            let l = x.len();
            let r: Vec<f64> = (0..l.min(len)).map(|t| x[(t + s) % l]).collect();
            let lo = r.iter().copied().fold(f64::INFINITY, f64::min);
            let w: f64 = r.iter().map(|v| v - lo).sum();
            (w > 0.0).then(|| {
                r.iter()
                    .enumerate()
                    .map(|(t, v)| t as f64 * (v - lo))
                    .sum::<f64>()
                    / w
            })
        })
        .collect();
    (centroids.len() >= 2).then(|| variance_stat(&centroids) / centroids.len() as f64)
}

pub(crate) fn variance_stat(m: &[f64]) -> f64 {
    let mean = m.iter().sum::<f64>() / m.len().max(1) as f64;
    m.iter().map(|v| (v - mean).powi(2)).sum()
}

/// Surrogate p of a unit's time-locking to the event on the first `len` steps of `trials`:
/// two statistics against the same `surrogates` per-trial circular shifts, Bonferroni
/// combined (`p = min(1, 2·min(p_S, p_D))`): the variance over time of the trial average,
/// `S` (dense activity: ramps, fields, evoked rhythms), and the dispersion over trials of
/// the single-trial activity centroids, `D` (sparse activity: a delay-line unit fires once
/// per trial, so shifting its trials hardly changes `S` while it scatters the centroids).
pub(crate) fn locking_p(
    trials: &[Vec<f64>],
    len: usize,
    surrogates: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> f64 {
    let zero = vec![0; trials.len()];
    let average = |shifts: &[usize]| -> Vec<f64> {
        rotated_average(trials, shifts, len)
            .into_iter()
            .map(|v| if v.is_finite() { v } else { 0.0 })
            .collect()
    };
    let s = variance_stat(&average(&zero));
    if s <= 0.0 {
        return 1.0;
    }
    let dispersion = centroid_dispersion(trials, &zero, len);
    let (mut above, mut tighter) = (0usize, 0usize);
    let mut shifts = vec![0usize; trials.len()];
    for _ in 0..surrogates {
        for (sh, x) in shifts.iter_mut().zip(trials) {
            *sh = rng.random_range(0..x.len());
        }
        if variance_stat(&average(&shifts)) >= s {
            above += 1;
        }
        match (dispersion, centroid_dispersion(trials, &shifts, len)) {
            (Some(d), Some(ds)) if ds <= d => tighter += 1,
            (None, _) => tighter += 1,
            _ => {}
        }
    }
    let p_of = |count: usize| (count + 1) as f64 / (surrogates + 1) as f64;
    (2.0 * p_of(above).min(p_of(tighter))).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::rotated_average;

    #[test]
    fn rotated_average_by_hand() {
        // Trial 1 rotated by 1: [2, 3, 1]; trial 2 rotated by 5 ≡ 1: [5, 6, 7, 4].
        let trials = vec![vec![1.0, 2.0, 3.0], vec![4.0, 5.0, 6.0, 7.0]];
        assert_eq!(
            rotated_average(&trials, &[1, 5], 4),
            vec![3.5, 4.5, 4.0, 4.0]
        );
        let none = rotated_average(&trials, &[0, 0], 5);
        assert_eq!(&none[..4], &[2.5, 3.5, 4.5, 7.0]);
        assert!(none[4].is_nan(), "no trial reaches step 4");
    }
}
