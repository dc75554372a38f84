//! The zoo of trained agents: final models the repository keeps (`zoo/<model>/<task>/`),
//! named `zoo:<model>/<task>` wherever a run folder is accepted (`eval`, `record`,
//! `export`, `adapt`, the Python package).
//!
//! A zoo agent is the part of a PPO run folder that plays (no checkpoints, no curves):
//! `config.json` (resolved training settings), `policy.json` (network description),
//! `model.bpk` (burnpack weights), `summary.json` (the run's own summary) and
//! `provenance.json` ([`Provenance`]: command, sweep job, seed, commit and the evaluation
//! it reached). `SHA256SUMS` records every one of them; [`verify_agent`] checks the whole
//! folder (every file recorded and intact, nothing else in it) before it is used, so a
//! corrupt or edited zoo file is an error naming it.
//!
//! Where the zoo is ([`zoo_root`]): `$CHRONOCOOKED_ZOO` when set; else a `zoo/index.json`
//! in the current folder or an ancestor (a repository checkout); else the copy compiled
//! into the program ([`embedded`]), unpacked once into a cache folder — so an installed
//! Python wheel or a copied binary finds the same agents.

pub mod embedded;

use chronocooked_env::integrity::{self, MANIFEST};
use chronocooked_models::run_folder;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Prefix that names a zoo agent where a run folder is expected (`zoo:lstm125/FixedInterval-v0`).
pub const ZOO_PREFIX: &str = "zoo:";

/// Environment variable naming a zoo folder (one holding `index.json`).
pub const ZOO_ENV: &str = "CHRONOCOOKED_ZOO";

/// Environment variable naming the cache folder the compiled-in zoo is unpacked into
/// (default `$XDG_CACHE_HOME/chronocooked`, else `$HOME/.cache/chronocooked`, else the
/// system's temporary folder).
pub const CACHE_ENV: &str = "CHRONOCOOKED_CACHE";

/// The zoo's index file (in the zoo folder).
pub const INDEX: &str = "index.json";

/// The files of one zoo agent besides `SHA256SUMS`, each recorded there.
pub const AGENT_FILES: [&str; 5] = [
    run_folder::CONFIG,
    run_folder::POLICY,
    run_folder::MODEL,
    run_folder::SUMMARY,
    PROVENANCE,
];

/// A zoo agent's provenance file ([`Provenance`]).
pub const PROVENANCE: &str = "provenance.json";

/// Why a zoo agent could not be found or trusted (every variant names the file or name).
#[derive(Debug, thiserror::Error)]
pub enum ZooError {
    /// No zoo agent of that name.
    #[error("no zoo agent `{name}` (agents: {known}); `chronocooked zoo list` shows them")]
    Unknown {
        /// The name asked for.
        name: String,
        /// The names the zoo has.
        known: String,
    },
    /// A file of the zoo could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The error.
        message: String,
    },
    /// A zoo file is malformed, unrecorded, modified or unexpected.
    #[error("{path}: {message}")]
    Corrupt {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
}

fn io(path: &Path, e: impl std::fmt::Display) -> ZooError {
    ZooError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

fn corrupt(path: &Path, message: impl Into<String>) -> ZooError {
    ZooError::Corrupt {
        path: path.display().to_string(),
        message: message.into(),
    }
}

/// The zoo's index: which agents it holds (`<model>/<task>`, also their folders).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ZooIndex {
    /// Format version (1).
    pub format: u32,
    /// Agent names, `<model>/<task>`.
    pub agents: Vec<String>,
}

/// The greedy reference evaluation an agent reached when it was added to the zoo.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ZooEvaluation {
    /// Episodes played (every start cell of every condition).
    pub episodes: usize,
    /// Success over all episodes (probes included), fraction.
    pub success_rate: f64,
    /// The leaderboard's headline numbers of the evaluation (column key → value; NaN
    /// values left out).
    pub headline: BTreeMap<String, f64>,
    /// Success per condition: (kind, TD in steps, episodes, success fraction).
    pub conditions: Vec<(String, u32, usize, f64)>,
}

