//! Typed errors for configuration, layouts, reset options and actions.
//!
//! Every message names the offending field and the values it accepts, so a
//! user can fix the input without reading the source.

use thiserror::Error;

/// Everything that can go wrong when building, resetting or stepping an env.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EnvError {
    /// A parameter has a value outside its allowed range.
    #[error("invalid value for `{field}`: {value} (allowed: {allowed})")]
    InvalidParam {
        /// Parameter name as used by `--set key=value`.
        field: String,
        /// The rejected value, as text.
        value: String,
        /// Human-readable description of the allowed values.
        allowed: String,
    },
    /// `--set key=value` named a key the task does not have.
    #[error("unknown parameter `{key}` for task {task} (known: {known})")]
    UnknownParam {
        /// The unknown key.
        key: String,
        /// The task id.
        task: String,
        /// Comma-separated known keys.
        known: String,
    },
    /// A `key=value` override could not be split or parsed.
    #[error("cannot parse override `{text}`: {reason}")]
    BadOverride {
        /// The raw override text.
        text: String,
        /// Why it was rejected.
        reason: String,
    },
    /// The task id is not registered.
    #[error("unknown task `{id}` (registered: {known})")]
    UnknownTask {
        /// The requested id.
        id: String,
        /// Comma-separated registered ids.
        known: String,
    },
    /// The layout is malformed or breaks the single-object-interaction rule.
    #[error("invalid layout: {reason}")]
    InvalidLayout {
        /// What is wrong, with the cell coordinates involved.
        reason: String,
    },
    /// An action index outside `0..=5`.
    #[error("invalid action {action} (allowed: 0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact)")]
    InvalidAction {
        /// The rejected action value.
        action: i64,
    },
    /// A reset option (start cell, TD) is not valid for this task.
    #[error("invalid reset option `{field}`: {value} (allowed: {allowed})")]
    InvalidResetOption {
        /// Option name (`start`, `td`).
        field: String,
        /// The rejected value.
        value: String,
        /// What is accepted.
        allowed: String,
    },
    /// `step` was called on an episode that already ended (call `reset`).
    #[error("step called after the episode ended: call reset first")]
    EpisodeOver,
    /// Writing an image or file failed.
    #[error("output error: {0}")]
    Output(String),
}

impl EnvError {
    /// Shorthand for [`EnvError::InvalidParam`].
    pub fn param(field: &str, value: impl ToString, allowed: impl Into<String>) -> Self {
        EnvError::InvalidParam {
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// Shorthand for [`EnvError::InvalidResetOption`].
    pub fn reset_option(field: &str, value: impl ToString, allowed: impl Into<String>) -> Self {
        EnvError::InvalidResetOption {
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}
