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
/// its `index.json`, written last) and returns that folder.
pub fn unpack(cache: &Path) -> Result<PathBuf, ZooError> {
    debug_assert!(
        AGENTS
            .iter()
            .all(|(_, f)| f[..5].iter().map(|x| x.0).eq(AGENT_FILES))
    );
    let dir = cache.join(format!("zoo-{}", content_key()));
    if dir.join(INDEX).is_file() {
        return Ok(dir);
    }
    for (name, files) in AGENTS {
        let agent = dir.join(name);
        std::fs::create_dir_all(&agent).map_err(|e| io(&agent, e))?;
        for (file, bytes) in files {
            let p = agent.join(file);
            chronocooked_env::fs::write_atomic(&p, bytes).map_err(|e| io(&p, e.error))?;
        }
    }
    std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
    let p = dir.join(INDEX);
    chronocooked_env::fs::write_atomic(&p, INDEX_JSON).map_err(|e| io(&p, e.error))?;
    Ok(dir)
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
}
