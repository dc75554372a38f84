//! Per-job progress: the finished stages of a job folder (`progress.json`, written
//! atomically after each stage), so a rerun redoes nothing that finished.

use crate::sweep::stage::Stage;
use chronocooked_training::TrainError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Stages a job folder has finished (from its `progress.json`; empty when absent or
/// unreadable, so a damaged file only causes work to be redone).
pub fn finished_stages(job_dir: &Path) -> Vec<Stage> {
    std::fs::read_to_string(job_dir.join(chronocooked_analysis::job_folder::PROGRESS))
        .ok()
        .and_then(|t| serde_json::from_str::<JobProgress>(&t).ok())
        .map(|p| p.finished)
        .unwrap_or_default()
}

/// Contents of a job's `progress.json`.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct JobProgress {
    /// Job id.
    pub id: String,
    /// Finished stages, in order.
    pub finished: Vec<Stage>,
    /// Wall seconds of each finished stage.
    pub seconds: Vec<f64>,
    /// Whether every stage the job needs is finished.
    pub done: bool,
}

/// Records that `stage` of the job in `job_dir` finished after `seconds`.
pub fn mark_stage(
    job_dir: &Path,
    id: &str,
    stage: Stage,
    seconds: f64,
    done: bool,
) -> Result<(), TrainError> {
    let mut p: JobProgress =
        std::fs::read_to_string(job_dir.join(chronocooked_analysis::job_folder::PROGRESS))
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or_default();
    p.id = id.into();
    if !p.finished.contains(&stage) {
        p.finished.push(stage);
        p.seconds.push(seconds);
    }
    p.done = done;
    let json = serde_json::to_string_pretty(&p).unwrap_or_default();
    chronocooked_env::fs::write_atomic(
        &job_dir.join(chronocooked_analysis::job_folder::PROGRESS),
        json.as_bytes(),
    )?;
    Ok(())
}

/// Whether the job in `job_dir` is completely finished.
pub fn job_done(job_dir: &Path) -> bool {
    std::fs::read_to_string(job_dir.join(chronocooked_analysis::job_folder::PROGRESS))
        .ok()
        .and_then(|t| serde_json::from_str::<JobProgress>(&t).ok())
        .is_some_and(|p| p.done)
}

/// Folder of job `id` under the sweep output `out`.
pub fn job_dir(out: &Path, id: &str) -> PathBuf {
    out.join(id)
}
