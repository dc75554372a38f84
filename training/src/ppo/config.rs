//! Training configuration: PPO hyperparameters, run settings and `key=value` overrides.

use crate::error::TrainError;
use crate::settings::{self, ppo::PPO_SETTINGS};
use chronocooked_env::{Task, TaskFamily};
use chronocooked_models::Architecture;
use serde::{Deserialize, Serialize};

/// PPO hyperparameters (names and defaults follow Stable-Baselines3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PpoConfig {
    /// Parallel environments `N`.
    pub n_envs: usize,
    /// Steps per env per rollout `T` (buffer = `N·T` transitions).
    pub n_steps: usize,
    /// Transitions per minibatch (recurrent: rounded to whole chunks of `bptt_len`).
    pub batch_size: usize,
    /// Passes over the buffer per update.
    pub n_epochs: usize,
    /// Discount γ.
    pub gamma: f32,
    /// GAE λ.
    pub gae_lambda: f32,
    /// Policy clip range ε.
    pub clip_range: f32,
    /// Value clip range (`None`: unclipped value loss, SB3's default).
    pub clip_range_vf: Option<f32>,
    /// Entropy bonus coefficient.
    pub ent_coef: f32,
    /// Value loss coefficient.
    pub vf_coef: f32,
    /// Global gradient-norm clip.
    pub max_grad_norm: f32,
    /// Adam learning rate.
    pub learning_rate: f64,
    /// Learning-rate schedule: `constant` or `linear` (to 0 at the end of the budget).
    pub lr_schedule: LrSchedule,
    /// Adam ε.
    pub adam_eps: f64,
    /// Stop the epochs of an update once approx-KL exceeds `1.5 · target_kl`.
    pub target_kl: Option<f32>,
    /// Normalise advantages per minibatch.
    pub normalize_advantage: bool,
    /// Recurrent policies: BPTT chunk length (steps). Each chunk starts from the
    /// hidden state stored during the rollout; `0` = whole rollout sequences.
    pub bptt_len: usize,
    /// Which implementation computes the network's forward pass and gradients.
    #[serde(default)]
    pub engine: Engine,
    /// How recurrent minibatches are cut from the rollout.
    #[serde(default)]
    pub recurrent_batches: RecurrentBatches,
    /// Recurrent policies: the critic reads a detached copy of the core output, so the value
    /// loss trains only the value head (sb3-contrib `shared_lstm=True,
    /// enable_critic_lstm=False`, the paper's setting). `false`: the value loss also trains
    /// the core and the trunk. No effect on CNN-MLP.
    #[serde(default)]
    pub detach_critic: bool,
    /// Reservoir cores (`ctrnn-reservoir…`): their never-applied gradients accumulate across
    /// minibatches and enter the global gradient-norm clip, as in the paper's code (PyTorch's
    /// `optimizer.zero_grad()` clears only the optimiser's parameters, while
    /// `clip_grad_norm_` sees — and rescales — every parameter of the policy). `false`:
    /// reservoir gradients are dropped before clipping.
    #[serde(default)]
    pub reservoir_grad_in_norm: bool,
}

/// How recurrent minibatches are cut from the rollout.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RecurrentBatches {
    /// Fixed chunks of `bptt_len` steps of one env (shuffled), each starting from the hidden
    /// state stored at its first step; backpropagation through time stops at chunk edges.
    #[default]
    Chunks,
    /// sb3-contrib's `RecurrentRolloutBuffer`: the env-major buffer is rotated by a random
    /// offset each epoch and cut into windows of `batch_size` consecutive transitions; each
    /// window is split into sequences at episode starts (and at env edges), each sequence
    /// starting from the hidden state stored during the rollout and padded to the longest.
    Sequences,
}

impl RecurrentBatches {
    /// Setting value (`chunks`, `sequences`).
    pub fn name(self) -> &'static str {
        match self {
            RecurrentBatches::Chunks => "chunks",
            RecurrentBatches::Sequences => "sequences",
        }
    }
}

/// Implementation of the network during training (same function and gradients).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    /// Hand-written fused forward/backward on the flat parameter vector
    /// (`chronocooked_models::deep::native`; tested equal to burn's autodiff). The default: 2–6×
    /// faster for these small networks on CPU.
    #[default]
    Native,
    /// burn modules with autodiff (the reference implementation).
    Burn,
}