/// Where a zoo agent comes from and what it reached (`provenance.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// Zoo name, `<model>/<task>`.
    pub name: String,
    /// Model (zoo model name, e.g. `lstm125`).
    pub model: String,
    /// The task it was trained on, with its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: chronocooked_env::Task,
    /// Training seed.
    pub seed: u64,
    /// Training preset.
    pub preset: String,
    /// Env steps trained.
    pub env_steps: u64,
    /// The sweep file and job id it was trained as (`sweeps/paper-core.toml`, job id).
    pub sweep: String,
    /// Sweep job id.
    pub job: String,
    /// The command that trained it (run from the repository root).
    pub command: String,
    /// Git commit of the code that trained it.
    pub commit: String,
    /// Training wall-clock seconds (one core, shared machine).
    pub train_wall_s: f64,
    /// Its evaluation when it was added.
    pub evaluation: ZooEvaluation,
    /// The committed compact job of the same study, model, task, settings and seed
    /// (`results/<study>/jobs/<job id>`), when there is one.
    pub study_job: Option<String>,
    /// Whether this agent's evaluation episodes equal that job's `episodes.csv` line for
    /// line (training and evaluation are reproducible from the seed; the job's
    /// `metrics.json` may differ where the metrics code changed since it was collected,
    /// e.g. bootstrap intervals).
    pub reproduces_study_job: Option<bool>,
}

/// One agent of the zoo.
#[derive(Debug, Clone)]
pub struct ZooAgent {
    /// Its folder (a run folder `eval`/`record` load).
    pub dir: PathBuf,
    /// Its provenance.
    pub provenance: Provenance,
    /// Total bytes of its files.
    pub bytes: u64,
}

impl ZooAgent {
    /// Its listing as JSON: `name` (`zoo:<model>/<task>`), `dir`, `bytes`, `provenance`
    /// (`zoo list --json` and the Python package's `zoo.agents()`).
    pub fn listing_json(&self) -> serde_json::Value {
        serde_json::json!({
            "name": format!("zoo:{}", self.provenance.name),
            "dir": self.dir,
            "bytes": self.bytes,
            "provenance": self.provenance,
        })
    }
}

/// Reads the zoo's index.
pub fn read_index(root: &Path) -> Result<ZooIndex, ZooError> {
    let p = root.join(INDEX);
    let text = std::fs::read_to_string(&p).map_err(|e| io(&p, e))?;
    let index: ZooIndex =
        serde_json::from_str(&text).map_err(|e| corrupt(&p, format!("not a zoo index: {e}")))?;
    for name in &index.agents {
        if !valid_name(name) {
            return Err(corrupt(
                &p,
                format!("field `agents`: `{name}` is not `<model>/<task>`"),
            ));
        }
    }
    Ok(index)
}

/// Whether `name` has the form `<model>/<task>` with plain components (no `..`, no
/// separators beyond the one).
fn valid_name(name: &str) -> bool {
    let parts: Vec<&str> = name.split('/').collect();
    parts.len() == 2
        && parts.iter().all(|p| {
            !p.is_empty()
                && *p != "."
                && *p != ".."
                && p.chars()
                    .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
        })
}

/// Checks a zoo agent's folder: `SHA256SUMS` records exactly [`AGENT_FILES`], every one is
/// a regular file matching its record, and the folder holds nothing else. Returns the
/// total bytes of the files.
pub fn verify_agent(dir: &Path) -> Result<u64, ZooError> {
    let records =
        integrity::read_manifest(dir).map_err(|e| corrupt(&dir.join(MANIFEST), e.to_string()))?;
    if records.is_empty() {
        return Err(corrupt(
            &dir.join(MANIFEST),
            "missing or empty: a zoo agent's files must be recorded",
        ));
    }
    let mut bytes = 0;
    for name in AGENT_FILES {
        let p = dir.join(name);
        let b = integrity::read_verified(&p).map_err(|e| corrupt(&p, e.to_string()))?;
        bytes += b.len() as u64;
    }
    for name in records.keys() {
        if !AGENT_FILES.contains(&name.as_str()) {
            return Err(corrupt(
                &dir.join(MANIFEST),
                format!(
                    "records `{name}`, which is not a zoo agent file ({})",
                    AGENT_FILES.join(", ")
                ),
            ));
        }
    }
    let entries = std::fs::read_dir(dir).map_err(|e| io(dir, e))?;
    for e in entries {
        let e = e.map_err(|e| io(dir, e))?;
        let name = e.file_name().to_string_lossy().into_owned();
        if name != MANIFEST && !AGENT_FILES.contains(&name.as_str()) {
            return Err(corrupt(
                &e.path(),
                "unexpected file in a zoo agent's folder (remove it, or the agent is not what was recorded)",
            ));
        }
    }
    Ok(bytes)
}

