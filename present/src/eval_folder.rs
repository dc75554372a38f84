//! The evaluation folder: what `chronocooked eval` (and the Python package's `evaluate`)
//! writes and what `report --eval DIR` reads.
//!
//! * [`RECORDS`] `records.jsonl` — one [`EvalRecord`] per episode (condition + actions +
//!   infos; read by [`chronocooked_analysis::evaluation::protocol::read_records`]);
//! * [`EVAL_INFO`] `eval.json` — [`EvalInfo`]: model, task, overrides, protocol mode, seed
//!   ([`read_eval_info`]);
//! * [`METRICS`] `metrics.json` — [`Metrics`] computed from the records;
//! * `figures/` — the evaluation figures (SVG + PNG).
//!
//! Every file is written atomically, the records, `eval.json`, `metrics.json` and the
//! activity with their SHA-256 records in the folder's `SHA256SUMS` (an edited record is
//! refused when read back), and `metrics.json` last ([`start_writing`]): a folder with
//! metrics is a complete one. Every crate names these files through the constants here and
//! reads `eval.json` through [`read_eval_info`].

use chronocooked_analysis::behaviour::metrics::{Metrics, compute_metrics};
use chronocooked_analysis::evaluation::protocol::EvalRecord;
use chronocooked_analysis::job_folder;
use chronocooked_env::integrity::write_recorded;
use std::path::{Path, PathBuf};

pub use chronocooked_analysis::records::{EVAL_INFO, EvalInfo, METRICS, RECORDS, read_eval_info};

/// `out` must be a folder (or not exist yet): a file there is named in the error.
fn check_out(out: &Path) -> Result<(), String> {
    match std::fs::metadata(out) {
        Ok(m) if !m.is_dir() => Err(format!(
            "{}: exists and is not a folder (the evaluation output is a folder)",
            out.display()
        )),
        _ => Ok(()),
    }
}

/// Writes `records.jsonl`, `eval.json`, `metrics.json` and the figures into `out` (after
/// [`begin_evaluation`] and the activity, if any); returns the metrics and the figure files.
pub fn write_eval_folder(
    out: &Path,
    info: &EvalInfo,
    records: &[EvalRecord],
) -> Result<(Metrics, Vec<PathBuf>), String> {
    check_out(out)?;
    start_writing(out)?;
    let mut lines = String::new();
    for r in records {
        lines += &serde_json::to_string(r).map_err(|e| e.to_string())?;
        lines.push('\n');
    }
    write_recorded(&out.join(RECORDS), lines.as_bytes()).map_err(|e| e.to_string())?;
    let info = EvalInfo {
        episodes: Some(records.len()),
        ..info.clone()
    };
    let json = serde_json::to_string_pretty(&info).map_err(|e| e.to_string())?;
    write_recorded(&out.join(EVAL_INFO), json.as_bytes()).map_err(|e| e.to_string())?;
    write_metrics(out, &info, records)
}

/// Starts a new evaluation in `out`, before anything of it is written (its activity
/// included): marks the folder unfinished ([`start_writing`]) and removes what only an
/// earlier evaluation there wrote — its activity and its export, its per-level episodes —
/// so that nothing of it stays beside the new one (a rerun equals a clean evaluation; the
/// figures are drawn afresh by [`write_metrics`]).
pub fn begin_evaluation(out: &Path) -> Result<(), String> {
    check_out(out)?;
    start_writing(out)?;
    for file in [
        job_folder::ACTIVITY,
        job_folder::ACTIVITY_SUMMARY,
        chronocooked_analysis::collect::LEVELS_CSV,
    ] {
        chronocooked_env::integrity::remove_recorded(&out.join(file)).map_err(|e| e.to_string())?;
    }
    remove_folder(&out.join("activity"))
}

/// Marks the evaluation folder `out` unfinished before anything in it is rewritten, by
/// removing its `metrics.json`: the metrics are written last, so a folder with metrics is
/// a complete one, and a writer stopped half-way (killed, out of disk) leaves a folder
/// that no reader takes for a finished evaluation, never new records beside old metrics.
pub fn start_writing(out: &Path) -> Result<(), String> {
    chronocooked_env::integrity::remove_recorded(&out.join(METRICS)).map_err(|e| e.to_string())
}

/// Writes the figures of `records` and then `metrics.json` into `out` (the records and
/// `eval.json` are left as they are); the metrics come last (see [`start_writing`]).
pub fn write_metrics(
    out: &Path,
    info: &EvalInfo,
    records: &[EvalRecord],
) -> Result<(Metrics, Vec<PathBuf>), String> {
    start_writing(out)?;
    let metrics = compute_metrics(&info.model, records, info.seed);
    let mut json = serde_json::to_string_pretty(&metrics).map_err(|e| e.to_string())?;
    json.push('\n');
    // The figures are drawn afresh: one of an earlier evaluation's conditions that this one
    // lacks would otherwise stay beside them.
    remove_folder(&out.join("figures"))?;
    let figures = crate::figures::eval_figures(&out.join("figures"), &metrics, records)
        .map_err(|e| e.to_string())?;
    write_recorded(&out.join(METRICS), json.as_bytes()).map_err(|e| e.to_string())?;
    Ok((metrics, figures))
}

/// Removes the folder `dir` and everything in it (nothing when it does not exist); the
/// error names it.
fn remove_folder(dir: &Path) -> Result<(), String> {
    match std::fs::remove_dir_all(dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(format!(
            "{}: cannot remove the earlier contents: {e}",
            dir.display()
        )),
        _ => Ok(()),
    }
}

/// Writes the activity recorded during an evaluation next to it: `activity.json` (the
/// dataset, as `record` writes it) and its NPZ export `activity/` (aligned window up to 200
/// steps). Trials are the evaluation's episodes, in `records.jsonl` order. Returns the files.
pub fn write_activity(
    out: &Path,
    dataset: &chronocooked_models::ActivityDataset,
) -> Result<Vec<PathBuf>, String> {
    let path = out.join(job_folder::ACTIVITY);
    let json = serde_json::to_vec(dataset).map_err(|e| e.to_string())?;
    write_recorded(&path, &json).map_err(|e| e.to_string())?;
    let mut files = vec![path];
    files.extend(crate::export::marker::write_export(
        &out.join("activity"),
        |dir| crate::export::export_activity(dataset, dir, 200),
    )?);
    Ok(files)
}
