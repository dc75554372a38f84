//! The lab's evaluation protocol with a Python policy.
//!
//! The policy is a [`PyAgent`] (see [`crate::agent`] for its contract). The protocol,
//! seeds and output folder are those of `chronocooked eval` (`run_protocol_recorded`,
//! `write_eval_folder`).

use crate::agent::PyAgent;
use crate::errors::{env_err, runtime_err, value_err};
use chronocooked_analysis::{Mode, run_protocol_recorded};
use chronocooked_env::Task;
use chronocooked_models::activity::{ActivityMeta, TrialRecorder};
use chronocooked_present::eval_folder::{EvalInfo, write_eval_folder};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;

/// Runs the reference protocol of `task` (or `stochastic` episodes per condition) with a
/// Python `policy` and writes the evaluation folder `out` (`records.jsonl`, `eval.json`,
/// `metrics.json`, `figures/`; plus `activity.json` and the NPZ export `activity/` when the
/// policy returns activity). Returns a summary dict (paths, episodes, success rate).
#[pyfunction]
#[pyo3(signature = (policy, task, out, overrides = Vec::new(), obs_mode = "codes", stochastic = None, seed = 0, name = "python-policy"))]
#[allow(clippy::too_many_arguments)]
pub fn evaluate<'py>(
    py: Python<'py>,
    policy: Bound<'py, PyAny>,
    task: &str,
    out: PathBuf,
    overrides: Vec<String>,
    obs_mode: &str,
    stochastic: Option<usize>,
    seed: u64,
    name: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let onehot = crate::agent::onehot_and_name(obs_mode, name)?;
    let mode = match stochastic {
        Some(0) => {
            return Err(value_err(
                "invalid value for `stochastic`: 0 (allowed: None for the reference protocol, or episodes per condition >= 1)",
            ));
        }
        Some(n) if n > chronocooked_analysis::evaluation::protocol::MAX_STOCHASTIC_EPISODES => {
            return Err(value_err(format!(
                "invalid value for `stochastic`: {n} (allowed: None for the reference protocol, or 1..={} episodes per condition)",
                chronocooked_analysis::evaluation::protocol::MAX_STOCHASTIC_EPISODES
            )));
        }
        Some(n) => Mode::Stochastic { episodes: n },
        None => Mode::Reference,
    };
    let task = Task::parse(task, &overrides).map_err(env_err)?;
    let conditions = chronocooked_analysis::reference_conditions(&task).map_err(env_err)?;
    let mut tasks: Vec<Task> = Vec::new();
    for c in &conditions {
        // One env per distinct task: conditions mostly differ only in TD.
        if !tasks.contains(&c.task) {
            tasks.push(c.task.clone());
        }
    }
    let mut agent = PyAgent::new(py, policy, name, onehot, &tasks, 1)?;
    let meta = ActivityMeta::new(name, &task, seed);
    let mut recorder = TrialRecorder::new(meta);
    let records = run_protocol_recorded(&mut agent, &conditions, mode, seed, Some(&mut recorder))
        .map_err(env_err)?;
    if let Some((episode, step, cause)) = agent.error.take() {
        return Err(policy_error(py, &records, episode, step, cause));
    }
    let info = EvalInfo {
        model: name.to_string(),
        task,
        mode,
        seed,
        unfinished_at_step: None,
        episodes: None,
    };
    // One writer per folder; the activity first and `metrics.json` last, so a folder with
    // metrics is a complete one.
    let _lock = chronocooked_env::fs::FolderLock::acquire(&out)
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(e.to_string()))?;
    chronocooked_present::eval_folder::begin_evaluation(&out).map_err(runtime_err)?;
    let summary = PyDict::new(py);
    let dataset = recorder.finish();
    if dataset.meta.n_units() > 0 {
        let files = chronocooked_present::eval_folder::write_activity(&out, &dataset)
            .map_err(runtime_err)?;
        summary.set_item("activity", &files[0])?;
        summary.set_item("activity_export", &files[1..])?;
        summary.set_item("units", dataset.meta.n_units())?;
    }
    let (metrics, figures) = write_eval_folder(&out, &info, &records).map_err(runtime_err)?;
    summary.set_item("out", out.clone())?;
    summary.set_item("episodes", metrics.episodes)?;
    summary.set_item("success_rate", metrics.success_rate)?;
    summary.set_item("figures", figures)?;
    Ok(summary)
}

/// A [`PolicyError`](crate::errors::PolicyError) saying where the policy failed (episode
/// and step, and the episode's task and TD from the protocol's records), with the
/// original error as its `__cause__`.
pub(crate) fn policy_error(
    py: Python<'_>,
    records: &[chronocooked_analysis::EvalRecord],
    episode: usize,
    step: usize,
    cause: PyErr,
) -> PyErr {
    let condition = episode
        .checked_sub(1)
        .and_then(|i| records.get(i))
        .map(|r| &r.condition);
    let (task, td) = condition.map_or((String::new(), 0), |c| (c.task.id().to_string(), c.td));
    let err = crate::errors::PolicyError::new_err(format!(
        "the policy failed at episode {episode} ({task}, TD {td}), step {step}: {}",
        cause.value(py)
    ));
    let value = err.value(py);
    for (k, v) in [("episode", episode), ("step", step), ("td", td as usize)] {
        let _ = value.setattr(k, v);
    }
    let _ = value.setattr("task", task);
    err.set_cause(py, Some(cause));
    err
}

/// The conditions of the reference protocol for `task` with `overrides` (list of dicts:
/// kind, task, env, td, never_ready, factor).
#[pyfunction]
#[pyo3(signature = (task, overrides = Vec::new()))]
pub fn reference_conditions<'py>(
    py: Python<'py>,
    task: &str,
    overrides: Vec<String>,
) -> PyResult<Bound<'py, PyList>> {
    let task = Task::parse(task, &overrides).map_err(env_err)?;
    let conditions = chronocooked_analysis::reference_conditions(&task).map_err(env_err)?;
    let out = PyList::empty(py);
    for c in conditions {
        let d = PyDict::new(py);
        d.set_item("kind", c.kind.as_str())?;
        d.set_item("task", c.task.id())?;
        d.set_item("env", c.task.overrides())?;
        d.set_item("td", c.td)?;
        d.set_item("never_ready", c.never_ready)?;
        d.set_item("factor", c.factor)?;
        out.append(d)?;
    }
    Ok(out)
}
