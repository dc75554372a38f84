//! Bisection psychometrics: P(long) per probe with the paper's exclusion rules and a logistic
//! fit by binomial maximum likelihood.
//!
//! `P(long | t) = 1 / (1 + e^{−(t − BP)/s})`. From the fit: the bisection point BP,
//! `T25 = BP − s ln 3`, `T75 = BP + s ln 3`, the difference limen `DL = (T75 − T25)/2 = s ln 3`
//! and the Weber fraction `WF = DL / BP`; BP is compared with the arithmetic (`(S+L)/2`) and
//! geometric (`√(S·L)`) means of the anchors. Confidence intervals: parametric bootstrap
//! (binomial resampling at the fitted probabilities, refit, percentile interval), seeded.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

/// Choices at one probe duration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ProbeCounts {
    /// Probe duration (steps).
    pub t: f64,
    /// Valid episodes (a delivery to either counter).
    pub valid: u32,
    /// Deliveries to the long counter.
    pub long: u32,
    /// Episodes excluded (no delivery: failed).
    pub failed: u32,
}

impl ProbeCounts {
    /// P(long) among valid episodes; NaN when more than half of the episodes failed
    /// (the paper's rule) or none is valid.
    pub fn p_long(&self) -> f64 {
        let total = self.valid + self.failed;
        if self.valid == 0 || 2 * self.failed > total {
            return f64::NAN;
        }
        f64::from(self.long) / f64::from(self.valid)
    }
}

/// Result of a logistic fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogisticFit {
    /// Bisection point (P = 0.5), steps.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub bp: f64,
    /// Scale `s` (steps); NaN (undefined) when the curve is a step (`separated`).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub scale: f64,
    /// `T25 = BP − s ln 3`.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub t25: f64,
    /// `T75 = BP + s ln 3`.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub t75: f64,
    /// Difference limen `(T75 − T25)/2`.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub dl: f64,
    /// Weber fraction `DL / BP`.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub wf: f64,
    /// Log-likelihood at the optimum.
    pub log_lik: f64,
    /// The choices switch from all-short to all-long with at most one mixed probe between
    /// (separation or quasi-separation: the maximum-likelihood slope is infinite). BP is
    /// then the 0.5 crossing of the empirical curve; the scale, DL, T25/T75 and WF are
    /// undefined (NaN, `null` in JSON): a step has no measurable Weber fraction.
    pub separated: bool,
    /// Bootstrap percentile interval of BP (`None` when not computed).
    pub bp_ci: Option<(f64, f64)>,
    /// Bootstrap percentile interval of the scale.
    pub scale_ci: Option<(f64, f64)>,
}

/// Why a fit could not be made.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, thiserror::Error)]
pub enum FitError {
    /// Fewer than two probes with valid data.
    #[error("not enough valid probes to fit ({0}; need 2)")]
    TooFewProbes(usize),
    /// All valid choices were to one counter: no transition to locate.
    #[error("all choices went to one counter: no bisection point")]
    NoTransition,
    /// The optimiser failed (non-finite values).
    #[error("the logistic fit did not converge")]
    NoConvergence,
}

fn sigmoid(x: f64) -> f64 {
    if x >= 0.0 {
        1.0 / (1.0 + (-x).exp())
    } else {
        let e = x.exp();
        e / (1.0 + e)
    }
}

fn log_lik(data: &[ProbeCounts], a: f64, b: f64) -> f64 {
    data.iter()
        .map(|d| {
            let z = a + b * d.t;
            // log σ(z) = −softplus(−z), log(1 − σ(z)) = −softplus(z)
            let sp = |x: f64| if x > 30.0 { x } else { x.exp().ln_1p() };
            -(f64::from(d.long) * sp(-z) + f64::from(d.valid - d.long) * sp(z))
        })
        .sum()
}

/// Usable probes: at least one valid episode and P(long) not NaN by the exclusion rule.
fn usable(data: &[ProbeCounts]) -> Vec<ProbeCounts> {
    data.iter()
        .copied()
        .filter(|d| d.p_long().is_finite())
        .collect()
}