/// Learning-rate schedule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LrSchedule {
    /// Fixed learning rate.
    Constant,
    /// Linear decay to 0 over the step budget.
    Linear,
}

impl Default for PpoConfig {
    fn default() -> Self {
        PpoConfig {
            n_envs: 1,
            n_steps: 1000,
            batch_size: 64,
            n_epochs: 20,
            gamma: 0.99,
            gae_lambda: 0.95,
            clip_range: 0.2,
            clip_range_vf: None,
            ent_coef: 0.0,
            vf_coef: 0.5,
            max_grad_norm: 0.5,
            learning_rate: 3e-4,
            lr_schedule: LrSchedule::Constant,
            adam_eps: 1e-5,
            target_kl: None,
            normalize_advantage: true,
            bptt_len: 0,
            engine: Engine::Native,
            recurrent_batches: RecurrentBatches::Chunks,
            detach_critic: false,
            reservoir_grad_in_norm: false,
        }
    }
}

/// Observation encoding fed to the trunk.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObsEncoding {
    /// The 6 integer code channels as floats (the paper's input).
    Codes,
    /// One-hot channels (13 + cue channels).
    Onehot,
}

/// Curriculum over the course of training.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Curriculum {
    /// No curriculum.
    None,
    /// Multi-timer: start with one TD and add the next one each time the mean reward
    /// of the last `window` episodes reaches the next threshold.
    MultiTimer {
        /// Reward thresholds, one per level change (reference: 0.95, 0.95, 0.9, 0.9, 0.9).
        thresholds: Vec<f32>,
        /// Episodes averaged.
        window: usize,
        /// The paper's level 0 before the first TD: one timer with the soup only takeable
        /// at `timer ≥ TD` (`mode=lower_bounded`), reduced reward 0.1 and no buffers (an
        /// FI-like warm-up); level `k ≥ 1` then runs `k` timers with the configured task.
        /// Levels are 0..=|tds| and `thresholds[level]` gates leaving `level`.
        #[serde(default)]
        warmup: bool,
    },
    /// Multi-anchor (reference): start with the first 2 anchors and add the next anchor's
    /// counter once the mean reward of the last `window` episodes, all finished since the
    /// last change, reaches `thresholds[level]` (reference: 0.98, 0.96); the envs are
    /// rebuilt and reset at a change, as the reference's `set_env`.
    MultiAnchor {
        /// Reward thresholds, one per level change.
        thresholds: Vec<f32>,
        /// Episodes averaged.
        window: usize,
        /// Clear Adam's moments at a change (the reference's multi-anchor scripts do).
        clear_adam: bool,
    },
    /// Multi-oven (reference): start with one oven and add the next (up to the task's
    /// `ovens`) under the same rule (reference: 0.95, 0.90; Adam kept).
    MultiOven {
        /// Reward thresholds, one per level change.
        thresholds: Vec<f32>,
        /// Episodes averaged.
        window: usize,
        /// Clear Adam's moments at a change (the reference's multi-oven scripts do not).
        clear_adam: bool,
    },
    /// Tasks with a reward window (Ready-Set-Go): the window starts wide and narrows to the
    /// task's own in `levels` steps (shaping, as the adaptive reward windows that trained
    /// monkeys in Ready-Set-Go: Jazayeri & Shadlen 2015, Remington et al. 2018). Level `k` of `L`
    /// pays inside `tolerance_k·g·ts + steps_k`, both interpolated linearly from
    /// (`tolerance_start`, `tolerance_steps_start`) at level 0 to the task's
    /// (`tolerance`, `tolerance_steps`) at level `L − 1`. Checked once `window` episodes
    /// have finished since the last change, on the share of them that delivered inside the
    /// window: the next (narrower) level once it reaches `thresholds[level]`, the previous
    /// (wider) one when it falls below `fallback` — an adaptive staircase, so a policy that
    /// stops producing in a window too narrow for it gets the wider window's reward back.
    Tolerance {
        /// Share of in-window deliveries that ends each level (the last one repeats).
        thresholds: Vec<f32>,
        /// Share of in-window deliveries below which the level steps back (0 = never).
        #[serde(default = "no_fallback")]
        fallback: f32,
        /// Episodes averaged.
        window: usize,
        /// Relative tolerance of level 0 (the task's is the last level's).
        tolerance_start: f64,
        /// Constant tolerance of level 0 (steps).
        tolerance_steps_start: f64,
        /// Levels, the task's own window included (≥ 2).
        levels: usize,
    },
    /// Uncertainty: never-ready probability ramps linearly from `start` to `end`
    /// over the first `ramp_fraction` of the budget.
    Uncertainty {
        /// Initial never-ready probability.
        start: f64,
        /// Final never-ready probability.
        end: f64,
        /// Fraction of the budget over which it ramps.
        ramp_fraction: f64,
    },
}

