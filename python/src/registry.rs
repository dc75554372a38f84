//! The task registry for Python: ids, documentation and parameters.

use crate::errors::{env_err, value_err};
use chronocooked_env::task::params::{ParamRow, rows};
use chronocooked_env::{all_tasks, make_config};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

fn param_dict<'py>(py: Python<'py>, p: &ParamRow) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("key", &p.key)?;
    d.set_item("aliases", p.aliases.clone())?;
    d.set_item("type", &p.kind)?;
    d.set_item("default", &p.default)?;
    d.set_item("allowed", &p.allowed)?;
    d.set_item("doc", &p.doc)?;
    Ok(d)
}

/// Every registered task: a list of dicts with `id`, `family`, `tags`, `summary`,
/// `description`, `source`, `params` (key, aliases, type, default, allowed values, doc;
/// common parameters included) and `reset_options` (key, doc: what `reset(options=…)`
/// takes), generated from the task family's declarations.
#[pyfunction]
pub fn tasks(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for t in all_tasks() {
        let d = PyDict::new(py);
        d.set_item("id", t.id)?;
        d.set_item("family", format!("{:?}", t.family))?;
        d.set_item("tags", t.tags.to_vec())?;
        d.set_item("summary", t.summary)?;
        d.set_item("description", t.description)?;
        d.set_item("source", t.source)?;
        let params = PyList::empty(py);
        for p in rows(&t.default_config()) {
            params.append(param_dict(py, &p)?)?;
        }
        d.set_item("params", params)?;
        let resets = PyList::empty(py);
        for o in chronocooked_env::task::family::reset_options_of(t.id).unwrap_or_default() {
            let r = PyDict::new(py);
            r.set_item("key", o.key())?;
            r.set_item("doc", o.doc())?;
            resets.append(r)?;
        }
        d.set_item("reset_options", resets)?;
        out.append(d)?;
    }
    Ok(out)
}

/// Validates `overrides` for `task` and returns the resolved configuration as JSON text
/// (`ValueError` naming the field and the allowed values otherwise).
#[pyfunction]
pub fn resolve(task: &str, overrides: Vec<String>) -> PyResult<String> {
    let config = make_config(task, &overrides).map_err(env_err)?;
    serde_json::to_string(&config).map_err(|e| value_err(e.to_string()))
}
