//! The eval stage: the task's evaluation protocol with a trained run or a reference agent,
//! written as an evaluation folder (`records.jsonl`, `eval.json`, `metrics.json`,
//! `figures/`, and with activity `activity.json` + `activity/`; a multi-timer run that kept
//! its curriculum levels' policies adds `levels.csv`, see [`super::levels`]).

use crate::PipelineError;
use chronocooked_analysis::{
    EvalRecord, Metrics, Mode, reference_conditions, run_protocol_recorded,
};
use chronocooked_env::{ChronoEnv, Task};
use chronocooked_models::Agent;
use chronocooked_models::activity::{ActivityMeta, TrialRecorder};
use chronocooked_models::agent::{OracleAgent, RandomAgent};
use chronocooked_present::eval_folder::{self as eval_folder, EvalInfo};
use chronocooked_training::RunFolder;
use chronocooked_training::timing_run::load_agent;
use std::path::{Path, PathBuf};

/// Who plays the protocol.
#[derive(Debug, Clone, PartialEq)]
pub enum EvalSubject {
    /// The trained agent of a run folder (PPO or timing model).
    Run(PathBuf),
    /// A reference agent by name: `oracle` or `random`.
    Reference(String),
}

/// What to evaluate and where to write it (the arguments of `chronocooked eval`).
#[derive(Debug, Clone)]
pub struct EvalRequest {
    /// Who plays.
    pub subject: EvalSubject,
    /// Task with its parameters (default: the run's own task; `FixedInterval-v0` for a
    /// reference agent).
    pub task: Option<Task>,
    /// Reference protocol (greedy, every start cell) or stochastic episodes per condition.
    pub mode: Mode,
    /// Seed of the evaluation.
    pub seed: u64,
    /// Output folder.
    pub out: PathBuf,
    /// Also record the model's activity, one trial per evaluated episode.
    pub activity: bool,
    /// Evaluate a run whose training did not finish (no `summary.json`: stopped, killed or
    /// out of disk) from its newest checkpoint; `eval.json` then says so. Without it such a
    /// run is refused.
    pub unfinished: bool,
}

/// The env step of the newest checkpoint of `run` (0 when it has none to name).
fn newest_checkpoint_step(run: &Path) -> u64 {
    std::fs::read_dir(run.join(chronocooked_models::run_folder::CHECKPOINTS))
        .map(|rd| {
            rd.flatten()
                .filter_map(|e| {
                    let name = e.file_name().into_string().ok()?;
                    name.strip_prefix("step-")?
                        .strip_suffix(".json")?
                        .parse()
                        .ok()
                })
                .max()
                .unwrap_or(0)
        })
        .unwrap_or(0)
}

/// Whether the run in `run` finished training; an unfinished one is refused unless
/// `unfinished` is set, and then named by its newest checkpoint's step.
fn check_finished(run: &Path, unfinished: bool) -> Result<Option<u64>, PipelineError> {
    chronocooked_env::fs::ensure_not_being_written(run)?;
    if run.join(chronocooked_models::run_folder::SUMMARY).is_file() {
        return Ok(None);
    }
    if chronocooked_training::timing_run::is_timing_run(run) {
        // A timing model has no checkpoints: its learned state is written at the end.
        let missing: Vec<String> = [
            chronocooked_models::run_folder::AGENT,
            chronocooked_models::run_folder::SUMMARY,
        ]
        .iter()
        .filter(|f| !run.join(f).is_file())
        .map(|f| run.join(f).display().to_string())
        .collect();
        return Err(PipelineError::Invalid(format!(
            "{}: the timing run did not finish: {} missing (stopped, killed or out of disk; a \
             timing model's learned state is written when its training ends). Complete it with \
             `chronocooked train --resume {}`",
            run.display(),
            missing.join(", "),
            run.display()
        )));
    }
    let step = newest_checkpoint_step(run);
    if unfinished {
        eprintln!(
            "warning: {} did not finish training; evaluating its newest checkpoint (env step {step})",
            run.display()
        );
        return Ok(Some(step));
    }
    Err(PipelineError::Invalid(format!(
        "{}: training did not finish (no {}; newest checkpoint at env step {step}): it was \
         stopped, killed or ran out of disk. Continue it with `chronocooked train --resume {}`, \
         or evaluate that checkpoint anyway with `eval --unfinished`",
        run.display(),
        chronocooked_models::run_folder::SUMMARY,
        run.display()
    )))
}

