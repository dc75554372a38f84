//! `fingerprint`: which timing mechanism does a Python agent resemble? The agent's policies
//! play the mechanisms protocol ([`PROTOCOL`]); its signature is placed among the
//! committed mechanism signatures (see `chronocooked_present::fingerprint`).

use crate::agent::PyAgent;
use crate::errors::{env_err, runtime_err, value_err};
use chronocooked_analysis::neural::probe::probe_task;
use chronocooked_env::Task;
use chronocooked_models::timing::agent::NOISE_DRAWS;
use chronocooked_present::fingerprint::{
    ConditionPlay, PROTOCOL, ProtocolCondition, play_condition, write_and_place,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyMapping};
use std::path::PathBuf;

/// The condition's task parameters as a dict of integers (`{"td": 6}`).
fn params<'py>(py: Python<'py>, c: &ProtocolCondition) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (key, value) in c.to_task().map_err(env_err)?.values_set() {
        let Some(n) = value.as_u64() else {
            return Err(runtime_err(format!(
                "protocol parameter `{key}` is not an integer: {value}"
            )));
        };
        d.set_item(key, n)?;
    }
    Ok(d)
}

/// The policy for condition `c`: `policies[c.name]` from a mapping, or
/// `policies(task, params)` from a factory; `None` when the agent has none for it (the key
/// is absent, or the factory returned `None`). A mapping with a key that is no condition
/// is refused (a typo would silently drop a condition).
fn policy_for<'py>(
    py: Python<'py>,
    policies: &Bound<'py, PyAny>,
    c: &ProtocolCondition,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let names: Vec<&str> = PROTOCOL.iter().map(|c| c.name).collect();
    if let Ok(m) = policies.cast::<PyMapping>() {
        for key in m.keys()?.iter() {
            let k: String = key.extract().unwrap_or_default();
            if !names.contains(&k.as_str()) {
                return Err(value_err(format!(
                    "`policies` has a key `{}` that is no condition of the protocol (allowed: {})",
                    key.repr().map_or_else(|_| "?".into(), |r| r.to_string()),
                    names.join(", ")
                )));
            }
        }
        return Ok(if m.contains(c.name)? {
            Some(m.get_item(c.name)?).filter(|p| !p.is_none())
        } else {
            None
        });
    }
    if policies.is_callable() {
        let p = policies.call1((c.task, params(py, c)?))?;
        return Ok((!p.is_none()).then_some(p));
    }
    Err(value_err(format!(
        "`policies` must be a callable make_policy(task, params) -> policy, or a mapping \
         condition -> policy with keys among {}",
        names.join(", ")
    )))
}

/// Every task the agent of condition `c` meets: its protocol's conditions and the probe
/// trials.
fn tasks_of(c: &ProtocolCondition) -> PyResult<Vec<Task>> {
    let task = c.to_task().map_err(env_err)?;
    let mut out: Vec<Task> = Vec::new();
    for cond in chronocooked_analysis::reference_conditions(&task).map_err(env_err)? {
        if !out.contains(&cond.task) {
            out.push(cond.task);
        }
    }
    if let Some(td) = c.probe_td {
        out.push(probe_task(&task, &[td]).map_err(runtime_err)?);
    }
    Ok(out)
}

