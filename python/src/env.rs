//! One Chronocooked env for Python: `reset`/`step` return fresh numpy arrays (never a view
//! of a reused buffer) and the info as a dict of plain values.

use crate::errors::{env_err, value_err};
use crate::info::info_dict;
use chronocooked_env::render::{PALETTE, ascii, frame};
use chronocooked_env::{ChronoEnv, Task};
use numpy::{IntoPyArray, PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Observation encoding handed to Python.
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::EnumString, strum::IntoStaticStr)]
#[strum(serialize_all = "lowercase")]
pub enum ObsMode {
    /// The reference codes, `uint8 [R, C, 6]`.
    Codes,
    /// The one-hot network view, `float32 [channels, R, C]`.
    OneHot,
}

impl ObsMode {
    /// Parses `"codes"` or `"onehot"`.
    pub fn parse(s: &str) -> PyResult<Self> {
        s.parse().map_err(|_| {
            value_err(format!(
                "invalid value for `obs_mode`: {s:?} (allowed: \"codes\", \"onehot\")"
            ))
        })
    }

    /// `"codes"` or `"onehot"`.
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// A fresh codes observation `uint8 [R, C, 6]`.
pub fn obs_array<'py>(py: Python<'py>, env: &ChronoEnv) -> PyResult<Bound<'py, PyAny>> {
    let space = env.codes_space();
    let a = PyArray1::from_slice(py, env.obs_codes());
    Ok(a.reshape(space.shape)?.into_any())
}

/// A fresh one-hot observation `float32 [channels, R, C]`.
pub fn onehot_array<'py>(py: Python<'py>, env: &ChronoEnv) -> PyResult<Bound<'py, PyAny>> {
    let shape = env.onehot_space().shape;
    let a = env.obs_onehot().into_pyarray(py);
    Ok(a.reshape(shape)?.into_any())
}

/// One Chronocooked env (the Rust `ChronoEnv`).
#[pyclass(module = "chronocooked._core")]
pub struct Env {
    env: ChronoEnv,
    mode: ObsMode,
    task: Task,
}

impl Env {
    fn obs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match self.mode {
            ObsMode::Codes => obs_array(py, &self.env),
            ObsMode::OneHot => onehot_array(py, &self.env),
        }
    }
}

#[pymethods]
impl Env {
    /// `Env(task, overrides=[], obs_mode="codes")`: a registered task with `key=value`
    /// overrides (the names of `--set`, reference aliases included).
    #[new]
    #[pyo3(signature = (task, overrides = Vec::new(), obs_mode = "codes"))]
    fn new(task: &str, overrides: Vec<String>, obs_mode: &str) -> PyResult<Self> {
        let mode = ObsMode::parse(obs_mode)?;
        let task = Task::parse(task, &overrides).map_err(env_err)?;
        let env = ChronoEnv::new(&task.config().map_err(env_err)?).map_err(env_err)?;
        Ok(Env { env, mode, task })
    }

    /// Starts an episode: `(obs, info)`. `seed` reseeds the env's RNG (None continues it);
    /// `options` (a dict) fixes what the episode would draw, with the options the task's
    /// family declares (`reset_options`).
    #[pyo3(signature = (seed = None, options = None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seed: Option<u64>,
        options: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>)> {
        let options = crate::errors::reset_options(&self.env.config().id, options.as_ref())?;
        let info = self.env.reset(seed, &options).map_err(env_err)?;
        Ok((
            self.obs(py)?,
            info_dict(py, &info, self.env.ovens().as_ref())?,
        ))
    }

    /// One step: `(obs, reward, terminated, truncated, info)`; `action` in `0..=5`.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        action: i64,
    ) -> PyResult<(Bound<'py, PyAny>, f64, bool, bool, Bound<'py, PyDict>)> {
        let t = self.env.step_code(action).map_err(env_err)?;
        Ok((
            self.obs(py)?,
            f64::from(t.reward),
            t.terminated,
            t.truncated,
            info_dict(py, &t.info, self.env.ovens().as_ref())?,
        ))
    }

    /// The current observation (a fresh array).
    fn observation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.obs(py)
    }

    /// Shape of the observation in this env's mode.
    #[getter]
    fn obs_shape(&self) -> Vec<usize> {
        match self.mode {
            ObsMode::Codes => self.env.codes_space().shape,
            ObsMode::OneHot => self.env.onehot_space().shape,
        }
    }

    /// Upper bound of every observation element (codes: the largest code of this task;
    /// one-hot: the largest value of the network view). The lower bound is 0.
    #[getter]
    fn obs_high(&self) -> f64 {
        match self.mode {
            ObsMode::Codes => f64::from(self.env.codes_space().high),
            ObsMode::OneHot => f64::from(self.env.onehot_space().high),
        }
    }

    /// `"codes"` or `"onehot"`.
    #[getter]
    fn obs_mode(&self) -> &'static str {
        self.mode.name()
    }

    /// Number of actions (6: wait, down, up, right, left, interact).
    #[getter]
    fn n_actions(&self) -> usize {
        self.env.action_space().n
    }

    /// Task id.
    #[getter]
    fn task(&self) -> &str {
        self.task.id()
    }

    /// The task parameters the env was built with, as `key=value` (canonical keys, in the
    /// task's table order).
    #[getter]
    fn overrides(&self) -> Vec<String> {
        self.task.overrides()
    }

    /// The resolved task configuration as JSON text.
    fn config_json(&self) -> PyResult<String> {
        serde_json::to_string(self.env.config()).map_err(|e| value_err(e.to_string()))
    }

    /// Grid size `(rows, cols)`.
    #[getter]
    fn grid(&self) -> (usize, usize) {
        (self.env.layout().rows(), self.env.layout().cols())
    }

    /// Free cells `(row, col)` (the possible start cells), row-major.
    fn free_cells(&self) -> Vec<(usize, usize)> {
        let layout = self.env.layout();
        layout.free_coords()
    }

    /// Whether the episode has ended.
    #[getter]
    fn done(&self) -> bool {
        self.env.is_done()
    }

    /// The current observation as text (one cell per column: objects, oven state, agent).
    fn render_ansi(&self) -> String {
        ascii(self.env.layout(), self.env.family(), self.env.obs_codes())
    }

    /// The current state as an RGB image `uint8 [H, W, 3]`.
    fn render_rgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let f = frame(self.env.layout(), self.env.family(), self.env.obs_codes());
        let rgb: Vec<u8> = f.pixels.iter().flat_map(|&p| PALETTE[p as usize]).collect();
        Ok(rgb
            .into_pyarray(py)
            .reshape([f.height, f.width, 3])?
            .into_any())
    }
}
