//! Small statistics shared by the behavioural and neural analyses:
//!
//! * [`Spread`] — mean, sample SD and count of one number across runs;
//! * [`nan_json`] — JSON with `null` for undefined floats read back as NaN;
//! * [`robust`] — interquartile mean, stratified bootstrap intervals, probability of
//!   improvement (few-run statistics as rliable reports them).
//!
//! Special functions (normal CDF, incomplete beta, …) come from `statrs`.

pub mod nan_json;
pub mod robust;

use serde::{Deserialize, Serialize};

/// Reads a number that serde_json wrote as `null` (NaN: an undefined statistic) back as NaN.
pub fn nan_if_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// Mean, sample SD and count of one number across runs (NaN values are left out).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    /// Mean over runs with a value.
    pub mean: f64,
    /// Sample SD (NaN below 2 values).
    pub sd: f64,
    /// Runs with a value.
    pub n: usize,
}

impl Spread {
    /// Spread of `values` (non-finite ones skipped).
    pub fn of(values: impl IntoIterator<Item = f64>) -> Self {
        let v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
        let n = v.len();
        let mean = if n > 0 {
            v.iter().sum::<f64>() / n as f64
        } else {
            f64::NAN
        };
        let sd = if n > 1 {
            (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        } else {
            f64::NAN
        };
        Spread { mean, sd, n }
    }
}
