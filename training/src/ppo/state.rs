//! Plain-data training state: episode outcomes, learning-curve rows and the checkpointed
//! trainer state.

use crate::ppo::adam::Adam;
use chronocooked_env::VecEnvSnapshot;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// Outcome of one finished training episode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EpisodeStat {
    /// Undiscounted return.
    pub ret: f32,
    /// Steps.
    pub len: u32,
    /// Ended with a delivery paying the full reward available (see `is_success`).
    pub success: bool,
    /// The oven never readied by itself in this episode (uncertainty task).
    #[serde(default)]
    pub never_ready: bool,
}

fn nan() -> f64 {
    f64::NAN
}

/// Reads an `f64` that JSON wrote as `null` (NaN/inf) back as NaN.
fn nan_or_f64<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// One row of the learning curve (one PPO update).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UpdateLog {
    /// Updates done.
    pub update: u64,
    /// Env steps done (all envs).
    pub env_steps: u64,
    /// Wall-clock seconds since the run started (excluding time before a resume's checkpoint).
    #[serde(deserialize_with = "nan_or_f64")]
    pub wall_s: f64,
    /// Env steps per second over this update (rollout + optimisation).
    #[serde(deserialize_with = "nan_or_f64")]
    pub steps_per_s: f64,
    /// Seconds spent collecting the rollout.
    #[serde(deserialize_with = "nan_or_f64")]
    pub rollout_s: f64,
    /// Seconds spent in the minibatch epochs.
    #[serde(deserialize_with = "nan_or_f64")]
    pub optimize_s: f64,
    /// Mean return of the last `stats_window` episodes.
    #[serde(deserialize_with = "nan_or_f64")]
    pub ep_return_mean: f64,
    /// Mean length of the last `stats_window` episodes.
    #[serde(deserialize_with = "nan_or_f64")]
    pub ep_len_mean: f64,
    /// Fraction of the last `stats_window` episodes ending in a success (`is_success`).
    #[serde(deserialize_with = "nan_or_f64")]
    pub success_rate: f64,
    /// Success rate among the never-ready episodes of the same window (uncertainty task;
    /// NaN when there were none).
    #[serde(default = "nan", deserialize_with = "nan_or_f64")]
    pub never_ready_success: f64,
    /// Episodes finished so far.
    pub episodes: u64,
    /// Mean clipped-surrogate loss over the update's minibatches.
    #[serde(deserialize_with = "nan_or_f64")]
    pub policy_loss: f64,
    /// Mean value loss.
    #[serde(deserialize_with = "nan_or_f64")]
    pub value_loss: f64,
    /// Mean policy entropy (nats).
    #[serde(deserialize_with = "nan_or_f64")]
    pub entropy: f64,
    /// Mean approx-KL.
    #[serde(deserialize_with = "nan_or_f64")]
    pub approx_kl: f64,
    /// Mean clip fraction.
    #[serde(deserialize_with = "nan_or_f64")]
    pub clip_fraction: f64,
    /// Explained variance of the rollout values.
    #[serde(deserialize_with = "nan_or_f64")]
    pub explained_variance: f64,
    /// Mean global gradient norm before clipping.
    #[serde(deserialize_with = "nan_or_f64")]
    pub grad_norm: f64,
    /// Learning rate used.
    #[serde(deserialize_with = "nan_or_f64")]
    pub learning_rate: f64,
    /// Multi-timer curriculum: active TDs.
    pub num_timers: usize,
    /// Multi-timer curriculum level (with the warm-up level 0: 0..=|tds|; else = active TDs).
    #[serde(default)]
    pub curriculum_level: usize,
    /// Uncertainty curriculum: never-ready probability.
    #[serde(deserialize_with = "nan_or_f64")]
    pub never_ready_prob: f64,
    /// Deterministic evaluation success (when run this update).
    pub eval_success: Option<f64>,
}

/// Everything needed to continue a run exactly (a checkpoint's content).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TrainerState {
    /// Env steps done.
    pub steps: u64,
    /// Updates done.
    pub updates: u64,
    /// Flat parameters.
    pub theta: Vec<f32>,
    /// Optimiser state.
    pub adam: Adam,
    /// Envs.
    pub envs: VecEnvSnapshot,
    /// `1 − episode_start` of the current observations.
    pub keep: Vec<f32>,
    /// Recurrent state carried into the next rollout.
    pub core_state: Option<(Vec<f32>, Option<Vec<f32>>)>,
    /// Run RNG (actions, shuffling).
    pub rng: Xoshiro256PlusPlus,
    /// Running return per env.
    pub ep_return: Vec<f32>,
    /// Running length per env.
    pub ep_len: Vec<u32>,
    /// Recent episodes (stats window).
    pub recent: VecDeque<EpisodeStat>,
    /// Episodes since the curriculum last changed.
    pub since_change: usize,
    /// Episodes finished.
    pub episodes: u64,
    /// Active TDs (multi-timer).
    pub num_timers: usize,
    /// Never-ready probability (uncertainty).
    pub never_ready_prob: f64,
    /// Wall seconds accumulated.
    pub wall_s: f64,
    /// Learning curve so far.
    pub curve: Vec<UpdateLog>,
    /// Multi-timer curriculum level (see `UpdateLog::curriculum_level`).
    #[serde(default)]
    pub curriculum_level: usize,
    /// Reservoir cores with `reservoir_grad_in_norm`: the never-applied core gradient
    /// accumulated (and rescaled by the clip) over every minibatch so far.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reservoir_grad: Vec<f32>,
}
