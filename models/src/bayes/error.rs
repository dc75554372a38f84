//! The typed errors of the Bayesian observers and their fits (temporal reproduction): every
//! bad input names its field and the allowed values; nothing panics on bad input.

/// A rejected input to an observer, its fit or its agent.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ObserverError {
    /// The task is not one an observer agent can play (it needs Ready-Set-Go mechanics:
    /// a prior of sample intervals and the gains of the production).
    #[error("an observer agent plays a Ready-Set-Go (reproduction) task: {0}")]
    Task(String),
    /// A value is NaN or infinite.
    #[error("{field} must be finite, got {value}")]
    NotFinite {
        /// The offending field (e.g. `"tp"`).
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// An interval (a sample interval or a prior value) is ≤ 0 steps.
    #[error("{field} must be > 0 steps, got {value}")]
    NotPositive {
        /// The offending field (e.g. `"ts"`).
        field: &'static str,
        /// Its value (steps).
        value: f64,
    },
    /// A Weber fraction outside its allowed range.
    #[error("{field} must be in [{min}, {max}], got {value}")]
    OutOfRange {
        /// The offending field (`"wm"` or `"wp"`).
        field: &'static str,
        /// Its value.
        value: f64,
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
    /// Too few entries (records, prior values, trials, distinct intervals).
    #[error("{field} has {got} entries; at least {min} needed")]
    TooFew {
        /// What is counted (e.g. `"records"`).
        field: &'static str,
        /// How many there are.
        got: usize,
        /// How many are needed.
        min: usize,
    },
    /// Fewer than the needed trials at one sample interval.
    #[error("ts = {ts} steps has {got} trials; at least {min} needed")]
    TooFewTrials {
        /// The sample interval (steps).
        ts: f64,
        /// Its number of trials.
        got: usize,
        /// How many are needed.
        min: usize,
    },
    /// A prior value given twice.
    #[error("prior values must be distinct; {value} steps appears more than once")]
    DuplicateValue {
        /// The repeated value (steps).
        value: f64,
    },
    /// A production that is not a whole number of steps under `Rounding::WholeSteps`.
    #[error("tp must be a whole number of steps when rounding is WholeSteps, got {value}")]
    NotWholeSteps {
        /// The production (steps).
        value: f64,
    },
    /// A negative weight or variance given to the summary.
    #[error("{field} must be ≥ 0 (weight > 0), got {value}")]
    Negative {
        /// The offending field (`"weight"` or `"var"`).
        field: &'static str,
        /// Its value.
        value: f64,
    },
}
