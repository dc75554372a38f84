//! A Python policy as a lab [`Agent`].
//!
//! The policy is a callable `(obs, state, episode_start) -> (action, state)` or
//! `-> (action, state, activity)`. `activity` is either a 1-D float vector of the same
//! length at every step (recorded as the population `units`) or a dict of such vectors,
//! name → vector, with the same names and lengths at every step (one population each, e.g.
//! an LSTM's `hidden` and `cell` states).

use crate::errors::{env_err, runtime_err, value_err};
use chronocooked_env::{Action, ChronoEnv, OneHotEncoder, Task};
use chronocooked_models::Agent;
use chronocooked_models::activity::StepRecorder;
use numpy::{IntoPyArray, PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// Observation geometry of one layout: codes length, codes shape, one-hot encoder.
struct Geometry {
    len: usize,
    shape: [usize; 3],
    encoder: OneHotEncoder,
}

/// What every entry point that plays a Python policy checks first: its `obs_mode` (returns
/// whether observations are one-hot) and the agent's `name` (not empty).
pub(crate) fn onehot_and_name(obs_mode: &str, name: &str) -> PyResult<bool> {
    let onehot = matches!(
        crate::env::ObsMode::parse(obs_mode)?,
        crate::env::ObsMode::OneHot
    );
    if name.trim().is_empty() {
        return Err(value_err(
            "invalid value for `name`: empty (allowed: a model name)",
        ));
    }
    Ok(onehot)
}

/// A Python callable as a lab [`Agent`]. The first Python error stops the policy (later
/// steps wait) and is kept in [`PyAgent::error`] for the caller to raise.
pub struct PyAgent<'py> {
    py: Python<'py>,
    policy: Bound<'py, PyAny>,
    name: String,
    onehot: bool,
    geometries: Vec<Geometry>,
    state: Bound<'py, PyAny>,
    episode_start: bool,
    /// The activity of the current step: `(population, values)`.
    activity: Vec<(String, Vec<f32>)>,
    /// The populations and sizes fixed by the first step with activity.
    shape: Option<Vec<(String, usize)>>,
    /// Episodes per start cell in the reference protocol ([`Agent::noise_draws`]).
    draws: usize,
    /// Whether a step has passed without activity (then none may follow).
    silent: bool,
    /// Episodes begun (1-based index of the current one) and steps of the current one.
    episode: usize,
    step: usize,
    /// The first failure: (episode, step, error).
    pub error: Option<(usize, usize, PyErr)>,
}

/// The population name of a plain activity vector.
pub const UNITS: &str = "units";

