//! Chronocooked Lab training:
//!
//! * [`ppo`] — PPO equivalent to Stable-Baselines3's (feed-forward and recurrent with BPTT):
//!   settings and presets, rollouts, GAE, the clipped loss, minibatches, Adam, the trainer
//!   with its curricula, a run trained to its budget (`ppo::run`), and the trained policy
//!   as an agent;
//! * [`run_dir`] — run folders (config, curves, checkpoints, model) with exact resume; [`timing_run`] — training runs of the
//!   timing models; [`evaluate`] — the deterministic evaluation used during training;
//! * [`adapt`] — adaptation to the uncertainty task; [`zoo`] — every model the lab can
//!   train, evaluate or record; [`agent_zoo`] — the trained agents the repository keeps
//!   (`zoo:<model>/<task>`);
//! * [`error`] — typed training errors.

#![warn(missing_docs)]

pub mod adapt;
pub mod agent_zoo;
pub mod checked;
pub mod error;
pub mod evaluate;
pub mod ppo;
pub mod run_config;
pub mod settings;
pub mod timing_check;
pub mod timing_run;
pub mod zoo;

pub use checked::{Check, Checked};
pub use error::TrainError;
pub use evaluate::eval_tds;
pub use ppo::agent::PpoAgent;
pub use ppo::config::{Curriculum, Engine, LrSchedule, ObsEncoding, PpoConfig, TrainConfig};
pub use ppo::evaluate::{EvalEpisode, evaluate_policy};
pub use ppo::presets::{PRESETS, preset_settings, resolve};
pub use ppo::run::{Progress, Silent, resume_trainer, run_training};
pub use ppo::run_dir;
pub use ppo::run_dir::{RunDir, RunSummary, load_policy};
pub use ppo::trainer::{Trainer, TrainerState, UpdateLog};
pub use run_config::{RunFolder, RunKind};
pub use timing_run::{
    TimingRunConfig, TimingRunSummary, is_timing_run, load_timing_agent, load_timing_config,
    run_timing_training,
};
