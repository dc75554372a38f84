//! Chronocooked Lab training: PPO equivalent to Stable-Baselines3's (feed-forward and
//! recurrent with BPTT), presets, curricula, run folders with exact resume.

pub mod act;
pub mod adam;
pub mod config;
pub mod error;
pub mod evaluate;
pub mod gae;
pub mod loss;
pub mod obs;
pub mod params;
pub mod presets;
pub mod rollout;
pub mod run_dir;
pub mod state;
pub mod trainer;

pub use config::{Curriculum, LrSchedule, ObsEncoding, PpoConfig, TrainConfig};
pub use error::TrainError;
pub use evaluate::{EvalEpisode, eval_tds, evaluate_policy, success_rate};
pub use presets::{PRESETS, preset_settings, resolve};
pub use run_dir::{Progress, RunDir, RunSummary, Silent, load_policy, run_training};
pub use trainer::{Trainer, TrainerState, UpdateLog};
