//! What every run folder shares, PPO or timing model: its `config.json` — written with its
//! SHA-256 record, read back checked, and the fields every kind of run has
//! ([`RunHeader`]) — and the `command.txt` lines. The PPO run folder is
//! [`crate::ppo::run_dir`], the timing run's [`crate::timing_run`].

use crate::error::TrainError;
use chronocooked_env::integrity;
use chronocooked_models::run_folder;
use serde::Deserialize;
use std::path::Path;

/// The text of the run folder `dir`'s `config.json` (PPO or timing model), checked against
/// its SHA-256 record when the folder has one (runs written since records were kept): a
/// hand-edited config is refused naming the file. A folder without the file is "not a run
/// folder".
pub fn read_config_text(dir: &Path) -> Result<String, TrainError> {
    let p = dir.join(run_folder::CONFIG);
    if !p.is_file() {
        return Err(TrainError::NotARun {
            path: dir.display().to_string(),
        });
    }
    let bytes = integrity::read_checked(&p)?;
    String::from_utf8(bytes).map_err(|_| TrainError::ConfigFile {
        file: p.display().to_string(),
        message: "not UTF-8 text".into(),
    })
}

/// The fields every run folder's `config.json` shares, PPO or timing model: what a reader
/// needs before it knows which kind of run it has (the full configurations are
/// [`crate::TrainConfig`] and [`crate::TimingRunConfig`]).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct RunHeader {
    /// Task id (runs written before the field existed trained on `FixedInterval-v0`).
    #[serde(default = "first_task")]
    pub task: String,
    /// Task overrides (`key=value`).
    #[serde(default)]
    pub env: Vec<String>,
    /// Training seed.
    #[serde(default)]
    pub seed: Option<u64>,
}

fn first_task() -> String {
    "FixedInterval-v0".into()
}

impl RunHeader {
    /// The header of `dir`'s `config.json` ([`read_config_text`]: checked against its
    /// SHA-256 record); errors name the file.
    pub fn read(dir: &Path) -> Result<Self, TrainError> {
        let text = read_config_text(dir)?;
        serde_json::from_str(&text).map_err(|e| TrainError::Resume {
            path: dir.join(run_folder::CONFIG).display().to_string(),
            reason: e.to_string(),
        })
    }
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
