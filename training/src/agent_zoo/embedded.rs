//! The repository's zoo (`zoo/` at the workspace root) compiled into the program, so a
//! binary or Python wheel used outside the repository has the same agents: [`unpack`]
//! writes it once into a cache folder named after its content, where it is checked like
//! any zoo folder on every load.
//!
//! Adding an agent to the zoo (`chronocooked zoo add`) means adding its name to
//! [`AGENTS`] here too; a test checks that this list and the files equal the zoo on disk.

use super::{AGENT_FILES, INDEX, ZooError, io};
use chronocooked_env::integrity::{MANIFEST, sha256_hex};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The files of one agent: (file name, content), [`AGENT_FILES`] then `SHA256SUMS`.
pub type AgentFiles = [(&'static str, &'static [u8]); 6];

macro_rules! zoo_file {
    ($name:literal, $file:literal) => {
        (
            $file,
            include_bytes!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../zoo/",
                $name,
                "/",
                $file
            ))
            .as_slice(),
        )
    };
}

macro_rules! zoo_agent {
    ($name:literal) => {
        (
            $name,
            [
                zoo_file!($name, "config.json"),
                zoo_file!($name, "policy.json"),
                zoo_file!($name, "model.bpk"),
                zoo_file!($name, "summary.json"),
                zoo_file!($name, "provenance.json"),
                zoo_file!($name, "SHA256SUMS"),
            ],
        )
    };
}

/// The zoo's `index.json` as compiled in.
pub static INDEX_JSON: &[u8] =
    include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/../zoo/index.json"));

/// Every compiled-in agent: (name `<model>/<task>`, its files).
pub static AGENTS: &[(&str, AgentFiles)] = &[
    zoo_agent!("cnn-mlp/FixedInterval-v0"),
    zoo_agent!("ctrnn125/FixedInterval-v0"),
    zoo_agent!("ctrnn-reservoir125/FixedInterval-v0"),
    zoo_agent!("cnn-mlp/Bisection-v0"),
    zoo_agent!("ctrnn125/Bisection-v0"),
    zoo_agent!("ctrnn-reservoir125/Bisection-v0"),
    zoo_agent!("lstm125/FixedInterval-v0"),
    zoo_agent!("lstm125/Bisection-v0"),
    zoo_agent!("cnn-mlp-stack4/FixedInterval-v0"),
];

/// Content key of the compiled-in zoo: SHA-256 of the index and every agent's records.
pub fn content_key() -> String {
    let mut all = INDEX_JSON.to_vec();
    for (name, files) in AGENTS {
        all.extend_from_slice(name.as_bytes());
        for (file, bytes) in files {
            if *file == MANIFEST {
                all.extend_from_slice(bytes);
            }
        }
    }
    sha256_hex(&all)[..16].to_string()
}

/// Unpacks the compiled-in zoo into `cache/zoo-<content key>/` (once: a complete copy has
/// its `index.json`, written last) and returns that folder. Unpacking holds the cache
/// folder's lock, so two processes never write one copy; a copy left incomplete by a killed
/// process (no index) is removed and written again, and temporary files a killed write
/// left in a complete copy are removed, so a kill at any point never breaks the cache.
pub fn unpack(cache: &Path) -> Result<PathBuf, ZooError> {
    debug_assert!(
        AGENTS
            .iter()
            .all(|(_, f)| f[..5].iter().map(|x| x.0).eq(AGENT_FILES))
    );
    let dir = cache.join(format!("zoo-{}", content_key()));
    let complete = |dir: &Path| dir.join(INDEX).is_file() && stray_temps(dir).is_empty();
    if complete(&dir) {
        return Ok(dir);
    }
    let _lock = chronocooked_env::fs::FolderLock::acquire_waiting(cache, Duration::from_secs(120))
        .map_err(|e| io(cache, e))?;
    if dir.join(INDEX).is_file() {
        // Complete, but a killed write (of an older version) left temporary files in it.
        for p in stray_temps(&dir) {
            std::fs::remove_file(&p).map_err(|e| io(&p, e))?;
        }
        return Ok(dir);
    }
    match std::fs::remove_dir_all(&dir) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(io(&dir, e)),
        _ => {}
    }
    for (name, files) in AGENTS {
        let agent = dir.join(name);
        std::fs::create_dir_all(&agent).map_err(|e| io(&agent, e))?;
        for (file, bytes) in files {
            let p = agent.join(file);
            chronocooked_env::fs::write_atomic(&p, bytes).map_err(|e| io(&p, e.error))?;
        }
    }
    let p = dir.join(INDEX);
    chronocooked_env::fs::write_atomic(&p, INDEX_JSON).map_err(|e| io(&p, e.error))?;
    Ok(dir)
}

/// Temporary files of interrupted writes in the agents' folders of the unpacked copy `dir`.
fn stray_temps(dir: &Path) -> Vec<PathBuf> {
    AGENTS
        .iter()
        .filter_map(|(name, _)| std::fs::read_dir(dir.join(name)).ok())
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| chronocooked_env::fs::is_temp_name(&n.to_string_lossy()))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compiled_in_zoo_equals_the_zoo_on_disk() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../zoo");
        let index = super::super::read_index(&root).unwrap();
        let names: Vec<&str> = AGENTS.iter().map(|a| a.0).collect();
        assert_eq!(
            names, index.agents,
            "embedded.rs AGENTS must list the zoo's index"
        );
        assert_eq!(
            INDEX_JSON,
            std::fs::read(root.join(INDEX)).unwrap().as_slice()
        );
        for (name, files) in AGENTS {
            for (file, bytes) in files {
                let disk = std::fs::read(root.join(name).join(file)).unwrap();
                assert_eq!(*bytes, disk.as_slice(), "{name}/{file}");
            }
        }
    }

    /// What a kill -9 during unpacking leaves — a copy without its index, temporary files of
    /// interrupted writes, with or without the index — is repaired by the next unpack, and
    /// every agent then verifies.
    #[test]
    fn an_unpack_killed_at_any_point_is_repaired_by_the_next() {
        let cache = tempfile::tempdir().unwrap();
        let dir = unpack(cache.path()).unwrap();
        let (first, _) = AGENTS[0];
        let stray = dir.join(first).join(".tmp-model.bpk.AbC123");
        // Killed before the index: a partial copy with a temporary file.
        std::fs::remove_file(dir.join(INDEX)).unwrap();
        std::fs::write(&stray, b"half").unwrap();
        std::fs::remove_file(dir.join(first).join("model.bpk")).unwrap();
        assert_eq!(unpack(cache.path()).unwrap(), dir);
        // Complete, with a temporary file a killed write left.
        std::fs::write(&stray, b"half").unwrap();
        assert_eq!(unpack(cache.path()).unwrap(), dir);
        for (name, _) in AGENTS {
            super::super::verify_agent(&dir.join(name)).unwrap();
        }
        assert!(!stray.exists());
    }
}
