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
/// when `default_baselines`, the repository's `results/paper-core`; with `improvement`, also
/// the probability of improvement between every two rows on that column. Returns the files.
#[pyfunction]
#[pyo3(signature = (evals, out, baselines = Vec::new(), default_baselines = true, improvement = None))]
pub fn report(
    evals: Vec<PathBuf>,
    out: PathBuf,
    baselines: Vec<PathBuf>,
    default_baselines: bool,
    improvement: Option<String>,
) -> PyResult<Vec<PathBuf>> {
    use chronocooked_present::report::baselines::{load_baseline_rows, locate_default_baselines};
    let mut rows = chronocooked_present::report::load_rows(&evals).map_err(value_err)?;
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
    let mut files = chronocooked_present::report::write_report(&rows, &out).map_err(runtime_err)?;
    if let Some(metric) = improvement {
        files.extend(
            chronocooked_present::report::write_improvement(&rows, &metric, &out)
                .map_err(value_err)?,
        );
    }
    Ok(files)
}

/// `P(X > Y)` for a random value of `x` and one of `y`, ties counting one half (NaN values
/// left out; NaN when either is empty).
#[pyfunction]
pub fn probability_of_improvement(x: Vec<f64>, y: Vec<f64>) -> f64 {
    chronocooked_analysis::stats::robust::probability_of_improvement(&x, &y)
}

/// The interquartile mean of `values` and its percentile bootstrap interval at `level`
/// (`strata`: one label per value, resampled within; default one stratum), `resamples`
/// resamples seeded by `seed`: `(iqm, (lo, hi) or None)`.
#[pyfunction]
#[pyo3(signature = (values, strata = None, level = 0.95, resamples = 2000, seed = 0))]
pub fn iqm(
    values: Vec<f64>,
    strata: Option<Vec<String>>,
    level: f64,
    resamples: usize,
    seed: u64,
) -> PyResult<(f64, Option<(f64, f64)>)> {
    use chronocooked_analysis::stats::robust;
    let strata = strata.unwrap_or_else(|| vec![String::new(); values.len()]);
    if strata.len() != values.len() {
        return Err(value_err(format!(
            "`strata` has {} labels for {} values (allowed: one label per value)",
            strata.len(),
            values.len()
        )));
    }
    if !(level > 0.0 && level < 1.0 && (1..=1_000_000).contains(&resamples)) {
        return Err(value_err(format!(
            "invalid `level` {level} or `resamples` {resamples} (allowed: 0 < level < 1, 1..=1000000 resamples)"
        )));
    }
    let ci = robust::stratified_bootstrap_ci(&values, &strata, robust::iqm, level, resamples, seed);
    Ok((robust::iqm(&values), ci))
}
