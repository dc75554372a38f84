//! The burn engine: the [`ActorCritic`] module with autodiff.

use super::{PolicyEngine, StepOut};
use crate::ppo::act::{FlatState, policy_step};
use crate::ppo::loss::{LossCoefs, LossStats};
use crate::ppo::minibatch::Minibatch;
use crate::ppo::params::{flat_grads, param_offset, write_params};
use burn::module::Module;
use burn::tensor::{Device, Tensor, TensorData};
use chronocooked_models::deep::cores::SeqAux;
use chronocooked_models::{ActorCritic, CoreState, PolicyConfig};

/// [`PolicyEngine`] on burn: a module on the autodiff device for the minibatches (θ
/// written into it at every [`PolicyEngine::sync`]) and, for acting, a copy without
/// autodiff made when a rollout first needs it.
pub struct BurnEngine {
    /// The policy with autodiff, holding the current θ.
    model: ActorCritic,
    /// Its device (autodiff).
    device: Device,
    /// `model` without autodiff for acting; `None` once θ changed.
    actor: Option<ActorCritic>,
    /// The device of `actor`.
    actor_device: Device,
    /// Observation cells and channels.
    obs_shape: (usize, usize),
    /// Actions `A`.
    actions: usize,
    /// The value head reads a detached copy of the core output.
    detach_critic: bool,
}

impl BurnEngine {
    /// The engine for `model` (on the autodiff CPU device) of policy `cfg`.
    pub fn new(model: ActorCritic, cfg: &PolicyConfig, detach_critic: bool) -> Self {
        BurnEngine {
            model,
            device: chronocooked_models::cpu_autodiff(),
            actor: None,
            actor_device: chronocooked_models::cpu(),
            obs_shape: (cfg.trunk.cells, cfg.trunk.channels),
            actions: cfg.actions,
            detach_critic,
        }
    }
}

impl PolicyEngine for BurnEngine {
    fn act(&mut self, _theta: &[f32], obs: &[f32], keep: &[f32], state: &FlatState) -> StepOut {
        let (model, device) = (&self.model, &self.actor_device);
        let actor = self.actor.get_or_insert_with(|| model.valid());
        let st = (!state.0.is_empty())
            .then(|| CoreState::from_vecs(state.0.clone(), state.1.clone(), keep.len(), device));
        let (cells, channels) = self.obs_shape;
        let (logits, values, st) = policy_step(actor, obs, cells, channels, keep, st, device);
        StepOut {
            logits,
            values,
            state: st.map(|s| s.to_vecs()).unwrap_or((Vec::new(), None)),
        }
    }

    fn loss_and_grad(
        &mut self,
        _theta: &[f32],
        batch: &Minibatch,
        coefs: LossCoefs,
        grad: &mut [f32],
    ) -> LossStats {
        let (stats, surrogate, aux) = self.loss(batch, coefs);
        grad.copy_from_slice(&self.gradient(surrogate, aux));
        stats
    }

    fn sync(&mut self, theta: &[f32]) {
        self.model = write_params(self.model.clone(), theta);
        self.actor = None;
    }
}

impl BurnEngine {
    /// Forward pass with autodiff and the loss; returns the surrogate
    /// `Σ logits·∂L/∂logits + Σ values·∂L/∂values`, whose parameter gradient is the
    /// loss's, and the split-BPTT auxiliary data of the core.
    fn loss(&self, batch: &Minibatch, coefs: LossCoefs) -> (LossStats, Tensor<1>, Option<SeqAux>) {
        let device = &self.device;
        let ((l, b), (cells, channels), actions) =
            ((batch.steps, batch.batch), self.obs_shape, self.actions);
        let m = l * b;
        let state = (!batch.h0.is_empty())
            .then(|| CoreState::from_vecs(batch.h0.clone(), batch.c0.clone(), b, device));
        let obs = Tensor::<4>::from_data(
            TensorData::new(batch.obs.clone(), [l, b, cells, channels]),
            device,
        );
        let keep: Vec<Option<Tensor<2>>> = batch
            .keep
            .chunks_exact(b)
            .map(|k| {
                k.iter()
                    .any(|&v| v != 1.0)
                    .then(|| Tensor::<2>::from_data(TensorData::new(k.to_vec(), [b, 1]), device))
            })
            .collect();
        let out = self
            .model
            .forward_seq_train(obs, state, &keep, self.detach_critic);
        let both = chronocooked_models::to_vec(&Tensor::cat(
            vec![out.logits.clone(), out.values.clone()],
            1,
        ));
        let mut logits = Vec::with_capacity(m * actions);
        let mut values = Vec::with_capacity(m);
        for row in both.chunks_exact(actions + 1) {
            logits.extend_from_slice(&row[..actions]);
            values.push(row[actions]);
        }
        let (stats, d_logits, d_values) = batch.output_grads(&logits, &values, coefs);
        let g_l = Tensor::<2>::from_data(TensorData::new(d_logits, [m, actions]), device);
        let g_v = Tensor::<2>::from_data(TensorData::new(d_values, [m, 1]), device);
        let surrogate = (out.logits * g_l).sum() + (out.values * g_v).sum();
        (stats, surrogate, out.aux)
    }

    /// The parameter gradient (flat layout) of a [`BurnEngine::loss`] surrogate, with the
    /// core's split-BPTT contributions added.
    fn gradient(&self, surrogate: Tensor<1>, aux: Option<SeqAux>) -> Vec<f32> {
        let model = &self.model;
        let grads = surrogate.backward();
        let mut g = flat_grads(model, &grads);
        if let Some(aux) = aux {
            let id = aux.weight_id;
            let (dw, sur) = aux.finish(&grads);
            if let Some(dw) = dw
                && let Some(off) = param_offset(model, id)
            {
                let dw = chronocooked_models::to_vec(&dw);
                g[off..off + dw.len()]
                    .iter_mut()
                    .zip(&dw)
                    .for_each(|(a, b)| *a += b);
            }
            if let Some(sur) = sur {
                let g2 = flat_grads(model, &sur.backward());
                g.iter_mut().zip(&g2).for_each(|(a, b)| *a += b);
            }
        }
        g
    }
}
