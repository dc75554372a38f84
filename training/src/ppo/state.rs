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
    /// Curriculum level: multi-timer (with the warm-up level 0: 0..=|tds|; else = active
    /// TDs), growth (counters or ovens added) or tolerance (windows narrowed).
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
    /// Stacked-frame policies: every env's last observations carried into the next rollout
    /// (`[N, frames, cells, channels]`; empty for one frame).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub frame_history: Vec<f32>,
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
    /// Curriculum level (see `UpdateLog::curriculum_level`).
    #[serde(default)]
    pub curriculum_level: usize,
    /// Reservoir cores with `reservoir_grad_in_norm`: the never-applied core gradient
    /// accumulated (and rescaled by the clip) over every minibatch so far.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reservoir_grad: Vec<f32>,
}

/// A field of a loaded checkpoint that does not fit the run (see [`TrainerState::validate`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("field `{field}`: {reason}")]
pub struct StateError {
    /// The field (`theta`, `adam.m`, `envs.kitchens[3].agent`, …).
    pub field: String,
    /// What is wrong and what it must be.
    pub reason: String,
}

fn bad(field: &str, reason: impl Into<String>) -> StateError {
    StateError {
        field: field.into(),
        reason: reason.into(),
    }
}

fn check_len(field: &str, len: usize, want: usize) -> Result<(), StateError> {
    if len == want {
        Ok(())
    } else {
        Err(bad(
            field,
            format!("{len} values, the run needs exactly {want}"),
        ))
    }
}

fn check_finite<T: Copy + Into<f64>>(field: &str, values: &[T]) -> Result<(), StateError> {
    match values.iter().position(|&v| !v.into().is_finite()) {
        Some(i) => Err(bad(field, format!("value {i} is not a finite number"))),
        None => Ok(()),
    }
}

impl TrainerState {
    /// Checks a state read from a checkpoint against `fresh`, the state a new trainer of
    /// the same configuration starts from (which fixes every length), before any of it is
    /// used: parameter and optimiser lengths, finite values, per-env lists, the recurrent
    /// state's shape (`hidden` units, a cell state for LSTMs only), counters that agree
    /// with each other and the learning curve. The env snapshot is checked by
    /// [`chronocooked_env::VecEnv::validate_snapshot`] when it is restored.
    pub fn validate(
        &self,
        fresh: &TrainerState,
        hidden: usize,
        lstm: bool,
        recurrent: bool,
        batch: u64,
    ) -> Result<(), StateError> {
        let n_params = fresh.theta.len();
        let n_envs = fresh.keep.len();
        check_len("theta", self.theta.len(), n_params)?;
        check_finite("theta", &self.theta)?;
        self.adam
            .validate(n_params)
            .map_err(|(f, r)| bad(&format!("adam.{f}"), r))?;
        check_len("keep", self.keep.len(), n_envs)?;
        if self.keep.iter().any(|&k| k != 0.0 && k != 1.0) {
            return Err(bad("keep", "every value must be 0 or 1"));
        }
        check_len("ep_return", self.ep_return.len(), n_envs)?;
        check_finite("ep_return", &self.ep_return)?;
        check_len("ep_len", self.ep_len.len(), n_envs)?;
        match &self.core_state {
            None => {}
            Some(_) if !recurrent => {
                return Err(bad(
                    "core_state",
                    "present, but the model has no recurrent core",
                ));
            }
            Some((h, c)) => {
                check_len("core_state.0", h.len(), n_envs * hidden)?;
                check_finite("core_state.0", h)?;
                match (c, lstm) {
                    (Some(c), true) => {
                        check_len("core_state.1", c.len(), n_envs * hidden)?;
                        check_finite("core_state.1", c)?;
                    }
                    (None, false) => {}
                    (Some(_), false) => {
                        return Err(bad("core_state.1", "a cell state, but the core is no LSTM"));
                    }
                    (None, true) => {
                        return Err(bad(
                            "core_state.1",
                            "missing (the LSTM core needs a cell state)",
                        ));
                    }
                }
            }
        }
        check_len(
            "frame_history",
            self.frame_history.len(),
            fresh.frame_history.len(),
        )?;
        check_finite("frame_history", &self.frame_history)?;
        if let Some(i) = self.recent.iter().position(|e| !e.ret.is_finite()) {
            return Err(bad(
                "recent",
                format!("episode {i} has a non-finite return"),
            ));
        }
        if self.steps != self.updates.saturating_mul(batch) {
            return Err(bad(
                "steps",
                format!(
                    "{} env steps after {} updates; each update takes exactly {batch}",
                    self.steps, self.updates
                ),
            ));
        }
        if self.curve.len() as u64 != self.updates {
            return Err(bad(
                "curve",
                format!(
                    "{} rows for {} updates (one row per update)",
                    self.curve.len(),
                    self.updates
                ),
            ));
        }
        if let Some(i) = self
            .curve
            .iter()
            .enumerate()
            .position(|(i, r)| r.update != i as u64 + 1)
        {
            return Err(bad("curve", format!("row {i} is not update {}", i + 1)));
        }
        if !(0.0..=1.0).contains(&self.never_ready_prob) {
            return Err(bad("never_ready_prob", "a probability in [0, 1]"));
        }
        if !(self.wall_s.is_finite() && self.wall_s >= 0.0) {
            return Err(bad("wall_s", "a finite number of seconds >= 0"));
        }
        if !self.reservoir_grad.is_empty() {
            check_finite("reservoir_grad", &self.reservoir_grad)?;
            if self.reservoir_grad.len() > n_params {
                return Err(bad("reservoir_grad", "longer than the parameter vector"));
            }
        }
        if self.envs.kitchens.len() != fresh.envs.kitchens.len() {
            return Err(bad(
                "envs.kitchens",
                format!(
                    "{} envs, the run has {}",
                    self.envs.kitchens.len(),
                    fresh.envs.kitchens.len()
                ),
            ));
        }
        Ok(())
    }
}
