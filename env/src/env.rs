//! The scalar, gymnasium-shaped environment.
//!
//! ```
//! use chronocooked_env::{Action, ChronoEnv, ResetOptions};
//! let mut env = ChronoEnv::from_id("FixedInterval-v0", &["td=4"]).unwrap();
//! let info = env.reset(Some(7), &ResetOptions::default()).unwrap();
//! assert_eq!(info.td, 4);
//! let t = env.step(Action::Wait).unwrap();
//! assert!(!t.terminated && !t.truncated);
//! assert_eq!(env.obs_codes().len(), 5 * 3 * 6);
//! ```
//!
//! `reset` and `step` return the info / transition; the observation is read
//! from the env (`obs_codes`, `obs_onehot`) so the hot path never allocates.

use crate::action::Action;
use crate::error::EnvError;
use crate::info::{Info, OvenSet};
use crate::kitchen::{CODE_CHANNELS, Kitchen, KitchenState, ResetOptions, Spec, Transition};
use crate::layout::Layout;
use crate::obs::{BoxSpace, Discrete, OneHotEncoder, codes_high, codes_to_nested};
use crate::task::make_config;
use crate::task::{TaskConfig, TaskFamily};
use std::sync::Arc;

/// One Chronocooked environment with its own seeded RNG.
#[derive(Debug, Clone)]
pub struct ChronoEnv {
    kitchen: Kitchen,
    encoder: OneHotEncoder,
    obs: Vec<u8>,
}

impl ChronoEnv {
    /// Builds an env from a validated configuration; the RNG starts from `seed = 0`
    /// until `reset(Some(seed), …)` reseeds it.
    pub fn new(config: &TaskConfig) -> Result<Self, EnvError> {
        let spec = Spec::new(config)?;
        let obs = spec.background.clone();
        let encoder = OneHotEncoder::new(&spec);
        Ok(ChronoEnv {
            kitchen: Kitchen::new(spec, 0),
            encoder,
            obs,
        })
    }

    /// Builds a registered task with `key=value` overrides.
    pub fn from_id<S: AsRef<str>>(id: &str, overrides: &[S]) -> Result<Self, EnvError> {
        Self::new(&make_config(id, overrides)?)
    }

    /// Starts an episode. `seed` reseeds the env's single RNG; `options` fix the
    /// start cell, the TD or (uncertainty) the never-ready draw.
    pub fn reset(&mut self, seed: Option<u64>, options: &ResetOptions) -> Result<Info, EnvError> {
        self.kitchen.reset(seed, options, &mut self.obs)
    }

    /// Takes one action. Errors if the episode is over (call `reset`).
    #[inline]
    pub fn step(&mut self, action: Action) -> Result<Transition, EnvError> {
        self.kitchen.step(action, &mut self.obs)
    }

    /// Takes one action given as a reference code (typed error outside `0..=5`).
    pub fn step_code(&mut self, code: i64) -> Result<Transition, EnvError> {
        self.step(Action::from_code(code)?)
    }

    /// Current observation, codes encoding, `[R, C, 6]` flattened row-major.
    #[inline]
    pub fn obs_codes(&self) -> &[u8] {
        &self.obs
    }

    /// Current observation as nested `[row][col][channel]` integers.
    pub fn obs_nested(&self) -> Vec<Vec<Vec<u8>>> {
        codes_to_nested(&self.obs, self.layout().rows(), self.layout().cols())
    }

    /// Current observation, one-hot encoding, `[C_onehot, R, C]` flattened.
    pub fn obs_onehot(&self) -> Vec<f32> {
        let mut out = vec![0.0; self.encoder.len()];
        self.encoder.encode(&self.obs, &mut out);
        out
    }

    /// Writes the one-hot observation into `out` (length `C_onehot·R·C`).
    pub fn obs_onehot_into(&self, out: &mut [f32]) {
        self.encoder.encode(&self.obs, out);
    }

    /// The one-hot encoder of this task.
    pub fn onehot_encoder(&self) -> &OneHotEncoder {
        &self.encoder
    }

    /// Action space: `Discrete(6)`.
    pub fn action_space(&self) -> Discrete {
        Discrete { n: Action::COUNT }
    }

    /// Codes observation space: `u8`, `[R, C, 6]`.
    pub fn codes_space(&self) -> BoxSpace<u8> {
        BoxSpace {
            shape: vec![self.layout().rows(), self.layout().cols(), CODE_CHANNELS],
            low: 0,
            high: codes_high(&self.kitchen.spec),
        }
    }

    /// One-hot observation space: `f32`, `[C_onehot, R, C]`.
    pub fn onehot_space(&self) -> BoxSpace<f32> {
        BoxSpace {
            shape: self.encoder.shape().to_vec(),
            low: 0.0,
            high: self.encoder.high(),
        }
    }

    /// The validated layout.
    pub fn layout(&self) -> &Layout {
        &self.kitchen.spec.layout
    }

    /// The configuration this env was built from.
    pub fn config(&self) -> &TaskConfig {
        &self.kitchen.spec.config
    }

    /// Task family.
    pub fn family(&self) -> TaskFamily {
        self.kitchen.spec.family
    }

    /// The Ready-Set-Go mechanics of the task (priors, gains, reward window, cues), or
    /// `None` for a task without them.
    pub fn ready_set_go(&self) -> Option<&crate::rules::ReadySetGo> {
        self.kitchen.spec.rsg.as_ref()
    }

    /// Hidden state snapshot (oracles, tests; never given to agents as observation).
    pub fn state(&self) -> KitchenState {
        self.kitchen.state()
    }

    /// Multi-oven task: every oven's state after the last step or reset (`None` for the
    /// other tasks; it is not part of [`Info`]).
    pub fn ovens(&self) -> Option<OvenSet> {
        self.kitchen.ovens()
    }

    /// Whether the episode has ended.
    pub fn is_done(&self) -> bool {
        self.kitchen.is_done()
    }

    /// Multi-timer curricula: number of active TDs (no-op for other tasks).
    pub fn set_num_timers(&mut self, n: usize) -> Result<(), EnvError> {
        self.kitchen.set_num_timers(n)
    }

    /// The underlying kitchen (for the vectorised env and oracles).
    pub fn kitchen(&self) -> &Kitchen {
        &self.kitchen
    }

    pub(crate) fn spec(&self) -> &Arc<Spec> {
        &self.kitchen.spec
    }
}
