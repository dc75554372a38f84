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

/// One agent of a sweep's output fingerprinted by [`fingerprint_sweep`].
#[derive(Debug, Clone)]
pub struct SweepFingerprint {
    /// The agent's model.
    pub model: String,
    /// Its training seed.
    pub seed: u64,
    /// Its fingerprint's folder (`<out>/<model>-<seed>/`).
    pub folder: PathBuf,
    /// Its placement in both views.
    pub placement: Fingerprint,
    /// Whether the folder held a finished fingerprint already (placed again from its
    /// recorded signature, nothing replayed).
    pub reused: bool,
}

/// An agent of a sweep: (model, seed) and its runs of the protocol's conditions.
type SweepAgentRuns = ((String, u64), Vec<PathBuf>);

/// The finished jobs of a sweep's output whose runs are conditions of the fingerprint
/// protocol, grouped into agents (model, seed), the [`MECHANISMS`] first in their order,
/// then other models by name; seeds ascending.
fn sweep_agents(sweep_out: &Path) -> Result<Vec<SweepAgentRuns>, PipelineError> {
    use chronocooked_analysis::job_folder::{RUN, job_done, read_job};
    use chronocooked_analysis::mechanisms::MECHANISMS;
    if !sweep_out.is_dir() {
        return Err(PipelineError::Invalid(format!(
            "{}: no such sweep output folder (`chronocooked sweep FILE --out DIR` writes one)",
            sweep_out.display()
        )));
    }
    let mut agents: std::collections::BTreeMap<(usize, String, u64), Vec<PathBuf>> =
        Default::default();
    // Job folders: <out>/<task>/<row>/seed<N>/.
    for task in chronocooked_env::fs::real_subdirs(sweep_out) {
        for row in chronocooked_env::fs::real_subdirs(&task) {
            for job in chronocooked_env::fs::real_subdirs(&row) {
                if !job.join(chronocooked_analysis::job_folder::JOB).is_file() || !job_done(&job) {
                    continue;
                }
                let record = read_job(&job).map_err(PipelineError::Invalid)?;
                let run = job.join(RUN);
                if condition_of(&run).is_err() {
                    continue;
                }
                let rank = MECHANISMS
                    .iter()
                    .position(|m| *m == record.model)
                    .unwrap_or(MECHANISMS.len());
                agents
                    .entry((rank, record.model.clone(), record.seed))
                    .or_default()
                    .push(run);
            }
        }
    }
    Ok(agents
        .into_iter()
        .map(|((_, model, seed), runs)| ((model, seed), runs))
        .collect())
}

/// Fingerprints every agent (model × seed) of a sweep's output from its runs of the
/// fingerprint protocol's conditions (fixed interval TD 6 and TD 12, bisection 4–12, as
/// `sweeps/mechanisms-heldout.toml` trains them), each into `<out>/<model>-<seed>/` with
/// the protocol's seed 0, as `chronocooked fingerprint --run …` with its defaults. Resumable:
/// an agent whose folder holds a finished `fingerprint.json` is placed again from its
/// recorded signature (the same placement: the bootstrap is seeded), not replayed.
pub fn fingerprint_sweep(
    sweep_out: &Path,
    out: &Path,
    resamples: usize,
) -> Result<Vec<SweepFingerprint>, PipelineError> {
    let agents = sweep_agents(sweep_out)?;
    if agents.is_empty() {
        return Err(PipelineError::Invalid(format!(
            "{}: no finished job of a fingerprint protocol condition ({})",
            sweep_out.display(),
            PROTOCOL
                .iter()
                .map(|c| format!("{} {}", c.task, c.env.join(" ")))
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    let mut done = Vec::new();
    for ((model, seed), runs) in agents {
        let folder = out.join(format!("{model}-{seed}"));
        let recorded = chronocooked_present::fingerprint::read_signature(&folder).ok();
        let (placement, reused) = match recorded {
            Some(mut signature) => {
                signature.seed = seed;
                let placement = Fingerprint::place(
                    &signature,
                    &chronocooked_present::fingerprint::reference_signatures(),
                    resamples,
                    0,
                );
                (placement, true)
            }
            None => {
                let _ = std::fs::remove_dir_all(&folder);
                let r = fingerprint(&FingerprintRequest {
                    runs,
                    name: None,
                    seed: 0,
                    resamples,
                    out: folder.clone(),
                })?;
                (r.placement, false)
            }
        };
        done.push(SweepFingerprint {
            model,
            seed,
            folder,
            placement,
            reused,
        });
    }
    Ok(done)
}

/// One line per agent of [`fingerprint_sweep`], per view: the nearest mechanism, its
/// distance and identification limit, the verdict and the nearest other mechanism
/// (`ddm seed 40: units: nearest ddm 0.84 (limit 2.47) identified; nearest other
/// timecells-laplace 14.83 | dynamics: …`).
pub fn sweep_line(agent: &SweepFingerprint) -> String {
    let parts: Vec<String> = agent
        .placement
        .views()
        .into_iter()
        .map(|p| {
            let Some(nearest) = &p.nearest else {
                return format!("{}: no verdict (no feature shared)", p.view.key());
            };
            // The distances are nearest first: the first other mechanism is the nearest other.
            let own = p.distances.iter().find(|x| &x.mechanism == nearest);
            let other = p.distances.iter().find(|x| &x.mechanism != nearest);
            let fmt = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("{v:.2}"));
            format!(
                "{}: nearest {nearest} {} (limit {}) {}; nearest other {} {}",
                p.view.key(),
                fmt(own.map(|x| x.distance)),
                fmt(own.and_then(|x| x.limit)),
                if p.identified {
                    "identified"
                } else {
                    "not-identified"
                },
                other.map_or("–", |x| x.mechanism.as_str()),
                fmt(other.map(|x| x.distance)),
            )
        })
        .collect();
    format!("{} seed {}: {}", agent.model, agent.seed, parts.join(" | "))
}
