//! Typed errors of the training crate.

use thiserror::Error;

/// Everything that can go wrong configuring, running or resuming training.
#[derive(Debug, Error)]
pub enum TrainError {
    /// A setting has a value outside what it accepts.
    #[error("invalid value `{value}` for `{field}` (allowed: {allowed})")]
    InvalidParam {
        /// Setting name.
        field: String,
        /// Value given.
        value: String,
        /// What is accepted.
        allowed: String,
    },
    /// An override names no setting of the configuration.
    #[error(
        "unknown setting `{key}` (allowed: {allowed}; `chronocooked zoo show MODEL` lists them with their values)"
    )]
    UnknownKey {
        /// Key given.
        key: String,
        /// The configuration's keys.
        allowed: String,
    },
    /// An override is not `key=value`.
    #[error("override `{0}` is not of the form key=value")]
    BadOverride(String),
    /// No preset of that name.
    #[error("unknown preset `{name}` (allowed: {allowed})")]
    UnknownPreset {
        /// Name given.
        name: String,
        /// Known presets.
        allowed: String,
    },
    /// A preset file is malformed (a bug in the shipped presets or a user file).
    #[error("preset file {file}: {message}")]
    PresetFile {
        /// File name.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// The burn module and the native engine's parameter specification disagree (a bug,
    /// reported instead of training on misread parameters).
    #[error("model definition mismatch: {0}")]
    SpecMismatch(String),
    /// The environment rejected the task or its overrides.
    #[error(transparent)]
    Env(#[from] chronocooked_env::EnvError),
    /// A loss or parameter became NaN/inf, or the loss exploded.
    #[error(
        "training diverged at env step {step}: {what}. The last good checkpoint is kept in {checkpoint}; lower learning_rate or max_grad_norm and resume from it"
    )]
    Diverged {
        /// Env step of the failed update.
        step: u64,
        /// What was non-finite.
        what: String,
        /// Checkpoint left in place.
        checkpoint: String,
    },
    /// Reading or writing the run folder failed.
    #[error("{path}: {source}")]
    Io {
        /// File involved.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// A sweep file is not valid TOML or does not describe a sweep.
    #[error("sweep file {file}: {message}")]
    SweepFile {
        /// File name.
        file: String,
        /// What is wrong (with the line and column for TOML errors).
        message: String,
    },
    /// A job of a sweep has settings its run would refuse.
    #[error("job {id}: {message}")]
    Job {
        /// The job id.
        id: String,
        /// What its run would refuse.
        message: String,
    },
    /// A run's `config.json` is unreadable or fails the configuration's checks.
    #[error("{file}: {message}")]
    ConfigFile {
        /// The file.
        file: String,
        /// What is wrong (the field and its allowed values for a range error).
        message: String,
    },
    /// A folder given as a run folder holds no run.
    #[error(
        "{path} is not a run folder (no config.json): give a folder written by `chronocooked train --out`; if that `train` stopped before it wrote its config.json (out of disk, killed), run the `chronocooked train` command again"
    )]
    NotARun {
        /// Folder.
        path: String,
    },
    /// A folder the lab began to write as a run (its records or lock file are there) whose
    /// `config.json` was never written: the first write of `train` failed (out of disk,
    /// killed). Nothing in it can be resumed.
    #[error(
        "{path}: the run never started (the lab's files are there but no config.json: its first \
         write failed, out of disk or killed); nothing of it can be resumed: run the \
         `chronocooked train` command again with `--out {path}`"
    )]
    NeverStarted {
        /// Folder.
        path: String,
    },
    /// A checkpoint's state does not fit the run's configuration (wrapped with the file by
    /// the caller that read it).
    #[error("checkpoint {0}")]
    BadState(crate::ppo::state::StateError),
    /// A file of learned state is missing its SHA-256 record, does not match it, or is not a
    /// regular file.
    #[error(transparent)]
    Integrity(#[from] chronocooked_env::integrity::IntegrityError),
    /// A file of learned state or its content is corrupt.
    #[error("{path}: {reason}")]
    Corrupt {
        /// The file.
        path: String,
        /// What is wrong (the field where there is one).
        reason: String,
    },
    /// Checkpoints exist but none can be used.
    #[error(
        "cannot resume {dir}: no valid checkpoint ({skipped}). To start over, remove the run folder (or its checkpoints/ folder and curves.csv) and train without --resume"
    )]
    NoValidCheckpoint {
        /// The run folder.
        dir: String,
        /// Every checkpoint tried, with why it was refused.
        skipped: String,
    },
    /// Another process is writing the run folder (or it cannot be written at all).
    #[error(transparent)]
    Lock(#[from] chronocooked_env::fs::LockError),
    /// Training stopped on SIGINT / SIGTERM after saving a checkpoint.
    #[error(
        "{dir}: training stopped by {signal_name} at env step {steps} after saving a checkpoint; continue it with `chronocooked train --resume {dir}`"
    )]
    Interrupted {
        /// The run folder.
        dir: String,
        /// The signal's number (2 = SIGINT, 15 = SIGTERM).
        signal: i32,
        /// Its name.
        signal_name: String,
        /// Env steps trained (those of the checkpoint).
        steps: u64,
    },
    /// A run folder or checkpoint is incomplete or does not match.
    #[error("cannot resume from {path}: {reason}")]
    Resume {
        /// Folder.
        path: String,
        /// Why.
        reason: String,
    },
}

impl TrainError {
    /// Shorthand for [`TrainError::InvalidParam`].
    pub fn param(field: &str, value: impl ToString, allowed: &str) -> Self {
        TrainError::InvalidParam {
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }

    /// Wraps an I/O error with the path involved.
    pub fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        TrainError::Io {
            path: path.display().to_string(),
            source,
        }
    }
}

impl From<chronocooked_env::fs::WriteError> for TrainError {
    fn from(e: chronocooked_env::fs::WriteError) -> Self {
        TrainError::io(&e.path, e.error)
    }
}