/// The agent `subject` names, to play `config`: a trained run's (PPO or timing model) or a
/// reference agent (oracle, random, a Bayesian observer).
pub(crate) fn subject_agent(
    subject: &EvalSubject,
    config: &chronocooked_env::TaskConfig,
) -> Result<Box<dyn Agent>, PipelineError> {
    Ok(match subject {
        EvalSubject::Run(run) => load_agent(run, Some(config))?,
        EvalSubject::Reference(name) if name == "oracle" => {
            Box::new(OracleAgent::new(&ChronoEnv::new(config)?))
        }
        EvalSubject::Reference(name) if name == "random" => Box::new(RandomAgent::default()),
        EvalSubject::Reference(name) if observer_agent(name).is_some() => {
            let Some(Ok((observer, wm, wp))) = observer_agent(name) else {
                return Err(PipelineError::Invalid(format!(
                    "--agent `{name}`: expected bls|map|ml, optionally :WM,WP with Weber fractions in [0.01, 1] (e.g. bls:0.1,0.06)"
                )));
            };
            let env = ChronoEnv::new(config)?;
            Box::new(
                chronocooked_models::bayes::ObserverAgent::new(&env, observer, wm, wp)
                    .map_err(|e| PipelineError::Invalid(format!("--agent `{name}`: {e}")))?,
            )
        }
        EvalSubject::Reference(other) => {
            return Err(PipelineError::Invalid(format!(
                "unknown --agent `{other}` (allowed: oracle, random, bls|map|ml[:WM,WP] on the reproduction task; trained models via --run DIR)"
            )));
        }
    })
}

/// What an evaluation wrote.
#[derive(Debug, Clone)]
pub struct EvalOutcome {
    /// The metrics (also in `metrics.json`).
    pub metrics: Metrics,
    /// Figure files written.
    pub figures: Vec<PathBuf>,
    /// With activity: (trials, units, the dataset file).
    pub activity: Option<(usize, usize, PathBuf)>,
    /// Curriculum levels whose policies were evaluated into `levels.csv` (multi-timer runs
    /// that kept them).
    pub levels: Option<usize>,
}

fn analysis(e: String) -> PipelineError {
    PipelineError::Analysis(e)
}

/// A Bayesian observer agent named `bls`, `map` or `ml`, optionally with `:WM,WP`
/// (defaults: J&S 2010's subjects' 0.1 and 0.06); `Some(Err)` for a malformed noise part.
fn observer_agent(
    name: &str,
) -> Option<Result<(chronocooked_analysis::reproduction::Observer, f64, f64), ()>> {
    use chronocooked_analysis::reproduction::{Observer, agent};
    let (kind, noise) = name.split_once(':').unwrap_or((name, ""));
    let observer = match kind {
        "bls" => Observer::Bls,
        "map" => Observer::Map,
        "ml" => Observer::Ml,
        _ => return None,
    };
    if noise.is_empty() {
        return Some(Ok((observer, agent::DEFAULT_WM, agent::DEFAULT_WP)));
    }
    let parsed: Vec<f64> = noise
        .split(',')
        .filter_map(|x| x.trim().parse().ok())
        .collect();
    Some(match parsed.as_slice() {
        [wm, wp] if (0.01..=1.0).contains(wm) && (0.01..=1.0).contains(wp) => {
            Ok((observer, *wm, *wp))
        }
        _ => Err(()),
    })
}

