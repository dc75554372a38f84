//! `record`: a Python policy's neural activity, as `chronocooked record` records a run's
//! (`record_dataset` over every free start cell × TD, repeated), with its NPZ export and
//! neural summary.

use crate::agent::PyAgent;
use crate::errors::{env_err, runtime_err, value_err};
use chronocooked_analysis::neural::probe::{can_probe, population_summaries, probe_task};
use chronocooked_env::Task;
use chronocooked_env::integrity::{remove_recorded, write_recorded};
use chronocooked_models::agent::record_dataset;
use chronocooked_training::eval_tds;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;

/// Most repetitions of the every-start-cell protocol (as `chronocooked record --repeats`).
const MAX_REPEATS: u64 = 100;

/// Plays `task` (or, with `probe`, its peak-interval probe trials) with a Python `policy`,
/// records its activity and writes into the folder `out`: `activity.json`, the NPZ export
/// `activity/` and (with `summary`) `activity.summary.json`, written last. Returns a dict
/// (`out`, `task`, `env`, `tds`, `trials`, `units`, `files`, `summary`).
#[pyfunction]
#[pyo3(signature = (policy, task, out, overrides = Vec::new(), probe = true, tds = None, repeats = 1, seed = 0, obs_mode = "codes", name = "python-policy", summary = true, units_correspond = true))]
#[allow(clippy::too_many_arguments)]
pub fn record<'py>(
    py: Python<'py>,
    policy: Bound<'py, PyAny>,
    task: &str,
    out: PathBuf,
    overrides: Vec<String>,
    probe: bool,
    tds: Option<Vec<u32>>,
    repeats: u64,
    seed: u64,
    obs_mode: &str,
    name: &str,
    summary: bool,
    units_correspond: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let onehot = crate::agent::onehot_and_name(obs_mode, name)?;
    if !(1..=MAX_REPEATS).contains(&repeats) {
        return Err(value_err(format!(
            "invalid value for `repeats`: {repeats} (allowed: 1..={MAX_REPEATS} repetitions of \
             every start cell)"
        )));
    }
    if probe && !can_probe(task) {
        return Err(value_err(format!(
            "invalid value for `probe`: True with task {task} (probe trials exist for \
             fixed-interval and peak-interval tasks; use probe=False to record {task}'s own \
             episodes)"
        )));
    }
    let chosen = Task::parse(task, &overrides).map_err(env_err)?;
    let own = chosen.config().map_err(env_err)?;
    let tds = match tds {
        Some(t) if t.is_empty() => {
            return Err(value_err(
                "invalid value for `tds`: empty list (allowed: None for the task's own TDs, or \
                 a list of target durations in steps)",
            ));
        }
        Some(t) => t,
        None if probe => vec![own.params.td().unwrap_or(12)],
        None => eval_tds(&own),
    };
    let play = if probe {
        probe_task(&chosen, &tds).map_err(value_err)?
    } else {
        chosen
    };
    let config = play.config().map_err(env_err)?;
    let mut agent = PyAgent::new(py, policy, name, onehot, std::slice::from_ref(&play), 1)?;
    let played = record_dataset(&mut agent, &config, &play, &tds, repeats, seed);
    // A policy error first: it is why the protocol stopped, if it did.
    if let Some((episode, step, cause)) = agent.error.take() {
        let err = crate::errors::PolicyError::new_err(format!(
            "the policy failed while recording {} ({}) at episode {episode}, step {step}: {}",
            play.id(),
            play.overrides().join(" "),
            cause.value(py)
        ));
        let value = err.value(py);
        for (k, v) in [("episode", episode), ("step", step)] {
            let _ = value.setattr(k, v);
        }
        let _ = value.setattr("task", play.id());
        err.set_cause(py, Some(cause));
        return Err(err);
    }
    let dataset = played.map_err(env_err)?;
    if dataset.meta.n_units() == 0 {
        return Err(value_err(
            "the policy returned no activity: `record` needs a policy returning (action, state, \
             activity), activity a 1-D float vector or a dict of named vectors",
        ));
    }
    // One writer per folder; the summary is removed first and written last, so a folder
    // never holds an old summary beside a new recording.
    let os_err = |e: String| PyOSError::new_err(e);
    let _lock =
        chronocooked_env::fs::FolderLock::acquire(&out).map_err(|e| os_err(e.to_string()))?;
    let summary_path = out.join(chronocooked_analysis::job_folder::ACTIVITY_SUMMARY);
    remove_recorded(&summary_path).map_err(|e| os_err(e.to_string()))?;
    let mut files = chronocooked_present::eval_folder::write_activity(&out, &dataset)
        .map_err(|e| os_err(format!("{}: {e}", out.display())))?;
    let result = PyDict::new(py);
    if summary {
        let summaries = population_summaries(&dataset, units_correspond, seed);
        let bytes =
            serde_json::to_vec_pretty(&summaries).map_err(|e| runtime_err(e.to_string()))?;
        write_recorded(&summary_path, &bytes).map_err(|e| os_err(e.to_string()))?;
        files.push(summary_path);
        result.set_item("summary", crate::info::to_py(py, &summaries)?)?;
    }
    result.set_item("out", out)?;
    result.set_item("task", play.id())?;
    result.set_item("env", play.overrides())?;
    result.set_item("tds", tds)?;
    result.set_item("trials", dataset.trials.len())?;
    result.set_item("units", dataset.meta.n_units())?;
    result.set_item("files", files)?;
    Ok(result)
}
