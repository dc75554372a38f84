//! Training configuration: PPO hyperparameters, run settings and `key=value` overrides.

use crate::error::TrainError;
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
    /// Task id (`FixedInterval-v0`, …).
    pub task: String,
    /// Task overrides as `key=value` (the env crate's parameter names).
    pub env: Vec<String>,
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
    pub fn base(task: &str, model: Architecture) -> Self {
        TrainConfig {
            task: task.to_string(),
            env: Vec::new(),
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

    /// Applies one `key=value` override (the keys of presets and `--set`).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), TrainError> {
        let v = value.trim();
        let p = &mut self.ppo;
        match key.trim() {
            "seed" => self.seed = parse(key, v, "integer >= 0")?,
            "total_steps" | "steps" => self.total_steps = parse_pos(key, v)?,
            "obs" => {
                self.obs = match v {
                    "codes" => ObsEncoding::Codes,
                    "onehot" => ObsEncoding::Onehot,
                    _ => return Err(TrainError::param(key, v, "codes|onehot")),
                }
            }
            "checkpoint_every" => self.checkpoint_every = parse(key, v, "integer >= 0")?,
            "keep_checkpoints" => self.keep_checkpoints = parse_pos(key, v)?,
            "eval_every" => self.eval_every = parse(key, v, "integer >= 0")?,
            "stats_window" => self.stats_window = parse_pos(key, v)?,
            "core_init" => {
                self.core_init = match v {
                    "lab" => chronocooked_models::CoreInit::Lab,
                    "torch" => chronocooked_models::CoreInit::Torch,
                    _ => return Err(TrainError::param(key, v, "lab|torch")),
                }
            }
            "init_from" => {
                self.init_from = match v {
                    "none" | "" => None,
                    _ => Some(v.to_string()),
                }
            }
            "stop_at_success" => {
                self.stop_at_success = match v {
                    "none" | "" => None,
                    _ => Some(parse_unit(key, v)?),
                }
            }
            "n_envs" => p.n_envs = parse_range(key, v, 1, 4096)?,
            "n_steps" => p.n_steps = parse_range(key, v, 1, 1_000_000)?,
            "batch_size" => p.batch_size = parse_range(key, v, 1, 10_000_000)?,
            "n_epochs" => p.n_epochs = parse_range(key, v, 1, 1000)?,
            "bptt_len" => p.bptt_len = parse(key, v, "integer >= 0 (0 = whole sequences)")?,
            "engine" => {
                p.engine = match v {
                    "native" => Engine::Native,
                    "burn" => Engine::Burn,
                    _ => return Err(TrainError::param(key, v, "native|burn")),
                }
            }
            "recurrent_batches" => {
                p.recurrent_batches = match v {
                    "chunks" => RecurrentBatches::Chunks,
                    "sequences" => RecurrentBatches::Sequences,
                    _ => return Err(TrainError::param(key, v, "chunks|sequences")),
                }
            }
            "detach_critic" => p.detach_critic = parse(key, v, "true|false")?,
            "reservoir_grad_in_norm" => p.reservoir_grad_in_norm = parse(key, v, "true|false")?,
            "gamma" => p.gamma = parse_unit(key, v)? as f32,
            "gae_lambda" => p.gae_lambda = parse_unit(key, v)? as f32,
            "clip_range" => p.clip_range = parse_positive_f(key, v)? as f32,
            "clip_range_vf" => {
                p.clip_range_vf = match v {
                    "none" | "" => None,
                    _ => Some(parse_positive_f(key, v)? as f32),
                }
            }
            "ent_coef" => p.ent_coef = parse_nonneg_f(key, v)? as f32,
            "vf_coef" => p.vf_coef = parse_nonneg_f(key, v)? as f32,
            "max_grad_norm" => p.max_grad_norm = parse_positive_f(key, v)? as f32,
            "learning_rate" | "lr" => p.learning_rate = parse_positive_f(key, v)?,
            "lr_schedule" => {
                p.lr_schedule = match v {
                    "constant" => LrSchedule::Constant,
                    "linear" => LrSchedule::Linear,
                    _ => return Err(TrainError::param(key, v, "constant|linear")),
                }
            }
            "adam_eps" => p.adam_eps = parse_positive_f(key, v)?,
            "target_kl" => {
                p.target_kl = match v {
                    "none" | "" => None,
                    _ => Some(parse_positive_f(key, v)? as f32),
                }
            }
            "normalize_advantage" => {
                p.normalize_advantage = parse(key, v, "true|false")?;
            }
            "curriculum" => {
                self.curriculum = match v {
                    "none" => Curriculum::None,
                    "multi_timer" => Curriculum::MultiTimer {
                        thresholds: vec![0.95, 0.95, 0.9, 0.9, 0.9],
                        window: 100,
                        warmup: false,
                    },
                    "uncertainty" => Curriculum::Uncertainty {
                        start: 0.0,
                        end: 0.2,
                        ramp_fraction: 0.5,
                    },
                    _ => return Err(TrainError::param(key, v, "none|multi_timer|uncertainty")),
                }
            }
            "curriculum_thresholds" => match &mut self.curriculum {
                Curriculum::MultiTimer { thresholds, .. } => {
                    *thresholds = v
                        .split(',')
                        .map(|x| parse_unit(key, x).map(|f| f as f32))
                        .collect::<Result<_, _>>()?;
                }
                _ => {
                    return Err(TrainError::param(
                        key,
                        v,
                        "only with curriculum=multi_timer",
                    ));
                }
            },
            "curriculum_warmup" => match &mut self.curriculum {
                Curriculum::MultiTimer { warmup, .. } => *warmup = parse(key, v, "true|false")?,
                _ => {
                    return Err(TrainError::param(
                        key,
                        v,
                        "only with curriculum=multi_timer",
                    ));
                }
            },
            "curriculum_window" => match &mut self.curriculum {
                Curriculum::MultiTimer { window, .. } => *window = parse_pos(key, v)?,
                _ => {
                    return Err(TrainError::param(
                        key,
                        v,
                        "only with curriculum=multi_timer",
                    ));
                }
            },
            "never_ready_start" | "never_ready_end" | "never_ready_ramp" => {
                match &mut self.curriculum {
                    Curriculum::Uncertainty {
                        start,
                        end,
                        ramp_fraction,
                    } => {
                        let x = parse_unit(key, v)?;
                        match key {
                            "never_ready_start" => *start = x,
                            "never_ready_end" => *end = x,
                            _ => *ramp_fraction = x,
                        }
                    }
                    _ => {
                        return Err(TrainError::param(
                            key,
                            v,
                            "only with curriculum=uncertainty",
                        ));
                    }
                }
            }
            k if k.starts_with("env.") => {
                let name = &k[4..];
                self.env.retain(|e| e.split('=').next() != Some(name));
                self.env.push(format!("{name}={v}"));
            }
            other => return Err(TrainError::UnknownKey(other.to_string())),
        }
        Ok(())
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

    /// Every setting as the `key=value` pair [`TrainConfig::set`] takes (the resolved
    /// configuration in the CLI's own terms; curriculum parameters after the curriculum).
    pub fn settings(&self) -> Vec<(&'static str, String)> {
        let p = &self.ppo;
        let opt = |o: Option<f64>| o.map_or_else(|| "none".to_string(), |x| x.to_string());
        let opt32 = |o: Option<f32>| o.map_or_else(|| "none".to_string(), |x| x.to_string());
        let mut v = vec![
            ("seed", self.seed.to_string()),
            ("total_steps", self.total_steps.to_string()),
            (
                "obs",
                match self.obs {
                    ObsEncoding::Codes => "codes",
                    ObsEncoding::Onehot => "onehot",
                }
                .into(),
            ),
            ("checkpoint_every", self.checkpoint_every.to_string()),
            ("keep_checkpoints", self.keep_checkpoints.to_string()),
            ("eval_every", self.eval_every.to_string()),
            ("stats_window", self.stats_window.to_string()),
            (
                "core_init",
                match self.core_init {
                    chronocooked_models::CoreInit::Lab => "lab",
                    chronocooked_models::CoreInit::Torch => "torch",
                }
                .into(),
            ),
            (
                "init_from",
                self.init_from.clone().unwrap_or_else(|| "none".into()),
            ),
            ("stop_at_success", opt(self.stop_at_success)),
            ("n_envs", p.n_envs.to_string()),
            ("n_steps", p.n_steps.to_string()),
            ("batch_size", p.batch_size.to_string()),
            ("n_epochs", p.n_epochs.to_string()),
            ("bptt_len", p.bptt_len.to_string()),
            (
                "engine",
                match p.engine {
                    Engine::Native => "native",
                    Engine::Burn => "burn",
                }
                .into(),
            ),
            ("recurrent_batches", p.recurrent_batches.name().into()),
            ("detach_critic", p.detach_critic.to_string()),
            (
                "reservoir_grad_in_norm",
                p.reservoir_grad_in_norm.to_string(),
            ),
            ("gamma", p.gamma.to_string()),
            ("gae_lambda", p.gae_lambda.to_string()),
            ("clip_range", p.clip_range.to_string()),
            ("clip_range_vf", opt32(p.clip_range_vf)),
            ("ent_coef", p.ent_coef.to_string()),
            ("vf_coef", p.vf_coef.to_string()),
            ("max_grad_norm", p.max_grad_norm.to_string()),
            ("learning_rate", p.learning_rate.to_string()),
            (
                "lr_schedule",
                match p.lr_schedule {
                    LrSchedule::Constant => "constant",
                    LrSchedule::Linear => "linear",
                }
                .into(),
            ),
            ("adam_eps", p.adam_eps.to_string()),
            ("target_kl", opt32(p.target_kl)),
            ("normalize_advantage", p.normalize_advantage.to_string()),
        ];
        match &self.curriculum {
            Curriculum::None => v.push(("curriculum", "none".into())),
            Curriculum::MultiTimer {
                thresholds,
                window,
                warmup,
            } => v.extend([
                ("curriculum", "multi_timer".into()),
                (
                    "curriculum_thresholds",
                    thresholds
                        .iter()
                        .map(|t| t.to_string())
                        .collect::<Vec<_>>()
                        .join(","),
                ),
                ("curriculum_window", window.to_string()),
                ("curriculum_warmup", warmup.to_string()),
            ]),
            Curriculum::Uncertainty {
                start,
                end,
                ramp_fraction,
            } => v.extend([
                ("curriculum", "uncertainty".into()),
                ("never_ready_start", start.to_string()),
                ("never_ready_end", end.to_string()),
                ("never_ready_ramp", ramp_fraction.to_string()),
            ]),
        }
        v
    }

    /// The one check of a configuration, however it was made (presets, `--set`, a
    /// hand-edited or resumed `config.json`): every setting's value is replayed through
    /// [`TrainConfig::set`] (so each field has one range rule, the CLI's), then the
    /// cross-field constraints and the task and overrides (a valid env).
    pub fn validate(&self) -> Result<(), TrainError> {
        let mut replay = self.clone();
        for (k, v) in self.settings() {
            replay.set(k, &v)?;
        }
        chronocooked_env::make_config(&self.task, &self.env)?;
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

fn parse<T: std::str::FromStr>(key: &str, v: &str, allowed: &str) -> Result<T, TrainError> {
    v.parse().map_err(|_| TrainError::param(key, v, allowed))
}

fn parse_pos<T: std::str::FromStr + PartialOrd + Default>(
    key: &str,
    v: &str,
) -> Result<T, TrainError> {
    parse::<T>(key, v, "integer >= 1")
        .ok()
        .filter(|x| *x > T::default())
        .ok_or_else(|| TrainError::param(key, v, "integer >= 1"))
}

fn parse_range(key: &str, v: &str, lo: usize, hi: usize) -> Result<usize, TrainError> {
    let allowed = format!("integer {lo}..={hi}");
    parse::<usize>(key, v, &allowed)
        .ok()
        .filter(|x| (lo..=hi).contains(x))
        .ok_or_else(|| TrainError::param(key, v, &allowed))
}

fn parse_unit(key: &str, v: &str) -> Result<f64, TrainError> {
    parse::<f64>(key, v.trim(), "number in [0, 1]")
        .ok()
        .filter(|x| (0.0..=1.0).contains(x))
        .ok_or_else(|| TrainError::param(key, v, "number in [0, 1]"))
}

fn parse_positive_f(key: &str, v: &str) -> Result<f64, TrainError> {
    parse::<f64>(key, v, "number > 0")
        .ok()
        .filter(|x| *x > 0.0 && x.is_finite())
        .ok_or_else(|| TrainError::param(key, v, "number > 0"))
}

fn parse_nonneg_f(key: &str, v: &str) -> Result<f64, TrainError> {
    parse::<f64>(key, v, "number >= 0")
        .ok()
        .filter(|x| *x >= 0.0 && x.is_finite())
        .ok_or_else(|| TrainError::param(key, v, "number >= 0"))
}
