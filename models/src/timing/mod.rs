//! Biologically plausible timing models, plain Rust (no autodiff): drift-diffusion,
//! striatal beat-frequency, time cells (microstimuli, CSC, presence, Laplace), linear
//! TD(λ) and a stand-alone CTRNN. The agents that play the tasks with them are in
//! [`crate::timing_agent`].

pub mod ctrnn;
pub mod ddm;
pub mod sbf;
pub mod td;
pub mod timecells;

pub use ctrnn::Ctrnn;
pub use ddm::DriftDiffusion;
pub use sbf::{BeatFrequency, FrequencyLayout};
pub use td::LinearTd;
pub use timecells::{Representation, TimeCells, microstimulus, microstimulus_peak};
