//! The adapt stage: a trained agent keeps learning on a new task (default
//! `Uncertainty-v0`) and the episodes it needs to adapt are counted (`adapt/`).

use crate::PipelineError;
use chronocooked_env::Task;
use chronocooked_training::RunFolder;
use chronocooked_training::adapt::{AdaptConfig, AdaptResult, run_adaptation};
use std::path::{Path, PathBuf};

/// What to adapt (the arguments of `chronocooked adapt`).
#[derive(Debug, Clone)]
pub struct AdaptRequest {
    /// Run folder of the trained agent (PPO or timing model).
    pub run: PathBuf,
    /// The protocol's settings; a task with no parameter set means "its parameters derived
    /// from the run" ([`adapt_task`]).
    pub config: AdaptConfig,
    /// Output folder (`adapt.json`, `adapt.csv`; PPO: the fine-tuning run in `run/`).
    pub out: PathBuf,
}

/// The task an adaptation plays when no parameter of `task` is given: the run's own task
/// parameters without `never_ready_prob` when it was trained on the task adapted to, else
/// its `td`.
pub fn adapt_task(run: &Path, task: &Task) -> Result<Task, PipelineError> {
    let own = RunFolder::open(run)?.task;
    let same = own.id() == task.id();
    let mut out = task.clone();
    for (key, value) in own.values_set() {
        let keep = if same {
            key != "never_ready_prob"
        } else {
            key == "td"
        };
        if keep {
            out.set_value(key, value.clone())?;
        }
    }
    out.config()?;
    Ok(out)
}

/// Runs the adaptation protocol of `req` and writes its folder.
pub fn adapt(req: &AdaptRequest) -> Result<AdaptResult, PipelineError> {
    chronocooked_env::fs::ensure_not_being_written(&req.run)?;
    let _lock = chronocooked_env::fs::FolderLock::acquire(&req.out)?;
    let mut config = req.config.clone();
    if config.task.is_default() {
        config.task = adapt_task(&req.run, &config.task)?;
    }
    Ok(run_adaptation(&req.run, &config, &req.out)?)
}
