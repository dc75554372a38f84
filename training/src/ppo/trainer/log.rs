//! The learning-curve row of an update: minibatch loss terms averaged, the episode stats
//! window summarised.

use super::Trainer;
use crate::ppo::gae::explained_variance;
use crate::ppo::loss::LossStats;
use crate::ppo::state::{EpisodeStat, UpdateLog};

/// Sums of the loss terms and gradient norms of an update's applied minibatches.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct LossSums {
    policy: f64,
    value: f64,
    entropy_loss: f64,
    approx_kl: f64,
    clip_fraction: f64,
    grad_norm: f64,
    count: usize,
}

impl LossSums {
    /// Adds one minibatch: its loss terms and its gradient norm before clipping.
    pub(super) fn add(&mut self, s: &LossStats, grad_norm: f64) {
        self.policy += s.policy_loss;
        self.value += s.value_loss;
        self.entropy_loss += s.entropy_loss;
        self.approx_kl += s.approx_kl;
        self.clip_fraction += s.clip_fraction;
        self.grad_norm += grad_norm;
        self.count += 1;
    }
}

/// Mean of `f` over the episodes of the window (NaN when it is empty).
fn mean(recent: &[&EpisodeStat], f: impl Fn(&EpisodeStat) -> f64) -> f64 {
    if recent.is_empty() {
        f64::NAN
    } else {
        recent.iter().map(|e| f(e)).sum::<f64>() / recent.len() as f64
    }
}

impl Trainer {
    /// The curve row of the update just finished: `sums` of its minibatches, learning rate
    /// `lr`, `rollout_s` of its `secs` seconds spent collecting.
    pub(super) fn curve_row(
        &self,
        sums: &LossSums,
        lr: f64,
        rollout_s: f64,
        secs: f64,
    ) -> UpdateLog {
        let p = &self.cfg.ppo;
        let c = sums.count.max(1) as f64;
        let recent: Vec<&EpisodeStat> = self.state.recent.iter().collect();
        let never_ready: Vec<&EpisodeStat> =
            self.state.recent.iter().filter(|e| e.never_ready).collect();
        let success = |e: &EpisodeStat| f64::from(u8::from(e.success));
        UpdateLog {
            update: self.state.updates,
            env_steps: self.state.steps,
            wall_s: self.state.wall_s,
            steps_per_s: (p.n_envs * p.n_steps) as f64 / secs.max(1e-9),
            rollout_s,
            optimize_s: secs - rollout_s,
            ep_return_mean: mean(&recent, |e| e.ret as f64),
            ep_len_mean: mean(&recent, |e| e.len as f64),
            success_rate: mean(&recent, success),
            never_ready_success: mean(&never_ready, success),
            episodes: self.state.episodes,
            policy_loss: sums.policy / c,
            value_loss: sums.value / c,
            entropy: -sums.entropy_loss / c,
            approx_kl: sums.approx_kl / c,
            clip_fraction: sums.clip_fraction / c,
            explained_variance: explained_variance(&self.rollout.values, &self.rollout.returns),
            grad_norm: sums.grad_norm / c,
            learning_rate: lr,
            num_timers: self.state.num_timers,
            curriculum_level: self.state.curriculum_level,
            never_ready_prob: self.state.never_ready_prob,
            eval_success: None,
        }
    }
}
