//! `export` from Python: an activity dataset and/or an evaluation folder's records as NPZ,
//! CSV and JSON metadata, closed by the completeness marker — what `chronocooked export`
//! writes (`chronocooked_present::export::export_folder`).

use crate::errors::value_err;
use chronocooked_models::ActivityDataset;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// Reads an activity dataset: `path` is `activity.json` or a folder holding it.
fn read_activity(path: &Path) -> PyResult<ActivityDataset> {
    let file = if path.is_dir() {
        path.join(chronocooked_analysis::job_folder::ACTIVITY)
    } else {
        path.to_path_buf()
    };
    let bytes = chronocooked_env::integrity::read_checked(&file).map_err(|e| match e {
        chronocooked_env::integrity::IntegrityError::Io { .. } => PyOSError::new_err(e.to_string()),
        other => value_err(other.to_string()),
    })?;
    ActivityDataset::from_json(&bytes).map_err(|m| {
        value_err(format!(
            "{}: not an activity dataset (from `record` or `evaluate`): {m}",
            file.display()
        ))
    })
}

/// Writes the export folder `out` from `activity` (an `activity.json` or a folder holding
/// one) and/or the evaluation folder `eval`; aligned activity spans up to `window` steps
/// after oven-on. Returns the files written, the marker `export.json` last.
#[pyfunction]
#[pyo3(signature = (out, activity = None, eval = None, window = 200))]
pub fn export(
    out: PathBuf,
    activity: Option<PathBuf>,
    eval: Option<PathBuf>,
    window: usize,
) -> PyResult<Vec<PathBuf>> {
    if activity.is_none() && eval.is_none() {
        return Err(value_err(
            "say what to export: activity=PATH (an activity.json or a folder with one) and/or \
             eval=DIR (an evaluation folder)",
        ));
    }
    if window == 0 {
        return Err(value_err(
            "invalid value for `window`: 0 (allowed: steps after oven-on, >= 1)",
        ));
    }
    // The inputs first: a bad one leaves an earlier complete export as it was.
    let ds = activity.as_deref().map(read_activity).transpose()?;
    let records = eval
        .as_deref()
        .map(|dir| {
            chronocooked_analysis::records::check_complete_eval(dir)
                .and_then(|()| chronocooked_analysis::evaluation::protocol::read_records(dir))
                .map_err(|e| value_err(format!("{e} (not an evaluation folder)")))
        })
        .transpose()?;
    let _lock = chronocooked_env::fs::FolderLock::acquire(&out)
        .map_err(|e| PyOSError::new_err(e.to_string()))?;
    chronocooked_present::export::export_folder(&out, ds.as_ref(), records.as_deref(), window)
        .map_err(|e| PyOSError::new_err(format!("{}: {e}", out.display())))
}
