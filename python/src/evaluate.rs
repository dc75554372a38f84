//! The lab's evaluation protocol with a Python policy.
//!
//! The policy is a callable `(obs, state, episode_start) -> (action, state)` or
//! `-> (action, state, activity)`; `activity` (a 1-D float vector of the same length at every
//! step) is recorded as the model's population `units`. The protocol, seeds and output
//! folder are those of `chronocooked eval` (`run_protocol_recorded`, `write_eval_folder`).

use crate::errors::{env_err, runtime_err, value_err};
use chronocooked_analysis::evaluation::folder::{EvalInfo, write_eval_folder};
use chronocooked_analysis::{Mode, run_protocol_recorded};
use chronocooked_env::{Action, ChronoEnv, OneHotEncoder};
use chronocooked_models::Agent;
use chronocooked_models::activity::{ActivityMeta, StepRecorder, TrialRecorder};
use numpy::{IntoPyArray, PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::path::PathBuf;

/// Observation geometry of one layout: codes length, codes shape, one-hot encoder.
struct Geometry {
    len: usize,
    shape: [usize; 3],
    encoder: OneHotEncoder,
}

/// A Python callable as a lab [`Agent`]. The first Python error stops the policy (later
/// steps wait) and is raised when the protocol returns.
struct PyAgent<'py> {
    py: Python<'py>,
    policy: Bound<'py, PyAny>,
    name: String,
    onehot: bool,
    geometries: Vec<Geometry>,
    state: Bound<'py, PyAny>,
    episode_start: bool,
    activity: Option<Vec<f32>>,
    units: Option<usize>,
    /// Episodes begun (1-based index of the current one) and steps of the current one.
    episode: usize,
    step: usize,
    /// The first failure: (episode, step, error).
    error: Option<(usize, usize, PyErr)>,
}

impl<'py> PyAgent<'py> {
    fn obs_array(&self, obs: &[u8]) -> PyResult<Bound<'py, PyAny>> {
        let g = self
            .geometries
            .iter()
            .find(|g| g.len == obs.len())
            .ok_or_else(|| runtime_err(format!("no layout with {} obs codes", obs.len())))?;
        if self.onehot {
            let mut out = vec![0f32; g.encoder.len()];
            g.encoder.encode(obs, &mut out);
            Ok(out
                .into_pyarray(self.py)
                .reshape(g.encoder.shape())?
                .into_any())
        } else {
            Ok(PyArray1::from_slice(self.py, obs)
                .reshape(g.shape)?
                .into_any())
        }
    }

    fn read_activity(&mut self, a: &Bound<'py, PyAny>) -> PyResult<()> {
        if a.is_none() {
            self.activity = None;
            return Ok(());
        }
        let v: Vec<f32> = if let Ok(x) = a.extract::<PyReadonlyArray1<'_, f32>>() {
            x.as_slice()?.to_vec()
        } else if let Ok(x) = a.extract::<PyReadonlyArray1<'_, f64>>() {
            x.as_slice()?.iter().map(|&v| v as f32).collect()
        } else {
            let np = self.py.import("numpy")?;
            let flat = np
                .call_method1("asarray", (a, "float32"))?
                .call_method0("ravel")?;
            flat.extract::<PyReadonlyArray1<'_, f32>>()?
                .as_slice()?
                .to_vec()
        };
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(value_err(format!(
                "policy activity holds {} at unit {i} (allowed: finite numbers)",
                v[i]
            )));
        }
        match self.units {
            Some(n) if n != v.len() => {
                return Err(value_err(format!(
                    "policy activity changed size: {} units, earlier {n} (allowed: the same length at every step)",
                    v.len()
                )));
            }
            None => self.units = Some(v.len()),
            _ => {}
        }
        self.activity = Some(v);
        Ok(())
    }

    fn call(&mut self, obs: &[u8]) -> PyResult<Action> {
        let o = self.obs_array(obs)?;
        let out = self
            .policy
            .call1((o, self.state.clone(), self.episode_start))?;
        self.episode_start = false;
        let tuple = out.cast::<PyTuple>().map_err(|_| {
            value_err(
                "the policy must return (action, state) or (action, state, activity), got a non-tuple",
            )
        })?;
        if !(2..=3).contains(&tuple.len()) {
            return Err(value_err(format!(
                "the policy returned {} values (allowed: (action, state) or (action, state, activity))",
                tuple.len()
            )));
        }
        let action = tuple.get_item(0)?;
        let code: i64 = action
            .extract::<i64>()
            .or_else(|_| action.call_method0("item")?.extract::<i64>())
            .map_err(|_| {
                value_err(format!(
                    "the policy's action must be an integer in 0..=5 (or a one-element integer array), got {}",
                    action.repr().map_or_else(|_| "?".into(), |r| r.to_string())
                ))
            })?;
        self.state = tuple.get_item(1)?;
        if tuple.len() == 3 {
            self.read_activity(&tuple.get_item(2)?)?;
        } else if self.units.is_some() {
            return Err(value_err(
                "the policy stopped returning activity (allowed: activity at every step or never)",
            ));
        }
        Action::from_code(code).map_err(env_err)
    }
}

