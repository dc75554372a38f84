//! The vectorised environment: N envs stepped together into preallocated buffers.
//!
//! Buffers (all preallocated, reused every step):
//! * `obs`: codes, `[N, R, C, 6]` u8;
//! * `rewards` `[N]`, `terminated` `[N]`, `truncated` `[N]`, `infos` `[N]`;
//! * `final_obs` `[N, R, C, 6]` and `final_infos` `[N]`: the last observation/info
//!   of an episode that ended this step (valid where `terminated || truncated`).
//!
//! Autoreset modes ([`Autoreset`]):
//! * `SameStep` (default, the Stable-Baselines3 convention): an env whose episode
//!   ends is reset inside the same `step`; `obs` holds the first observation of the
//!   new episode and `final_obs` the terminal one (needed to bootstrap the value of
//!   truncated episodes).
//! * `NextStep` (gymnasium ≥ 1.0 convention): the terminal observation stays in
//!   `obs`; the next `step` call resets that env instead of stepping it, ignoring its
//!   action, and reports reward 0, not done.
//! * `Disabled`: finished envs stay finished; stepping them is an error.
//!
//! Sub-env `i` is seeded with [`derive_seed`]`(seed, i)`.

use crate::action::Action;
use crate::env::ChronoEnv;
use crate::error::EnvError;
use crate::info::Info;
use crate::kitchen::{Kitchen, KitchenSnapshot, ResetOptions, Spec, derive_seed};
use crate::obs::OneHotEncoder;
use crate::task::TaskConfig;
use std::sync::Arc;

/// Serialisable state of a [`VecEnv`] (see [`VecEnv::snapshot`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct VecEnvSnapshot {
    /// Per-env kitchen state.
    pub kitchens: Vec<KitchenSnapshot>,
    /// Current codes observations `[N, R, C, 6]`.
    pub obs: Vec<u8>,
    /// Envs waiting for a next-step reset.
    pub pending_reset: Vec<bool>,
    /// Current infos.
    pub infos: Vec<Info>,
}

/// What happens to an env whose episode ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Autoreset {
    /// Reset in the same step; terminal obs in `final_obs` (SB3 convention).
    #[default]
    SameStep,
    /// Reset on the following step (gymnasium ≥ 1.0 convention).
    NextStep,
    /// Never reset automatically.
    Disabled,
}

/// N environments of one task stepped in lockstep.
#[derive(Debug, Clone)]
pub struct VecEnv {
    kitchens: Vec<Kitchen>,
    encoder: OneHotEncoder,
    obs_len: usize,
    mode: Autoreset,
    pending_reset: Vec<bool>,
    /// Codes observations `[N, R, C, 6]`.
    pub obs: Vec<u8>,
    /// Terminal observations of episodes that ended this step `[N, R, C, 6]`.
    pub final_obs: Vec<u8>,
    /// Rewards of this step `[N]`.
    pub rewards: Vec<f32>,
    /// Terminated flags of this step `[N]`.
    pub terminated: Vec<bool>,
    /// Truncated flags of this step `[N]`.
    pub truncated: Vec<bool>,
    /// Infos of this step `[N]` (the new episode's reset info after an autoreset).
    pub infos: Vec<Info>,
    /// Infos of the last step of episodes that ended this step `[N]`.
    pub final_infos: Vec<Info>,
}

impl VecEnv {
    /// Builds `n` envs of `config` with the given autoreset mode.
    pub fn new(config: &TaskConfig, n: usize, mode: Autoreset) -> Result<Self, EnvError> {
        if n == 0 {
            return Err(EnvError::param("n_envs", 0, "integer >= 1"));
        }
        let spec = Spec::new(config)?;
        Ok(Self::from_spec(spec, n, mode))
    }

    pub(crate) fn from_spec(spec: Arc<Spec>, n: usize, mode: Autoreset) -> Self {
        let obs_len = spec.obs_len();
        let encoder = OneHotEncoder::new(&spec);
        let kitchens = (0..n)
            .map(|i| Kitchen::new(spec.clone(), derive_seed(0, i as u64)))
            .collect();
        VecEnv {
            kitchens,
            encoder,
            obs_len,
            mode,
            pending_reset: vec![false; n],
            obs: vec![0; n * obs_len],
            final_obs: vec![0; n * obs_len],
            rewards: vec![0.0; n],
            terminated: vec![false; n],
            truncated: vec![false; n],
            infos: vec![Info::default(); n],
            final_infos: vec![Info::default(); n],
        }
    }

    /// Builds a vectorised env from the config of a scalar env.
    pub fn like(env: &ChronoEnv, n: usize, mode: Autoreset) -> Self {
        Self::from_spec(env.spec().clone(), n.max(1), mode)
    }

