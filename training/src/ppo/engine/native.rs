//! The native engine: hand-written forward and backward passes on the flat parameters.

use super::{PolicyEngine, StepOut};
use crate::ppo::act::FlatState;
use crate::ppo::loss::{LossCoefs, LossStats};
use crate::ppo::minibatch::Minibatch;
use chronocooked_models::deep::native::{Cache, NativePolicy, SeqBatch};

/// [`PolicyEngine`] on [`NativePolicy`]: it reads θ directly, so it keeps no parameters
/// of its own; one work [`Cache`] serves acting and the minibatches.
pub struct NativeEngine {
    net: NativePolicy,
    cache: Cache,
}

impl NativeEngine {
    /// The engine running `net`.
    pub fn new(net: NativePolicy) -> Self {
        NativeEngine {
            net,
            cache: Cache::default(),
        }
    }
}

impl PolicyEngine for NativeEngine {
    fn act(&mut self, theta: &[f32], obs: &[f32], keep: &[f32], state: &FlatState) -> StepOut {
        let batch = SeqBatch {
            obs,
            steps: 1,
            batch: keep.len(),
            keep,
            h0: &state.0,
            c0: state.1.as_deref(),
            active: None,
        };
        self.net.forward(theta, &batch, &mut self.cache);
        let (h, c) = self.cache.final_state();
        StepOut {
            state: (h.to_vec(), c.map(<[f32]>::to_vec)),
            logits: self.cache.logits.clone(),
            values: self.cache.values.clone(),
        }
    }

    fn loss_and_grad(
        &mut self,
        theta: &[f32],
        batch: &Minibatch,
        coefs: LossCoefs,
        grad: &mut [f32],
    ) -> LossStats {
        let seq = SeqBatch {
            obs: &batch.obs,
            steps: batch.steps,
            batch: batch.batch,
            keep: &batch.keep,
            h0: &batch.h0,
            c0: batch.c0.as_deref(),
            active: Some(&batch.active),
        };
        self.net.forward(theta, &seq, &mut self.cache);
        let (stats, d_logits, d_values) =
            batch.output_grads(&self.cache.logits, &self.cache.values, coefs);
        self.net
            .backward(theta, &mut self.cache, &d_logits, &d_values, grad);
        stats
    }

    fn sync(&mut self, _theta: &[f32]) {}
}