impl Curriculum {
    /// The curriculum `name` (one of [`crate::settings::ppo::CURRICULA`]) with its defaults.
    pub fn named(name: &str) -> Option<Curriculum> {
        match name {
            "none" => Some(Curriculum::None),
            "multi_timer" => Some(Curriculum::MultiTimer {
                thresholds: vec![0.95, 0.95, 0.9, 0.9, 0.9],
                window: 100,
                warmup: false,
            }),
            "uncertainty" => Some(Curriculum::Uncertainty {
                start: 0.0,
                end: 0.2,
                ramp_fraction: 0.5,
            }),
            "multi_anchor" => Some(Curriculum::MultiAnchor {
                thresholds: vec![0.98, 0.96],
                window: 100,
                clear_adam: true,
            }),
            "multi_oven" => Some(Curriculum::MultiOven {
                thresholds: vec![0.95, 0.90],
                window: 100,
                clear_adam: false,
            }),
            // Level 0 is the window on which LSTM125 learned the task in the pilot
            // (`results/reproduction/ppo-pilot`); 80% in the window is the usual
            // criterion of shaping; below 50% it steps back, where a one-up-one-down
            // staircase on the window (as monkeys were trained) would settle.
            "tolerance" => Some(Curriculum::Tolerance {
                thresholds: vec![0.8],
                fallback: 0.5,
                window: 100,
                tolerance_start: 0.5,
                tolerance_steps_start: 3.0,
                levels: 4,
            }),
            _ => None,
        }
    }

    /// Curricula that grow the task (multi-anchor counters, multi-oven ovens): the family
    /// they grow (the family declares the parameter and its sizes), the thresholds, the
    /// window and whether a change clears Adam.
    pub fn growth(&self) -> Option<Growth<'_>> {
        match self {
            Curriculum::MultiAnchor {
                thresholds,
                window,
                clear_adam,
            } => Some(Growth {
                family: TaskFamily::MultiAnchor,
                thresholds,
                window: *window,
                clear_adam: *clear_adam,
            }),
            Curriculum::MultiOven {
                thresholds,
                window,
                clear_adam,
            } => Some(Growth {
                family: TaskFamily::MultiOven,
                thresholds,
                window: *window,
                clear_adam: *clear_adam,
            }),
            _ => None,
        }
    }

    /// The reward window of tolerance-curriculum level `level` for a task whose own window
    /// is `task` = (`tolerance`, `tolerance_steps`): `(tolerance, steps)` interpolated
    /// linearly from the curriculum's start (level 0) to `task` (the last level and
    /// beyond). `None` for other curricula.
    pub fn tolerance_at(&self, level: usize, task: (f64, f64)) -> Option<(f64, f64)> {
        let Curriculum::Tolerance {
            tolerance_start,
            tolerance_steps_start,
            levels,
            ..
        } = self
        else {
            return None;
        };
        let last = levels.saturating_sub(1).max(1);
        let f = level.min(last) as f64 / last as f64;
        let lerp = |a: f64, b: f64| a + (b - a) * f;
        Some((
            lerp(*tolerance_start, task.0),
            lerp(*tolerance_steps_start, task.1),
        ))
    }

    /// Episodes averaged by the curriculum's checks (`None` without such checks).
    pub fn window(&self) -> Option<usize> {
        match self {
            Curriculum::MultiTimer { window, .. }
            | Curriculum::MultiAnchor { window, .. }
            | Curriculum::MultiOven { window, .. }
            | Curriculum::Tolerance { window, .. } => Some(*window),
            Curriculum::None | Curriculum::Uncertainty { .. } => None,
        }
    }

    /// Whether the curriculum moves through levels whose policies are kept
    /// (`run/levels/level-L.bpk`).
    pub fn has_levels(&self) -> bool {
        matches!(self, Curriculum::MultiTimer { .. }) || self.growth().is_some()
    }
}

