//! The completeness marker of an export folder, `export.json`: removed before an export
//! writes anything and written last, listing every file with its size (bytes) and SHA-256.
//! A folder whose marker is missing, or whose files differ from it, is an interrupted
//! export (a crash, a full disk, a kill between two files) or one mixed with another: the
//! readers refuse it (`chronocooked.load_activity` in Python) and a rerun rewrites it.

use chronocooked_env::fs::write_atomic;
use chronocooked_env::integrity::sha256_hex;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// File name of the marker.
pub const MARKER: &str = "export.json";

/// The marker's contents (`export.json`), read and written only through this type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExportMarker {
    /// Format version (1).
    pub format: u32,
    /// Always `true`: the marker is written after every file.
    pub complete: bool,
    /// Every file of the export, in the order written.
    pub files: Vec<ExportedFile>,
}

/// One exported file as the marker records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExportedFile {
    /// Path relative to the export folder.
    pub name: String,
    /// Size (bytes).
    pub bytes: u64,
    /// SHA-256 of the contents, hex.
    pub sha256: String,
}

/// Runs `write` (which writes the export's files into `dir` and returns them) between
/// removing `dir/export.json` and writing it anew; returns the files with the marker last.
pub fn write_export(
    dir: &Path,
    write: impl FnOnce(&Path) -> Result<Vec<PathBuf>, String>,
) -> Result<Vec<PathBuf>, String> {
    let marker = dir.join(MARKER);
    match std::fs::remove_file(&marker) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(format!("{}: {e}", marker.display())),
    }
    let mut files = write(dir)?;
    let mut listed = Vec::new();
    for f in &files {
        let bytes = std::fs::read(f).map_err(|e| format!("{}: {e}", f.display()))?;
        let name = f.strip_prefix(dir).map_err(|_| {
            format!(
                "{}: written outside the export folder {}",
                f.display(),
                dir.display()
            )
        })?;
        listed.push(ExportedFile {
            name: name.to_string_lossy().into_owned(),
            bytes: bytes.len() as u64,
            sha256: sha256_hex(&bytes),
        });
    }
    let text = serde_json::to_string_pretty(&ExportMarker {
        format: 1,
        complete: true,
        files: listed,
    })
    .map_err(|e| e.to_string())?;
    write_atomic(&marker, text.as_bytes()).map_err(|e| e.to_string())?;
    files.push(marker);
    Ok(files)
}

/// Checks that `dir` holds a complete export: its marker exists and every file it lists
/// has the recorded size and SHA-256. The error names the folder and the file.
pub fn check_export(dir: &Path) -> Result<(), String> {
    let marker = dir.join(MARKER);
    let text = std::fs::read_to_string(&marker).map_err(|e| {
        format!(
            "{}: {e} — the export in {} is incomplete (interrupted, or written by an older \
             version): rerun `chronocooked export`",
            marker.display(),
            dir.display()
        )
    })?;
    let record: ExportMarker =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", marker.display()))?;
    for f in &record.files {
        let path = dir.join(&f.name);
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        if f.bytes != bytes.len() as u64 || f.sha256 != sha256_hex(&bytes) {
            return Err(format!(
                "{}: differs from its record in {} (the folder mixes two exports): rerun \
                 `chronocooked export`",
                path.display(),
                marker.display()
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_marker_is_written_last_and_a_changed_or_missing_file_fails_the_check() {
        let dir = tempfile::tempdir().unwrap();
        let files = write_export(dir.path(), |d| {
            let a = d.join("a.csv");
            std::fs::write(&a, "x,y\n1,2\n").unwrap();
            Ok(vec![a])
        })
        .unwrap();
        assert_eq!(files.last().unwrap(), &dir.path().join(MARKER));
        check_export(dir.path()).unwrap();
        std::fs::write(dir.path().join("a.csv"), "x,y\n1,3\n").unwrap();
        let e = check_export(dir.path()).unwrap_err();
        assert!(e.contains("a.csv") && e.contains("differs"), "{e}");
        // A writer that fails leaves no marker: the folder reads as incomplete.
        let r = write_export(dir.path(), |_| Err("disk full".into()));
        assert_eq!(r.unwrap_err(), "disk full");
        let e = check_export(dir.path()).unwrap_err();
        assert!(e.contains("export.json") && e.contains("incomplete"), "{e}");
    }
}
