//! Rollout collection: `n_steps` batched steps of every env with the current policy,
//! sampling actions, bootstrapping time-limit truncations and recording finished episodes.

use super::Trainer;
use crate::error::TrainError;
use crate::ppo::act::{FlatState, sample};
use crate::ppo::state::EpisodeStat;
use chronocooked_env::Action;
use chronocooked_models::CoreKind;

impl Trainer {
    /// Collects one rollout with the current policy into the rollout buffer; returns the
    /// values `[N]` of the observations after its last step (GAE's bootstrap).
    pub(super) fn collect(&mut self) -> Result<Vec<f32>, TrainError> {
        let (n, t_len) = (self.cfg.ppo.n_envs, self.cfg.ppo.n_steps);
        let gamma = self.cfg.ppo.gamma;
        let olen = self.encoder.len();
        let l = self.state_stride();
        let arch = self.cfg.model;
        let recurrent = arch.is_recurrent();
        let mut core: FlatState = match self.state.core_state.take() {
            Some(st) => st,
            None if recurrent => (
                vec![0.0; n * arch.hidden],
                (arch.core == Some(CoreKind::Lstm)).then(|| vec![0.0; n * arch.hidden]),
            ),
            None => (Vec::new(), None),
        };
        self.encoder.set_history(&self.state.frame_history);
        self.rollout.chunk_states.clear();
        let obs_tensor_len = n * olen;
        let mut final_buf = vec![0f32; olen];
        for t in 0..t_len {
            if recurrent && t % l == 0 {
                self.rollout.chunk_states.push(core.clone());
            }
            self.encoder
                .encode_batch(&self.envs.obs, &mut self.scratch_obs);
            let keep = self.state.keep.clone();
            let step = self
                .engine
                .act(&self.state.theta, &self.scratch_obs, &keep, &core);
            core = step.state;
            let base = t * n;
            self.rollout.obs[base * olen..base * olen + obs_tensor_len]
                .copy_from_slice(&self.scratch_obs);
            let mut actions = vec![0u8; n];
            for e in 0..n {
                let na = Action::COUNT;
                let (a, lp) = sample(&step.logits[e * na..(e + 1) * na], &mut self.state.rng);
                actions[e] = a as u8;
                self.rollout.actions[base + e] = a as i64;
                self.rollout.log_probs[base + e] = lp;
                self.rollout.values[base + e] = step.values[e];
                self.rollout.keep[base + e] = keep[e];
            }
            self.envs.step(&actions)?;
            for e in 0..n {
                let mut r = self.envs.rewards[e];
                let term = self.envs.terminated[e];
                let trunc = self.envs.truncated[e];
                self.state.ep_return[e] += r;
                self.state.ep_len[e] += 1;
                if trunc && !term {
                    // Time-limit bootstrap: r += γ V(final obs), with the state after this step.
                    self.encoder.encode_final(
                        e,
                        &self.envs.final_obs
                            [e * self.envs.obs_len()..(e + 1) * self.envs.obs_len()],
                        &mut final_buf,
                    );
                    let h = arch.hidden;
                    let st: FlatState = (
                        core.0.get(e * h..(e + 1) * h).unwrap_or(&[]).to_vec(),
                        core.1.as_ref().map(|c| c[e * h..(e + 1) * h].to_vec()),
                    );
                    let v = self.engine.act(&self.state.theta, &final_buf, &[1.0], &st);
                    r += gamma * v.values[0];
                }
                self.rollout.rewards[base + e] = r;
                self.rollout.dones[base + e] = term || trunc;
                self.state.keep[e] = if term || trunc { 0.0 } else { 1.0 };
                if term || trunc {
                    self.encoder.reset_env(e);
                    self.end_episode(e);
                }
            }
        }
        let history_before_last = self.encoder.history();
        self.encoder
            .encode_batch(&self.envs.obs, &mut self.scratch_obs);
        let keep = self.state.keep.clone();
        let last = self
            .engine
            .act(&self.state.theta, &self.scratch_obs, &keep, &core);
        self.state.core_state = recurrent.then_some(core);
        // The last observations were encoded for the bootstrap value only: the next rollout
        // encodes them again, so the history carried over is the one before them.
        self.state.frame_history = history_before_last;
        Ok(last.values)
    }

    /// Records the episode env `e` just finished in the stats window and resets its
    /// running return and length.
    fn end_episode(&mut self, e: usize) {
        let info = &self.envs.final_infos[e];
        let success = chronocooked_models::agent::is_success(info, self.envs.rewards[e]);
        self.state.recent.push_back(EpisodeStat {
            ret: self.state.ep_return[e],
            len: self.state.ep_len[e],
            success,
            never_ready: info.never_ready,
        });
        while self.state.recent.len() > self.cfg.stats_window.max(1) {
            self.state.recent.pop_front();
        }
        self.state.episodes += 1;
        self.state.since_change += 1;
        self.state.ep_return[e] = 0.0;
        self.state.ep_len[e] = 0;
    }
}
