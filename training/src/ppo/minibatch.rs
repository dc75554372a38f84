//! One PPO minibatch: gathered from the rollout as whole BPTT chunks, then its loss and
//! parameter gradient computed on either engine (native or burn autodiff).

use crate::ppo::loss::{LossCoefs, LossStats, OutputBatch, normalize_advantages, ppo_output_grads};
use crate::ppo::params::{flat_grads, param_offset};
use crate::ppo::rollout::{Chunk, Rollout};
use burn::tensor::{Device, Tensor, TensorData};
use chronocooked_models::deep::cores::SeqAux;
use chronocooked_models::deep::native::{Cache, NativePolicy, SeqBatch};
use chronocooked_models::{ActorCritic, CoreState};

/// Time-major minibatch of `B` chunks of `L` steps (row `t·B + j`; padding rows have mask 0).
#[derive(Debug, Clone)]
pub struct Minibatch {
    /// Steps per chunk `L`.
    pub steps: usize,
    /// Chunks `B`.
    pub batch: usize,
    /// Observations `[L, B, cells, C]`.
    pub obs: Vec<f32>,
    /// `[L·B]`: 0 where an episode starts.
    pub keep: Vec<f32>,
    /// `[L·B]`: 1 real sample, 0 padding.
    pub mask: Vec<f32>,
    /// Actions `[L·B]`.
    pub actions: Vec<i64>,
    /// Rollout log-probabilities `[L·B]`.
    pub old_log_prob: Vec<f32>,
    /// Advantages `[L·B]` (normalised if configured).
    pub advantages: Vec<f32>,
    /// Returns `[L·B]`.
    pub returns: Vec<f32>,
    /// Rollout values `[L·B]`.
    pub old_values: Vec<f32>,
    /// Initial hidden state of each chunk `[B, H]` (empty for CNN-MLP).
    pub h0: Vec<f32>,
    /// Initial LSTM cell state `[B, H]`.
    pub c0: Option<Vec<f32>>,
    /// `[L]`: chunks still running at step `t` (chunks are stored longest first, so these
    /// are the first `active[t]`; the native engine skips the padding after the others).
    pub active: Vec<usize>,
}

impl Minibatch {
    /// Gathers the chunks `mb` (each `≤ l` steps) of rollout `r`, longest first (stable
    /// order among equal lengths); `hidden` is the core size (0 for CNN-MLP).
    pub fn gather(r: &Rollout, mb: &[Chunk], l: usize, hidden: usize, normalize: bool) -> Self {
        let mut sorted = mb.to_vec();
        sorted.sort_by_key(|c| std::cmp::Reverse(c.len));
        let mb = &sorted[..];
        let (n, b, olen) = (r.n_envs, mb.len(), r.obs_len);
        let m = l * b;
        let mut s = Minibatch {
            steps: l,
            batch: b,
            obs: vec![0f32; m * olen],
            keep: vec![1f32; m],
            mask: vec![0f32; m],
            actions: vec![0i64; m],
            old_log_prob: vec![0f32; m],
            advantages: vec![0f32; m],
            returns: vec![0f32; m],
            old_values: vec![0f32; m],
            h0: Vec::with_capacity(b * hidden),
            c0: None,
            active: (0..l)
                .map(|t| mb.iter().filter(|c| c.len > t).count())
                .collect(),
        };
        for (j, c) in mb.iter().enumerate() {
            for t in 0..c.len {
                let src = (c.start + t) * n + c.env;
                let dst = t * b + j;
                s.obs[dst * olen..(dst + 1) * olen]
                    .copy_from_slice(&r.obs[src * olen..(src + 1) * olen]);
                s.keep[dst] = r.keep[src];
                s.mask[dst] = 1.0;
                s.actions[dst] = r.actions[src];
                s.old_log_prob[dst] = r.log_probs[src];
                s.advantages[dst] = r.advantages[src];
                s.returns[dst] = r.returns[src];
                s.old_values[dst] = r.values[src];
            }
            if hidden > 0 {
                let (hs, cs) = &r.chunk_states[c.index];
                s.h0.extend_from_slice(&hs[c.env * hidden..(c.env + 1) * hidden]);
                if let Some(cs) = cs {
                    s.c0.get_or_insert_with(Vec::new)
                        .extend_from_slice(&cs[c.env * hidden..(c.env + 1) * hidden]);
                }
            }
        }
        if normalize {
            normalize_advantages(&mut s.advantages, &s.mask);
        }
        s
    }

