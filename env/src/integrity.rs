//! SHA-256 records of learned state: every file that holds what a run learned (`model.bpk`,
//! `policy.json`, a timing model's `agent.json`, `checkpoints/step-*.json`) is written with
//! [`write_recorded`] and read back with [`read_verified`].
//!
//! The records live in one `SHA256SUMS` file per folder, in the standard `sha256sum` format
//! (`<64 hex digits>  <name>` per line), so `sha256sum -c SHA256SUMS` checks a folder by hand.
//! A file whose content does not match its record, or that has no record, is refused with an
//! error naming it: a corrupt model never loads silently.

use crate::fs::write_atomic;
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Name of the per-folder manifest of SHA-256 records.
pub const MANIFEST: &str = "SHA256SUMS";

/// Largest manifest read (bytes): a folder's records are a few lines.
const MAX_MANIFEST_BYTES: u64 = 1 << 20;

/// Why a file of learned state was refused (every variant names the file).
#[derive(Debug, Error)]
pub enum IntegrityError {
    /// The file (or its manifest) could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The operating-system error.
        source: std::io::Error,
    },
    /// The path is not a regular file (a folder, a device, …).
    #[error("{path}: not a regular file (it is a {kind}); learned state must be a plain file")]
    NotAFile {
        /// The path.
        path: String,
        /// What it is instead.
        kind: String,
    },
    /// The folder's manifest holds no record of the file.
    #[error(
        "{path}: no SHA-256 record in {manifest}, so its content cannot be trusted (written by an older version or copied by hand?); if you trust the file, record it with `sha256sum {name} >> {MANIFEST}` in its folder"
    )]
    NoRecord {
        /// The file.
        path: String,
        /// Its name inside the folder.
        name: String,
        /// The manifest consulted.
        manifest: String,
    },
    /// The content does not match the record.
    #[error(
        "{path}: content does not match its SHA-256 record in {manifest} (recorded {expected}, found {actual}): the file is corrupt or was modified"
    )]
    Mismatch {
        /// The file.
        path: String,
        /// The manifest consulted.
        manifest: String,
        /// Recorded digest.
        expected: String,
        /// Digest of the content.
        actual: String,
    },
    /// The manifest itself is malformed.
    #[error("{manifest} line {line}: {reason} (expected `<64 hex digits>  <file name>`)")]
    BadManifest {
        /// The manifest.
        manifest: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
}

impl IntegrityError {
    fn io(path: &Path, source: std::io::Error) -> Self {
        IntegrityError::Io {
            path: path.display().to_string(),
            source,
        }
    }
}

/// Lower-case hex SHA-256 digest of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let digest = Sha256::digest(bytes);
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

fn split(path: &Path) -> (PathBuf, String) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    (dir, name)
}

/// The records of folder `dir` (name → digest); an absent manifest has none.
pub fn read_manifest(dir: &Path) -> Result<BTreeMap<String, String>, IntegrityError> {
    let path = dir.join(MANIFEST);
    let meta = match std::fs::metadata(&path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(e) => return Err(IntegrityError::io(&path, e)),
    };
    let shown = path.display().to_string();
    let bad = |line: usize, reason: &str| IntegrityError::BadManifest {
        manifest: shown.clone(),
        line,
        reason: reason.into(),
    };
    if !meta.is_file() {
        return Err(IntegrityError::NotAFile {
            path: shown.clone(),
            kind: kind_of(&meta),
        });
    }
    if meta.len() > MAX_MANIFEST_BYTES {
        return Err(bad(0, "the manifest is larger than 1 MiB"));
    }
    let bytes = std::fs::read(&path).map_err(|e| IntegrityError::io(&path, e))?;
    let text = String::from_utf8(bytes).map_err(|_| bad(0, "not UTF-8 text"))?;
    let mut out = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let (digest, rest) = line
            .split_once(' ')
            .ok_or_else(|| bad(i + 1, "no file name"))?;
        if digest.len() != 64 || !digest.bytes().all(|b| b.is_ascii_hexdigit()) {
            return Err(bad(i + 1, "the digest is not 64 hex digits"));
        }
        // `sha256sum` writes two spaces (text mode) or a space and `*` (binary mode).
        let name = rest
            .strip_prefix(' ')
            .or_else(|| rest.strip_prefix('*'))
            .ok_or_else(|| bad(i + 1, "the digest and name must be separated by two spaces"))?;
        if name.is_empty() || name.contains('/') {
            return Err(bad(i + 1, "the name must be a file of this folder"));
        }
        out.insert(name.to_string(), digest.to_ascii_lowercase());
    }
    Ok(out)
}

