//! The train stage: a PPO agent or a timing model into a run folder, new or resumed.

use crate::PipelineError;
use chronocooked_env::Task;
use chronocooked_env::fs::FolderLock;
use chronocooked_models::{Architecture, TimingCurvePoint};
use chronocooked_training::{
    Check, Progress, RunSummary, TimingRunConfig, TimingRunSummary, UpdateLog, load_timing_config,
    resolve, run_timing_training, run_training,
};
use serde::Serialize;
use std::path::PathBuf;

/// What to train (the arguments of `chronocooked train`).
#[derive(Debug, Clone)]
pub struct TrainRequest {
    /// Task id (`FixedInterval-v0`, …).
    pub task: String,
    /// Model name (`cnn-mlp`, `lstm125`, `ctrnn-reservoir125`, `ddm`, `timecells-ms`, …).
    pub model: String,
    /// PPO hyperparameter preset (`reference`, `fast`, or a preset file); unused by timing
    /// models.
    pub preset: String,
    /// Seed of everything random in the run.
    pub seed: u64,
    /// PPO env-step budget (`steps`) overriding the preset's; timing models train by
    /// episodes (`--set episodes=N`).
    pub steps: Option<u64>,
    /// Setting overrides `key=value` (`env.<param>=v` for task parameters).
    pub sets: Vec<String>,
    /// Run folder of a new run (default `runs/<task>/<model>/seed<N>`).
    pub out: Option<PathBuf>,
    /// Continue the run in this folder with its saved (and re-checked) config instead.
    pub resume: Option<PathBuf>,
    /// The command line recorded in the run folder.
    pub command: String,
}

/// What a train stage produced.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum TrainOutcome {
    /// A PPO run.
    Ppo(RunSummary),
    /// A timing-model run.
    Timing(TimingRunSummary),
}

impl TrainOutcome {
    /// The run folder.
    pub fn dir(&self) -> &std::path::Path {
        match self {
            TrainOutcome::Ppo(s) => &s.dir,
            TrainOutcome::Timing(s) => &s.dir,
        }
    }
}

/// Sees the progress of a training run (progress bars, logs); every method does nothing by
/// default.
pub trait TrainObserver {
    /// After every PPO update (`total_steps`: the run's env-step budget).
    fn ppo_update(&mut self, _row: &UpdateLog, _total_steps: u64) {}
    /// At every learning-curve point of a timing model (`total_episodes`: its budget).
    fn timing_point(&mut self, _point: &TimingCurvePoint, _total_episodes: usize) {}
}

/// A [`TrainObserver`] that reports nothing.
pub struct Quiet;
impl TrainObserver for Quiet {}

struct PpoBridge<'a>(&'a mut dyn TrainObserver);
impl Progress for PpoBridge<'_> {
    fn update(&mut self, row: &UpdateLog, total_steps: u64) {
        self.0.ppo_update(row, total_steps);
    }
}

/// Trains (or resumes) the run of `req`, then draws its learning curve. Returns the run's
/// summary and, when the figure could not be drawn, why (the run is kept either way).
pub fn train(
    req: &TrainRequest,
    observer: &mut dyn TrainObserver,
) -> Result<(TrainOutcome, Option<String>), PipelineError> {
    let timing_resume = req
        .resume
        .as_deref()
        .is_some_and(chronocooked_training::run_config::says_timing);
    let timing = timing_resume || chronocooked_models::timing::zoo::is_timing_model(&req.model);
    // The run folder's lock is held over training and the figure (training takes it again:
    // a no-op inside this process); each trainer takes it once the folder is known.
    let (outcome, _lock) = if timing {
        let (o, l) = train_timing(req, observer)?;
        (TrainOutcome::Timing(o), l)
    } else {
        let (o, l) = train_ppo(req, observer)?;
        (TrainOutcome::Ppo(o), l)
    };
    chronocooked_env::fs::remove_temp_files(
        &outcome.dir().join(chronocooked_models::run_folder::FIGURES),
    );
    let figure_error = chronocooked_present::figures::learning_curve(outcome.dir())
        .err()
        .map(|e| e.to_string());
    Ok((outcome, figure_error))
}

fn default_dir(task: &str, model: &str, seed: u64) -> PathBuf {
    PathBuf::from(format!("runs/{task}/{model}/seed{seed}"))
}

fn train_ppo(
    req: &TrainRequest,
    observer: &mut dyn TrainObserver,
) -> Result<(RunSummary, FolderLock), PipelineError> {
    let mut progress = PpoBridge(observer);
    if let Some(dir) = &req.resume {
        if !req.sets.is_empty() {
            return Err(PipelineError::Invalid(
                "--resume continues a run with its saved config; --set cannot be combined with it (--steps N extends its budget)"
                    .into(),
            ));
        }
        // Not a run folder: said before any lock file is made there.
        let run = chronocooked_training::RunDir::open(dir)?;
        let lock = FolderLock::acquire(dir)?;
        if let Some(steps) = req.steps {
            run.extend_budget(steps)?;
        }
        return Ok((run_training(None, dir, &req.command, &mut progress)?, lock));
    }
    let model: Architecture = req.model.parse().map_err(PipelineError::Invalid)?;
    let mut sets = req.sets.clone();
    if let Some(s) = req.steps {
        sets.push(format!("total_steps={s}"));
    }
    let cfg = resolve(&req.task, model, &req.preset, req.seed, &sets)?;
    let dir = req
        .out
        .clone()
        .unwrap_or_else(|| default_dir(cfg.task.id(), &model.name(), req.seed));
    let lock = FolderLock::acquire(&dir)?;
    Ok((
        run_training(Some(cfg.check()?), &dir, &req.command, &mut progress)?,
        lock,
    ))
}

fn train_timing(
    req: &TrainRequest,
    observer: &mut dyn TrainObserver,
) -> Result<(TimingRunSummary, FolderLock), PipelineError> {
    if req.steps.is_some() {
        return Err(PipelineError::Invalid(
            "timing models train by episodes: use --set episodes=N instead of --steps".into(),
        ));
    }
    let (cfg, dir) = match &req.resume {
        Some(dir) if dir.join(chronocooked_models::run_folder::SUMMARY).is_file() => {
            // A finished run: nothing to train; its learning-curve figure is drawn again (a
            // run whose figure write failed gets it here).
            let lock = FolderLock::acquire(dir)?;
            let path = dir.join(chronocooked_models::run_folder::SUMMARY);
            let text = std::fs::read(&path).map_err(|e| PipelineError::read(&path, e))?;
            let mut summary: TimingRunSummary =
                serde_json::from_slice(&text).map_err(|e| PipelineError::NotA {
                    path,
                    what: "a timing run's summary",
                    message: e.to_string(),
                })?;
            // The folder as given now, not as it was named when the run was made (a
            // relative path from another working directory, or a moved folder).
            summary.dir = dir.clone();
            return Ok((summary, lock));
        }
        Some(dir) => (load_timing_config(dir)?, dir.clone()),
        None => {
            let mut cfg = TimingRunConfig::new(&Task::new(&req.task)?, &req.model, req.seed);
            for kv in &req.sets {
                cfg.set(kv)?;
            }
            let dir = req
                .out
                .clone()
                .unwrap_or_else(|| default_dir(&req.task, &req.model, req.seed));
            (cfg, dir)
        }
    };
    let total = cfg.train.episodes;
    cfg.validate()?;
    let lock = FolderLock::acquire(&dir)?;
    let summary = run_timing_training(&cfg, &dir, &req.command, |p| {
        observer.timing_point(p, total)
    })?;
    Ok((summary, lock))
}