    /// Number of envs.
    pub fn len(&self) -> usize {
        self.kitchens.len()
    }

    /// Whether there are no envs (never: construction requires n ≥ 1).
    pub fn is_empty(&self) -> bool {
        self.kitchens.is_empty()
    }

    /// Length of one codes observation (`R·C·6`).
    pub fn obs_len(&self) -> usize {
        self.obs_len
    }

    /// The one-hot encoder shared by all envs.
    pub fn onehot_encoder(&self) -> &OneHotEncoder {
        &self.encoder
    }

    /// Resets every env; env `i` is reseeded with `derive_seed(seed, i)`.
    pub fn reset(&mut self, seed: u64) {
        let options = ResetOptions::default();
        for (i, k) in self.kitchens.iter_mut().enumerate() {
            let obs = &mut self.obs[i * self.obs_len..(i + 1) * self.obs_len];
            // Default options cannot fail validation.
            if let Ok(info) = k.reset(Some(derive_seed(seed, i as u64)), &options, obs) {
                self.infos[i] = info;
            }
        }
        self.pending_reset.fill(false);
        self.rewards.fill(0.0);
        self.terminated.fill(false);
        self.truncated.fill(false);
    }

    /// Resets env `i` with explicit options (evaluation protocols).
    pub fn reset_one(
        &mut self,
        i: usize,
        seed: Option<u64>,
        options: &ResetOptions,
    ) -> Result<(), EnvError> {
        let obs = &mut self.obs[i * self.obs_len..(i + 1) * self.obs_len];
        self.infos[i] = self.kitchens[i].reset(seed, options, obs)?;
        self.pending_reset[i] = false;
        Ok(())
    }

    /// One action (and `mask_len` mask entries) per env, every code in `0..=5`.
    fn check_actions(&self, actions: &[u8], mask_len: usize) -> Result<(), EnvError> {
        let n = self.kitchens.len();
        if actions.len() != n || mask_len != n {
            return Err(EnvError::param(
                "actions",
                format!("{} actions", actions.len()),
                format!("exactly {n} (one per env)"),
            ));
        }
        match actions.iter().find(|&&a| a as usize >= Action::COUNT) {
            Some(&bad) => Err(EnvError::InvalidAction { action: bad as i64 }),
            None => Ok(()),
        }
    }

    /// Steps every env with `actions[i]` (reference codes `0..=5`).
    ///
    /// Errors (before any env is stepped) on a wrong number of actions or a code
    /// outside `0..=5`; in `Disabled` mode, on stepping a finished env.
    pub fn step(&mut self, actions: &[u8]) -> Result<(), EnvError> {
        self.check_actions(actions, actions.len())?;
        if self.mode == Autoreset::Disabled && self.kitchens.iter().any(Kitchen::is_done) {
            return Err(EnvError::EpisodeOver);
        }
        let len = self.obs_len;
        for (i, (k, &a)) in self.kitchens.iter_mut().zip(actions).enumerate() {
            let obs = &mut self.obs[i * len..(i + 1) * len];
            if self.pending_reset[i] {
                self.pending_reset[i] = false;
                self.infos[i] = k.reset_random(obs);
                self.rewards[i] = 0.0;
                self.terminated[i] = false;
                self.truncated[i] = false;
                continue;
            }
            let t = k.step_unchecked(Action::ALL[a as usize], obs);
            self.rewards[i] = t.reward;
            self.terminated[i] = t.terminated;
            self.truncated[i] = t.truncated;
            self.infos[i] = t.info;
            if t.terminated || t.truncated {
                self.final_infos[i] = t.info;
                match self.mode {
                    Autoreset::SameStep => {
                        self.final_obs[i * len..(i + 1) * len].copy_from_slice(obs);
                        self.infos[i] = k.reset_random(obs);
                    }
                    Autoreset::NextStep => self.pending_reset[i] = true,
                    Autoreset::Disabled => {}
                }
            }
        }
        Ok(())
    }

    /// Steps only the envs with `skip[i] == false` (evaluation batches in which some
    /// episodes already ended; `Disabled` mode). Skipped envs keep their outputs.
    pub fn step_masked(&mut self, actions: &[u8], skip: &[bool]) -> Result<(), EnvError> {
        self.check_actions(actions, skip.len())?;
        let len = self.obs_len;
        for (i, k) in self.kitchens.iter_mut().enumerate() {
            if skip[i] {
                continue;
            }
            if k.is_done() {
                return Err(EnvError::EpisodeOver);
            }
            let obs = &mut self.obs[i * len..(i + 1) * len];
            let t = k.step_unchecked(Action::ALL[actions[i] as usize], obs);
            self.rewards[i] = t.reward;
            self.terminated[i] = t.terminated;
            self.truncated[i] = t.truncated;
            self.infos[i] = t.info;
            if t.terminated || t.truncated {
                self.final_infos[i] = t.info;
            }
        }
        Ok(())
    }

