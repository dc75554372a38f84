//! Chronocooked Lab training: PPO equivalent to Stable-Baselines3's (feed-forward and
//! recurrent with BPTT), presets, curricula, run folders with exact resume.

pub mod act;
pub mod adam;
pub mod adapt;
pub mod config;
pub mod error;
pub mod evaluate;
pub mod gae;
pub mod loss;
pub mod minibatch;
pub mod obs;
pub mod params;
pub mod ppo_agent;
pub mod presets;
pub mod rollout;
pub mod run_dir;
pub mod state;
pub mod sweep;
pub mod timing_run;
pub mod trainer;
pub mod zoo;

pub use config::{Curriculum, Engine, LrSchedule, ObsEncoding, PpoConfig, TrainConfig};
pub use error::TrainError;
pub use evaluate::{EvalEpisode, eval_tds, evaluate_policy, success_rate};
pub use ppo_agent::PpoAgent;
pub use presets::{PRESETS, preset_settings, resolve};
pub use run_dir::{Progress, RunDir, RunSummary, Silent, load_policy, run_training};
pub use timing_run::{
    TimingRunConfig, TimingRunSummary, is_timing_run, is_timing_run_config, load_timing_agent,
    run_timing_training,
};
pub use trainer::{Trainer, TrainerState, UpdateLog};
