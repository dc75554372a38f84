//! N envs stepped in Rust for Python: batched numpy outputs, gymnasium ≥ 1.0 next-step
//! autoreset by default (same-step selectable).

use crate::env::ObsMode;
use crate::errors::{env_err, value_err};
use crate::info::info_arrays;
use chronocooked_env::{Autoreset, ChronoEnv, VecEnv as RustVecEnv};
use numpy::{IntoPyArray, PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// N envs of one task (the Rust `VecEnv`).
#[pyclass(module = "chronocooked._core")]
pub struct VecEnv {
    envs: RustVecEnv,
    mode: ObsMode,
    autoreset: Autoreset,
    obs_shape: Vec<usize>,
    obs_high: f64,
    actions: Vec<u8>,
}

fn parse_autoreset(s: &str) -> PyResult<Autoreset> {
    match s {
        "next_step" => Ok(Autoreset::NextStep),
        "same_step" => Ok(Autoreset::SameStep),
        "disabled" => Ok(Autoreset::Disabled),
        other => Err(value_err(format!(
            "invalid value for `autoreset_mode`: {other:?} (allowed: \"next_step\", \"same_step\", \"disabled\")"
        ))),
    }
}

impl VecEnv {
    fn batch<'py>(&self, py: Python<'py>, codes: &[u8]) -> PyResult<Bound<'py, PyAny>> {
        let n = self.envs.len();
        let mut shape = vec![n];
        shape.extend_from_slice(&self.obs_shape);
        match self.mode {
            ObsMode::Codes => Ok(PyArray1::from_slice(py, codes).reshape(shape)?.into_any()),
            ObsMode::OneHot => {
                let enc = self.envs.onehot_encoder();
                let len = enc.len();
                let per = self.envs.obs_len();
                let mut out = vec![0f32; n * len];
                for (o, c) in out.chunks_exact_mut(len).zip(codes.chunks_exact(per)) {
                    enc.encode(c, o);
                }
                Ok(out.into_pyarray(py).reshape(shape)?.into_any())
            }
        }
    }

    fn read_actions(&mut self, actions: &Bound<'_, PyAny>) -> PyResult<()> {
        let n = self.envs.len();
        let codes: Vec<i64> = match actions.extract::<PyReadonlyArray1<'_, i64>>() {
            Ok(a) => a.as_slice()?.to_vec(),
            Err(_) => actions.extract().map_err(|_| {
                value_err("`actions` must be a 1-D array (or sequence) of integers in 0..=5")
            })?,
        };
        if codes.len() != n {
            return Err(value_err(format!(
                "invalid value for `actions`: {} actions (allowed: exactly {n}, one per env)",
                codes.len()
            )));
        }
        self.actions.clear();
        for x in codes {
            if !(0..6).contains(&x) {
                return Err(value_err(format!(
                    "invalid action {x} (allowed: 0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact)"
                )));
            }
            self.actions.push(x as u8);
        }
        Ok(())
    }
}

#[pymethods]
impl VecEnv {
    /// `VecEnv(task, num_envs, overrides=[], obs_mode="codes", autoreset_mode="next_step")`.
    #[new]
    #[pyo3(signature = (task, num_envs, overrides = Vec::new(), obs_mode = "codes", autoreset_mode = "next_step"))]
    fn new(
        task: &str,
        num_envs: usize,
        overrides: Vec<String>,
        obs_mode: &str,
        autoreset_mode: &str,
    ) -> PyResult<Self> {
        let mode = ObsMode::parse(obs_mode)?;
        let autoreset = parse_autoreset(autoreset_mode)?;
        if num_envs == 0 {
            return Err(value_err(
                "invalid value for `num_envs`: 0 (allowed: integer >= 1)",
            ));
        }
        let one = ChronoEnv::from_id(task, &overrides).map_err(env_err)?;
        let (obs_shape, obs_high) = match mode {
            ObsMode::Codes => (one.codes_space().shape, f64::from(one.codes_space().high)),
            ObsMode::OneHot => (one.onehot_space().shape, f64::from(one.onehot_space().high)),
        };
        Ok(VecEnv {
            envs: RustVecEnv::like(&one, num_envs, autoreset),
            mode,
            autoreset,
            obs_shape,
            obs_high,
            actions: Vec::with_capacity(num_envs),
        })
    }

