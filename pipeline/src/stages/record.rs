//! The record stage: the neural activity of a trained agent as an activity dataset
//! (`activity.json`), with its neural summary and figures.

use crate::PipelineError;
use chronocooked_env::make_config;
use chronocooked_models::agent::record_dataset;
use chronocooked_training::eval_tds;
use chronocooked_training::timing_run::{load_agent, run_task};
use std::path::PathBuf;

/// What to record (the arguments of `chronocooked record`).
#[derive(Debug, Clone)]
pub struct RecordRequest {
    /// Run folder of the trained agent (PPO or timing model).
    pub run: PathBuf,
    /// Task to play (default: the run's own task).
    pub task: Option<String>,
    /// Task overrides `key=value` (with `task`).
    pub env: Vec<String>,
    /// Target durations to record (steps; default: the task's evaluation TDs).
    pub tds: Vec<u32>,
    /// Repetitions of the every-start-cell protocol (seeds `seed + r`).
    pub repeats: u64,
    /// Seed of the recording.
    pub seed: u64,
    /// Output file (JSON activity dataset).
    pub out: PathBuf,
    /// Also write the neural summary of every population to `<out>.summary.json`.
    pub summary: bool,
    /// Also write heat maps and population figures into this folder.
    pub figures: Option<PathBuf>,
}

/// What a recording wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordOutcome {
    /// The recorded model.
    pub model: String,
    /// The task played.
    pub task: String,
    /// Trials recorded.
    pub trials: usize,
    /// Units per step.
    pub units: usize,
}

fn json_bytes<T: serde::Serialize>(value: &T, pretty: bool) -> Result<Vec<u8>, PipelineError> {
    let bytes = if pretty {
        serde_json::to_vec_pretty(value)
    } else {
        serde_json::to_vec(value)
    };
    bytes.map_err(|e| PipelineError::Analysis(format!("serialising the activity: {e}")))
}

/// Records the activity of `req` and writes the dataset (and summary, figures).
pub fn record(req: &RecordRequest) -> Result<RecordOutcome, PipelineError> {
    let (task, env) = match &req.task {
        Some(t) => (t.clone(), req.env.clone()),
        None => run_task(&req.run)?,
    };
    let config = make_config(&task, &env)?;
    let mut agent = load_agent(&req.run, Some(&config))?;
    let tds = if req.tds.is_empty() {
        eval_tds(&config)
    } else {
        req.tds.clone()
    };
    let dataset = record_dataset(
        agent.as_mut(),
        &config,
        &task,
        &env,
        &tds,
        req.repeats,
        req.seed,
    )?;
    let write = |path: &std::path::Path, bytes: &[u8]| {
        chronocooked_env::fs::write_atomic(path, bytes).map_err(|e| PipelineError::write(path, e))
    };
    write(&req.out, &json_bytes(&dataset, false)?)?;
    if let Some(dir) = &req.figures {
        chronocooked_analysis::report::figures::neural_figures(&dataset, dir)
            .map_err(|e| PipelineError::Analysis(e.to_string()))?;
    }
    if req.summary {
        let summaries: Vec<_> = dataset
            .meta
            .populations
            .iter()
            .filter_map(|p| {
                chronocooked_analysis::neural::summary::neural_summary(
                    &dataset,
                    Some(&p.name),
                    None,
                    req.seed,
                )
            })
            .collect();
        write(
            &req.out.with_extension("summary.json"),
            &json_bytes(&summaries, true)?,
        )?;
    }
    Ok(RecordOutcome {
        model: dataset.meta.model.clone(),
        task,
        trials: dataset.trials.len(),
        units: dataset.meta.n_units(),
    })
}
