//! Rust errors as Python exceptions.

use chronocooked_env::EnvError;
use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};

pyo3::create_exception!(
    chronocooked,
    PolicyError,
    PyRuntimeError,
    "A Python policy failed during `evaluate`: it raised (the original exception is the \
     `__cause__`), or returned an action outside 0..=5, a non-integer action, or activity that \
     changed length or held NaN/inf. The message and the attributes `episode` (1-based, in \
     protocol order), `step` (1-based within the episode), `task` and `td` say where. Nothing \
     is written to the output folder."
);

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

/// Reset options from the Python arguments (`context`: the reproduction task's prior and
/// gain indices); per-oven lists of more than 3 values are a `ValueError` naming the option.
pub fn reset_options(
    start: Option<(usize, usize)>,
    td: Option<u32>,
    never_ready: Option<bool>,
    oven_tds: Option<Vec<u32>>,
    on_times: Option<Vec<u32>>,
    context: (Option<u8>, Option<u8>),
) -> Result<chronocooked_env::ResetOptions, PyErr> {
    let per_oven = |field: &str, v: Option<Vec<u32>>| {
        v.map(|v| chronocooked_env::PerOven::new(field, &v))
            .transpose()
            .map_err(env_err)
    };
    Ok(chronocooked_env::ResetOptions {
        start,
        td,
        never_ready,
        oven_tds: per_oven("oven_tds", oven_tds)?,
        on_times: per_oven("on_times", on_times)?,
        prior: context.0,
        gain: context.1,
    })
}