/// Writes the records of `dir` atomically (records of files that no longer exist dropped,
/// except `pending`: a file about to be written).
fn write_manifest(
    dir: &Path,
    records: &BTreeMap<String, String>,
    pending: Option<&str>,
) -> Result<(), IntegrityError> {
    let mut text = String::new();
    for (name, digest) in records {
        if pending == Some(name.as_str()) || dir.join(name).exists() {
            text.push_str(&format!("{digest}  {name}\n"));
        }
    }
    let path = dir.join(MANIFEST);
    write_atomic(&path, text.as_bytes()).map_err(|e| IntegrityError::io(&path, e.error))
}

/// Writes `bytes` to `path` atomically ([`write_atomic`]) and records their SHA-256 in the
/// folder's manifest.
///
/// A new file (no record, or not there yet: every checkpoint) is recorded *before* it is
/// renamed into place, so a kill between the two leaves a record of a missing file (dropped
/// at the next write), never a complete file without its record — which a resume would
/// have to refuse. A file that replaces a recorded one is recorded after the rename (until
/// then its old record stands for the old content).
pub fn write_recorded(path: &Path, bytes: &[u8]) -> Result<(), IntegrityError> {
    let (dir, name) = split(path);
    let mut records = read_manifest(&dir)?;
    let replaces = records.contains_key(&name) && std::fs::symlink_metadata(path).is_ok();
    records.insert(name.clone(), sha256_hex(bytes));
    if !replaces {
        write_manifest(&dir, &records, Some(&name))?;
    }
    write_atomic(path, bytes).map_err(|e| IntegrityError::io(path, e.error))?;
    if replaces {
        write_manifest(&dir, &records, None)?;
    }
    Ok(())
}

/// Removes the file `path` of learned state and its record.
pub fn remove_recorded(path: &Path) -> Result<(), IntegrityError> {
    match std::fs::remove_file(path) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(IntegrityError::io(path, e)),
    }
    let (dir, name) = split(path);
    let mut records = read_manifest(&dir)?;
    if records.remove(&name).is_some() {
        write_manifest(&dir, &records, None)?;
    }
    Ok(())
}

fn kind_of(meta: &std::fs::Metadata) -> String {
    if meta.is_dir() {
        "folder".into()
    } else if meta.is_symlink() {
        "symbolic link".into()
    } else {
        "special file".into()
    }
}

/// Reads the file `path` of learned state and checks it against its record: an error names
/// the file when it is not a regular file (a folder, a symlink loop), has no record, or its
/// content differs from the record.
pub fn read_verified(path: &Path) -> Result<Vec<u8>, IntegrityError> {
    let meta = std::fs::metadata(path).map_err(|e| IntegrityError::io(path, e))?;
    if !meta.is_file() {
        return Err(IntegrityError::NotAFile {
            path: path.display().to_string(),
            kind: kind_of(&meta),
        });
    }
    let bytes = std::fs::read(path).map_err(|e| IntegrityError::io(path, e))?;
    verify(path, &bytes)?;
    Ok(bytes)
}

/// Reads the file `path` that the lab records but that older versions wrote without a
/// record (a run's `config.json`, an evaluation's records and metrics): checked like
/// [`read_verified`] when its folder's manifest records it, read as it is otherwise. An
/// edited file of a recorded folder is refused naming it; a file that was never recorded is
/// taken for what it says (its reader checks its meaning).
pub fn read_checked(path: &Path) -> Result<Vec<u8>, IntegrityError> {
    let bytes = std::fs::read(path).map_err(|e| IntegrityError::io(path, e))?;
    let (dir, name) = split(path);
    if read_manifest(&dir)?.contains_key(&name) {
        verify(path, &bytes)?;
    }
    Ok(bytes)
}

