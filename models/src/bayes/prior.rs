//! The prior over sample intervals: a discrete uniform distribution over ≥ 2 distinct
//! positive values (steps), sorted ascending.

use super::{ObserverError, Record, check_interval};

/// A discrete uniform prior over sample intervals: each of its values (steps) has
/// probability `1/K`. Invariants: `K ≥ 2`, values finite, > 0, distinct, ascending.
#[derive(Debug, Clone, PartialEq)]
pub struct Prior {
    values: Vec<f64>,
}

impl Prior {
    /// The prior over `values` (steps, any order; `K ≥ 2`, finite, > 0, distinct).
    pub fn new(values: &[f64]) -> Result<Self, ObserverError> {
        if values.len() < 2 {
            return Err(ObserverError::TooFew {
                field: "prior values",
                got: values.len(),
                min: 2,
            });
        }
        for &v in values {
            check_interval("prior value", v)?;
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Err(ObserverError::DuplicateValue { value: w[0] });
        }
        Ok(Prior { values: sorted })
    }

    /// The prior over the distinct sample intervals found in `records` (steps).
    pub fn from_records(records: &[Record]) -> Result<Self, ObserverError> {
        if records.is_empty() {
            return Err(ObserverError::TooFew {
                field: "records",
                got: 0,
                min: 1,
            });
        }
        let mut values = Vec::with_capacity(records.len());
        for r in records {
            values.push(check_interval("ts", r.ts)?);
        }
        values.sort_by(f64::total_cmp);
        values.dedup();
        Prior::new(&values)
    }

    /// The values `sₖ` (steps), ascending; length `K ≥ 2`.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The shortest value (steps).
    pub fn min(&self) -> f64 {
        self.values[0]
    }

    /// The longest value (steps).
    pub fn max(&self) -> f64 {
        self.values[self.values.len() - 1]
    }

    /// The prior mean `Σ sₖ / K` (steps).
    pub fn mean(&self) -> f64 {
        self.values.iter().sum::<f64>() / self.values.len() as f64
    }
}
