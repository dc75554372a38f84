//! The completeness marker of an export folder, `export.json`: removed before an export
//! writes anything and written last, listing every file with its size (bytes) and SHA-256.
//! A folder whose marker is missing, or whose files differ from it, is an interrupted
//! export (a crash, a full disk, a kill between two files) or one mixed with another: the
//! readers refuse it (`chronocooked.load_activity` in Python) and a rerun rewrites it.

use chronocooked_env::fs::write_atomic;
use chronocooked_env::integrity::sha256_hex;
use serde_json::json;
use std::path::{Path, PathBuf};

/// File name of the marker.
pub const MARKER: &str = "export.json";

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
        listed.push(json!({
            "name": name.to_string_lossy(),
            "bytes": bytes.len(),
            "sha256": sha256_hex(&bytes),
        }));
    }
    let text = serde_json::to_string_pretty(&json!({
        "format": 1,
        "complete": true,
        "files": listed,
    }))
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
    let v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", marker.display()))?;
    let files = v["files"]
        .as_array()
        .ok_or_else(|| format!("{}: no `files` list", marker.display()))?;
    for f in files {
        let name = f["name"]
            .as_str()
            .ok_or_else(|| format!("{}: a file without `name`", marker.display()))?;
        let path = dir.join(name);
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        if f["bytes"].as_u64() != Some(bytes.len() as u64)
            || f["sha256"].as_str() != Some(sha256_hex(&bytes).as_str())
        {
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
