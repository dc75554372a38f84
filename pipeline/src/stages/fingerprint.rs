//! The fingerprint stage: which timing mechanism do the lab's own trained runs resemble?
//! Each run folder (or zoo agent) plays the fingerprint protocol's condition it was trained
//! for (matched by its task and settings), and the agent's signature is placed among the
//! committed mechanism signatures (`chronocooked_present::fingerprint`).

use crate::PipelineError;
use crate::stages::record::units_correspond;
use chronocooked_env::TaskParams;
use chronocooked_present::fingerprint::{
    Fingerprint, PROTOCOL, ProtocolCondition, play_condition, write_and_place,
};
use chronocooked_training::RunFolder;
use chronocooked_training::timing_run::load_agent;
use std::path::{Path, PathBuf};

/// What to fingerprint (the arguments of `chronocooked fingerprint`).
#[derive(Debug, Clone)]
pub struct FingerprintRequest {
    /// Run folders of one agent, one per protocol condition it has (fixed interval at TD 6
    /// and TD 12, bisection 4–12); conditions without a run are left out.
    pub runs: Vec<PathBuf>,
    /// The agent's name in the outputs (default: the first run's model).
    pub name: Option<String>,
    /// Seed of the protocol's episodes, the category tests and the bootstrap.
    pub seed: u64,
    /// Bootstrap resamples of the mechanisms' seeds.
    pub resamples: usize,
    /// Output folder.
    pub out: PathBuf,
}

/// What the stage wrote.
#[derive(Debug, Clone)]
pub struct FingerprintOutcome {
    /// The placements among the mechanisms, in the unit and the dynamics view.
    pub placement: Fingerprint,
    /// Conditions played, in protocol order.
    pub conditions: Vec<&'static str>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// A bisection task's anchors (`None` for other tasks).
fn anchors(p: &TaskParams) -> Option<(u32, u32)> {
    match p {
        TaskParams::Bisection { short, long } => Some((*short, *long)),
        _ => None,
    }
}

/// The condition a run was trained for: same task, same settings as far as the condition
/// sets them (TD, anchors).
fn condition_of(run: &Path) -> Result<&'static ProtocolCondition, PipelineError> {
    let folder = RunFolder::open(run)?;
    let config = folder.task_config()?;
    let task = folder.task.id();
    PROTOCOL
        .iter()
        .find(|c| {
            c.task == task
                && c.to_task().and_then(|t| t.config()).is_ok_and(|want| {
                    want.params.td() == config.params.td()
                        && anchors(&want.params) == anchors(&config.params)
                })
        })
        .ok_or_else(|| {
            PipelineError::Invalid(format!(
                "{}: trained on {task} {} — no condition of the fingerprint protocol ({})",
                run.display(),
                folder.task.overrides().join(" "),
                PROTOCOL
                    .iter()
                    .map(|c| format!("{} {}", c.task, c.env.join(" ")))
                    .collect::<Vec<_>>()
                    .join("; ")
            ))
        })
}

/// Plays each run's condition, writes the condition folders and the fingerprint into
/// `req.out`.
pub fn fingerprint(req: &FingerprintRequest) -> Result<FingerprintOutcome, PipelineError> {
    if req.runs.is_empty() {
        return Err(PipelineError::Invalid(
            "give the agent's runs: --run RUN for each of fixed interval TD 6, fixed interval \
             TD 12 and bisection 4-12 that it has"
                .into(),
        ));
    }
    let mut matched: Vec<(&'static ProtocolCondition, &PathBuf)> = Vec::new();
    for run in &req.runs {
        chronocooked_env::fs::ensure_not_being_written(run)?;
        let c = condition_of(run)?;
        if let Some((_, other)) = matched.iter().find(|(m, _)| m.name == c.name) {
            return Err(PipelineError::Invalid(format!(
                "{} and {} are both runs of the condition {} (one run per condition)",
                other.display(),
                run.display(),
                c.name
            )));
        }
        matched.push((c, run));
    }
    matched.sort_by_key(|(c, _)| PROTOCOL.iter().position(|p| p.name == c.name));
    let mut model = None;
    let mut plays = Vec::new();
    for (c, run) in &matched {
        let config = c.to_task()?.config()?;
        let mut agent = load_agent(run, Some(&config))?;
        model.get_or_insert_with(|| agent.name());
        plays.push(
            play_condition(agent.as_mut(), c, req.seed)
                .map_err(|e| PipelineError::Analysis(e.to_string()))?,
        );
    }
    let name = req.name.clone().or(model).unwrap_or_else(|| "agent".into());
    let runs: Vec<&PathBuf> = matched.iter().map(|(_, r)| *r).collect();
    let (placement, files) = write_and_place(
        &req.out,
        &plays,
        &name,
        units_correspond(&runs),
        req.seed,
        req.resamples,
    )
    .map_err(|e| PipelineError::Analysis(e.to_string()))?;
    Ok(FingerprintOutcome {
        placement,
        conditions: matched.iter().map(|(c, _)| c.name).collect(),
        files,
    })
}
