//! The adapt stage: a trained agent keeps learning on a new task (default
//! `Uncertainty-v0`) and the episodes it needs to adapt are counted (`adapt/`).

use crate::PipelineError;
use chronocooked_training::RunFolder;
use chronocooked_training::adapt::{AdaptConfig, AdaptResult, run_adaptation};
use std::path::{Path, PathBuf};

/// What to adapt (the arguments of `chronocooked adapt`).
#[derive(Debug, Clone)]
pub struct AdaptRequest {
    /// Run folder of the trained agent (PPO or timing model).
    pub run: PathBuf,
    /// The protocol's settings; an empty `config.env` means "derived from the run"
    /// ([`adapt_env`]).
    pub config: AdaptConfig,
    /// Output folder (`adapt.json`, `adapt.csv`; PPO: the fine-tuning run in `run/`).
    pub out: PathBuf,
}

/// The task overrides an adaptation uses when none are given: the run's own task settings
/// without `never_ready_prob` when it was trained on the task adapted to, else its `td`.
pub fn adapt_env(run: &Path, task: &str) -> Result<Vec<String>, PipelineError> {
    let RunFolder {
        task: own_task,
        env: own,
        ..
    } = RunFolder::open(run)?;
    Ok(own
        .into_iter()
        .filter(|s| {
            if own_task == task {
                !s.starts_with("never_ready_prob")
            } else {
                s.starts_with("td=")
            }
        })
        .collect())
}

/// Runs the adaptation protocol of `req` and writes its folder.
pub fn adapt(req: &AdaptRequest) -> Result<AdaptResult, PipelineError> {
    chronocooked_env::fs::ensure_not_being_written(&req.run)?;
    let _lock = chronocooked_env::fs::FolderLock::acquire(&req.out)?;
    let mut config = req.config.clone();
    if config.env.is_empty() {
        config.env = adapt_env(&req.run, &config.task)?;
    }
    Ok(run_adaptation(&req.run, &config, &req.out)?)
}