    /// Number of envs.
    #[getter]
    fn num_envs(&self) -> usize {
        self.envs.len()
    }

    /// Shape of one env's observation in this env's mode.
    #[getter]
    fn obs_shape(&self) -> Vec<usize> {
        self.obs_shape.clone()
    }

    /// Upper bound of every observation element (the lower bound is 0).
    #[getter]
    fn obs_high(&self) -> f64 {
        self.obs_high
    }

    /// `"codes"` or `"onehot"`.
    #[getter]
    fn obs_mode(&self) -> &'static str {
        self.mode.name()
    }

    /// Resets the envs whose `mask` entry is true (all when None): env `i` is reseeded
    /// with `seeds[i]` (None continues its RNG); `options` (a dict) fixes what the episodes
    /// would draw, with the options the task's family declares. Returns `(obs [N, …], info)`.
    #[pyo3(signature = (seeds, mask = None, options = None))]
    fn reset<'py>(
        &mut self,
        py: Python<'py>,
        seeds: Vec<Option<u64>>,
        mask: Option<Vec<bool>>,
        options: Option<Bound<'py, PyAny>>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>)> {
        let n = self.envs.len();
        if seeds.len() != n {
            return Err(value_err(format!(
                "invalid value for `seed`: {} seeds (allowed: one int, or exactly {n})",
                seeds.len()
            )));
        }
        if let Some(m) = &mask
            && m.len() != n
        {
            return Err(value_err(format!(
                "invalid value for `reset_mask`: {} entries (allowed: exactly {n})",
                m.len()
            )));
        }
        let options = crate::errors::reset_options(&self.envs.config().id, options.as_ref())?;
        for (i, seed) in seeds.into_iter().enumerate() {
            if mask.as_ref().is_none_or(|m| m[i]) {
                self.envs.reset_one(i, seed, &options).map_err(env_err)?;
            }
        }
        let obs = self.batch(py, &self.envs.obs)?;
        Ok((obs, info_arrays(py, &self.envs.infos)?))
    }

    /// Steps every env: `(obs, rewards, terminated, truncated, info)`, fresh arrays `[N]`.
    /// Next-step autoreset: an env that ended on the previous call is reset instead (its
    /// action ignored, reward 0, not done). Same-step: `info["final_obs"]`,
    /// `info["final_info"]` and the mask `info["_final_obs"]` hold the ended episodes' last
    /// observation and info.
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        actions: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyAny>,
        Bound<'py, PyDict>,
    )> {
        self.read_actions(actions)?;
        self.envs.step(&self.actions).map_err(env_err)?;
        let e = &self.envs;
        let obs = self.batch(py, &e.obs)?;
        let rewards: Vec<f64> = e.rewards.iter().map(|&r| f64::from(r)).collect();
        let info = info_arrays(py, &e.infos)?;
        if self.autoreset == Autoreset::SameStep {
            let ended: Vec<bool> = e
                .terminated
                .iter()
                .zip(&e.truncated)
                .map(|(a, b)| *a || *b)
                .collect();
            if ended.iter().any(|&x| x) {
                info.set_item("final_obs", self.batch(py, &e.final_obs)?)?;
                info.set_item("final_info", info_arrays(py, &e.final_infos)?)?;
                info.set_item("_final_obs", ended.clone().into_pyarray(py))?;
                info.set_item("_final_info", ended.into_pyarray(py))?;
            }
        }
        Ok((
            obs,
            rewards.into_pyarray(py).into_any(),
            PyArray1::from_slice(py, &e.terminated).into_any(),
            PyArray1::from_slice(py, &e.truncated).into_any(),
            info,
        ))
    }
}
