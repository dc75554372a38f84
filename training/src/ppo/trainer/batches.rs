//! The minibatch orders of an update: transitions (feed-forward), fixed BPTT chunks, or
//! sb3-contrib's whole sequences (recurrent).

use super::Trainer;
use crate::ppo::config::RecurrentBatches;
use crate::ppo::rollout::{Chunk, sequence_batches};
use rand::Rng;
use rand::seq::SliceRandom;

impl Trainer {
    /// Steps per stored chunk: 1 for feed-forward policies, else the BPTT length (whole
    /// rollouts with `bptt_len = 0`).
    pub(super) fn chunk_len(&self) -> usize {
        match (self.cfg.model.is_recurrent(), self.cfg.ppo.bptt_len) {
            (false, _) => 1,
            (true, 0) => self.cfg.ppo.n_steps,
            (true, l) => l.min(self.cfg.ppo.n_steps),
        }
    }

    /// Whether recurrent minibatches are sb3-contrib sequences (else fixed chunks).
    fn sequence_batches(&self) -> bool {
        self.cfg.model.is_recurrent()
            && self.cfg.ppo.recurrent_batches == RecurrentBatches::Sequences
    }

    /// Rollout steps between stored recurrent states (every step for sequence batches,
    /// whose sequences may start anywhere).
    pub(super) fn state_stride(&self) -> usize {
        if self.sequence_batches() {
            1
        } else {
            self.chunk_len()
        }
    }

    /// One epoch's minibatches: each a list of chunks and the padded chunk length.
    pub(super) fn epoch_batches(&mut self, all: &mut [Chunk]) -> Vec<(Vec<Chunk>, usize)> {
        let p = &self.cfg.ppo;
        if self.sequence_batches() {
            let m = p.n_envs * p.n_steps;
            let split = self.state.rng.random_range(0..m);
            sequence_batches(&self.rollout.keep, p.n_envs, p.n_steps, p.batch_size, split)
                .into_iter()
                .map(|mb| {
                    let l = mb.iter().map(|c| c.len).max().unwrap_or(1);
                    (mb, l)
                })
                .collect()
        } else {
            let l = self.chunk_len();
            let per_mb = (p.batch_size / l).max(1);
            all.shuffle(&mut self.state.rng);
            all.chunks(per_mb).map(|mb| (mb.to_vec(), l)).collect()
        }
    }
}