/// Reads and checks one agent of the zoo at `root` (`name` = `<model>/<task>`).
pub fn load_agent_entry(root: &Path, name: &str) -> Result<ZooAgent, ZooError> {
    let dir = root.join(name);
    let bytes = verify_agent(&dir)?;
    let p = dir.join("provenance.json");
    let text = std::fs::read_to_string(&p).map_err(|e| io(&p, e))?;
    let provenance: Provenance = serde_json::from_str(&text)
        .map_err(|e| corrupt(&p, format!("not a provenance record: {e}")))?;
    if provenance.name != name {
        return Err(corrupt(
            &p,
            format!(
                "field `name`: `{}`, but the folder is `{name}`",
                provenance.name
            ),
        ));
    }
    Ok(ZooAgent {
        dir,
        provenance,
        bytes,
    })
}

/// Every agent of the zoo at `root`, in index order, each checked.
pub fn list_agents(root: &Path) -> Result<Vec<ZooAgent>, ZooError> {
    read_index(root)?
        .agents
        .iter()
        .map(|n| load_agent_entry(root, n))
        .collect()
}

/// The zoo folder: `$CHRONOCOOKED_ZOO`, else `zoo/` (with an `index.json`) in the current
/// folder or an ancestor, else the compiled-in copy unpacked into the cache folder.
pub fn zoo_root() -> Result<PathBuf, ZooError> {
    if let Some(p) = std::env::var_os(ZOO_ENV) {
        let p = PathBuf::from(p);
        if !p.join(INDEX).is_file() {
            return Err(corrupt(
                &p.join(INDEX),
                format!("${ZOO_ENV} names a folder without a zoo index"),
            ));
        }
        return Ok(p);
    }
    if let Ok(cwd) = std::env::current_dir()
        && let Some(found) = cwd
            .ancestors()
            .map(|a| a.join("zoo"))
            .find(|z| z.join(INDEX).is_file())
    {
        return Ok(found);
    }
    embedded::unpack(&cache_dir())
}

/// The cache folder the compiled-in zoo is unpacked into.
pub fn cache_dir() -> PathBuf {
    let var = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    var(CACHE_ENV)
        .or_else(|| var("XDG_CACHE_HOME").map(|p| p.join("chronocooked")))
        .or_else(|| var("HOME").map(|p| p.join(".cache").join("chronocooked")))
        .unwrap_or_else(|| std::env::temp_dir().join("chronocooked-cache"))
}

/// The agent named `name` (`<model>/<task>`, with or without the `zoo:` prefix), checked.
pub fn find_agent(name: &str) -> Result<ZooAgent, ZooError> {
    let name = name.strip_prefix(ZOO_PREFIX).unwrap_or(name);
    let root = zoo_root()?;
    let index = read_index(&root)?;
    if !index.agents.iter().any(|a| a == name) {
        return Err(ZooError::Unknown {
            name: name.to_string(),
            known: index.agents.join(", "),
        });
    }
    load_agent_entry(&root, name)
}

/// A run folder argument: `zoo:<model>/<task>` becomes the zoo agent's checked folder,
/// anything else is returned as given.
pub fn resolve_run(arg: &Path) -> Result<PathBuf, ZooError> {
    match arg.to_str().and_then(|s| s.strip_prefix(ZOO_PREFIX)) {
        Some(name) => Ok(find_agent(name)?.dir),
        None => Ok(arg.to_path_buf()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_model_slash_task_without_path_tricks() {
        assert!(valid_name("lstm125/FixedInterval-v0"));
        for bad in ["lstm125", "a/b/c", "../x", "a/..", "a/b c", "/a", "a/"] {
            assert!(!valid_name(bad), "{bad}");
        }
    }

    #[test]
    fn a_plain_path_is_not_a_zoo_name() {
        assert_eq!(
            resolve_run(Path::new("runs/x")).unwrap(),
            PathBuf::from("runs/x")
        );
    }
}
