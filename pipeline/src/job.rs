//! One sweep job, run in this process: its unfinished stages in order (train → eval →
//! adapt → record → export), each marked finished in `progress.json` when it ends, so an
//! interrupted job reruns only what did not finish (a PPO run continues from its newest
//! checkpoint).

use crate::PipelineError;
use crate::stages::{self, AdaptRequest, EvalRequest, EvalSubject, RecordRequest, TrainRequest};
use crate::sweep::{Job, Stage, SweepFile, finished_stages, job_dir, mark_stage};
use chronocooked_analysis::Mode;
use chronocooked_analysis::job_folder;
use chronocooked_env::Task;
use chronocooked_models::run_folder;
use chronocooked_training::adapt::{self, AdaptConfig};
use chronocooked_training::zoo::Family;
use std::path::Path;
use std::time::Instant;

/// Longest window (steps after oven-on) of the aligned activity arrays a job exports.
pub const EXPORT_WINDOW: usize = 200;

/// Sees a job's stages start and end (logs, progress bars); does nothing by default.
pub trait JobObserver {
    /// `stage` of `job` starts.
    fn stage_started(&mut self, _job: &Job, _stage: Stage) {}
    /// `stage` of `job` finished after `seconds`; `summary` is one line saying what it made.
    fn stage_finished(&mut self, _job: &Job, _stage: Stage, _seconds: f64, _summary: &str) {}
}

/// A [`JobObserver`] that logs to stderr: `[<job id>] <stage>` when a stage starts and its
/// one-line summary when it ends (what sweep workers write to their job's `log.txt`).
pub struct LogObserver;

impl JobObserver for LogObserver {
    fn stage_started(&mut self, job: &Job, stage: Stage) {
        eprintln!("[{}] {stage}", job.id);
    }
    fn stage_finished(&mut self, job: &Job, stage: Stage, seconds: f64, summary: &str) {
        eprintln!("[{}] {stage} done in {seconds:.1} s: {summary}", job.id);
    }
}

/// The job of `sweep` (loaded from `file`) with id `id`.
pub fn find_job(sweep: &SweepFile, file: &Path, id: &str) -> Result<Job, PipelineError> {
    sweep
        .jobs()?
        .into_iter()
        .find(|j| j.id == id)
        .ok_or_else(|| PipelineError::UnknownJob {
            id: id.to_string(),
            file: file.display().to_string(),
        })
}

/// Removes temporary files a killed writer left behind
/// ([`chronocooked_env::fs::is_temp_name`]).
fn remove_stale_temps(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        // Symbolic links are never followed (a link loop would never end).
        if e.file_type().is_ok_and(|t| t.is_dir()) {
            remove_stale_temps(&p);
        } else if p
            .file_name()
            .and_then(|x| x.to_str())
            .is_some_and(chronocooked_env::fs::is_temp_name)
        {
            let _ = std::fs::remove_file(&p);
        }
    }
}

/// Runs the unfinished stages of `job` of `sweep` in its folder `out/<job id>/`:
/// `job.json`, `run/` (train), `eval/`, `adapt/`, `activity.json` + `neural_figures/`
/// (record), `export/`, and `progress.json` after every stage.
pub fn run_job(
    sweep: &SweepFile,
    job: &Job,
    out: &Path,
    observer: &mut dyn JobObserver,
) -> Result<(), PipelineError> {
    let dir = job_dir(out, &job.id);
    std::fs::create_dir_all(&dir).map_err(|e| PipelineError::write(&dir, e))?;
    remove_stale_temps(&dir);
    let job_json = serde_json::to_string_pretty(job)
        .map_err(|e| PipelineError::Analysis(format!("serialising job {}: {e}", job.id)))?;
    let job_file = dir.join(job_folder::JOB);
    chronocooked_env::fs::write_atomic(&job_file, job_json.as_bytes())?;
    let done = finished_stages(&dir);
    let wanted = Stage::for_job(sweep, job);
    for (k, &stage) in wanted.iter().enumerate() {
        if done.contains(&stage) {
            continue;
        }
        let t0 = Instant::now();
        observer.stage_started(job, stage);
        let summary = run_stage(sweep, job, &dir, stage)?;
        let seconds = t0.elapsed().as_secs_f64();
        mark_stage(&dir, &job.id, stage, seconds, k + 1 == wanted.len())?;
        observer.stage_finished(job, stage, seconds, &summary);
    }
    Ok(())
}

/// The task an uncertainty job adapts on: its own parameters but `never_ready_prob` (the
/// protocol's default, never-ready ovens included).
fn uncertainty_task(task: &Task) -> Result<Task, PipelineError> {
    let mut out = Task::new("Uncertainty-v0")?;
    for (key, value) in task.values_set() {
        if key != "never_ready_prob" {
            out.set_value(key, value.clone())?;
        }
    }
    Ok(out)
}