/// Checks `bytes` (the content of `path`) against the record of `path`.
pub fn verify(path: &Path, bytes: &[u8]) -> Result<(), IntegrityError> {
    let (dir, name) = split(path);
    let manifest = dir.join(MANIFEST).display().to_string();
    let records = read_manifest(&dir)?;
    let Some(expected) = records.get(&name) else {
        return Err(IntegrityError::NoRecord {
            path: path.display().to_string(),
            name,
            manifest,
        });
    };
    let actual = sha256_hex(bytes);
    if &actual != expected {
        return Err(IntegrityError::Mismatch {
            path: path.display().to_string(),
            manifest,
            expected: expected.clone(),
            actual,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_digest_of_abc() {
        // FIPS 180-2 test vector.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn recorded_files_verify_and_changed_ones_do_not() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.json");
        write_recorded(&a, b"{\"x\":1}").unwrap();
        write_recorded(&dir.path().join("b.bin"), b"\0\x01").unwrap();
        assert_eq!(read_verified(&a).unwrap(), b"{\"x\":1}");
        let manifest = std::fs::read_to_string(dir.path().join(MANIFEST)).unwrap();
        assert_eq!(manifest.lines().count(), 2, "{manifest}");
        assert!(manifest.contains(&format!("{}  a.json", sha256_hex(b"{\"x\":1}"))));
        std::fs::write(&a, b"{\"x\":2}").unwrap();
        let e = read_verified(&a).unwrap_err().to_string();
        assert!(e.contains("a.json") && e.contains("does not match"), "{e}");
        std::fs::write(dir.path().join("c.json"), b"{}").unwrap();
        let e = read_verified(&dir.path().join("c.json"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("c.json") && e.contains("no SHA-256 record"),
            "{e}"
        );
    }

    #[test]
    fn a_new_file_is_recorded_before_it_is_in_place() {
        let dir = tempfile::tempdir().unwrap();
        // The rename fails (a folder holds the name): the record was written first, so a
        // write interrupted at that point leaves a record, never an unrecorded file.
        let blocked = dir.path().join("step-000000004000.json");
        std::fs::create_dir(&blocked).unwrap();
        std::fs::write(blocked.join("x"), b"").unwrap();
        assert!(write_recorded(&blocked, b"state").is_err());
        let records = read_manifest(dir.path()).unwrap();
        assert_eq!(
            records.get("step-000000004000.json"),
            Some(&sha256_hex(b"state"))
        );
        // A record of a file that never arrived is dropped at the next write.
        let other = dir.path().join("step-000000005000.json");
        std::fs::remove_dir_all(&blocked).unwrap();
        write_recorded(&other, b"next").unwrap();
        let records = read_manifest(dir.path()).unwrap();
        assert!(!records.contains_key("step-000000004000.json"));
        assert_eq!(read_verified(&other).unwrap(), b"next");
        // Replacing a recorded file keeps it verifiable.
        write_recorded(&other, b"newer").unwrap();
        assert_eq!(read_verified(&other).unwrap(), b"newer");
    }

    #[test]
    fn folders_and_symlink_loops_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path().join("model.bpk");
        std::fs::create_dir(&d).unwrap();
        let e = read_verified(&d).unwrap_err().to_string();
        assert!(e.contains("model.bpk") && e.contains("folder"), "{e}");
        #[cfg(unix)]
        {
            let l = dir.path().join("loop.bpk");
            std::os::unix::fs::symlink(&l, &l).unwrap();
            let e = read_verified(&l).unwrap_err().to_string();
            assert!(e.contains("loop.bpk"), "{e}");
        }
    }

    #[test]
    fn removal_drops_the_record_and_bad_manifests_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a");
        write_recorded(&a, b"1").unwrap();
        remove_recorded(&a).unwrap();
        assert!(!a.exists());
        assert!(read_manifest(dir.path()).unwrap().is_empty());
        std::fs::write(dir.path().join(MANIFEST), "zz  a\n").unwrap();
        let e = read_manifest(dir.path()).unwrap_err().to_string();
        assert!(e.contains(MANIFEST) && e.contains("line 1"), "{e}");
    }
}