    /// The loss and its gradient at the outputs, given the outputs.
    fn output_grads(
        &self,
        logits: &[f32],
        values: &[f32],
        c: LossCoefs,
    ) -> (LossStats, Vec<f32>, Vec<f32>) {
        ppo_output_grads(
            OutputBatch {
                logits,
                values,
                actions: &self.actions,
                old_log_prob: &self.old_log_prob,
                advantages: &self.advantages,
                returns: &self.returns,
                old_values: &self.old_values,
                mask: &self.mask,
            },
            c,
        )
    }

    /// Native engine: forward pass into `cache`, loss, and `∂L/∂(logits, values)`.
    pub fn loss_native(
        &self,
        net: &NativePolicy,
        theta: &[f32],
        cache: &mut Cache,
        c: LossCoefs,
    ) -> (LossStats, Vec<f32>, Vec<f32>) {
        let batch = SeqBatch {
            obs: &self.obs,
            steps: self.steps,
            batch: self.batch,
            keep: &self.keep,
            h0: &self.h0,
            c0: self.c0.as_deref(),
            active: Some(&self.active),
        };
        net.forward(theta, &batch, cache);
        self.output_grads(&cache.logits, &cache.values, c)
    }

    /// burn engine: forward pass with autodiff and loss; returns the surrogate whose
    /// `backward` gives the parameter gradient (finish with [`burn_gradient`]). With
    /// `detach_critic` the value head reads a detached copy of the core output.
    pub fn loss_burn(
        &self,
        model: &ActorCritic,
        device: &Device,
        (cells, channels): (usize, usize),
        actions: usize,
        c: LossCoefs,
        detach_critic: bool,
    ) -> (LossStats, Tensor<1>, Option<SeqAux>) {
        let (l, b) = (self.steps, self.batch);
        let m = l * b;
        let state = (!self.h0.is_empty())
            .then(|| CoreState::from_vecs(self.h0.clone(), self.c0.clone(), b, device));
        let obs_t = Tensor::<4>::from_data(
            TensorData::new(self.obs.clone(), [l, b, cells, channels]),
            device,
        );
        let keep_t: Vec<Option<Tensor<2>>> = self
            .keep
            .chunks_exact(b)
            .map(|k| {
                k.iter()
                    .any(|&v| v != 1.0)
                    .then(|| Tensor::<2>::from_data(TensorData::new(k.to_vec(), [b, 1]), device))
            })
            .collect();
        let out = model.forward_seq_train(obs_t, state, &keep_t, detach_critic);
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
        let (stats, d_logits, d_values) = self.output_grads(&logits, &values, c);
        let g_l = Tensor::<2>::from_data(TensorData::new(d_logits, [m, actions]), device);
        let g_v = Tensor::<2>::from_data(TensorData::new(d_values, [m, 1]), device);
        // Same parameter gradients as the full loss: backward of Σ out·(∂L/∂out).
        let surrogate = (out.logits * g_l).sum() + (out.values * g_v).sum();
        (stats, surrogate, out.aux)
    }
}

/// Parameter gradient (flat layout) from a [`Minibatch::loss_burn`] surrogate.
pub fn burn_gradient(model: &ActorCritic, surrogate: Tensor<1>, aux: Option<SeqAux>) -> Vec<f32> {
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
