//! One writer per output folder: a command that writes a folder (a run, an evaluation, a
//! sweep's output, a results folder, a report) first takes its [`FolderLock`], so a second
//! process on the same folder is refused with a message naming the holder instead of
//! interleaving with it.
//!
//! The lock is an advisory `flock(2)` on the file [`LOCK_FILE`] in the folder, which holds
//! who took it (command, pid, host, time) for the message. The operating system releases the
//! lock when its holder ends in any way (`kill -9` included), so a lock never outlives its
//! holder and there is nothing stale to clean up by hand. Readers of a folder call
//! [`ensure_not_being_written`] to refuse a folder another process is still writing.
//!
//! A process may take the lock of a folder it already holds (a sweep job's stages inside
//! the job's folder): the inner guard is a no-op.

use serde::{Deserialize, Serialize};
use std::fs::{File, OpenOptions};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// Name of the lock file in a locked folder.
pub const LOCK_FILE: &str = ".chronocooked.lock";

/// Levels of sub-folders below a locked output folder in which [`FolderLock::acquire`]
/// removes temporary files (1: `eval/figures/`, `run/checkpoints/`).
pub const CLEAN_DEPTH: usize = 1;

/// Folders this process holds (canonical paths).
static HELD: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Who holds a folder (the content of its lock file).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Holder {
    /// The holder's command line (program arguments joined by spaces).
    pub command: String,
    /// Process id.
    pub pid: u32,
    /// Host name of the holder's machine.
    pub host: String,
    /// When the lock was taken (seconds since the Unix epoch).
    pub since_unix_s: u64,
}

impl Holder {
    fn this_process() -> Self {
        Holder {
            command: std::env::args().collect::<Vec<_>>().join(" "),
            pid: std::process::id(),
            host: host_name(),
            since_unix_s: SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_secs()),
        }
    }
}

impl std::fmt::Display for Holder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let ago = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map_or(0, |d| d.as_secs())
            .saturating_sub(self.since_unix_s);
        write!(
            f,
            "`{}` (pid {} on {}, for {ago} s)",
            self.command, self.pid, self.host
        )
    }
}

/// The machine's host name (`/proc/sys/kernel/hostname`, else `$HOSTNAME`, else `unknown`).
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown".into())
}

/// Why a folder could not be locked (every variant names the folder).
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another process holds the folder.
    #[error(
        "{}: another process is writing this folder: {}; wait for it to finish or stop it (its lock frees itself when it ends), or choose another output folder",
        dir.display(),
        holder.as_ref().map_or_else(|| "a process that has not yet said who it is".to_string(), |h| h.to_string())
    )]
    Busy {
        /// The folder.
        dir: PathBuf,
        /// Who holds it, when its lock file says so.
        holder: Option<Holder>,
    },
    /// The folder or its lock file could not be created or opened (unwritable, read-only).
    #[error("{}: cannot write here ({error}); nothing was done", path.display())]
    Io {
        /// The folder or lock file.
        path: PathBuf,
        /// The operating-system error.
        error: std::io::Error,
    },
}

/// The lock of one output folder, held until dropped (then its lock file is removed).
#[derive(Debug)]
pub struct FolderLock {
    /// `None` when this process already held the folder (the guard does nothing).
    owned: Option<(File, PathBuf)>,
    dir: PathBuf,
}

impl FolderLock {
    /// Takes the lock of the output folder `dir` (created if missing) for this process, or
    /// fails at once with [`LockError::Busy`] naming the holder. Then removes the temporary
    /// files that killed writers left in `dir` and its sub-folders ([`CLEAN_DEPTH`] levels:
    /// `figures/`, `checkpoints/`, …; [`super::remove_temp_files`]), except in sub-folders
    /// that another process holds: while the lock is held nobody else writes there. For folders the lab owns (a run,
    /// an evaluation, an export, a report); [`FolderLock::acquire_shared_folder`] for a
    /// folder that may hold the user's own files.
    pub fn acquire(dir: &Path) -> Result<FolderLock, LockError> {
        let lock = Self::acquire_waiting(dir, Duration::ZERO)?;
        if lock.owned.is_some() {
            remove_temp_files_below(&lock.dir, CLEAN_DEPTH);
        }
        Ok(lock)
    }

