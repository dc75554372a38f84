//! What every run folder shares, PPO or timing model: its `config.json` — written with its
//! SHA-256 record, read back checked, and the fields every kind of run has
//! ([`RunFolder`]) — and the `command.txt` lines. The PPO run folder is
//! [`crate::ppo::run_dir`], the timing run's [`crate::timing_run`].

use crate::error::TrainError;
use chronocooked_env::integrity;
use chronocooked_env::{Task, TaskConfig};
use chronocooked_models::run_folder;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The error for a folder without `config.json`: [`TrainError::NeverStarted`] when the lab
/// began to write a run there (its `SHA256SUMS`, `command.txt`, lock or temporary files),
/// else [`TrainError::NotARun`].
pub fn not_a_run(dir: &Path) -> TrainError {
    let traces = std::fs::read_dir(dir).is_ok_and(|rd| {
        rd.flatten().any(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name == integrity::MANIFEST
                || name == run_folder::COMMAND
                || name == chronocooked_env::fs::lock::LOCK_FILE
                || chronocooked_env::fs::is_temp_name(&name)
        })
    });
    let path = dir.display().to_string();
    if traces {
        TrainError::NeverStarted { path }
    } else {
        TrainError::NotARun { path }
    }
}

/// The text of the run folder `dir`'s `config.json` (PPO or timing model), checked against
/// its SHA-256 record when the folder has one (runs written since records were kept): a
/// hand-edited config is refused naming the file. A folder without the file is "not a run
/// folder".
pub fn read_config_text(dir: &Path) -> Result<String, TrainError> {
    let p = dir.join(run_folder::CONFIG);
    if !p.is_file() {
        return Err(not_a_run(dir));
    }
    let bytes = integrity::read_checked(&p)?;
    String::from_utf8(bytes).map_err(|_| TrainError::ConfigFile {
        file: p.display().to_string(),
        message: "not UTF-8 text".into(),
    })
}

/// Which kind of agent a run folder holds (its `config.json`'s `kind`: `"timing"` for a
/// timing model, absent for PPO).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunKind {
    /// A PPO policy ([`crate::TrainConfig`], [`crate::ppo::run_dir`]).
    Ppo,
    /// A timing model's agent ([`crate::TimingRunConfig`], [`crate::timing_run`]).
    Timing,
}

/// The fields every `config.json` shares, PPO or timing model, in one serde schema (the
/// full configurations are [`crate::TrainConfig`] and [`crate::TimingRunConfig`]).
#[derive(Debug, Clone, PartialEq, Deserialize)]
struct SharedConfig {
    /// `"timing"` for a timing-model run; absent for PPO runs.
    #[serde(default)]
    kind: Option<String>,
    /// Task id (runs written before the field existed trained on `FixedInterval-v0`).
    #[serde(default = "first_task")]
    task: String,
    /// The task's parameters ([`Task`]'s `env`).
    #[serde(default)]
    env: Option<serde_json::Value>,
    /// Training seed.
    #[serde(default)]
    seed: Option<u64>,
}

fn first_task() -> String {
    "FixedInterval-v0".into()
}

/// A run folder opened for reading, PPO or timing model: what a reader needs before it
/// knows which kind of run it has — the kind, the task (its id and parameters, and the
/// validated [`TaskConfig`]), the seed and whether the run finished — read from `config.json`
/// ([`read_config_text`]: checked against its SHA-256 record). The one reader of what every
/// run's `config.json` shares; the kinds' own loaders ([`crate::ppo::run_dir`],
/// [`crate::timing_run::load_timing_config`]) read the rest.
#[derive(Debug, Clone, PartialEq)]
pub struct RunFolder {
    /// The folder.
    pub path: PathBuf,
    /// PPO or timing model.
    pub kind: RunKind,
    /// The task and its parameters.
    pub task: Task,
    /// Training seed (`None` in folders written before it was stored).
    pub seed: Option<u64>,
}

impl RunFolder {
    /// Opens `dir`: "not a run folder" without `config.json`; errors name the file.
    pub fn open(dir: &Path) -> Result<Self, TrainError> {
        let text = read_config_text(dir)?;
        let file = || dir.join(run_folder::CONFIG).display().to_string();
        let shared: SharedConfig = serde_json::from_str(&text).map_err(|e| TrainError::Resume {
            path: file(),
            reason: e.to_string(),
        })?;
        let kind = match shared.kind.as_deref() {
            None => RunKind::Ppo,
            Some("timing") => RunKind::Timing,
            Some(other) => {
                return Err(TrainError::ConfigFile {
                    file: file(),
                    message: format!("`kind`: {other:?} (allowed: \"timing\", or absent for PPO)"),
                });
            }
        };
        let env = shared.env.unwrap_or_else(|| serde_json::json!({}));
        let fields = serde_json::json!({ "task": shared.task, "env": env });
        let task = Task::deserialize(fields).map_err(|e| TrainError::ConfigFile {
            file: file(),
            message: e.to_string(),
        })?;
        Ok(RunFolder {
            path: dir.to_path_buf(),
            kind,
            task,
            seed: shared.seed,
        })
    }

    /// The task the run trained on, validated as a whole; errors name `config.json`.
    pub fn task_config(&self) -> Result<TaskConfig, TrainError> {
        self.task.config().map_err(|e| TrainError::ConfigFile {
            file: self.path.join(run_folder::CONFIG).display().to_string(),
            message: e.to_string(),
        })
    }

    /// Whether the run finished (its `summary.json`, written last, exists).
    pub fn finished(&self) -> bool {
        self.path.join(run_folder::SUMMARY).is_file()
    }
}

/// Whether `dir`'s `config.json` says it is a timing-model run, read without the integrity
/// check or any other field: a damaged timing config is still recognised as one, so
/// loading it reports what is wrong rather than a PPO config error.
pub fn says_timing(dir: &Path) -> bool {
    #[derive(Deserialize)]
    struct KindOnly {
        #[serde(default)]
        kind: Option<String>,
    }
    std::fs::read_to_string(dir.join(run_folder::CONFIG))
        .ok()
        .and_then(|t| serde_json::from_str::<KindOnly>(&t).ok())
        .is_some_and(|k| k.kind.as_deref() == Some("timing"))
}

/// Writes a run's `config.json` with its SHA-256 record (so later edits are seen).
pub fn write_config(dir: &Path, json: &[u8]) -> Result<(), TrainError> {
    integrity::write_recorded(&dir.join(run_folder::CONFIG), json)?;
    Ok(())
}

/// Appends `line` to `path` (created with the process umask if missing).
pub fn append_line(path: &Path, line: &str) -> Result<(), TrainError> {
    chronocooked_env::fs::append(path, line).map_err(|e| TrainError::io(path, e))
}
