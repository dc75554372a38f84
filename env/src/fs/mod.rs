//! The one atomic file write of the lab: every file a command writes (run folders,
//! checkpoints, evaluation records, exports, reports, figures) goes through [`write_atomic`]
//! or [`write_atomic_with`], so an interrupted write never leaves a truncated file behind,
//! and every output is created with the process umask. Also the symlink-free folder walk
//! ([`real_subdirs`]) and the removal of a killed writer's temporary files. [`lock`] keeps
//! one writer per output folder; [`fault`] injects a full disk or a sudden death at a chosen
//! write for the fault-tolerance tests.

pub mod fault;
pub mod lock;

pub use lock::{FolderLock, LockError, ensure_not_being_written, remove_temp_files_below};

use std::io::Write;
use std::path::{Path, PathBuf};

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

/// The name prefix of the temporary files of writes to `path`: [`TEMP_PREFIX`], the file's
/// name (its first 100 characters) and a dot, so the leftovers of one output can be told
/// from other files ([`remove_temp_files_of`]).
fn temp_prefix_of(path: &Path) -> String {
    let name: String = path
        .file_name()
        .map(|n| n.to_string_lossy().chars().take(100).collect())
        .unwrap_or_default();
    format!("{TEMP_PREFIX}{name}.")
}

/// Removes the temporary files that interrupted writes of `path` left beside it (and only
/// those: for outputs in a folder that holds other files, such as `record --out FILE`).
pub fn remove_temp_files_of(path: &Path) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let prefix = temp_prefix_of(path);
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let is_file = e.file_type().is_ok_and(|t| t.is_file());
        if is_file
            && e.file_name()
                .to_str()
                .is_some_and(|n| n.starts_with(&prefix))
        {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// A temporary file beside `path` (its folder created if missing), created like any other
/// output: mode 0666 minus the process umask (0644 under umask 022), not `tempfile`'s 0600.
fn temp_beside(path: &Path, suffix: &str) -> std::io::Result<tempfile::NamedTempFile> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir)?;
    let mut builder = tempfile::Builder::new();
    let prefix = temp_prefix_of(path);
    builder.prefix(&prefix).suffix(suffix);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // open(2) applies the umask to this mode.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir)
}

/// A file [`write_atomic`] could not write: the file and the I/O error (displayed as
/// `PATH: ERROR`). Every crate's error type converts from it, so a write is `write_atomic(..)?`.
#[derive(Debug, thiserror::Error)]
#[error("{}: {error}", path.display())]
pub struct WriteError {
    /// The file being written.
    pub path: PathBuf,
    /// What failed.
    pub error: std::io::Error,
}

/// Writes `bytes` to `path` atomically: into a temporary file in the same folder (created
/// if missing), flushed to disk, then renamed over `path`. On error the temporary file is
/// removed and `path` keeps its previous content. The file is created with the process
/// umask (0644 under umask 022), like every output of the lab. The one atomic write of the
/// lab: no crate wraps it.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let write = || -> std::io::Result<()> {
        let mut tmp = temp_beside(path, "")?;
        tmp.write_all(bytes)?;
        tmp.as_file().sync_all()?;
        fault::before_commit(path)?;
        tmp.persist(path).map_err(|e| e.error)?;
        Ok(())
    };
    write().map_err(|error| WriteError {
        path: path.to_path_buf(),
        error,
    })
}

/// Writes `path` atomically through a writer that only takes a path (a plotting backend):
/// `write` fills a temporary file in the same folder, which is then flushed to disk and
/// renamed over `path`. On error the temporary file is removed and `path` is unchanged.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> std::io::Result<()> {
    // The temporary file keeps the extension: writers pick the format from it.
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    let tmp = temp_beside(path, &ext)?.into_temp_path();
    write(&tmp).map_err(std::io::Error::other)?;
    std::fs::File::open(&tmp)?.sync_all()?;
    fault::before_commit(path)?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// Appends `text` to `path` (created if missing): the one append of the lab (learning
/// curves, command histories), which a resume cuts back to its checkpoint.
pub fn append(path: &Path, text: &str) -> std::io::Result<()> {
    fault::before_commit(path)?;
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)?
        .write_all(text.as_bytes())
}

/// Removes the temporary files of interrupted atomic writes ([`is_temp_name`]) directly in
/// `dir` (not below it). Returns the files removed.
pub fn remove_temp_files(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut removed = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return removed;
    };
    for e in entries.flatten() {
        let is_file = e.file_type().is_ok_and(|t| t.is_file());
        if is_file && e.file_name().to_str().is_some_and(is_temp_name) {
            let p = e.path();
            if std::fs::remove_file(&p).is_ok() {
                removed.push(p);
            }
        }
    }
    removed
}

/// The real sub-folders of `dir`, sorted: symbolic links are never followed (a link to a
/// folder, or a link loop, is not a sub-folder), so a walk built on this visits each real
/// folder once and always ends.
pub fn real_subdirs(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut out: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.flatten()
                .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
                .map(|e| e.path())
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
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

    #[cfg(unix)]
    #[test]
    fn files_get_the_process_umask_not_0600() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.json");
        write_atomic(&a, b"x").unwrap();
        let b = dir.path().join("b.png");
        super::write_atomic_with(&b, |p| std::fs::write(p, b"y").map_err(|e| e.to_string()))
            .unwrap();
        // The mode is 0666 minus the umask: group/other read bits follow the umask, never
        // tempfile's owner-only 0600 (the test runner's umask is 022 or 002).
        for p in [a, b] {
            let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode & 0o044, 0o044, "{p:?}: {mode:o}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn walks_do_not_follow_links() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("real")).unwrap();
        std::os::unix::fs::symlink(dir.path(), dir.path().join("real").join("up")).unwrap();
        std::os::unix::fs::symlink(dir.path().join("real"), dir.path().join("alias")).unwrap();
        assert_eq!(
            super::real_subdirs(dir.path()),
            vec![dir.path().join("real")]
        );
        assert!(super::real_subdirs(&dir.path().join("real")).is_empty());
    }

    #[test]
    fn stale_temporary_files_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(".tmp-abc123"), b"half").unwrap();
        std::fs::write(dir.path().join("model.bpk.tmp4242"), b"half").unwrap();
        std::fs::write(dir.path().join("curves.csv"), b"keep").unwrap();
        assert_eq!(super::remove_temp_files(dir.path()).len(), 2);
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1);
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
