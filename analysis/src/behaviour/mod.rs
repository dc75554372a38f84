//! Behavioural metrics of evaluated episodes:
//!
//! * [`foc`] — first oven check (the paper's FI measure), per-TD statistics, scalar property;
//! * [`psychometric`] — bisection P(long), logistic fit by binomial maximum likelihood,
//!   BP / T25 / T75 / DL / WF with bootstrap intervals;
//! * [`peak`] — peak-interval Gaussian(+baseline) fit and single-trial start/stop analysis;
//! * [`categorization`] — multi-anchor choices, category error rates, one psychometric
//!   boundary per pair of neighbouring anchors, WF constancy across boundaries;
//! * [`concurrent`] — multi-oven per-oven curves, interference against the one-oven curve,
//!   accuracy by onset offset, delivery order;
//! * [`reproduction`] — temporal reproduction: tp against ts per prior and gain, the
//!   regression slope, BIAS, √VAR, and the best Bayesian observer;
//! * [`metrics`] — the metrics of one evaluation from its per-episode records;
//! * [`aggregate`] — the spread of a number across seeds ([`aggregate::Spread`]);
//! * [`human`] — recorded human play (`env play`) as evaluation records.

pub mod aggregate;
pub mod categorization;
pub mod concurrent;
pub mod foc;
pub mod human;
pub mod metrics;
pub mod peak;
pub mod predicted;
pub mod psychometric;
pub mod reproduction;