/// The 0.5 crossing of a step-shaped curve (probes sorted by duration): `Some(BP)` when the
/// probes are all-short, then at most one mixed probe, then all-long; `None` otherwise.
fn step_crossing(sorted: &[ProbeCounts]) -> Option<f64> {
    let p = |d: &ProbeCounts| f64::from(d.long) / f64::from(d.valid);
    let is_mixed = |d: &ProbeCounts| d.long > 0 && d.long < d.valid;
    if sorted.iter().filter(|d| is_mixed(d)).count() > 1 {
        return None;
    }
    // All-short probes must all precede every non-short probe, and all-long ones follow
    // every non-long probe.
    let first_not_short = sorted.iter().position(|d| d.long > 0)?;
    let last_not_long = sorted.iter().rposition(|d| d.long < d.valid)?;
    let ordered = sorted[first_not_short..].iter().all(|d| d.long > 0)
        && sorted[..=last_not_long].iter().all(|d| d.long < d.valid);
    if !ordered || first_not_short == 0 || last_not_long + 1 == sorted.len() {
        return None;
    }
    // Interpolate P = 0.5 between consecutive probes of the empirical curve.
    sorted.windows(2).find_map(|w| {
        let (p0, p1) = (p(&w[0]), p(&w[1]));
        (p0 < 0.5 && p1 >= 0.5).then(|| w[0].t + (0.5 - p0) / (p1 - p0) * (w[1].t - w[0].t))
    })
}

/// Fits the logistic by binomial maximum likelihood (Newton's method with step halving on
/// `p = σ(a + b t)`, BP = −a/b, s = 1/b). No confidence intervals (see [`fit_with_ci`]).
pub fn fit_logistic(data: &[ProbeCounts]) -> Result<LogisticFit, FitError> {
    let data = usable(data);
    if data.len() < 2 {
        return Err(FitError::TooFewProbes(data.len()));
    }
    let total_long: u32 = data.iter().map(|d| d.long).sum();
    let total: u32 = data.iter().map(|d| d.valid).sum();
    if total_long == 0 || total_long == total {
        return Err(FitError::NoTransition);
    }
    // A step: every probe is all-short below the transition and all-long above it, with
    // at most one mixed probe between. The likelihood then keeps rising as the slope
    // grows (separation or quasi-separation), so the slope — and with it DL and WF — is
    // not identified: they are undefined (NaN, written as null), never a tiny number. BP
    // is where the empirical curve crosses 0.5 (linear interpolation).
    let mut sorted = data.clone();
    sorted.sort_by(|x, y| x.t.total_cmp(&y.t));
    if let Some(bp) = step_crossing(&sorted) {
        return Ok(LogisticFit {
            bp,
            scale: f64::NAN,
            t25: f64::NAN,
            t75: f64::NAN,
            dl: f64::NAN,
            wf: f64::NAN,
            log_lik: 0.0,
            separated: true,
            bp_ci: None,
            scale_ci: None,
        });
    }
    // Start: BP at the mean probe, scale a quarter of the range.
    let tmin = sorted[0].t;
    let tmax = sorted[sorted.len() - 1].t;
    let mut b = 4.0 / (tmax - tmin).max(1e-6);
    let mut a = -b * 0.5 * (tmin + tmax);
    let mut ll = log_lik(&data, a, b);
    for _ in 0..200 {
        // Gradient and Hessian of the log-likelihood in (a, b).
        let (mut ga, mut gb, mut haa, mut hab, mut hbb) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for d in &data {
            let p = sigmoid(a + b * d.t);
            let n = f64::from(d.valid);
            let r = f64::from(d.long) - n * p;
            let w = n * p * (1.0 - p);
            ga += r;
            gb += r * d.t;
            haa += w;
            hab += w * d.t;
            hbb += w * d.t * d.t;
        }
        let det = haa * hbb - hab * hab;
        if det.abs() < 1e-300 {
            break;
        }
        let da = (hbb * ga - hab * gb) / det;
        let db = (haa * gb - hab * ga) / det;
        let mut step = 1.0;
        let mut improved = false;
        for _ in 0..40 {
            let (na, nb) = (a + step * da, b + step * db);
            let nll = log_lik(&data, na, nb);
            if nll.is_finite() && nll >= ll - 1e-12 {
                let done = (nll - ll).abs() < 1e-12;
                a = na;
                b = nb;
                ll = nll;
                improved = !done;
                break;
            }
            step *= 0.5;
        }
        if !improved {
            break;
        }
    }
    if !(a.is_finite() && b.is_finite()) || b.abs() < 1e-12 {
        return Err(FitError::NoConvergence);
    }
    let bp = -a / b;
    let scale = 1.0 / b;
    let dl = scale * 3f64.ln();
    Ok(LogisticFit {
        bp,
        scale,
        t25: bp - dl,
        t75: bp + dl,
        dl,
        wf: dl / bp,
        log_lik: ll,
        separated: false,
        bp_ci: None,
        scale_ci: None,
    })
}

