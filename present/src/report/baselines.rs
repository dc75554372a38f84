//! Committed baselines on the leaderboard: compact study results (what `paper collect`
//! writes and the repository keeps, `results/<study>/jobs/<task>/<row>/seed<N>/` with
//! `job.json`, `metrics.json`, `episodes.csv`, `curve.csv` and, for recorded jobs,
//! `activity.summary.json`) read as leaderboard rows next to ordinary evaluation folders.
//!
//! Each job is one run: its row label is the sweep row of `job.json` (the model plus its
//! non-task variant settings), its metrics are the `metrics.json` the job's evaluation wrote
//! (the same [`Metrics`] an evaluation folder's records give), and the runs are grouped by
//! [`group_rows`] exactly as evaluation folders are — one row per model, size and variant,
//! aggregated over seeds and task settings. The row's label carries the study name
//! (`lstm125 (paper-core)`), so a user's run of the same model (e.g. a zoo agent) keeps
//! its own row, and [`Row::baseline`] names the study.

use crate::report::leaderboard::{Row, RunResult, group_rows};
use chronocooked_analysis::behaviour::metrics::Metrics;
use chronocooked_analysis::collect::{JobSummary, job_folders};
use chronocooked_analysis::job_folder;
use chronocooked_analysis::neural::summary::NeuralSummary;
use std::path::{Path, PathBuf};

/// The committed study whose results are the default baseline, relative to the
/// repository root.
pub const DEFAULT_BASELINES: &str = "results/paper-core";

/// Environment variable naming the default baseline folder (overrides the search of
/// [`locate_default_baselines`]).
pub const BASELINES_ENV: &str = "CHRONOCOOKED_BASELINES";

/// Why committed baselines could not be read.
#[derive(Debug, thiserror::Error)]
pub enum BaselineError {
    /// The folder is missing or holds no compact job.
    #[error("{path}: {message}")]
    NotStudyResults {
        /// The folder given.
        path: String,
        /// What is missing.
        message: String,
    },
    /// A job file could not be read.
    #[error("{path}: {message}")]
    Read {
        /// The file.
        path: String,
        /// The I/O error.
        message: String,
    },
    /// A job file is not what the compact layout holds.
    #[error("{path}: field `{field}`: {message}")]
    Field {
        /// The file.
        path: String,
        /// The field (or `-` for the whole file).
        field: String,
        /// What is wrong.
        message: String,
    },
    /// The default baseline folder was not found.
    #[error(
        "the committed baselines ({DEFAULT_BASELINES}) were not found from {searched}; run from the repository, or name them: --baselines PATH/results/paper-core (or set {BASELINES_ENV})"
    )]
    NoDefault {
        /// The places searched.
        searched: String,
    },
}

