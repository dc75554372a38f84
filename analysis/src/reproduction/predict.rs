//! Analytic (numerical-integration) predictions of an observer: the mean and variance of
//! the estimate and of the production at each sample interval, and the predicted
//! behavioural summary.
//!
//! `E[tp|ts] = E[te|ts]` (production noise is unbiased) and, for continuous productions,
//! `Var[tp|ts] = Var[te|ts] + wp²·E[te²|ts]` (law of total variance). Under
//! [`Rounding::WholeSteps`] the moments of `⌊tp + ½⌋` given `te` are computed exactly by
//! summing the normal masses of the bins (for a production SD < 4 steps) or by Sheppard's
//! correction, mean unchanged and variance `+ 1/12` (SD ≥ 4 steps, where the neglected
//! periodic terms are below `e^(−2π²·16)`), then integrated over `te`.

use super::grid::te_distribution;
use super::normal::interval_mass;
use super::observer::Observer;
use super::summary::{Summary, TsMoments, summary_from_moments};
use super::{ObserverError, Prior, Rounding, check_interval, check_weber, round_step};

/// An observer's predicted moments at one sample interval (steps, steps²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// Sample interval (steps).
    pub ts: f64,
    /// `E[te | ts]` (steps).
    pub mean_te: f64,
    /// `Var[te | ts]` (steps²).
    pub var_te: f64,
    /// `E[tp | ts]` (steps; of the rounded production under `WholeSteps`).
    pub mean_tp: f64,
    /// `Var[tp | ts]` (steps²), production noise included (and rounding under
    /// `WholeSteps`).
    pub var_tp: f64,
}

/// The prediction at every prior value, ascending (`K` entries).
pub fn predict(
    observer: Observer,
    wm: f64,
    wp: f64,
    prior: &Prior,
    rounding: Rounding,
) -> Result<Vec<Prediction>, ObserverError> {
    prior
        .values()
        .iter()
        .map(|&ts| predict_at(observer, wm, wp, prior, ts, rounding))
        .collect()
}

/// The prediction at one sample interval `ts` (steps, > 0; need not be a prior value, e.g.
/// a probe interval), for an observer whose prior is `prior`.
pub fn predict_at(
    observer: Observer,
    wm: f64,
    wp: f64,
    prior: &Prior,
    ts: f64,
    rounding: Rounding,
) -> Result<Prediction, ObserverError> {
    check_weber("wm", wm)?;
    check_weber("wp", wp)?;
    check_interval("ts", ts)?;
    let dist = te_distribution(observer, ts, wm, wp, prior.values(), 1.0);
    let pts = || dist.te.iter().zip(&dist.weight);
    let mean_te: f64 = pts().map(|(t, w)| w * t).sum();
    let var_te: f64 = pts().map(|(t, w)| w * (t - mean_te).powi(2)).sum();
    let (mean_tp, var_tp) = match rounding {
        Rounding::None => {
            let m2: f64 = pts().map(|(t, w)| w * t * t).sum();
            (mean_te, var_te + wp * wp * m2)
        }
        Rounding::WholeSteps => {
            let moments: Vec<(f64, f64, f64)> = pts()
                .map(|(&t, &w)| {
                    let (m, v) = rounded_moments(t, wp * t.abs());
                    (w, m, v)
                })
                .collect();
            let mean: f64 = moments.iter().map(|(w, m, _)| w * m).sum();
            let var: f64 = moments
                .iter()
                .map(|(w, m, v)| w * (v + (m - mean).powi(2)))
                .sum();
            (mean, var)
        }
    };
    Ok(Prediction {
        ts,
        mean_te,
        var_te,
        mean_tp,
        var_tp,
    })
}

/// The summary ([`Summary`]) an infinite, balanced data set from this observer would have:
/// J&S's slope, BIAS, VAR, RMSE and Weber fraction computed from the predicted moments,
/// every prior value weighted equally.
pub fn predicted_summary(
    observer: Observer,
    wm: f64,
    wp: f64,
    prior: &Prior,
    rounding: Rounding,
) -> Result<Summary, ObserverError> {
    let moments: Vec<TsMoments> = predict(observer, wm, wp, prior, rounding)?
        .into_iter()
        .map(|p| TsMoments {
            ts: p.ts,
            weight: 1.0,
            mean: p.mean_tp,
            var: p.var_tp,
        })
        .collect();
    summary_from_moments(&moments)
}

/// Mean and variance of `⌊X + ½⌋` for `X ~ N(mean, sd²)` (steps, steps²).
pub(crate) fn rounded_moments(mean: f64, sd: f64) -> (f64, f64) {
    if sd >= 4.0 {
        return (mean, sd * sd + 1.0 / 12.0);
    }
    if sd <= 0.0 {
        return (round_step(mean), 0.0);
    }
    let lo = (mean - 12.0 * sd).floor() as i64 - 1;
    let hi = (mean + 12.0 * sd).ceil() as i64 + 1;
    let masses: Vec<(f64, f64)> = (lo..=hi)
        .map(|n| {
            let n = n as f64;
            let p = interval_mass((n - 0.5 - mean) / sd, (n + 0.5 - mean) / sd);
            (n, p)
        })
        .collect();
    let total: f64 = masses.iter().map(|(_, p)| p).sum();
    let m: f64 = masses.iter().map(|(n, p)| p * n).sum::<f64>() / total;
    let v: f64 = masses.iter().map(|(n, p)| p * (n - m).powi(2)).sum::<f64>() / total;
    (m, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounded_moments_limits() {
        // Just below the switch to Sheppard's correction the exact bin sum agrees with it
        // (to the ~1e-10 accuracy of statrs' erfc; the periodic terms are ~e^(−316)).
        let sd = 3.999_999f64;
        let (m, v) = rounded_moments(20.3, sd);
        assert!(
            (m - 20.3).abs() < 1e-8 && (v - (sd * sd + 1.0 / 12.0)).abs() < 1e-8,
            "{m} {v}"
        );
        // At SD 0.5 rounding is far from Sheppard: the exact variance is larger than
        // 0.25 + 1/12 (periodic term e^(−2π²·0.25) ≈ 7 %).
        let (_, v) = rounded_moments(20.3, 0.5);
        assert!(v - (0.25 + 1.0 / 12.0) > 1e-3, "{v}");
        // Tiny SD: a point mass at the rounded value.
        let (m, v) = rounded_moments(20.3, 1e-4);
        assert!((m - 20.0).abs() < 1e-12 && v.abs() < 1e-12);
        // Half-way between two integers with tiny SD: a fair coin between 20 and 21.
        let (m, v) = rounded_moments(20.5, 1e-4);
        assert!((m - 20.5).abs() < 1e-9 && (v - 0.25).abs() < 1e-9);
    }
}