/// [`Curriculum::Tolerance`]'s `fallback` when a stored configuration has none: 0, the
/// behaviour before the field existed (never step back), so a resumed run keeps its rule.
fn no_fallback() -> f32 {
    0.0
}

/// A curriculum that grows the task by one counter or oven per level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Growth<'a> {
    /// The family whose task grows (its parameter and sizes: [`chronocooked_env::Growth`]).
    pub family: TaskFamily,
    /// Mean reward that ends each level.
    pub thresholds: &'a [f32],
    /// Episodes averaged.
    pub window: usize,
    /// Clear Adam's moments at a change.
    pub clear_adam: bool,
}

/// How task parameters are set (named in unknown-key errors).
pub const ENV_KEY: &str = "env.<task parameter>";

/// Most transitions of one rollout (`n_envs · n_steps`).
pub const MAX_ROLLOUT: usize = 1 << 20;

/// Default [`TrainConfig::keep_checkpoints`]: the newest three checkpoints (a corrupt newest
/// one still leaves two to resume from).
pub const DEFAULT_KEEP_CHECKPOINTS: usize = 3;

fn default_keep_checkpoints() -> usize {
    DEFAULT_KEEP_CHECKPOINTS
}

/// A complete, resolved training configuration (saved in every run folder).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainConfig {
    /// The task and its parameters (serialised as `task`, the id, and `env`, the parameters
    /// set: `{"td": 6}`).
    #[serde(flatten)]
    pub task: Task,
    /// Architecture.
    pub model: Architecture,
    /// Preset the run started from (`reference`, `fast`).
    pub preset: String,
    /// Seed of everything random in the run.
    pub seed: u64,
    /// Env-step budget (all envs together).
    pub total_steps: u64,
    /// Observation encoding.
    pub obs: ObsEncoding,
    /// Write a checkpoint every this many env steps (rounded up to whole updates; 0 = only at the end).
    pub checkpoint_every: u64,
    /// Checkpoints kept in `checkpoints/` (the newest; the oldest is deleted right after a new
    /// one is written, so storage stays bounded: at most one more while a write is in
    /// flight; the final model is kept besides). At least 1.
    #[serde(default = "default_keep_checkpoints")]
    pub keep_checkpoints: usize,
    /// Episodes in the training success-rate window (progress bar and CSV).
    pub stats_window: usize,
    /// Deterministic evaluation from every start cell every this many env steps (0 = only at the end).
    pub eval_every: u64,
    /// Stop early once the deterministic evaluation reaches this success rate (`None`: never).
    pub stop_at_success: Option<f64>,
    /// PPO hyperparameters.
    pub ppo: PpoConfig,
    /// Curriculum.
    pub curriculum: Curriculum,
    /// Initial weight distribution of the recurrent core (`lab` or `torch`: PyTorch's
    /// defaults, as in the paper's code).
    #[serde(default)]
    pub core_init: chronocooked_models::CoreInit,
    /// Run folder whose final policy initialises the weights (fine-tuning, e.g. an FI agent
    /// adapting to the uncertainty task); the architecture must match.
    #[serde(default)]
    pub init_from: Option<String>,
}

impl TrainConfig {
    /// Defaults for `task` and `model` before any preset.
    pub fn base(task: Task, model: Architecture) -> Self {
        TrainConfig {
            task,
            model,
            preset: "reference".into(),
            seed: 0,
            total_steps: 900_000,
            obs: ObsEncoding::Codes,
            checkpoint_every: 100_000,
            keep_checkpoints: DEFAULT_KEEP_CHECKPOINTS,
            stats_window: 100,
            eval_every: 0,
            stop_at_success: None,
            ppo: PpoConfig::default(),
            curriculum: Curriculum::None,
            core_init: chronocooked_models::CoreInit::Lab,
            init_from: None,
        }
    }