impl<'py> PyAgent<'py> {
    /// An agent for `policy` on the tasks `tasks` (every layout it may meet), observations as one-hot arrays when `onehot` (a policy's own
    /// `obs_mode` attribute, when it has one, decides instead), `draws` episodes per start
    /// cell in the reference protocol.
    pub fn new(
        py: Python<'py>,
        policy: Bound<'py, PyAny>,
        name: &str,
        onehot: bool,
        tasks: &[Task],
        draws: usize,
    ) -> PyResult<Self> {
        if !policy.is_callable() {
            return Err(value_err(
                "a policy must be callable: (obs, state, episode_start) -> (action, state[, activity])",
            ));
        }
        // A policy that says which observations it takes (`policy.obs_mode`, e.g. the SB3
        // adapter's, from its model's observation space) gets those.
        let onehot = match policy.getattr("obs_mode") {
            Ok(m) if !m.is_none() => {
                let mode: String = m.extract().map_err(|_| {
                    value_err("the policy's `obs_mode` attribute must be \"codes\" or \"onehot\"")
                })?;
                matches!(
                    crate::env::ObsMode::parse(&mode)?,
                    crate::env::ObsMode::OneHot
                )
            }
            _ => onehot,
        };
        let mut geometries: Vec<Geometry> = Vec::new();
        for task in tasks {
            let env = ChronoEnv::new(&task.config().map_err(env_err)?).map_err(env_err)?;
            let shape = env.codes_space().shape;
            let shape = [shape[0], shape[1], shape[2]];
            let len = shape.iter().product();
            match geometries.iter().find(|g| g.len == len) {
                Some(g) if g.shape != shape => {
                    return Err(runtime_err(format!(
                        "the conditions of {} mix layouts {:?} and {shape:?} of equal size",
                        task.id(),
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
        Ok(Self {
            py,
            policy,
            name: name.to_string(),
            onehot,
            geometries,
            state: py.None().into_bound(py),
            episode_start: true,
            activity: Vec::new(),
            shape: None,
            draws: draws.max(1),
            silent: false,
            episode: 0,
            step: 0,
            error: None,
        })
    }

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

    /// One population's values as finite `f32`s (`what` names it in errors).
    fn vector(&self, a: &Bound<'py, PyAny>, what: &str) -> PyResult<Vec<f32>> {
        let v: Vec<f32> = if let Ok(x) = a.extract::<PyReadonlyArray1<'_, f32>>() {
            x.as_slice()?.to_vec()
        } else if let Ok(x) = a.extract::<PyReadonlyArray1<'_, f64>>() {
            x.as_slice()?.iter().map(|&v| v as f32).collect()
        } else {
            let np = self.py.import("numpy")?;
            let flat = np
                .call_method1("asarray", (a, "float32"))
                .map_err(|e| {
                    value_err(format!(
                        "policy activity {what} is not numeric: {}",
                        e.value(self.py)
                    ))
                })?
                .call_method0("ravel")?;
            flat.extract::<PyReadonlyArray1<'_, f32>>()?
                .as_slice()?
                .to_vec()
        };
        if let Some(i) = v.iter().position(|x| !x.is_finite()) {
            return Err(value_err(format!(
                "policy activity {what}holds {} at unit {i} (allowed: finite numbers)",
                v[i]
            )));
        }
        Ok(v)
    }

    fn read_activity(&mut self, a: &Bound<'py, PyAny>) -> PyResult<()> {
        if a.is_none() {
            if self.shape.is_some() {
                return Err(value_err(
                    "the policy stopped returning activity (allowed: activity at every step or never)",
                ));
            }
            self.silent = true;
            return Ok(());
        }
        let pops: Vec<(String, Vec<f32>)> = if let Ok(d) = a.cast::<PyDict>() {
            let mut out = Vec::new();
            for (k, v) in d.iter() {
                let name: String = k.extract().map_err(|_| {
                    value_err("policy activity dict keys must be population names (str)")
                })?;
                if name.trim().is_empty() {
                    return Err(value_err("policy activity has an empty population name"));
                }
                let values = self.vector(&v, &format!("`{name}` "))?;
                out.push((name, values));
            }
            out
        } else {
            vec![(UNITS.to_string(), self.vector(a, "")?)]
        };
        let shape: Vec<(String, usize)> = pops.iter().map(|(n, v)| (n.clone(), v.len())).collect();
        if self.shape.is_none() && self.silent {
            return Err(value_err(
                "the policy began returning activity after steps without it (allowed: activity \
                 at every step or never)",
            ));
        }
        match &self.shape {
            Some(s) if *s != shape => {
                return Err(value_err(format!(
                    "policy activity changed size: {}, earlier {} (allowed: the same \
                     populations and lengths at every step)",
                    describe(&shape),
                    describe(s)
                )));
            }
            None => self.shape = Some(shape),
            _ => {}
        }
        self.activity = pops;
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
        } else if self.shape.is_some() {
            return Err(value_err(
                "the policy stopped returning activity (allowed: activity at every step or never)",
            ));
        } else {
            self.silent = true;
        }
        Action::from_code(code).map_err(env_err)
    }
}

fn describe(shape: &[(String, usize)]) -> String {
    shape
        .iter()
        .map(|(n, k)| format!("{n}[{k}]"))
        .collect::<Vec<_>>()
        .join(", ")
}

impl Agent for PyAgent<'_> {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn noise_draws(&self) -> usize {
        self.draws
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
        for (name, values) in &self.activity {
            rec.record(name, values);
        }
    }
}
