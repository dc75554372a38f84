//! The fingerprint protocol: the conditions an agent plays, the folders they leave, and the
//! agent's signature read back from them.

use crate::eval_folder::{EvalInfo, begin_evaluation, write_eval_folder};
use chronocooked_analysis::evaluation::protocol::{EvalRecord, reference_conditions, run_protocol};
use chronocooked_analysis::job_folder;
use chronocooked_analysis::mechanisms::{
    JobFiles, MechanismError, Signature, assemble, geometry_index_of_summary,
    scaling_index_of_summary,
};
use chronocooked_analysis::neural::probe::{population_summaries, probe_task};
use chronocooked_analysis::records::{METRICS, Mode};
use chronocooked_env::integrity::write_recorded;
use chronocooked_env::{EnvError, Task};
use chronocooked_models::agent::record_dataset;
use chronocooked_models::{ActivityDataset, Agent};
use std::path::{Path, PathBuf};

/// One condition of the fingerprint protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProtocolCondition {
    /// Folder name, and the key of a policy for it (`fi-td6`, `fi-td12`, `bisection-4-12`).
    pub name: &'static str,
    /// Task id the agent is trained and evaluated on.
    pub task: &'static str,
    /// Task parameters (`key=value`).
    pub env: &'static [&'static str],
    /// The TD of a fixed-interval condition (steps): it is also recorded on probe trials.
    pub probe_td: Option<u32>,
}

impl ProtocolCondition {
    /// The condition's task with its parameters.
    pub fn to_task(&self) -> Result<Task, EnvError> {
        Task::parse(self.task, self.env)
    }
}

/// The mechanisms study's conditions (`sweeps/mechanisms-reference.toml`): fixed interval
/// at TD 6 and TD 12 (the temporal scaling of the activity between them), bisection 4–12.
pub const PROTOCOL: [ProtocolCondition; 3] = [
    ProtocolCondition {
        name: "fi-td6",
        task: "FixedInterval-v0",
        env: &["td=6"],
        probe_td: Some(6),
    },
    ProtocolCondition {
        name: "fi-td12",
        task: "FixedInterval-v0",
        env: &["td=12"],
        probe_td: Some(12),
    },
    ProtocolCondition {
        name: "bisection-4-12",
        task: "Bisection-v0",
        env: &["short=4", "long=12"],
        probe_td: None,
    },
];

/// What an agent did in one condition: the evaluation's episodes and, for a fixed-interval
/// condition, its recording on probe trials (`None` when the agent has no activity).
pub struct ConditionPlay {
    /// The condition.
    pub condition: ProtocolCondition,
    /// Every episode of the reference protocol.
    pub records: Vec<EvalRecord>,
    /// The probe-trial recording.
    pub probe: Option<ActivityDataset>,
}

/// Plays `condition` with `agent`: the reference evaluation protocol (seeded by `seed`),
/// then — for a fixed-interval condition — one probe trial per free start cell at its TD.
/// Writes nothing (see [`write_condition`]).
pub fn play_condition(
    agent: &mut dyn Agent,
    condition: &ProtocolCondition,
    seed: u64,
) -> Result<ConditionPlay, MechanismError> {
    let here = Path::new(condition.name);
    let task = condition
        .to_task()
        .map_err(|e| MechanismError::at(here, e))?;
    let conditions = reference_conditions(&task).map_err(|e| MechanismError::at(here, e))?;
    let records = run_protocol(agent, &conditions, Mode::Reference, seed)
        .map_err(|e| MechanismError::at(here, e))?;
    let probe = match condition.probe_td {
        Some(td) => {
            let probe = probe_task(&task, &[td]).map_err(|e| MechanismError::at(here, e))?;
            let config = probe.config().map_err(|e| MechanismError::at(here, e))?;
            let ds = record_dataset(agent, &config, &probe, &[td], 1, seed)
                .map_err(|e| MechanismError::at(here, e))?;
            (ds.meta.n_units() > 0).then_some(ds)
        }
        None => None,
    };
    Ok(ConditionPlay {
        condition: *condition,
        records,
        probe,
    })
}

