//! The spread of a number across seeds / runs ([`Spread`]: mean, SD, n). The headline
//! numbers themselves, and their mean ± SD over a leaderboard row's runs, are the
//! leaderboard's columns ([`crate::columns`]), declared once there.

pub use crate::stats::Spread;
