//! Rust errors as Python exceptions.

use chronocooked_env::task;
use chronocooked_env::{BASIC_RESET_OPTIONS, EnvError, PerOven, ResetOption, ResetOptions};
use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

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

/// Reset options from Python's `options` dict, each key read as the option of that name
/// ([`ResetOption`]): an unknown key, or a value of the wrong kind, is a `ValueError` naming
/// the task's own options with their values; an option the task's family does not declare
/// is refused by `reset` (naming the tasks that take it). `reset_mask` (the vector env's own)
/// and `None` values are skipped.
pub fn reset_options(
    task: &str,
    options: Option<&Bound<'_, PyAny>>,
) -> Result<ResetOptions, PyErr> {
    let mut out = ResetOptions::default();
    let Some(options) = options.filter(|o| !o.is_none()) else {
        return Ok(out);
    };
    let Ok(options) = options.cast::<PyDict>() else {
        return Err(value_err(format!(
            "invalid value for `options`: {options} (allowed: a dict or None)"
        )));
    };
    let declared = task::family::reset_options_of(task).unwrap_or(BASIC_RESET_OPTIONS);
    let allowed = declared
        .iter()
        .map(|o| format!("{}: {}", o.key(), o.doc()))
        .collect::<Vec<_>>()
        .join("; ");
    for (key, value) in options.iter() {
        let key: String = key
            .extract()
            .map_err(|_| value_err(format!("reset option keys are strings, not {key}")))?;
        if key == "reset_mask" || value.is_none() {
            continue;
        }
        let Some(option) = ResetOption::from_key(&key) else {
            return Err(value_err(format!(
                "unknown reset option `{key}` for {task} (allowed: {allowed})"
            )));
        };
        let bad = || {
            value_err(format!(
                "invalid reset option `{key}`: {value} (allowed: {})",
                option.doc()
            ))
        };
        let per_oven = |v: Vec<u32>| PerOven::new(&key, &v).map_err(env_err);
        match option {
            ResetOption::Start => {
                let cell: Vec<usize> = value.extract().map_err(|_| bad())?;
                let [r, c] = cell[..] else {
                    return Err(bad());
                };
                out.start = Some((r, c));
            }
            ResetOption::Td => out.td = Some(value.extract().map_err(|_| bad())?),
            ResetOption::NeverReady => out.never_ready = Some(value.extract().map_err(|_| bad())?),
            ResetOption::OvenTds => {
                out.oven_tds = Some(per_oven(value.extract().map_err(|_| bad())?)?)
            }
            ResetOption::OnTimes => {
                out.on_times = Some(per_oven(value.extract().map_err(|_| bad())?)?)
            }
            ResetOption::Prior => out.prior = Some(value.extract().map_err(|_| bad())?),
            ResetOption::Gain => out.gain = Some(value.extract().map_err(|_| bad())?),
        }
    }
    Ok(out)
}
