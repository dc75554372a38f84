//! One PPO minibatch: gathered from the rollout as whole BPTT chunks, with its loss and
//! gradient at the network outputs (an engine, [`crate::ppo::engine`], runs the network
//! and back-propagates them).

use crate::ppo::loss::{LossCoefs, LossStats, OutputBatch, normalize_advantages, ppo_output_grads};
use crate::ppo::rollout::{Chunk, Rollout};

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

    /// The PPO loss of this minibatch given the network's outputs, logits `[L·B, A]` and
    /// values `[L·B]`, and its gradient with respect to them (`∂L/∂logits`, `∂L/∂values`).
    pub fn output_grads(
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
}
