//! Chronocooked Lab analysis: behavioural and neural metrics of recorded episodes and
//! activity (grows with its issue).
//!
//! * [`foc`] — first oven check (the paper's FI measure), per-TD statistics, scalar property;
//! * [`psychometric`] — bisection P(long), logistic fit by binomial maximum likelihood,
//!   BP / T25 / T75 / DL / WF with bootstrap intervals.

pub mod foc;
pub mod psychometric;

pub use foc::{
    FocStats, ScalarProperty, episode_foc, first_oven_check, foc_stats, scalar_property,
};
pub use psychometric::{FitError, LogisticFit, ProbeCounts, fit_logistic, fit_with_ci};
