//! Studies from Python: `paper collect`, `paper analyse` and `mechanisms` on a sweep's
//! output and its compact results, as the CLI runs them.

use crate::info::to_py;
use chronocooked_analysis::mechanisms::MechanismError;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;

/// `paper collect` from Python: writes the compact results of every finished job of the
/// sweep output `sweep_out` into `out` (`out/jobs/<job id>/`, the layout `report
/// --baselines`, `paper analyse` and `mechanisms` read); returns `(written, unfinished)`.
#[pyfunction]
pub fn collect(sweep_out: PathBuf, out: PathBuf) -> PyResult<(usize, usize)> {
    chronocooked_analysis::collect::collect(&sweep_out, &out)
        .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// `paper analyse` from Python: the paper's analyses of the compact results `results`,
/// written into that folder; returns the study as a dict plus `report` and `figures`.
#[pyfunction]
pub fn analyse<'py>(py: Python<'py>, results: PathBuf) -> PyResult<Bound<'py, PyAny>> {
    let a = chronocooked_paper::analyse::analyse_folder(&results)
        .map_err(|e| PyOSError::new_err(e.to_string()))?;
    let d = to_py(py, &a.study)?;
    d.set_item("report", a.report)?;
    d.set_item("figures", a.figures)?;
    Ok(d)
}

/// `mechanisms` from Python: every model's signature in the compact results `results`,
/// the leave-one-seed-out identification of the timing mechanisms and every agent's
/// nearest mechanism, written into `out` (default `results`); returns a dict (`files`,
/// `signatures`, `agents`, `held_out`, `verdicts`).
#[pyfunction]
#[pyo3(signature = (results, out = None, resamples = 1000, seed = 0))]
pub fn mechanisms<'py>(
    py: Python<'py>,
    results: PathBuf,
    out: Option<PathBuf>,
    resamples: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    if !(1..=100_000).contains(&resamples) {
        return Err(PyValueError::new_err(format!(
            "invalid value for `resamples`: {resamples} (allowed: 1..=100000)"
        )));
    }
    let out = out.unwrap_or_else(|| results.clone());
    let w = chronocooked_present::mechanisms::write_tables(
        &results,
        &out,
        resamples,
        seed,
        &chronocooked_analysis::mechanisms::View::ALL,
    )
    .map_err(|e| match e {
        MechanismError::Empty(_) => PyValueError::new_err(e.to_string()),
        MechanismError::File { .. } => PyOSError::new_err(e.to_string()),
    })?;
    let d = pyo3::types::PyDict::new(py);
    d.set_item("files", w.files)?;
    d.set_item("signatures", w.signatures)?;
    d.set_item("agents", w.agents)?;
    // Top level: the unit view (as before the dynamics view); both under `views`.
    let units = &w.identifications[0];
    d.set_item("held_out", to_py(py, &units.held_out)?)?;
    d.set_item("verdicts", to_py(py, &units.agents)?)?;
    let views = pyo3::types::PyDict::new(py);
    for id in &w.identifications {
        let v = pyo3::types::PyDict::new(py);
        v.set_item("held_out", to_py(py, &id.held_out)?)?;
        v.set_item("verdicts", to_py(py, &id.agents)?)?;
        views.set_item(id.view.key(), v)?;
    }
    d.set_item("views", views)?;
    Ok(d.into_any())
}
