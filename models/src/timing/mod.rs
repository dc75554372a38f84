//! Biologically plausible timing models, plain Rust (no autodiff), and the agents that
//! play the tasks with them:
//!
//! * [`ddm`] — drift-diffusion accumulator; [`sbf`] — striatal beat frequency;
//!   [`timecells`] — time cells (microstimuli, CSC, presence, Laplace); [`td`] — linear
//!   TD(λ); [`ctrnn`] — a stand-alone CTRNN;
//! * [`timers`] — a timing model as the clock of an agent (onset, tick, gate, features,
//!   learning at reinforcement);
//! * [`judgment`] — bisection judgments from each model's anchor memories;
//! * [`sarsa`] — linear SARSA(λ) over state × temporal features;
//! * [`agent`] — the timing-model agent ([`TimingAgent`]); [`train`] — its training loop;
//! * [`zoo`] — the registry of timing models (names, descriptions, construction).

pub mod agent;
pub mod ctrnn;
pub mod ddm;
pub mod judgment;
pub mod sarsa;
pub mod sbf;
pub mod td;
pub mod timecells;
pub mod timers;
pub mod train;
pub mod zoo;

pub use agent::{TimingAgent, TimingAgentConfig};

pub use ctrnn::Ctrnn;
pub use ddm::DriftDiffusion;
pub use sbf::{BeatFrequency, FrequencyLayout};
pub use td::LinearTd;
pub use timecells::{Representation, TimeCells, microstimulus, microstimulus_peak};
