//! The one atomic file write of the lab: every file a command writes (run folders,
//! checkpoints, evaluation records, exports, reports) goes through [`write_atomic`], so an
//! interrupted write never leaves a truncated file behind.

use std::io::Write;
use std::path::Path;

/// Name prefix of the temporary files [`write_atomic`] creates.
pub const TEMP_PREFIX: &str = ".tmp-";

/// Whether a file name is a temporary file of an interrupted atomic write: one of
/// [`write_atomic`] (`.tmp-XXXXXX`, or `tempfile`'s default `.tmpXXXXXX`), or a
/// `NAME.tmpPID` of a writer that renames into place (the model save of a run folder).
pub fn is_temp_name(name: &str) -> bool {
    name.starts_with(".tmp")
        || name
            .rsplit_once('.')
            .is_some_and(|(_, ext)| ext.contains("tmp"))
}

/// Writes `bytes` to `path` atomically: into a temporary file in the same folder (created
/// if missing), flushed to disk, then renamed over `path`. On error the temporary file is
/// removed and `path` keeps its previous content.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    let mut tmp = tempfile::Builder::new()
        .prefix(TEMP_PREFIX)
        .tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::write_atomic;

    #[test]
    fn writes_replaces_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("a.json");
        write_atomic(&path, b"first").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        write_atomic(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(path.parent().unwrap())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }

    #[test]
    fn a_failed_write_keeps_the_old_content() {
        let dir = tempfile::tempdir().unwrap();
        // The target is a non-empty folder: the rename fails, nothing else changes.
        let target = dir.path().join("taken");
        std::fs::create_dir_all(target.join("inside")).unwrap();
        assert!(write_atomic(&target, b"x").is_err());
        assert!(target.join("inside").is_dir());
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1);
    }
}