/// Runs one stage of `job` in its folder `dir`; returns a one-line summary.
fn run_stage(
    sweep: &SweepFile,
    job: &Job,
    dir: &Path,
    stage: Stage,
) -> Result<String, PipelineError> {
    let trained = job.family != Family::Baseline;
    let run = dir.join(job_folder::RUN);
    Ok(match stage {
        Stage::Train => {
            if run.join(run_folder::SUMMARY).is_file() {
                // Trained by a worker that may have died before its learning-curve figure
                // (drawn after the summary): the figure is drawn again under the folder's
                // lock, which also clears what a killed holder left there (its lock file,
                // temporary files), so the folder equals an uninterrupted run's.
                let _lock = chronocooked_env::fs::FolderLock::acquire(&run)?;
                chronocooked_env::fs::remove_temp_files(&run.join(run_folder::FIGURES));
                chronocooked_present::figures::learning_curve(&run)
                    .map_err(|e| PipelineError::Analysis(e.to_string()))?;
                return Ok("already trained (learning-curve figure drawn)".into());
            }
            let resume = job.family == Family::DeepRl && run.join(run_folder::CONFIG).is_file();
            let req = TrainRequest {
                task: job.task.id().to_string(),
                model: job.model.clone(),
                preset: sweep.preset.clone(),
                seed: job.seed,
                steps: None,
                sets: if resume { vec![] } else { job.sets.clone() },
                out: (!resume).then(|| run.clone()),
                resume: resume.then(|| run.clone()),
                command: format!(
                    "sweep {}: job {} ({})",
                    sweep.name,
                    job.id,
                    if resume { "resumed" } else { "started" }
                ),
            };
            let (outcome, figure_error) = stages::train(&req, &mut stages::train::Quiet)?;
            let mut line = format!("trained → {}", outcome.dir().display());
            if let Some(e) = figure_error {
                line += &format!(" (learning-curve figure not written: {e})");
            }
            line
        }
        Stage::Eval => {
            let req = EvalRequest {
                subject: if trained {
                    EvalSubject::Run(run.clone())
                } else {
                    EvalSubject::Reference(job.model.clone())
                },
                task: (!trained).then(|| job.task.clone()),
                mode: match sweep.stochastic {
                    Some(n) => Mode::Stochastic { episodes: n },
                    None => Mode::Reference,
                },
                seed: job.seed,
                out: dir.join(job_folder::EVAL),
                activity: false,
                unfinished: false,
            };
            let outcome = stages::evaluate(&req)?;
            let m = outcome.metrics;
            let mut line = format!(
                "{}: {} episodes, success {:.1}%",
                m.model,
                m.episodes,
                m.success_rate * 100.0
            );
            if let Some(n) = outcome.levels {
                line += &format!("; {n} curriculum levels' policies evaluated (levels.csv)");
            }
            line
        }
        Stage::Adapt => {
            let config = AdaptConfig {
                task: uncertainty_task(&job.task)?,
                episodes: sweep.adapt_episodes.unwrap_or(adapt::DEFAULT_EPISODES),
                steps: sweep.adapt_steps.unwrap_or(adapt::DEFAULT_STEPS),
                window: adapt::DEFAULT_WINDOW,
                threshold: adapt::DEFAULT_THRESHOLD,
                epsilon: adapt::DEFAULT_EPSILON,
                seed: job.seed,
            };
            let r = stages::adapt(&AdaptRequest {
                run,
                config,
                out: dir.join("adapt"),
            })?;
            format!(
                "{} episodes; adapted {}",
                r.episodes,
                r.episodes_to_adapt
                    .map_or("never".to_string(), |n| format!("after {n} episodes"))
            )
        }
        Stage::Record => {
            let r = stages::record(&RecordRequest {
                probe: stages::record::can_probe(job.task.id()),
                run,
                more_runs: vec![],
                task: None,
                tds: vec![],
                repeats: sweep.record_repeats.unwrap_or(1),
                seed: job.seed,
                out: dir.join(job_folder::ACTIVITY),
                summary: true,
                figures: Some(dir.join("neural_figures")),
            })?;
            format!("{} trials × {} units", r.trials, r.units)
        }
        Stage::Export => {
            let activity = dir.join(job_folder::ACTIVITY);
            let files = stages::export(
                (trained && sweep.record).then_some(activity.as_path()),
                Some(&dir.join(job_folder::EVAL)),
                EXPORT_WINDOW,
                &dir.join("export"),
            )?;
            format!("{} files", files.len())
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_files_of_atomic_writes_are_recognised_and_removed() {
        use chronocooked_env::fs::is_temp_name;
        for t in [".tmpAb12Cd", ".tmp-x1y2", "metrics.json.tmp123", "a.tmp"] {
            assert!(is_temp_name(t), "{t}");
        }
        for keep in [
            "metrics.json",
            "records.jsonl",
            "tmp_notes.txt",
            "activity.npz",
        ] {
            assert!(!is_temp_name(keep), "{keep}");
        }
        let guard = tempfile::tempdir().unwrap();
        let dir = guard.path();
        std::fs::create_dir_all(dir.join("eval")).unwrap();
        std::fs::write(dir.join("eval/.tmp-XYZ123"), b"half").unwrap();
        std::fs::write(dir.join("eval/metrics.json"), b"{}").unwrap();
        remove_stale_temps(dir);
        assert!(!dir.join("eval/.tmp-XYZ123").exists());
        assert!(dir.join("eval/metrics.json").exists());
    }
}
