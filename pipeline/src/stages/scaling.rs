//! Temporal scaling of a study's agents: each model × seed's fixed-interval runs at two or
//! more TDs recorded together on peak-interval probe trials, so the neural summary can
//! compare their activity between the shortest and the longest TD.
//!
//! A sweep job trains and records one TD; scaling needs a model's runs at several TDs in one
//! dataset, so it is a step after the sweep: [`record_scaling`] walks a sweep's output
//! (`<out>/FixedInterval-v0/<row>/seed<N>/{job.json, run/}`), groups the finished runs by
//! (row, seed), records every group with at least two TDs (`record --probe --summary --run
//! TD_short --run TD_long …`) and keeps only the compact summary:
//! `<results>/scaling/<row>/seed<N>/{scaling.json, activity.summary.json}`.

use crate::error::PipelineError;
use crate::stages::record::{RecordRequest, record};
use chronocooked_analysis::job_folder;
use chronocooked_models::run_folder;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where a study's fixed-interval jobs are.
const FI_TASK: &str = "FixedInterval-v0";

pub use chronocooked_analysis::job_folder::ScalingJob;

/// What [`record_scaling`] did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ScalingOutcome {
    /// Groups recorded now.
    pub recorded: Vec<ScalingJob>,
    /// Groups whose summary was already there (skipped).
    pub skipped: usize,
}

/// Run folders by TD (steps) of one (row, seed).
type RunsByTd = BTreeMap<u32, PathBuf>;

/// Finished fixed-interval runs of `study` grouped by (row, seed).
fn groups(study: &Path) -> Result<BTreeMap<(String, u64), RunsByTd>, PipelineError> {
    let mut out: BTreeMap<(String, u64), RunsByTd> = BTreeMap::new();
    let root = study.join(FI_TASK);
    for row in chronocooked_env::fs::real_subdirs(&root) {
        for job_dir in chronocooked_env::fs::real_subdirs(&row) {
            let (job_file, run) = (job_dir.join(job_folder::JOB), job_dir.join(job_folder::RUN));
            if !job_file.is_file() || !run.join(run_folder::SUMMARY).is_file() {
                continue;
            }
            let job = job_folder::read_job(&job_dir).map_err(PipelineError::Invalid)?;
            let td = job
                .task
                .value_set("td")
                .and_then(|v| v.as_u64())
                .and_then(|v| u32::try_from(v).ok())
                .ok_or_else(|| {
                    PipelineError::Invalid(format!(
                        "{}: the job sets no fixed-interval TD (task parameter `td`)",
                        job_file.display()
                    ))
                })?;
            let (model, seed) = (job.label().to_string(), job.seed);
            out.entry((model, seed)).or_default().insert(td, run);
        }
    }
    Ok(out)
}

/// Records every (row, seed) of `study` with fixed-interval runs at two or more TDs into
/// `<results>/scaling/<row>/seed<N>/` (`activity.summary.json` with the scaling between
/// the shortest and the longest TD, `scaling.json` naming the runs). Groups already
/// recorded are skipped; the activity dataset itself is not kept.
pub fn record_scaling(study: &Path, results: &Path) -> Result<ScalingOutcome, PipelineError> {
    let mut outcome = ScalingOutcome::default();
    for ((model, seed), runs) in groups(study)? {
        if runs.len() < 2 {
            continue;
        }
        let dir = results
            .join("scaling")
            .join(&model)
            .join(format!("seed{seed}"));
        if dir.join(job_folder::SCALING).is_file()
            && dir.join(job_folder::ACTIVITY_SUMMARY).is_file()
        {
            outcome.skipped += 1;
            continue;
        }
        std::fs::create_dir_all(&dir).map_err(|e| PipelineError::write(&dir, e))?;
        let paths: Vec<PathBuf> = runs.values().cloned().collect();
        let dataset = dir.join(job_folder::ACTIVITY);
        record(&RecordRequest {
            run: paths[0].clone(),
            more_runs: paths[1..].to_vec(),
            probe: true,
            task: None,
            tds: vec![],
            repeats: 1,
            seed: 0,
            out: dataset.clone(),
            summary: true,
            figures: None,
        })?;
        std::fs::remove_file(&dataset).map_err(|e| PipelineError::write(&dataset, e))?;
        let job = ScalingJob {
            model,
            seed,
            tds: runs.keys().copied().collect(),
            runs: paths
                .iter()
                .map(|p| {
                    p.strip_prefix(study)
                        .unwrap_or(p)
                        .to_string_lossy()
                        .into_owned()
                })
                .collect(),
        };
        let file = dir.join(job_folder::SCALING);
        let text = serde_json::to_vec_pretty(&job)
            .map_err(|e| PipelineError::Invalid(format!("{}: {e}", file.display())))?;
        chronocooked_env::fs::write_atomic(&file, &text)?;
        outcome.recorded.push(job);
    }
    Ok(outcome)
}