fn read_text(path: &Path) -> Result<String, BaselineError> {
    std::fs::read_to_string(path).map_err(|e| BaselineError::Read {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The study name of a results folder: its last path component (`paper-core`).
pub fn study_name(root: &Path) -> String {
    let canon = std::fs::canonicalize(root).unwrap_or_else(|_| root.to_path_buf());
    canon
        .file_name()
        .map_or_else(|| "baseline".into(), |n| n.to_string_lossy().into_owned())
}

/// One compact job as a leaderboard run (its row label, unmarked).
pub fn read_job(dir: &Path) -> Result<RunResult, BaselineError> {
    let job_path = dir.join(job_folder::JOB);
    let job: JobSummary =
        serde_json::from_str(&read_text(&job_path)?).map_err(|e| BaselineError::Field {
            path: job_path.display().to_string(),
            field: "-".into(),
            message: format!("not a compact job summary: {e}"),
        })?;
    let m_path = dir.join(chronocooked_analysis::records::METRICS);
    // Undefined statistics were written as `null`: read back as NaN, as they were computed.
    let metrics: Metrics = chronocooked_analysis::stats::nan_json::from_str_nan(&read_text(
        &m_path,
    )?)
    .map_err(|e| BaselineError::Field {
        path: m_path.display().to_string(),
        field: "-".into(),
        message: format!("not a metrics file: {e}"),
    })?;
    if metrics.model != job.model {
        return Err(BaselineError::Field {
            path: m_path.display().to_string(),
            field: "model".into(),
            message: format!(
                "`{}` but job.json says `{}` (files of different jobs?)",
                metrics.model, job.model
            ),
        });
    }
    let n_path = dir.join(job_folder::ACTIVITY_SUMMARY);
    let neural = if n_path.is_file() {
        let all: Vec<NeuralSummary> =
            serde_json::from_str(&read_text(&n_path)?).map_err(|e| BaselineError::Field {
                path: n_path.display().to_string(),
                field: "-".into(),
                message: format!("not a list of population summaries: {e}"),
            })?;
        // The primary population, as for evaluation folders: the most units, first on ties.
        let max = all.iter().map(|s| s.units).max();
        all.into_iter().find(|s| Some(s.units) == max)
    } else {
        None
    };
    Ok(RunResult {
        label: job.label().to_string(),
        path: dir.to_path_buf(),
        metrics,
        neural,
        adapt: None,
    })
}

/// Every job of a compact results folder (`root/jobs/...`, sorted by path) as leaderboard
/// runs; an error names the first file that is missing or malformed.
pub fn read_jobs(root: &Path) -> Result<Vec<RunResult>, BaselineError> {
    chronocooked_analysis::results_folder::check_complete(root).map_err(|message| {
        BaselineError::NotStudyResults {
            path: root.display().to_string(),
            message,
        }
    })?;
    let jobs = root.join("jobs");
    if !jobs.is_dir() {
        return Err(BaselineError::NotStudyResults {
            path: root.display().to_string(),
            message: "no `jobs/` folder (compact study results are written by `chronocooked paper collect`)".into(),
        });
    }
    let dirs = job_folders(&jobs);
    if dirs.is_empty() {
        return Err(BaselineError::NotStudyResults {
            path: jobs.display().to_string(),
            message: "no job folder (with a job.json) below it".into(),
        });
    }
    dirs.iter().map(|d| read_job(d)).collect()
}

/// The rows of one committed study: its jobs grouped as evaluation folders are, each row
/// labelled `<row> (<study>)` and marked with [`Row::baseline`].
pub fn load_baseline_rows(root: &Path) -> Result<Vec<Row>, BaselineError> {
    let study = study_name(root);
    let mut runs = read_jobs(root)?;
    for r in &mut runs {
        r.label = format!("{} ({study})", r.label);
    }
    let mut rows = group_rows(runs);
    for r in &mut rows {
        r.baseline = Some(study.clone());
    }
    Ok(rows)
}

/// Folders searched for [`DEFAULT_BASELINES`]: the current folder and its ancestors, then
/// the ancestors of the running executable (a repository's `target/release/chronocooked`).
fn search_roots() -> Vec<PathBuf> {
    let mut roots = Vec::new();
    if let Ok(cwd) = std::env::current_dir() {
        roots.extend(cwd.ancestors().map(Path::to_path_buf));
    }
    if let Ok(exe) = std::env::current_exe() {
        let exe = std::fs::canonicalize(&exe).unwrap_or(exe);
        roots.extend(exe.ancestors().skip(1).map(Path::to_path_buf));
    }
    roots
}

/// The default baseline folder: `$CHRONOCOOKED_BASELINES` when set, else the first
/// `results/paper-core/jobs` found in the current folder, its ancestors, or the ancestors
/// of the running program.
pub fn locate_default_baselines() -> Result<PathBuf, BaselineError> {
    if let Some(p) = std::env::var_os(BASELINES_ENV) {
        return Ok(PathBuf::from(p));
    }
    let roots = search_roots();
    roots
        .iter()
        .map(|r| r.join(DEFAULT_BASELINES))
        .find(|p| p.join("jobs").is_dir())
        .ok_or_else(|| BaselineError::NoDefault {
            searched: roots.first().map_or("nowhere".into(), |r| {
                format!("{} and its ancestors", r.display())
            }),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_or_empty_results_are_named() {
        let guard = tempfile::tempdir().unwrap();
        let d = guard.path();
        let e = read_jobs(d).unwrap_err().to_string();
        assert!(e.contains("no `jobs/` folder"), "{e}");
        std::fs::create_dir_all(d.join("jobs")).unwrap();
        let e = read_jobs(d).unwrap_err().to_string();
        assert!(e.contains("no job folder"), "{e}");
    }

    #[test]
    fn a_malformed_job_file_is_an_error_naming_it() {
        let guard = tempfile::tempdir().unwrap();
        let d = guard.path();
        let job = d.join("jobs/FixedInterval-v0/x~env.td-12/seed1");
        std::fs::create_dir_all(&job).unwrap();
        std::fs::write(job.join("job.json"), "{\"id\": 3}").unwrap();
        let e = read_jobs(d).unwrap_err().to_string();
        assert!(
            e.contains("job.json") && e.contains("not a compact job summary"),
            "{e}"
        );
    }
}
