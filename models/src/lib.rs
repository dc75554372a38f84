//! Chronocooked Lab models: the paper's CNN trunk, recurrent cores (LSTM, GRU, RNN,
//! CTRNN) and actor–critic policies as burn modules; the biologically plausible timing
//! models ([`timing`]) and the agents that play the tasks with them ([`timing_agent`]);
//! the one agent interface ([`agent`]) and activity recording ([`activity`]).

pub mod activity;
pub mod agent;
pub mod cores;
pub mod init;
pub mod native;
pub mod policy;
pub mod sarsa;
pub mod timers;
pub mod timing;
pub mod timing_agent;
pub mod timing_train;
pub mod trunk;
pub mod zoo;

pub use activity::{ActivityDataset, ActivityMeta, Marker, StepRecorder, TrialRecorder};
pub use agent::{Agent, EpisodeRecord, Percept, PerceptParser, evaluate_agent, run_episode};
pub use cores::{CoreConfig, CoreInit, CoreKind, CoreState, RecurrentCore};
pub use policy::{ActorCritic, Architecture, PAPER_SIZES, PolicyConfig, PolicyOutput};
pub use timing_agent::{TimingAgent, TimingAgentConfig};
pub use timing_train::{
    TimingCurvePoint, TimingTrainConfig, adaptation_episodes, train_timing_agent,
};
pub use trunk::{Trunk, TrunkConfig};

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