    /// Takes the lock of `dir` like [`FolderLock::acquire`] but removes nothing: for a
    /// folder that holds other files than the command's (the folder of `record --out
    /// FILE`, which may be the working directory).
    pub fn acquire_shared_folder(dir: &Path) -> Result<FolderLock, LockError> {
        Self::acquire_waiting(dir, Duration::ZERO)
    }

    /// Like [`FolderLock::acquire_shared_folder`], but waits up to `wait` for a holder to
    /// finish (a sweep job whose previous worker is still saving its checkpoint).
    pub fn acquire_waiting(dir: &Path, wait: Duration) -> Result<FolderLock, LockError> {
        let io = |path: &Path, error| LockError::Io {
            path: path.to_path_buf(),
            error,
        };
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        let canonical = dir.canonicalize().map_err(|e| io(dir, e))?;
        if held_by_this_process(&canonical) {
            return Ok(FolderLock {
                owned: None,
                dir: canonical,
            });
        }
        let path = canonical.join(LOCK_FILE);
        let start = Instant::now();
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(|e| io(&path, e))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    if start.elapsed() < wait {
                        std::thread::sleep(Duration::from_millis(250));
                        continue;
                    }
                    return Err(LockError::Busy {
                        dir: canonical,
                        holder: read_holder(&mut file),
                    });
                }
                Err(std::fs::TryLockError::Error(e)) => return Err(io(&path, e)),
            }
            // The previous holder may have removed the file between our open and our lock:
            // then we hold a lock on a file no one else can see, and must take the new one.
            if !same_file(&file, &path) {
                continue;
            }
            let holder = serde_json::to_vec(&Holder::this_process()).unwrap_or_default();
            file.set_len(0).map_err(|e| io(&path, e))?;
            file.rewind().map_err(|e| io(&path, e))?;
            file.write_all(&holder).map_err(|e| io(&path, e))?;
            hold(canonical.clone());
            return Ok(FolderLock {
                owned: Some((file, path)),
                dir: canonical,
            });
        }
    }

    /// The locked folder (canonical path).
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        if let Some((file, path)) = self.owned.take() {
            if let Ok(mut held) = HELD.lock() {
                held.retain(|d| d != &self.dir);
            }
            // Removed while still locked, so a waiting process re-opens the path and finds
            // either no file or a new holder's (see `same_file`).
            let _ = std::fs::remove_file(&path);
            drop(file);
        }
    }
}

/// Refuses a folder that another process is writing: `Err(LockError::Busy)` naming the
/// holder while someone holds its lock, `Ok` otherwise (no lock file, a lock file whose
/// holder has ended, or a folder this process holds). Readers call it before they read a
/// folder (an evaluation of a run being trained, a report of an evaluation being written).
pub fn ensure_not_being_written(dir: &Path) -> Result<(), LockError> {
    let Ok(canonical) = dir.canonicalize() else {
        return Ok(());
    };
    if held_by_this_process(&canonical) {
        return Ok(());
    }
    let path = canonical.join(LOCK_FILE);
    let Ok(mut file) = File::open(&path) else {
        return Ok(());
    };
    match file.try_lock_shared() {
        Ok(()) => Ok(()),
        Err(std::fs::TryLockError::WouldBlock) => Err(LockError::Busy {
            dir: canonical,
            holder: read_holder(&mut file),
        }),
        // A file system without locks cannot tell: reading goes on, as without a lock file.
        Err(std::fs::TryLockError::Error(_)) => Ok(()),
    }
}

/// Removes temporary files of interrupted writes in `dir` and, `depth` levels down, in its
/// real sub-folders that no other process is writing.
pub fn remove_temp_files_below(dir: &Path, depth: usize) {
    super::remove_temp_files(dir);
    if depth == 0 {
        return;
    }
    for sub in super::real_subdirs(dir) {
        if ensure_not_being_written(&sub).is_ok() {
            remove_temp_files_below(&sub, depth - 1);
        }
    }
}

