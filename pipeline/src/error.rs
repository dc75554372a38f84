//! Errors of the pipeline stages.

use std::path::PathBuf;

impl From<chronocooked_env::fs::WriteError> for PipelineError {
    fn from(e: chronocooked_env::fs::WriteError) -> Self {
        PipelineError::write(e.path, e.error)
    }
}

/// Why a stage could not run; messages name the file, the field or the job at fault.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// Training, run folders, configs, sweep files.
    #[error(transparent)]
    Train(#[from] chronocooked_training::TrainError),
    /// Task ids and task settings.
    #[error(transparent)]
    Env(#[from] chronocooked_env::EnvError),
    /// Another process is writing the folder, or it cannot be written.
    #[error(transparent)]
    Lock(#[from] chronocooked_env::fs::LockError),
    /// Analysis outputs (evaluation folders, metrics, figures, exports).
    #[error("{0}")]
    Analysis(String),
    /// Reading or writing a file.
    #[error("{action} {path}: {error}")]
    Io {
        /// `reading` or `writing`.
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// The underlying error.
        error: std::io::Error,
    },
    /// A file that does not hold what the stage reads from it.
    #[error("{path} is not {what}: {message}")]
    NotA {
        /// The file.
        path: PathBuf,
        /// What it should be (e.g. "an activity dataset (from `record`)").
        what: &'static str,
        /// The parser's message (line and column for JSON).
        message: String,
    },
    /// A request that cannot be carried out as asked (the message says what to change).
    #[error("{0}")]
    Invalid(String),
    /// A job id that the sweep file does not expand to.
    #[error("no job `{id}` in {file} (list them with `sweep {file} --dry-run`)")]
    UnknownJob {
        /// The id asked for.
        id: String,
        /// The sweep file.
        file: String,
    },
}

impl PipelineError {
    /// An analysis error (the analysis crate reports with messages).
    pub fn analysis(message: impl Into<String>) -> Self {
        PipelineError::Analysis(message.into())
    }

    /// An error reading `path`.
    pub fn read(path: impl Into<PathBuf>, error: std::io::Error) -> Self {
        PipelineError::Io {
            action: "reading",
            path: path.into(),
            error,
        }
    }

    /// An error writing (or creating) `path`.
    pub fn write(path: impl Into<PathBuf>, error: std::io::Error) -> Self {
        PipelineError::Io {
            action: "writing",
            path: path.into(),
            error,
        }
    }
}
