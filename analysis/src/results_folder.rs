//! A study's compact results folder (what `paper collect` writes): whether it is complete.
//! `paper collect` marks the folder unfinished ([`UNFINISHED_MARKER`]) before its first job
//! and removes the mark after its last, and holds the folder's lock meanwhile; every reader
//! of compact results (`paper analyse`, `mechanisms`, `report --baselines`) calls
//! [`check_complete`] first, so a collect that was killed or ran out of disk is never read
//! as a study.

use std::path::Path;

/// The marker of a results folder that `paper collect` is writing or left unfinished.
pub const UNFINISHED_MARKER: &str = "collect-unfinished.json";

/// The [`UNFINISHED_MARKER`]'s contents: the sweep output the unfinished collect read.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct UnfinishedCollect {
    /// The sweep output folder, as given to `paper collect`.
    pub sweep_out: String,
}

/// Refuses a results folder that another process is writing, or that a `paper collect`
/// left unfinished; the error names the marker and the command that completes the folder.
pub fn check_complete(root: &Path) -> Result<(), String> {
    chronocooked_env::fs::ensure_not_being_written(root).map_err(|e| e.to_string())?;
    let marker = root.join(UNFINISHED_MARKER);
    if !marker.exists() {
        return Ok(());
    }
    let from = std::fs::read_to_string(&marker)
        .ok()
        .and_then(|t| serde_json::from_str::<UnfinishedCollect>(&t).ok())
        .map_or_else(|| "SWEEP_OUT".into(), |m| m.sweep_out);
    Err(format!(
        "{}: this results folder is incomplete: a `paper collect` into it did not finish \
         (killed, or stopped by an error); complete it with `chronocooked paper collect {from} \
         --out {}`",
        marker.display(),
        root.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_marked_folder_is_refused_naming_the_command_that_completes_it() {
        let dir = tempfile::tempdir().unwrap();
        check_complete(dir.path()).unwrap();
        std::fs::write(
            dir.path().join(UNFINISHED_MARKER),
            r#"{"sweep_out": "lab-out/study"}"#,
        )
        .unwrap();
        let e = check_complete(dir.path()).unwrap_err();
        assert!(e.contains("paper collect lab-out/study --out"), "{e}");
        assert!(e.contains(UNFINISHED_MARKER), "{e}");
    }
}