/// Writes one condition's folder `<dir>/<condition>/`: the evaluation folder `eval/` and,
/// with a probe recording, `activity.json` and its neural summary `activity.summary.json`
/// (the summary first removed, so an old one never stays beside a new recording).
/// Returns the condition's folder.
pub fn write_condition(
    dir: &Path,
    play: &ConditionPlay,
    model: &str,
    seed: u64,
) -> Result<PathBuf, MechanismError> {
    let folder = dir.join(play.condition.name);
    let eval = folder.join(job_folder::EVAL);
    let info = EvalInfo {
        model: model.to_string(),
        task: play
            .condition
            .to_task()
            .map_err(|e| MechanismError::at(&eval, e))?,
        mode: Mode::Reference,
        seed,
        unfinished_at_step: None,
        episodes: None,
    };
    begin_evaluation(&eval).map_err(|e| MechanismError::at(&eval, e))?;
    write_eval_folder(&eval, &info, &play.records).map_err(|e| MechanismError::at(&eval, e))?;
    let activity = folder.join(job_folder::ACTIVITY);
    let summary = folder.join(job_folder::ACTIVITY_SUMMARY);
    chronocooked_env::integrity::remove_recorded(&summary)
        .map_err(|e| MechanismError::at(&summary, e))?;
    chronocooked_env::integrity::remove_recorded(&activity)
        .map_err(|e| MechanismError::at(&activity, e))?;
    if let Some(ds) = &play.probe {
        let bytes = serde_json::to_vec(ds).map_err(|e| MechanismError::at(&activity, e))?;
        write_recorded(&activity, &bytes).map_err(|e| MechanismError::at(&activity, e))?;
        let summaries = population_summaries(ds, true, seed);
        let bytes =
            serde_json::to_vec_pretty(&summaries).map_err(|e| MechanismError::at(&summary, e))?;
        write_recorded(&summary, &bytes).map_err(|e| MechanismError::at(&summary, e))?;
    }
    Ok(folder)
}

/// Reads a recorded activity dataset (`None` when the file does not exist).
fn read_dataset(path: &Path) -> Result<Option<ActivityDataset>, MechanismError> {
    if !path.is_file() {
        return Ok(None);
    }
    let bytes =
        chronocooked_env::integrity::read_checked(path).map_err(|e| MechanismError::at(path, e))?;
    ActivityDataset::from_json(&bytes)
        .map(Some)
        .map_err(|e| MechanismError::at(path, e))
}

/// The signature of the agent whose protocol folders are under `dir` (conditions without a
/// finished evaluation are left out: their features are missing). `units_correspond` says
/// whether unit `j` of the TD-6 agent is unit `j` of the TD-12 agent (one network timing
/// both, or copies of one model): only then is the per-unit scaling factor defined, where
/// the population geometry cannot tell (a straight ramp). `seed` seeds the category tests.
pub fn agent_signature(
    dir: &Path,
    model: &str,
    units_correspond: bool,
    seed: u64,
) -> Result<Signature, MechanismError> {
    let mut jobs = Vec::new();
    let mut probes: Vec<ActivityDataset> = Vec::new();
    for c in &PROTOCOL {
        let folder = dir.join(c.name);
        let metrics = folder.join(job_folder::EVAL).join(METRICS);
        if !metrics.is_file() {
            continue;
        }
        jobs.push(JobFiles {
            model: model.to_string(),
            seed,
            task: c.task.to_string(),
            metrics,
            summary: folder.join(job_folder::ACTIVITY_SUMMARY),
        });
        if c.probe_td.is_some()
            && let Some(ds) = read_dataset(&folder.join(job_folder::ACTIVITY))?
        {
            probes.push(ds);
        }
    }
    if jobs.is_empty() {
        return Err(MechanismError::Empty(dir.to_path_buf()));
    }
    // Temporal scaling: the fixed-interval recordings merged (trials of both TDs).
    let mut scaling = Vec::new();
    let mut it = probes.into_iter();
    if let Some(mut merged) = it.next() {
        let mut tds = 1;
        for more in it {
            if more.meta.populations == merged.meta.populations {
                merged.trials.extend(more.trials);
                tds += 1;
            }
        }
        if tds >= 2 {
            let summaries = population_summaries(&merged, units_correspond, seed);
            let view = chronocooked_analysis::mechanisms::PopulationView::all(&summaries);
            if let Some(i) = scaling_index_of_summary(&view).filter(|i| i.is_finite()) {
                scaling.push((model.to_string(), seed, "scaling_index", i));
            }
            if let Some(i) = geometry_index_of_summary(&view).filter(|i| i.is_finite()) {
                scaling.push((model.to_string(), seed, "dyn_scaling", i));
            }
        }
    }
    let mut sigs = assemble(&jobs, &scaling)?;
    sigs.pop()
        .ok_or_else(|| MechanismError::Empty(dir.to_path_buf()))
}
