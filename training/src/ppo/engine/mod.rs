//! The network side of a PPO update behind one trait, [`PolicyEngine`]: acting during
//! rollouts, the loss of a minibatch with its parameter gradient, and keeping any copy of
//! the parameters an engine holds in step with the flat vector θ that Adam updates.
//!
//! Two implementations compute the same function (`tests/native_engine.rs` compares their
//! outputs, gradients and training runs):
//!
//! * [`NativeEngine`] — the hand-written forward and backward passes of
//!   [`chronocooked_models::deep::native`] (`engine=native`, the default);
//! * [`BurnEngine`] — burn autodiff on the [`ActorCritic`] module (`engine=burn`).
//!
//! Both evaluate the PPO loss on the network outputs with
//! [`crate::ppo::loss::ppo_output_grads`] and back-propagate its gradient with respect to
//! the logits and values.

mod burn_engine;
mod native;

pub use burn_engine::BurnEngine;
pub use native::NativeEngine;

use crate::ppo::act::FlatState;
use crate::ppo::config::Engine;
use crate::ppo::loss::{LossCoefs, LossStats};
use crate::ppo::minibatch::Minibatch;
use chronocooked_models::deep::native::NativePolicy;
use chronocooked_models::{ActorCritic, PolicyConfig};

/// One batched policy step: what a rollout needs from the network.
#[derive(Debug, Clone, PartialEq)]
pub struct StepOut {
    /// Action logits `[N, A]`.
    pub logits: Vec<f32>,
    /// Value estimates `[N]`.
    pub values: Vec<f32>,
    /// The recurrent state after the step (empty for CNN-MLP).
    pub state: FlatState,
}

/// A way to run the policy network of a PPO trainer. The parameters live in the trainer
/// as one flat vector θ (the layout of [`crate::ppo::params::flat_params`]); every call
/// receives the current θ, and [`PolicyEngine::sync`] is called whenever θ changes.
pub trait PolicyEngine: Send {
    /// One batched step with parameters `theta`: observations `obs [N, cells, C]`,
    /// `keep [N]` (0 where an episode starts: the recurrent state is reset), the recurrent
    /// `state` before the step.
    fn act(&mut self, theta: &[f32], obs: &[f32], keep: &[f32], state: &FlatState) -> StepOut;

    /// The PPO loss of `batch` with parameters `theta`, and its gradient with respect to θ
    /// written into `grad` (`[P]`, the flat layout).
    fn loss_and_grad(
        &mut self,
        theta: &[f32],
        batch: &Minibatch,
        coefs: LossCoefs,
        grad: &mut [f32],
    ) -> LossStats;

    /// θ changed (an optimiser step, a restored checkpoint): brings the engine's own copy
    /// of the parameters, if it keeps one, up to date.
    fn sync(&mut self, theta: &[f32]);
}

/// The engine `engine` for policy `cfg` whose initial parameters are `model`'s (the
/// native engine reads θ directly and ignores `model`). `detach_critic`: the value head
/// reads a detached copy of the core output; `frozen_core`: the core's weights get no
/// gradient (reservoirs whose gradient is not carried into the norm).
pub fn new_engine(
    engine: Engine,
    cfg: &PolicyConfig,
    model: &ActorCritic,
    detach_critic: bool,
    frozen_core: bool,
) -> Box<dyn PolicyEngine> {
    match engine {
        Engine::Native => Box::new(NativeEngine::new(
            NativePolicy::new(cfg)
                .with_detached_critic(detach_critic)
                .with_frozen_core(frozen_core),
        )),
        Engine::Burn => Box::new(BurnEngine::new(model.clone(), cfg, detach_critic)),
    }
}
