//! Small statistics shared by the behavioural and neural analyses:
//!
//! * [`Spread`] — mean, sample SD and count of one number across runs.
//!
//! Special functions (normal CDF, incomplete beta, …) come from `statrs`.

use serde::{Deserialize, Serialize};

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