/// [`fit_logistic`] plus parametric-bootstrap percentile intervals at level `level`
/// (e.g. 0.95) from `resamples` refits (seeded by `seed`).
pub fn fit_with_ci(
    data: &[ProbeCounts],
    level: f64,
    resamples: usize,
    seed: u64,
) -> Result<LogisticFit, FitError> {
    let mut fit = fit_logistic(data)?;
    if fit.separated || resamples == 0 {
        return Ok(fit);
    }
    let used = usable(data);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let (mut bps, mut scales) = (Vec::new(), Vec::new());
    for _ in 0..resamples {
        let sample: Vec<ProbeCounts> = used
            .iter()
            .map(|d| {
                let p = sigmoid((d.t - fit.bp) / fit.scale);
                let long = (0..d.valid).filter(|_| rng.random::<f64>() < p).count() as u32;
                ProbeCounts { long, ..*d }
            })
            .collect();
        if let Ok(f) = fit_logistic(&sample) {
            bps.push(f.bp);
            scales.push(f.scale);
        }
    }
    let interval = |v: &mut Vec<f64>| {
        if v.len() < 10 {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let q = |p: f64| v[((p * (v.len() - 1) as f64).round() as usize).min(v.len() - 1)];
        Some((q((1.0 - level) / 2.0), q((1.0 + level) / 2.0)))
    };
    fit.bp_ci = interval(&mut bps);
    fit.scale_ci = interval(&mut scales);
    Ok(fit)
}

/// BP relative to the anchors' arithmetic and geometric means: `(BP/AM, BP/GM)`.
pub fn bp_relative(bp: f64, short: f64, long: f64) -> (f64, f64) {
    (bp / (0.5 * (short + long)), bp / (short * long).sqrt())
}

/// Likelihood-ratio test of the fitted logistic against a flat P(long) (one parameter
/// fewer): `p = P(χ²₁ > 2 (ℓ_fit − ℓ_flat))`. Small `p`: a real psychometric transition.
pub fn transition_p_value(data: &[ProbeCounts], fit: &LogisticFit) -> f64 {
    if fit.separated {
        return 0.0;
    }
    let used = usable(data);
    let long: f64 = used.iter().map(|d| f64::from(d.long)).sum();
    let total: f64 = used.iter().map(|d| f64::from(d.valid)).sum();
    let p = long / total;
    if p <= 0.0 || p >= 1.0 {
        return 1.0;
    }
    let flat = long * p.ln() + (total - long) * (1.0 - p).ln();
    let lr = (2.0 * (fit.log_lik - flat)).max(0.0);
    statrs::function::erf::erfc((lr / 2.0).sqrt())
}

/// Largest fall of P(long) from a shorter to a longer probe, each with at least
/// [`MIN_VALID_FOR_REVERSAL`] valid episodes: `(t_short, p_short, t_long, p_long)`, or
/// `None` when P(long) never falls. A psychometric curve rises; a large fall (e.g. "long"
/// at probes far shorter than the short anchor, then "short" at the anchor) is not a
/// transition a logistic describes.
pub fn largest_reversal(data: &[ProbeCounts]) -> Option<(f64, f64, f64, f64)> {
    let mut used: Vec<(f64, f64)> = usable(data)
        .iter()
        .filter(|d| d.valid >= MIN_VALID_FOR_REVERSAL)
        .map(|d| (d.t, d.p_long()))
        .collect();
    used.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best: Option<(f64, f64, f64, f64)> = None;
    let mut peak: Option<(f64, f64)> = None;
    for &(t, p) in &used {
        if let Some((tp, pp)) = peak
            && pp - p > best.map_or(0.0, |b| b.1 - b.3)
        {
            best = Some((tp, pp, t, p));
        }
        if peak.is_none_or(|(_, pp)| p > pp) {
            peak = Some((t, p));
        }
    }
    best
}

/// Valid episodes a probe needs to count in [`largest_reversal`].
pub const MIN_VALID_FOR_REVERSAL: u32 = 4;

/// Largest fall of P(long) [`check_transition`] tolerates (binomial noise at a few
/// episodes per probe).
pub const MAX_REVERSAL: f64 = 0.5;

/// Whether a fit describes a real psychometric transition: rising (`s > 0`), significant
/// against a flat P(long) (likelihood ratio, p ≤ 0.05), with BP inside the probed range,
/// and P(long) never falling by more than [`MAX_REVERSAL`] from a shorter to a longer probe
/// (a non-monotone curve is not a transition). The error says which condition failed.
pub fn check_transition(data: &[ProbeCounts], fit: &LogisticFit) -> Result<(), String> {
    let tmin = data.iter().map(|p| p.t).fold(f64::INFINITY, f64::min);
    let tmax = data.iter().map(|p| p.t).fold(f64::NEG_INFINITY, f64::max);
    if let Some((ta, pa, tb, pb)) = largest_reversal(data).filter(|r| r.1 - r.3 > MAX_REVERSAL) {
        return Err(format!(
            "P(long) is not monotone: {pa:.2} at probe {ta} but {pb:.2} at the longer probe {tb}"
        ));
    }
    let p = transition_p_value(data, fit);
    if fit.scale < 0.0 || p > 0.05 || fit.bp < tmin || fit.bp > tmax {
        return Err(format!(
            "no reliable psychometric transition (BP {:.2}, scale {:.2}, likelihood-ratio p = {:.3})",
            fit.bp, fit.scale, p
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(p_long: &[Option<f64>], n: u32) -> Vec<ProbeCounts> {
        p_long
            .iter()
            .enumerate()
            .map(|(i, p)| ProbeCounts {
                t: (i + 1) as f64,
                valid: if p.is_some() { n } else { 0 },
                long: p.map_or(0, |p| (p * n as f64).round() as u32),
                failed: if p.is_some() { 0 } else { n },
            })
            .collect()
    }

    #[test]
    fn the_non_monotone_sbf_curve_is_not_a_transition() {
        // SBF on bisection 4-12 before the criterion readout: "long" at probes 1-2, "short"
        // at 3-5 (probe 6 failed), "long" from 7 on — the logistic still fits a rising
        // curve, the reversal test rejects it.
        let mut p = vec![Some(1.0), Some(1.0), Some(0.0), Some(0.0), Some(0.0), None];
        p.extend(std::iter::repeat_n(Some(1.0), 10));
        let data = curve(&p, 8);
        assert_eq!(largest_reversal(&data), Some((1.0, 1.0, 3.0, 0.0)));
        let fit = fit_logistic(&data).unwrap();
        let err = check_transition(&data, &fit).unwrap_err();
        assert!(err.contains("not monotone"), "{err}");
    }

    #[test]
    fn a_monotone_curve_with_binomial_noise_passes() {
        let p: Vec<Option<f64>> = [0.0, 0.0, 0.0, 0.125, 0.5, 0.25, 0.875, 1.0, 0.875, 1.0]
            .iter()
            .map(|&p| Some(p))
            .collect();
        let data = curve(&p, 8);
        let (_, pa, _, pb) = largest_reversal(&data).unwrap();
        assert!((pa - pb - 0.25).abs() < 1e-12);
        let fit = fit_logistic(&data).unwrap();
        check_transition(&data, &fit).unwrap();
        let rising = curve(&[Some(0.0), Some(0.5), Some(1.0)], 8);
        assert_eq!(largest_reversal(&rising), None);
    }
}
