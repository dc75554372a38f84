//! Chronocooked Lab analysis: behavioural and neural metrics of recorded episodes and
//! activity (grows with its issue).

pub mod foc;

pub use foc::{episode_foc, first_oven_check};
