//! Chronocooked Lab models, by family:
//!
//! * [`deep`] — the paper's deep-RL networks: CNN trunk, recurrent cores (LSTM, GRU, RNN,
//!   CTRNN), actor–critic policies as burn modules, the one parameter specification
//!   (`deep::spec`) and their native twin (`deep::native`);
//! * [`timing`] — the biologically plausible timing models (drift-diffusion, striatal beat
//!   frequency, time cells, TD), the agents that play the tasks with them and their zoo;
//! * [`bayes`] — the Bayesian observers of temporal reproduction (BLS, MAP, ML; Jazayeri &
//!   Shadlen 2010) and the agent that plays the task with them;
//! * [`agent`] — the one agent interface every model plays through, episodes and the
//!   deterministic evaluation loop; [`activity`] — recording of neural activity;
//! * [`run_folder`] — the file names of a run folder (a trained agent), shared by the
//!   crates that write and read it.

#![warn(missing_docs)]

pub mod activity;
pub mod agent;
pub mod bayes;
pub mod deep;
pub mod run_folder;
pub mod timing;

pub use activity::{
    ActivityDataset, ActivityMeta, Marker, StepRecorder, TrialRecorder, oven_suffix,
    population_oven,
};
pub use agent::{Agent, EpisodeRecord, Percept, PerceptParser, evaluate_agent, run_episode};
pub use deep::cores::{CoreConfig, CoreInit, CoreKind, CoreState, RecurrentCore};
pub use deep::policy::{ActorCritic, Architecture, PAPER_SIZES, PolicyConfig, PolicyOutput};
pub use deep::trunk::{Trunk, TrunkConfig};
pub use timing::agent::{TimingAgent, TimingAgentConfig};
pub use timing::train::{
    TimingCurvePoint, TimingTrainConfig, adaptation_episodes, train_timing_agent,
};

/// The compute device used by the lab: burn's `flex` CPU backend.
pub fn cpu() -> burn::tensor::Device {
    burn::tensor::Device::flex()
}

/// The same device with autodiff enabled (training).
pub fn cpu_autodiff() -> burn::tensor::Device {
    burn::tensor::Device::flex().autodiff()
}

/// Reads a tensor into a `Vec<f32>` (row-major).
pub fn to_vec<const D: usize>(t: &burn::tensor::Tensor<D>) -> Vec<f32> {
    t.to_data()
        .convert::<f32>()
        .try_into_vec::<f32>()
        .unwrap_or_default()
}

/// `tanh(x)` computed as `2·σ(2x) − 1`.
///
/// Same function (absolute error ~1e-7), but burn's autodiff re-evaluates `tanh` in its
/// backward pass with libm's slow `tanhf`, while the sigmoid's backward reuses its
/// output: measured ~25% of a CNN-MLP PPO update on flex went to `tanhf`/`expm1f`.
pub fn fast_tanh<const D: usize>(x: burn::tensor::Tensor<D>) -> burn::tensor::Tensor<D> {
    burn::tensor::activation::sigmoid(x * 2.0) * 2.0 - 1.0
}
