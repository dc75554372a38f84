//! The record stage: the neural activity of a trained agent as an activity dataset
//! (`activity.json`), with its neural summary and figures.
//!
//! With `probe`, an agent trained on fixed interval plays peak-interval probe trials
//! (`PeakInterval-v0`, `probe_factor=0`: the soup is never released), so every trial goes
//! on for at least `2 × TD` steps after oven-on — the window the neural summary analyses.
//! Several runs (the same model trained at different TDs) are recorded each at its own TD
//! into one dataset, so the summary can measure temporal scaling between TDs.

use crate::PipelineError;
pub use chronocooked_analysis::neural::probe::{PROBE_MARGIN, can_probe};
use chronocooked_analysis::neural::probe::{population_summaries, probe_task};
use chronocooked_env::Task;
use chronocooked_models::ActivityDataset;
use chronocooked_models::agent::record_dataset;
use chronocooked_training::RunFolder;
use chronocooked_training::eval_tds;
use chronocooked_training::timing_run::{is_timing_run, load_agent, load_timing_config};
use std::path::{Path, PathBuf};

/// What to record (the arguments of `chronocooked record`).
#[derive(Debug, Clone)]
pub struct RecordRequest {
    /// Run folder of the trained agent (PPO or timing model).
    pub run: PathBuf,
    /// More run folders of the same model (e.g. trained at other TDs), recorded into the
    /// same dataset (each at its own TD when `tds` is empty).
    pub more_runs: Vec<PathBuf>,
    /// Task to play, with its parameters (default: the run's own task).
    pub task: Option<Task>,
    /// Target durations to record (steps; default: the task's evaluation TDs — with
    /// `probe`, the run's own TD).
    pub tds: Vec<u32>,
    /// Play peak-interval probe trials (soup withheld for the whole episode) with the run's
    /// fixed-interval settings; needs runs trained on `FixedInterval-v0` or
    /// `PeakInterval-v0`.
    pub probe: bool,
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

/// Most repetitions of the every-start-cell protocol one recording takes (`record
/// --repeats`, a sweep's `record_repeats`): a repeat of an SBF agent (1,000 oscillators)
/// holds ≈ 2.5 MB of activity per TD in memory; 100 repeats (≈ 1,000 trials per TD) are well
/// beyond what the summaries need.
pub const MAX_REPEATS: u64 = 100;

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
    /// The populations those units belong to, in column order: (name, units), e.g. an
    /// LSTM's `latent` 125, `cell` 125 and `value` 1.
    pub populations: Vec<(String, usize)>,
}

fn json_bytes<T: serde::Serialize>(value: &T, pretty: bool) -> Result<Vec<u8>, PipelineError> {
    let bytes = if pretty {
        serde_json::to_vec_pretty(value)
    } else {
        serde_json::to_vec(value)
    };
    bytes.map_err(|e| PipelineError::Analysis(format!("serialising the activity: {e}")))
}

/// Records one run: the task played and the dataset.
fn record_run(req: &RecordRequest, run: &Path) -> Result<(Task, ActivityDataset), PipelineError> {
    let task = match &req.task {
        Some(t) => t.clone(),
        None => RunFolder::open(run)?.task,
    };
    let own = task.config()?;
    let tds = if !req.tds.is_empty() {
        req.tds.clone()
    } else if req.probe {
        vec![own.params.td().unwrap_or(12)]
    } else {
        eval_tds(&own)
    };
    let task = if req.probe {
        probe_task(&task, &tds).map_err(PipelineError::Invalid)?
    } else {
        task
    };
    let config = task.config()?;
    let mut agent = load_agent(run, Some(&config))?;
    let dataset = record_dataset(agent.as_mut(), &config, &task, &tds, req.repeats, req.seed)?;
    Ok((task, dataset))
}

/// Whether unit `j` is the same unit in every run: one run, or timing-model runs of the
/// same model and seed (fixed oscillator frequencies, time-cell bases).
pub(crate) fn units_correspond(runs: &[&PathBuf]) -> bool {
    if runs.len() <= 1 {
        return true;
    }
    let keys: Option<Vec<(String, u64)>> = runs
        .iter()
        .map(|r| {
            is_timing_run(r)
                .then(|| load_timing_config(r).ok().map(|c| (c.model, c.seed)))
                .flatten()
        })
        .collect();
    keys.is_some_and(|k| k.windows(2).all(|w| w[0] == w[1]))
}

/// Records the activity of `req` and writes the dataset (and summary, figures).
pub fn record(req: &RecordRequest) -> Result<RecordOutcome, PipelineError> {
    let runs: Vec<&PathBuf> = std::iter::once(&req.run).chain(&req.more_runs).collect();
    for run in &runs {
        chronocooked_env::fs::ensure_not_being_written(run)?;
    }
    // One writer per output folder (the dataset's folder; a sweep job already holds it).
    let folder = match req.out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let _lock = chronocooked_env::fs::FolderLock::acquire_shared_folder(&folder)?;
    let (task, mut dataset) = record_run(req, &req.run)?;
    for run in &req.more_runs {
        let (_, more) = record_run(req, run)?;
        if more.meta.populations != dataset.meta.populations
            || more.meta.model != dataset.meta.model
        {
            return Err(PipelineError::Invalid(format!(
                "{} records {} with other populations than {} ({}): record runs of one model \
                 together",
                run.display(),
                more.meta.model,
                req.run.display(),
                dataset.meta.model
            )));
        }
        dataset.trials.extend(more.trials);
    }
    // With SHA-256 records (`SHA256SUMS` beside them): an edited dataset is refused.
    let write = |path: &std::path::Path, bytes: &[u8]| {
        chronocooked_env::integrity::write_recorded(path, bytes)
            .map_err(|e| PipelineError::Analysis(e.to_string()))
    };
    // The summary of an older dataset never stays beside a new one: removed first, written
    // after the dataset.
    let summary_path = req.out.with_extension("summary.json");
    let manifest = folder.join(chronocooked_env::integrity::MANIFEST);
    for p in [&req.out, &summary_path, &manifest] {
        chronocooked_env::fs::remove_temp_files_of(p);
    }
    chronocooked_env::integrity::remove_recorded(&summary_path)
        .map_err(|e| PipelineError::Analysis(e.to_string()))?;
    write(&req.out, &json_bytes(&dataset, false)?)?;
    if let Some(dir) = &req.figures {
        // What a killed earlier `record` left half-written in its figure folders goes first
        // (one folder per population below `dir`).
        chronocooked_env::fs::remove_temp_files_below(dir, 2);
        chronocooked_present::figures::neural_figures(&dataset, dir)
            .map_err(|e| PipelineError::Analysis(e.to_string()))?;
    }
    if req.summary {
        let summaries = population_summaries(&dataset, units_correspond(&runs), req.seed);
        write(&summary_path, &json_bytes(&summaries, true)?)?;
    }
    Ok(RecordOutcome {
        model: dataset.meta.model.clone(),
        task: task.id().to_string(),
        trials: dataset.trials.len(),
        units: dataset.meta.n_units(),
        populations: dataset
            .meta
            .populations
            .iter()
            .map(|p| (p.name.clone(), p.size))
            .collect(),
    })
}
