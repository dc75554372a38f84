//! The export stage: activity datasets and evaluation records as NPZ (numpy) + CSV + JSON
//! metadata describing every array.

use crate::PipelineError;
use std::path::{Path, PathBuf};

/// Exports the activity dataset `activity` (JSON, from `record` or `eval --activity`) and/or
/// the records of the evaluation folder `eval` into `out`; aligned activity arrays span up
/// to `window` steps after oven-on. Returns the files written.
pub fn export(
    activity: Option<&Path>,
    eval: Option<&Path>,
    window: usize,
    out: &Path,
) -> Result<Vec<PathBuf>, PipelineError> {
    if activity.is_none() && eval.is_none() {
        return Err(PipelineError::Invalid(
            "say what to export: --activity FILE.json (from `record`) and/or --eval DIR (from `eval`)"
                .into(),
        ));
    }
    for input in activity.iter().chain(eval.iter()) {
        if input.is_dir() {
            chronocooked_env::fs::ensure_not_being_written(input)?;
        } else if let Some(parent) = input.parent().filter(|p| !p.as_os_str().is_empty()) {
            chronocooked_env::fs::ensure_not_being_written(parent)?;
        }
    }
    let _lock = chronocooked_env::fs::FolderLock::acquire(out)?;
    // The inputs are read first: a bad one leaves an earlier complete export as it was.
    let ds = match activity {
        Some(path) => {
            let text = chronocooked_env::integrity::read_checked(path).map_err(|e| match e {
                chronocooked_env::integrity::IntegrityError::Io { source, .. } => {
                    PipelineError::read(path, source)
                }
                other => PipelineError::Analysis(other.to_string()),
            })?;
            Some(
                chronocooked_models::ActivityDataset::from_json(&text).map_err(|message| {
                    PipelineError::NotA {
                        path: path.to_path_buf(),
                        what: "an activity dataset (from `record`)",
                        message,
                    }
                })?,
            )
        }
        None => None,
    };
    let records = match eval {
        Some(dir) => Some(
            chronocooked_analysis::records::check_complete_eval(dir)
                .and_then(|()| chronocooked_analysis::evaluation::protocol::read_records(dir))
                .map_err(|e| PipelineError::Analysis(format!("{e} (not an eval folder)")))?,
        ),
        None => None,
    };
    let files =
        chronocooked_present::export::export_folder(out, ds.as_ref(), records.as_deref(), window)
            .map_err(PipelineError::Analysis)?;
    Ok(files)
}
