//! The zoo of trained agents and the leaderboard from Python.
//!
//! * `zoo_agents()` — the zoo's agents with their provenance (JSON text);
//! * `ZooPolicy(name)` — a zoo agent as a Python policy `(obs, state, episode_start) ->
//!   (action, state, activity)` for `evaluate` or a gymnasium loop (greedy actions; the
//!   activity is its recurrent/latent population, `float32 [units]`);
//! * `report(evals, out, baselines, default_baselines)` — the leaderboard of `chronocooked
//!   report`, with committed baselines.

use crate::errors::{runtime_err, value_err};
use chronocooked_models::Agent;
use chronocooked_models::activity::StepRecorder;
use chronocooked_training::agent_zoo;
use numpy::{PyArray1, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use std::path::PathBuf;

/// Every agent of the zoo as JSON text: `{"root", "agents": [{"name", "dir", "bytes",
/// "provenance"}]}` (the zoo is found as by the CLI: `$CHRONOCOOKED_ZOO`, a `zoo/` in the
/// current folder or an ancestor, else the copy compiled into the package).
#[pyfunction]
pub fn zoo_agents() -> PyResult<String> {
    let root = agent_zoo::zoo_root().map_err(|e| value_err(e.to_string()))?;
    let agents = agent_zoo::list_agents(&root).map_err(|e| value_err(e.to_string()))?;
    let v = serde_json::json!({
        "root": root,
        "agents": agents.iter().map(agent_zoo::ZooAgent::listing_json).collect::<Vec<_>>(),
    });
    Ok(v.to_string())
}

/// A zoo agent as a Python policy. Observations are the reference codes (`uint8 [R, C, 6]`,
/// `obs_mode="codes"`) of the task it was trained on; actions are greedy.
#[pyclass(unsendable, module = "chronocooked._core")]
pub struct ZooPolicy {
    agent: Box<dyn Agent>,
    name: String,
    dir: PathBuf,
    provenance: String,
}

#[pymethods]
impl ZooPolicy {
    /// Loads zoo agent `name` (`<model>/<task>`, with or without `zoo:`); its files are
    /// checked against their SHA-256 records first (a corrupt file raises `ValueError`
    /// naming it).
    #[new]
    fn new(name: &str) -> PyResult<Self> {
        let entry = agent_zoo::find_agent(name).map_err(|e| value_err(e.to_string()))?;
        let agent = chronocooked_training::timing_run::load_agent(&entry.dir, None)
            .map_err(|e| value_err(e.to_string()))?;
        Ok(ZooPolicy {
            agent,
            name: format!("zoo:{}", entry.provenance.name),
            dir: entry.dir,
            provenance: serde_json::to_string(&entry.provenance)
                .map_err(|e| runtime_err(e.to_string()))?,
        })
    }

    /// The agent's zoo name (`zoo:<model>/<task>`).
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// The agent's folder (a run folder the CLI accepts too).
    #[getter]
    fn dir(&self) -> PathBuf {
        self.dir.clone()
    }

    /// The agent's provenance record as JSON text.
    #[getter]
    fn provenance_json(&self) -> String {
        self.provenance.clone()
    }

    /// One step: `(obs uint8 [R, C, 6], state, episode_start) -> (action, state,
    /// activity float32 [units])`. The state is kept inside (returned as `None`);
    /// `episode_start=True` resets it.
    fn __call__<'py>(
        &mut self,
        py: Python<'py>,
        obs: PyReadonlyArrayDyn<'py, u8>,
        state: Bound<'py, PyAny>,
        episode_start: bool,
    ) -> PyResult<(u8, Bound<'py, PyAny>, Bound<'py, PyArray1<f32>>)> {
        let codes: Vec<u8> = obs.as_array().iter().copied().collect();
        if episode_start {
            self.agent.begin_episode(&codes, 0);
        }
        let action = self.agent.act(&codes);
        let mut rec = StepRecorder::default();
        self.agent.record(&mut rec);
        let activity = rec.population("latent").unwrap_or(&[]).to_vec();
        let _ = state;
        Ok((
            action.code(),
            py.None().into_bound(py),
            PyArray1::from_vec(py, activity),
        ))
    }
}

/// Writes the leaderboard of evaluation folders `evals` into `out` (report.html, .md,
/// .csv), with the committed baselines `baselines` (compact study results folders) and,
/// when `default_baselines`, the repository's `results/paper-core`. Returns the files.
#[pyfunction]
#[pyo3(signature = (evals, out, baselines = Vec::new(), default_baselines = true))]
pub fn report(
    evals: Vec<PathBuf>,
    out: PathBuf,
    baselines: Vec<PathBuf>,
    default_baselines: bool,
) -> PyResult<Vec<PathBuf>> {
    use chronocooked_analysis::report::baselines::{load_baseline_rows, locate_default_baselines};
    let mut rows = chronocooked_analysis::report::load_rows(&evals).map_err(value_err)?;
    let mut dirs = baselines;
    if default_baselines {
        dirs.insert(
            0,
            locate_default_baselines().map_err(|e| value_err(e.to_string()))?,
        );
    }
    for d in dirs {
        rows.extend(load_baseline_rows(&d).map_err(|e| value_err(e.to_string()))?);
    }
    if rows.is_empty() {
        return Err(value_err(
            "nothing to report: no evaluation folder and no baselines",
        ));
    }
    chronocooked_analysis::report::write_report(&rows, &out).map_err(runtime_err)
}