/// Whether `dir` (canonical) is held by this process.
fn held_by_this_process(dir: &Path) -> bool {
    HELD.lock().is_ok_and(|held| held.iter().any(|d| d == dir))
}

fn hold(dir: PathBuf) {
    if let Ok(mut held) = HELD.lock() {
        held.push(dir);
    }
}

/// The holder a held lock file names. A holder writes its name right after it takes the
/// lock, so a file found empty is read again for up to 0.5 s before the holder is reported
/// unknown (two processes that start together would otherwise see each other unnamed).
fn read_holder(file: &mut File) -> Option<Holder> {
    let start = Instant::now();
    loop {
        let mut text = String::new();
        let read = file
            .rewind()
            .ok()
            .and_then(|()| (&*file).take(64 * 1024).read_to_string(&mut text).ok());
        if let Some(holder) = read.and_then(|_| serde_json::from_str(&text).ok()) {
            return Some(holder);
        }
        if start.elapsed() >= Duration::from_millis(500) {
            return None;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_file: &File, path: &Path) -> bool {
    path.exists()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two processes that start together: the second finds the lock taken but not yet
    /// named, and waits for the name instead of reporting an unknown holder.
    #[test]
    fn a_holder_that_names_itself_just_after_locking_is_still_named() {
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join(LOCK_FILE);
        let mut holding = File::create(&path).unwrap();
        holding.try_lock().unwrap();
        let writer = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(100));
            let name = serde_json::to_vec(&Holder::this_process()).unwrap();
            holding.write_all(&name).unwrap();
            holding
        });
        let mut other = File::open(&path).unwrap();
        assert!(matches!(
            other.try_lock(),
            Err(std::fs::TryLockError::WouldBlock)
        ));
        let holder = read_holder(&mut other);
        assert_eq!(holder.map(|h| h.pid), Some(std::process::id()));
        drop(writer.join().unwrap());
    }

    #[test]
    fn a_second_open_of_a_held_folder_is_busy_and_names_this_process() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("run");
        let lock = FolderLock::acquire(&dir).unwrap();
        assert!(dir.join(LOCK_FILE).is_file());
        // Another open file description of the lock file conflicts like another process.
        let mut other = File::open(dir.join(LOCK_FILE)).unwrap();
        assert!(matches!(
            other.try_lock(),
            Err(std::fs::TryLockError::WouldBlock)
        ));
        let holder = read_holder(&mut other).unwrap();
        assert_eq!(holder.pid, std::process::id());
        drop(other);
        // The same process re-entering its own folder gets a no-op guard.
        let inner = FolderLock::acquire(&dir).unwrap();
        assert!(inner.owned.is_none());
        drop(inner);
        assert!(
            dir.join(LOCK_FILE).is_file(),
            "the inner guard removed the lock"
        );
        drop(lock);
        assert!(!dir.join(LOCK_FILE).exists());
        // Free again: taken anew.
        let again = FolderLock::acquire(&dir).unwrap();
        assert!(again.owned.is_some());
    }

    #[test]
    fn a_lock_file_without_a_holder_is_taken_and_temporary_files_are_removed() {
        let tmp = tempfile::tempdir().unwrap();
        // What `kill -9` leaves: the lock file (the OS dropped the lock) and a half write.
        std::fs::write(tmp.path().join(LOCK_FILE), b"{\"pid\": 1}").unwrap();
        std::fs::write(tmp.path().join(".tmp-abc123"), b"half").unwrap();
        std::fs::write(tmp.path().join("metrics.json"), b"{}").unwrap();
        ensure_not_being_written(tmp.path()).unwrap();
        let lock = FolderLock::acquire(tmp.path()).unwrap();
        assert!(!tmp.path().join(".tmp-abc123").exists());
        assert!(tmp.path().join("metrics.json").exists());
        drop(lock);
    }

    #[test]
    fn an_unwritable_place_is_an_error_naming_it() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join("a-file");
        std::fs::write(&file, b"x").unwrap();
        let err = FolderLock::acquire(&file.join("sub")).unwrap_err();
        assert!(matches!(err, LockError::Io { .. }), "{err}");
        assert!(err.to_string().contains("a-file"), "{err}");
    }
}