impl Agent for PyAgent<'_> {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn begin_episode(&mut self, _obs: &[u8], _seed: u64) {
        self.episode += 1;
        self.step = 0;
        self.episode_start = true;
        self.state = self.py.None().into_bound(self.py);
    }

    fn act(&mut self, obs: &[u8]) -> Action {
        if self.error.is_some() {
            return Action::Wait;
        }
        self.step += 1;
        match self.call(obs) {
            Ok(a) => a,
            Err(e) => {
                self.error = Some((self.episode, self.step, e));
                Action::Wait
            }
        }
    }

    fn record(&self, rec: &mut StepRecorder) {
        if let Some(a) = &self.activity {
            rec.record("units", a);
        }
    }
}

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
    if !policy.is_callable() {
        return Err(value_err(
            "`policy` must be callable: (obs, state, episode_start) -> (action, state[, activity])",
        ));
    }
    let onehot = match crate::env::ObsMode::parse(obs_mode)? {
        crate::env::ObsMode::Codes => false,
        crate::env::ObsMode::OneHot => true,
    };
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
    if name.trim().is_empty() {
        return Err(value_err(
            "invalid value for `name`: empty (allowed: a model name)",
        ));
    }
    let conditions =
        chronocooked_analysis::reference_conditions(task, &overrides).map_err(env_err)?;
    let mut geometries: Vec<Geometry> = Vec::new();
    let mut seen: Vec<(&str, &[String])> = Vec::new();
    for c in &conditions {
        // One env per distinct (task, overrides): conditions mostly differ only in TD.
        if seen.contains(&(c.task.as_str(), c.env.as_slice())) {
            continue;
        }
        seen.push((c.task.as_str(), c.env.as_slice()));
        let env = ChronoEnv::from_id(&c.task, &c.env).map_err(env_err)?;
        let shape = env.codes_space().shape;
        let shape = [shape[0], shape[1], shape[2]];
        let len = shape.iter().product();
        match geometries.iter().find(|g| g.len == len) {
            Some(g) if g.shape != shape => {
                return Err(runtime_err(format!(
                    "conditions of {task} mix layouts {:?} and {shape:?} of equal size",
                    g.shape
                )));
            }
            Some(_) => {}
            None => geometries.push(Geometry {
                len,
                shape,
                encoder: env.onehot_encoder().clone(),
            }),
        }
    }
    let mut agent = PyAgent {
        py,
        policy,
        name: name.to_string(),
        onehot,
        geometries,
        state: py.None().into_bound(py),
        episode_start: true,
        activity: None,
        units: None,
        episode: 0,
        step: 0,
        error: None,
    };
    let meta = ActivityMeta::new(name, task, &overrides, seed);
    let mut recorder = TrialRecorder::new(meta);
    let records = run_protocol_recorded(&mut agent, &conditions, mode, seed, Some(&mut recorder))
        .map_err(env_err)?;
    if let Some((episode, step, cause)) = agent.error.take() {
        return Err(policy_error(py, &records, episode, step, cause));
    }
    let info = EvalInfo {
        model: name.to_string(),
        task: task.to_string(),
        env: overrides,
        mode,
        seed,
        unfinished_at_step: None,
    };
    // One writer per folder; the activity first and `metrics.json` last, so a folder with
    // metrics is a complete one.
    let _lock = chronocooked_env::fs::FolderLock::acquire(&out)
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(e.to_string()))?;
    chronocooked_analysis::evaluation::folder::start_writing(&out).map_err(runtime_err)?;
    let summary = PyDict::new(py);
    let dataset = recorder.finish();
    if dataset.meta.n_units() > 0 {
        let files = chronocooked_analysis::evaluation::folder::write_activity(&out, &dataset)
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
fn policy_error(
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
    let (task, td) = condition.map_or((String::new(), 0), |c| (c.task.clone(), c.td));
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
    let conditions =
        chronocooked_analysis::reference_conditions(task, &overrides).map_err(env_err)?;
    let out = PyList::empty(py);
    for c in conditions {
        let d = PyDict::new(py);
        d.set_item("kind", c.kind.as_str())?;
        d.set_item("task", c.task)?;
        d.set_item("env", c.env)?;
        d.set_item("td", c.td)?;
        d.set_item("never_ready", c.never_ready)?;
        d.set_item("factor", c.factor)?;
        out.append(d)?;
    }
    Ok(out)
}