    /// Writes every env's one-hot observation into `out` (`[N, C_onehot, R, C]`).
    pub fn write_onehot(&self, out: &mut [f32]) {
        let per = self.encoder.len();
        for i in 0..self.kitchens.len() {
            self.encoder.encode(
                &self.obs[i * self.obs_len..(i + 1) * self.obs_len],
                &mut out[i * per..(i + 1) * per],
            );
        }
    }

    /// Multi-timer curricula: sets the active TD count of every env.
    pub fn set_num_timers(&mut self, n: usize) -> Result<(), EnvError> {
        for k in &mut self.kitchens {
            k.set_num_timers(n)?;
        }
        Ok(())
    }

    /// The task configuration the envs run.
    pub fn config(&self) -> &TaskConfig {
        &self.kitchens[0].spec.config
    }

    /// Runs every env on `config` from the next step on, keeping episodes in flight
    /// (curricula that edit the task: the never-ready ramp, the multi-timer warm-up, a reward
    /// window). Its layout must be the envs' own; an error names `layout` otherwise.
    pub fn set_config(&mut self, config: &TaskConfig) -> Result<(), EnvError> {
        let spec = Spec::new(config)?;
        if !self.keeps_layout(&spec) {
            return Err(EnvError::param(
                "layout",
                spec.layout.to_text(),
                format!("the envs' own ({})", self.kitchens[0].spec.layout.to_text()),
            ));
        }
        self.install(spec);
        Ok(())
    }

    fn keeps_layout(&self, spec: &Spec) -> bool {
        spec.layout.to_text() == self.kitchens[0].spec.layout.to_text()
    }

    fn install(&mut self, spec: Arc<Spec>) {
        for k in &mut self.kitchens {
            k.spec = spec.clone();
        }
    }

    /// Captures every env's dynamic state, observations and pending resets (checkpoints).
    pub fn snapshot(&self) -> VecEnvSnapshot {
        VecEnvSnapshot {
            kitchens: self.kitchens.iter().map(Kitchen::snapshot).collect(),
            obs: self.obs.clone(),
            pending_reset: self.pending_reset.clone(),
            infos: self.infos.clone(),
        }
    }

    /// Checks a snapshot (read from a checkpoint) against this vec-env: as many envs,
    /// every list of their length, every kitchen state valid for the task
    /// ([`Kitchen::check_snapshot`]) and every observation the one of its kitchen's state.
    /// Errors name the field (`envs.<field>`) and what it must be.
    pub fn validate_snapshot(&self, s: &VecEnvSnapshot) -> Result<(), EnvError> {
        let n = self.kitchens.len();
        for (field, len, want) in [
            ("envs.kitchens", s.kitchens.len(), n),
            ("envs.obs", s.obs.len(), self.obs.len()),
            ("envs.pending_reset", s.pending_reset.len(), n),
            ("envs.infos", s.infos.len(), n),
        ] {
            if len != want {
                return Err(EnvError::param(
                    field,
                    format!("{len} entries"),
                    format!("exactly {want} (a snapshot of {n} envs of this task)"),
                ));
            }
        }
        let len = self.obs_len;
        for (i, (k, ks)) in self.kitchens.iter().zip(&s.kitchens).enumerate() {
            k.check_snapshot(ks).map_err(|e| match e {
                EnvError::InvalidParam {
                    field,
                    value,
                    allowed,
                } => EnvError::InvalidParam {
                    field: format!("envs.kitchens[{i}].{field}"),
                    value,
                    allowed,
                },
                other => other,
            })?;
            let mut probe = k.clone();
            probe.restore(ks);
            if probe.observation() != s.obs[i * len..(i + 1) * len] {
                return Err(EnvError::param(
                    "envs.obs",
                    format!("env {i}'s observation"),
                    "the observation of the env's saved state",
                ));
            }
        }
        Ok(())
    }

    /// Restores a snapshot taken from a vec-env of the same task and size (checked with
    /// [`VecEnv::validate_snapshot`] first; nothing changes on error).
    pub fn restore(&mut self, s: &VecEnvSnapshot) -> Result<(), EnvError> {
        self.validate_snapshot(s)?;
        for (k, ks) in self.kitchens.iter_mut().zip(&s.kitchens) {
            k.restore(ks);
        }
        self.obs.copy_from_slice(&s.obs);
        self.pending_reset.clone_from(&s.pending_reset);
        self.infos.clone_from(&s.infos);
        Ok(())
    }

    /// The kitchens (hidden state; oracles and tests).
    pub fn kitchens(&self) -> &[Kitchen] {
        &self.kitchens
    }
}