    /// Applies one `key=value` override (the keys of presets and `--set`, listed with their
    /// accepted values in [`crate::settings::ppo::PPO_SETTINGS`]): the value is parsed by the
    /// key's rule and written into the field through the serialised configuration.
    /// `curriculum=NAME` starts the named curriculum with its defaults; `env.<param>=v`
    /// sets a task parameter (checked by its rule now, with the other parameters in
    /// [`TrainConfig::validate`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), TrainError> {
        let (key, value) = (key.trim(), value.trim());
        if let Some(name) = key.strip_prefix("env.") {
            return Ok(self.task.set(name, value)?);
        }
        let specs = PPO_SETTINGS;
        let Some(spec) = settings::find(specs, key) else {
            return Err(settings::unknown(specs, self, key, ENV_KEY));
        };
        if spec.key == "curriculum" {
            self.curriculum = Curriculum::named(value)
                .ok_or_else(|| TrainError::param(key, value, &spec.rule.allowed()))?;
            return Ok(());
        }
        settings::set_field(self, spec, key, value)
    }

    /// The guide's table of PPO settings (docs/training.md): every key with its default before any preset (a
    /// curriculum's parameters with that curriculum's defaults).
    pub fn settings_markdown() -> String {
        let mut rows: Vec<settings::Setting> = Vec::new();
        for name in settings::ppo::CURRICULA {
            let model = "cnn-mlp".parse().expect("cnn-mlp is a model");
            let fi = Task::new("FixedInterval-v0").expect("FI is registered");
            let mut cfg = TrainConfig::base(fi, model);
            cfg.curriculum = Curriculum::named(name).expect("a curriculum name");
            for s in cfg.listing() {
                if !rows.iter().any(|r| r.key == s.key) {
                    rows.push(s);
                }
            }
        }
        let order = |key: &str| PPO_SETTINGS.iter().position(|s| s.key == key);
        rows.sort_by_key(|r| order(&r.key));
        settings::markdown_table(&rows)
    }

    /// Applies `key=value` strings (from `--set`).
    pub fn apply_overrides<S: AsRef<str>>(&mut self, sets: &[S]) -> Result<(), TrainError> {
        for s in sets {
            let s = s.as_ref();
            let (k, v) = s
                .split_once('=')
                .ok_or_else(|| TrainError::BadOverride(s.to_string()))?;
            self.set(k, v)?;
        }
        Ok(())
    }

    /// Every setting with its current value, type, accepted values and meaning (what
    /// `zoo show` lists; the curriculum's parameters only for the curriculum it has).
    pub fn listing(&self) -> Vec<settings::Setting> {
        settings::listing(PPO_SETTINGS, self)
    }

    /// Every setting as the `key=value` pair [`TrainConfig::set`] takes (the resolved
    /// configuration in the CLI's own terms; curriculum parameters after the curriculum).
    pub fn settings(&self) -> Vec<(&'static str, String)> {
        let v = self.listing();
        PPO_SETTINGS
            .iter()
            .filter_map(|s| {
                v.iter()
                    .find(|x| x.key == s.key)
                    .map(|x| (s.key, x.value.clone()))
            })
            .collect()
    }

    /// Tolerance curriculum: the reward window (`tolerance`, `tolerance_steps`) of the
    /// configured task ([`TaskConfig::reward_window`]: a Ready-Set-Go task's), its last
    /// level; `(0, 0)` under other curricula. An error naming `curriculum` when the
    /// curriculum is set on a task without a reward window, or naming
    /// `curriculum_tolerance_start` when its first window is narrower than the task's.
    ///
    /// [`TaskConfig::reward_window`]: chronocooked_env::TaskConfig::reward_window
    pub(crate) fn reward_window(&self) -> Result<(f64, f64), TrainError> {
        let Curriculum::Tolerance {
            tolerance_start,
            tolerance_steps_start,
            ..
        } = self.curriculum
        else {
            return Ok((0.0, 0.0));
        };
        let task = self.task.config()?;
        let Some((tolerance, tolerance_steps)) = task.reward_window() else {
            return Err(TrainError::InvalidParam {
                field: "curriculum".into(),
                value: "tolerance".into(),
                allowed: format!(
                    "a curriculum of the task's family (task {} has no reward window to narrow)",
                    self.task
                ),
            });
        };
        // Compared as the task stores them (f32), so a start equal to the task's passes.
        let start = (tolerance_start as f32, tolerance_steps_start as f32);
        if start.0 < tolerance || start.1 < tolerance_steps {
            return Err(TrainError::InvalidParam {
                field: "curriculum_tolerance_start".into(),
                value: format!("{tolerance_start}, {tolerance_steps_start} steps"),
                allowed: format!(
                    "a first window at least the task's own (tolerance >= {tolerance}, tolerance_steps >= {tolerance_steps})"
                ),
            });
        }
        // The first level's task must itself be valid (e.g. its window inside the time limit).
        task.with_reward_window(start.0, start.1)
            .map_err(|e| TrainError::InvalidParam {
                field: "curriculum_tolerance_start".into(),
                value: format!("{tolerance_start}, {tolerance_steps_start} steps"),
                allowed: format!("a first window the task accepts ({e})"),
            })?;
        Ok((f64::from(tolerance), f64::from(tolerance_steps)))
    }

    /// The never-ready ramp and the multi-timer levels edit a task of their kind: an error
    /// naming `curriculum` when the task has no never-ready episodes (no `never_ready` reset
    /// option) or no timers to add (not a multi-timer task), instead of a run without its
    /// curriculum. (The growing and tolerance curricula check their tasks in
    /// [`Curriculum::growth`]'s levels and [`TrainConfig::reward_window`].)
    fn check_curriculum_task(&self, task: &chronocooked_env::TaskConfig) -> Result<(), TrainError> {
        let (name, missing) = match self.curriculum {
            Curriculum::Uncertainty { .. }
                if !task
                    .reset_options()
                    .contains(&chronocooked_env::ResetOption::NeverReady) =>
            {
                ("uncertainty", "no never-ready episodes to ramp")
            }
            Curriculum::MultiTimer { .. }
                if !matches!(task.params, chronocooked_env::TaskParams::MultiTimer { .. }) =>
            {
                ("multi_timer", "no timers to add")
            }
            _ => return Ok(()),
        };
        Err(TrainError::InvalidParam {
            field: "curriculum".into(),
            value: name.into(),
            allowed: format!(
                "a curriculum of the task's family (task {} has {missing})",
                self.task
            ),
        })
    }

    /// The one check of a configuration, however it was made (presets, `--set`, a
    /// hand-edited or resumed `config.json`): every setting's value against its rule in
    /// [`PPO_SETTINGS`] (the rule `--set` parses with), then the cross-field constraints
    /// and the task and overrides (a valid env).
    pub fn validate(&self) -> Result<(), TrainError> {
        settings::check(PPO_SETTINGS, self)?;
        let task = self.task.config()?;
        self.reward_window()?;
        self.check_curriculum_task(&task)?;
        if let Some(window) = self.curriculum.window()
            && window > self.stats_window
        {
            return Err(TrainError::param(
                "curriculum_window",
                window,
                &format!(
                    "at most stats_window ({}): the episodes kept for the curriculum's checks",
                    self.stats_window
                ),
            ));
        }
        // The rollout buffer holds n_envs · n_steps transitions: bounded so that a
        // hand-edited config.json cannot ask for more memory than any machine has.
        if self.ppo.n_envs.saturating_mul(self.ppo.n_steps) > MAX_ROLLOUT {
            return Err(TrainError::param(
                "n_steps",
                self.ppo.n_steps,
                &format!("n_envs * n_steps <= {MAX_ROLLOUT} (the rollout buffer)"),
            ));
        }
        if self.ppo.n_envs * self.ppo.n_steps < 2 {
            return Err(TrainError::param(
                "n_steps",
                self.ppo.n_steps,
                "n_envs * n_steps >= 2",
            ));
        }
        Ok(())
    }
}

impl crate::checked::Check for TrainConfig {
    type Error = TrainError;

    /// [`TrainConfig::validate`].
    fn validate(&self) -> Result<(), TrainError> {
        TrainConfig::validate(self)
    }
}