/// Plays the mechanisms protocol with the user's policies and writes the fingerprint into
/// `out`; returns the placement as a dict (see `chronocooked.fingerprint`).
#[pyfunction]
#[pyo3(signature = (policies, out, seed = 0, obs_mode = "codes", units_correspond = false, name = "python-agent", draws = NOISE_DRAWS, resamples = 1000))]
#[allow(clippy::too_many_arguments)]
pub fn fingerprint<'py>(
    py: Python<'py>,
    policies: Bound<'py, PyAny>,
    out: PathBuf,
    seed: u64,
    obs_mode: &str,
    units_correspond: bool,
    name: &str,
    draws: usize,
    resamples: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let onehot = crate::agent::onehot_and_name(obs_mode, name)?;
    if !(1..=256).contains(&draws) {
        return Err(value_err(format!(
            "invalid value for `draws`: {draws} (allowed: 1..=256 episodes per start cell; the \
             lab's noisy timing models get {NOISE_DRAWS})"
        )));
    }
    if !(1..=100_000).contains(&resamples) {
        return Err(value_err(format!(
            "invalid value for `resamples`: {resamples} (allowed: 1..=100000)"
        )));
    }
    // Play every condition first: a failing policy leaves nothing behind.
    let mut plays: Vec<ConditionPlay> = Vec::new();
    for c in &PROTOCOL {
        let Some(policy) = policy_for(py, &policies, c)? else {
            continue;
        };
        let mut agent = PyAgent::new(py, policy, name, onehot, &tasks_of(c)?, draws)?;
        let play = play_condition(&mut agent, c, seed).map_err(|e| runtime_err(e.to_string()))?;
        if let Some((episode, step, cause)) = agent.error.take() {
            let err = crate::errors::PolicyError::new_err(format!(
                "the policy failed in condition {} ({} {}) at episode {episode}, step {step}: {}",
                c.name,
                c.task,
                c.env.join(" "),
                cause.value(py)
            ));
            let value = err.value(py);
            for (k, v) in [("episode", episode), ("step", step)] {
                let _ = value.setattr(k, v);
            }
            let _ = value.setattr("task", c.task);
            let _ = value.setattr("condition", c.name);
            let _ = value.setattr("td", c.probe_td.unwrap_or(0));
            err.set_cause(py, Some(cause));
            return Err(err);
        }
        plays.push(play);
    }
    if plays.is_empty() {
        return Err(value_err(format!(
            "`policies` gave no policy for any condition (conditions: {})",
            PROTOCOL
                .iter()
                .map(|c| c.name)
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let (fingerprint, files) =
        write_and_place(&out, &plays, name, units_correspond, seed, resamples)
            .map_err(|e| pyo3::exceptions::PyOSError::new_err(e.to_string()))?;
    let view = |p: &chronocooked_present::fingerprint::Placement| {
        serde_json::json!({
            "missing": p.missing,
            "distances": p.distances,
            "nearest": p.nearest,
            "identified": p.identified,
            "verdict": chronocooked_present::fingerprint::verdict(p),
            "reference_identification": p.reference_identification,
        })
    };
    let units = &fingerprint.units;
    // Top-level placement keys: the unit view (as before the dynamics view existed); the
    // two views side by side under `units` and `dynamics`.
    let json = serde_json::json!({
        "out": out,
        "conditions": plays.iter().map(|p| p.condition.name).collect::<Vec<_>>(),
        "model": units.model,
        "signature": units.signature,
        "missing": units.missing,
        "distances": units.distances,
        "nearest": units.nearest,
        "identified": units.identified,
        "verdict": chronocooked_present::fingerprint::verdict(units),
        "reference_identification": units.reference_identification,
        "units": view(units),
        "dynamics": view(&fingerprint.dynamics),
        "views_agree": fingerprint.views_agree(),
        "agreement": chronocooked_present::fingerprint::agreement(&fingerprint),
        "files": files,
    });
    crate::info::to_py(py, &json)
}

/// The neural summary of an activity dataset (an evaluation folder with `activity.json`,
/// or the file itself), written beside it as `activity.summary.json`; returns the list of
/// per-population summaries (dicts).
#[pyfunction]
#[pyo3(signature = (path, units_correspond = false, seed = 0))]
pub fn summarize<'py>(
    py: Python<'py>,
    path: PathBuf,
    units_correspond: bool,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let (_, summaries) =
        chronocooked_analysis::neural::probe::summarize_file(&path, units_correspond, seed)
            .map_err(value_err)?;
    crate::info::to_py(py, &summaries)
}

/// The distance between two fingerprint folders' signatures in `view` (`dynamics` or
/// `units`), on the committed mechanisms' scale (see `chronocooked.distance`).
#[pyfunction]
#[pyo3(signature = (a, b, view = "dynamics"))]
pub fn fingerprint_distance(a: PathBuf, b: PathBuf, view: &str) -> PyResult<f64> {
    use chronocooked_analysis::mechanisms::{Signature, View, signature_distance};
    let view = match view {
        "dynamics" => View::Dynamics,
        "units" => View::Units,
        other => {
            return Err(value_err(format!(
                "invalid value for `view`: {other:?} (allowed: \"dynamics\", \"units\")"
            )));
        }
    };
    let read = |dir: &std::path::Path| -> PyResult<Signature> {
        chronocooked_present::fingerprint::read_signature(dir).map_err(value_err)
    };
    let reference = chronocooked_present::fingerprint::reference_signatures();
    Ok(signature_distance(&read(&a)?, &read(&b)?, &reference, view))
}
