//! J&S's behavioural summaries of one prior condition: mean and SD of `tp` per `ts`, the
//! regression slope of `tp` on `ts`, BIAS, VAR, RMSE and the Weber fraction of `tp`.
//!
//! Definitions (J&S 2010, Fig. 2 and Methods; `K` sample intervals, each counted once):
//!
//! * `BIAS = √( (1/K) Σₖ (mean tpₖ − tsₖ)² )` — root mean squared bias over intervals;
//! * `VAR = (1/K) Σₖ var(tpₖ)` — mean variance over intervals (steps²);
//! * `RMSE = √(BIAS² + VAR)` — J&S plot `√VAR` against `BIAS`; RMSE is the distance from
//!   the origin;
//! * slope — the ordinary-least-squares slope of `tp` on `ts` over **all trials** (with an
//!   intercept). It equals the trial-weighted regression of the per-interval means on `ts`,
//!   which is how it is computed (within-interval scatter does not covary with `ts`);
//! * Weber fraction of `tp` — `(1/K) Σₖ sd(tpₖ)/mean(tpₖ)`, the mean coefficient of
//!   variation across intervals (meaningful when every mean is > 0).
//!
//! Per-interval variances from records are unbiased sample variances (divisor `n − 1`).

use super::{ObserverError, Record, check_finite, check_interval};

/// The moments of the productions at one sample interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TsMoments {
    /// Sample interval (steps, > 0).
    pub ts: f64,
    /// Weight in the slope: the number of trials (records) or 1 (predictions); > 0.
    pub weight: f64,
    /// Mean production (steps).
    pub mean: f64,
    /// Variance of the production (steps², ≥ 0).
    pub var: f64,
}

impl TsMoments {
    /// Standard deviation of the production (steps).
    pub fn sd(&self) -> f64 {
        self.var.sqrt()
    }
}

/// The summary of one prior condition.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Moments per sample interval, ascending in `ts` (`K ≥ 2` entries).
    pub per_ts: Vec<TsMoments>,
    /// OLS slope of `tp` on `ts` over trials (dimensionless; 1 = veridical, < 1 =
    /// regression to the mean).
    pub slope: f64,
    /// OLS intercept (steps).
    pub intercept: f64,
    /// `BIAS` (steps).
    pub bias: f64,
    /// `VAR` (steps²).
    pub var: f64,
    /// `RMSE = √(BIAS² + VAR)` (steps).
    pub rmse: f64,
    /// Mean over intervals of `sd/mean` of `tp` (dimensionless).
    pub weber: f64,
}

impl Summary {
    /// `√VAR` (steps), the ordinate of J&S's BIAS–√VAR plane.
    pub fn sqrt_var(&self) -> f64 {
        self.var.sqrt()
    }
}

/// The summary of `records` from one prior condition: needs ≥ 2 distinct `ts` values and
/// ≥ 2 trials at each; every `ts` finite and > 0, every `tp` finite (steps).
pub fn summarize(records: &[Record]) -> Result<Summary, ObserverError> {
    if records.is_empty() {
        return Err(ObserverError::TooFew {
            field: "records",
            got: 0,
            min: 2,
        });
    }
    let mut sorted = Vec::with_capacity(records.len());
    for r in records {
        check_interval("ts", r.ts)?;
        check_finite("tp", r.tp)?;
        sorted.push(*r);
    }
    sorted.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    let mut moments = Vec::new();
    for group in sorted.chunk_by(|a, b| a.ts == b.ts) {
        let n = group.len();
        if n < 2 {
            return Err(ObserverError::TooFewTrials {
                ts: group[0].ts,
                got: n,
                min: 2,
            });
        }
        let mean = group.iter().map(|r| r.tp).sum::<f64>() / n as f64;
        let var = group.iter().map(|r| (r.tp - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        moments.push(TsMoments {
            ts: group[0].ts,
            weight: n as f64,
            mean,
            var,
        });
    }
    summary_from_moments(&moments)
}

/// The summary from per-interval moments (any order; ≥ 2 distinct `ts`, each given once;
/// `ts > 0`, `weight > 0`, `var ≥ 0`, all finite). The slope is the weighted least-squares
/// slope of the means on `ts` with the weights (= the OLS slope over trials when the weights
/// are trial counts).
pub fn summary_from_moments(moments: &[TsMoments]) -> Result<Summary, ObserverError> {
    for m in moments {
        check_interval("ts", m.ts)?;
        check_finite("weight", m.weight)?;
        check_finite("mean", m.mean)?;
        check_finite("var", m.var)?;
        if m.weight <= 0.0 {
            return Err(ObserverError::Negative {
                field: "weight",
                value: m.weight,
            });
        }
        if m.var < 0.0 {
            return Err(ObserverError::Negative {
                field: "var",
                value: m.var,
            });
        }
    }
    let mut per_ts = moments.to_vec();
    per_ts.sort_by(|a, b| a.ts.total_cmp(&b.ts));
    if let Some(w) = per_ts.windows(2).find(|w| w[0].ts == w[1].ts) {
        return Err(ObserverError::DuplicateValue { value: w[0].ts });
    }
    if per_ts.len() < 2 {
        return Err(ObserverError::TooFew {
            field: "distinct ts values",
            got: per_ts.len(),
            min: 2,
        });
    }
    let w_sum: f64 = per_ts.iter().map(|m| m.weight).sum();
    let ts_bar = per_ts.iter().map(|m| m.weight * m.ts).sum::<f64>() / w_sum;
    let tp_bar = per_ts.iter().map(|m| m.weight * m.mean).sum::<f64>() / w_sum;
    let sxx: f64 = per_ts
        .iter()
        .map(|m| m.weight * (m.ts - ts_bar).powi(2))
        .sum();
    let sxy: f64 = per_ts
        .iter()
        .map(|m| m.weight * (m.ts - ts_bar) * (m.mean - tp_bar))
        .sum();
    let slope = sxy / sxx;
    let k = per_ts.len() as f64;
    let bias = (per_ts.iter().map(|m| (m.mean - m.ts).powi(2)).sum::<f64>() / k).sqrt();
    let var = per_ts.iter().map(|m| m.var).sum::<f64>() / k;
    let weber = per_ts.iter().map(|m| m.sd() / m.mean).sum::<f64>() / k;
    Ok(Summary {
        slope,
        intercept: tp_bar - slope * ts_bar,
        bias,
        var,
        rmse: (bias * bias + var).sqrt(),
        weber,
        per_ts,
    })
}
