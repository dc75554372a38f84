//! Rust errors as Python exceptions.

use chronocooked_env::EnvError;
use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};

/// A Rust env error as a Python exception: bad parameters, actions and options become
/// `ValueError` (the message names the field and the allowed values); stepping a finished
/// episode `RuntimeError`; output errors `OSError`.
pub fn env_err(e: EnvError) -> PyErr {
    match e {
        EnvError::Output(_) => PyOSError::new_err(e.to_string()),
        EnvError::EpisodeOver => PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// A `ValueError` with `msg`.
pub fn value_err(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// A `RuntimeError` with `msg` (failures that are not the caller's input).
pub fn runtime_err(msg: impl Into<String>) -> PyErr {
    PyRuntimeError::new_err(msg.into())
}