/// Plays the protocol of `req` and writes its evaluation folder.
pub fn evaluate(req: &EvalRequest) -> Result<EvalOutcome, PipelineError> {
    if req.mode == (Mode::Stochastic { episodes: 0 }) {
        return Err(PipelineError::Invalid(
            "--stochastic needs a positive number of episodes per condition".into(),
        ));
    }
    let task = match (&req.task, &req.subject) {
        (Some(t), _) => t.clone(),
        (None, EvalSubject::Run(run)) => RunFolder::open(run)?.task,
        (None, EvalSubject::Reference(_)) => Task::new("FixedInterval-v0")?,
    };
    let unfinished_at_step = match &req.subject {
        EvalSubject::Run(run) => check_finished(run, req.unfinished)?,
        EvalSubject::Reference(_) => None,
    };
    let config = task.config()?;
    let mut agent = subject_agent(&req.subject, &config)?;
    let conditions = reference_conditions(&task)?;
    // One writer per evaluation folder, taken before the protocol is played.
    let _lock = chronocooked_env::fs::FolderLock::acquire(&req.out)?;
    // Nothing of an earlier evaluation in the folder stays beside this one.
    eval_folder::begin_evaluation(&req.out).map_err(analysis)?;
    let meta = ActivityMeta::new(&agent.name(), &task, req.seed);
    let mut recorder = TrialRecorder::new(meta);
    let records = run_protocol_recorded(
        agent.as_mut(),
        &conditions,
        req.mode,
        req.seed,
        req.activity.then_some(&mut recorder),
    )?;
    let info = EvalInfo {
        model: agent.name(),
        task,
        mode: req.mode,
        seed: req.seed,
        unfinished_at_step,
        episodes: None,
    };
    // A multi-timer run's per-level policies, each in its level's test setting — before
    // `metrics.json`, so that an evaluation folder with metrics is a finished one.
    let levels = match (&req.subject, &req.task, req.mode) {
        (EvalSubject::Run(run), None, Mode::Reference) => {
            super::levels::evaluate_levels(run, &req.out, req.seed)?
        }
        _ => None,
    };
    // The activity before the records and metrics: `metrics.json`, written last, marks a
    // complete folder.
    let activity = if req.activity {
        let dataset = recorder.finish();
        if dataset.meta.n_units() == 0 {
            return Err(PipelineError::Invalid(format!(
                "{} records no activity (reference agents have no units); drop --activity",
                info.model
            )));
        }
        let files = eval_folder::write_activity(&req.out, &dataset).map_err(analysis)?;
        Some((
            dataset.trials.len(),
            dataset.meta.n_units(),
            files[0].clone(),
        ))
    } else {
        None
    };
    let (metrics, figures) =
        eval_folder::write_eval_folder(&req.out, &info, &records).map_err(analysis)?;
    Ok(EvalOutcome {
        metrics,
        figures,
        activity,
        levels,
    })
}

/// Writes the evaluation folder of recorded human play (`env play --record FILE`, JSON
/// lines) into `out`.
pub fn evaluate_human(file: &Path, seed: u64, out: &Path) -> Result<EvalOutcome, PipelineError> {
    let text = std::fs::read_to_string(file).map_err(|e| PipelineError::read(file, e))?;
    let records =
        chronocooked_analysis::behaviour::human::records_from_trace(&text).map_err(|e| {
            PipelineError::NotA {
                path: file.to_path_buf(),
                what: "a recording of human play (`env play --record`)",
                message: e.to_string(),
            }
        })?;
    let Some(first) = records.first() else {
        return Err(PipelineError::Invalid(format!(
            "{} holds no episodes (record some with `env play --record`)",
            file.display()
        )));
    };
    let info = EvalInfo {
        model: "human".into(),
        task: first.condition.task.clone(),
        mode: Mode::Stochastic {
            episodes: records.len(),
        },
        seed,
        unfinished_at_step: None,
        episodes: None,
    };
    let _lock = chronocooked_env::fs::FolderLock::acquire(out)?;
    eval_folder::begin_evaluation(out).map_err(analysis)?;
    let (metrics, figures) =
        eval_folder::write_eval_folder(out, &info, &records).map_err(analysis)?;
    Ok(EvalOutcome {
        metrics,
        figures,
        activity: None,
        levels: None,
    })
}

/// Recomputes `metrics.json` and the figures into `out` from the records of the earlier
/// evaluation folder `from`.
pub fn rescore_eval_folder(from: &Path, out: &Path) -> Result<EvalOutcome, PipelineError> {
    chronocooked_env::fs::ensure_not_being_written(from)?;
    let _lock = chronocooked_env::fs::FolderLock::acquire(out)?;
    let info = eval_folder::read_eval_info(from).map_err(analysis)?;
    let records: Vec<EvalRecord> = chronocooked_analysis::evaluation::protocol::read_records(from)
        .map_err(|e| PipelineError::Analysis(format!("{e} (not an eval folder)")))?;
    let (metrics, figures) = eval_folder::write_metrics(out, &info, &records).map_err(analysis)?;
    Ok(EvalOutcome {
        metrics,
        figures,
        activity: None,
        levels: None,
    })
}
