//! `chronocooked._core`: the Rust side of the Python package.
//!
//! * [`env`] — one Chronocooked env (`Env`): reset/step with fresh numpy arrays, spaces,
//!   ANSI and RGB rendering;
//! * [`vector`] — N envs stepped in Rust (`VecEnv`), batched numpy outputs;
//! * [`info`] — the Rust `Info` as a dict of plain Python values, or a dict of arrays;
//! * [`agent`] — a Python policy as a lab agent (actions, state, named activity);
//! * [`evaluate`] — the lab's evaluation protocol with a Python policy;
//! * [`fingerprint`] — the mechanisms protocol with a Python agent's policies, its
//!   placement among the timing mechanisms, and the neural summary of any recording;
//! * [`record`] — a Python policy's activity on probe trials, with its neural summary;
//! * [`export`] — activity and evaluation records as NPZ/CSV/JSON (`chronocooked export`);
//! * [`study`] — `paper collect`, `paper analyse` and `mechanisms` on a study's results;
//! * [`registry`] — the task registry and parameter documentation;
//! * [`zoo`] — the zoo of trained agents (`ZooPolicy`) and the leaderboard (`report`);
//! * [`errors`] — Rust errors as Python exceptions (`ValueError` for bad input).
//!
//! The gymnasium classes live in Python (`chronocooked/envs.py`) on top of these.

#![warn(missing_docs)]

mod agent;
mod env;
mod errors;
mod evaluate;
mod export;
mod fingerprint;
mod info;
mod record;
mod registry;
mod study;
mod vector;
mod zoo;

use pyo3::prelude::*;

/// Panics on purpose: the test suite checks that a Rust panic reaches Python as an
/// exception (`pyo3_runtime.PanicException`) and the interpreter goes on.
#[pyfunction]
fn _panic_for_tests() {
    panic!("deliberate panic (test of the panic boundary)");
}

/// The extension module `chronocooked._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<env::Env>()?;
    m.add_class::<vector::VecEnv>()?;
    m.add_function(wrap_pyfunction!(registry::tasks, m)?)?;
    m.add_function(wrap_pyfunction!(registry::resolve, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::evaluate, m)?)?;
    m.add("PolicyError", m.py().get_type::<errors::PolicyError>())?;
    m.add_function(wrap_pyfunction!(fingerprint::fingerprint, m)?)?;
    m.add_function(wrap_pyfunction!(fingerprint::summarize, m)?)?;
    m.add_function(wrap_pyfunction!(fingerprint::fingerprint_distance, m)?)?;
    m.add_function(wrap_pyfunction!(record::record, m)?)?;
    m.add_function(wrap_pyfunction!(export::export, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::reference_conditions, m)?)?;
    m.add_class::<zoo::ZooPolicy>()?;
    m.add_function(wrap_pyfunction!(zoo::zoo_agents, m)?)?;
    m.add_function(wrap_pyfunction!(zoo::report, m)?)?;
    m.add_function(wrap_pyfunction!(zoo::probability_of_improvement, m)?)?;
    m.add_function(wrap_pyfunction!(zoo::iqm, m)?)?;
    m.add_function(wrap_pyfunction!(study::collect, m)?)?;
    m.add_function(wrap_pyfunction!(study::analyse, m)?)?;
    m.add_function(wrap_pyfunction!(study::mechanisms, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    m.add("EVENT_FLAGS", info::event_flags(m.py())?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
