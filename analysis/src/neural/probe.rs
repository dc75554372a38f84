//! Peak-interval probe trials: the recording condition of the neural summary.
//!
//! An agent trained on fixed interval plays `PeakInterval-v0` with the same settings and
//! `probe_factor=0` (the soup is never released), so every trial goes on for at least
//! `2 × TD` steps after oven-on — the window the neural summary analyses. Used by `record
//! --probe`, the mechanisms study and the fingerprint protocol.

use crate::neural::summary::{NeuralSummary, SummaryOptions, neural_summary};
use chronocooked_env::{Task, TaskFamily};
use chronocooked_models::ActivityDataset;

/// Steps a probe episode lasts beyond `2 × TD`: time to fetch the onion and turn the oven
/// on (the kitchen's free cells are at most ~10 steps from the oven).
pub const PROBE_MARGIN: u32 = 40;

/// The task probe trials are played on.
pub const PROBE_TASK: &str = "PeakInterval-v0";

/// Whether agents trained on `task` can be recorded on probe trials.
pub fn can_probe(task: &str) -> bool {
    Task::new(task).is_ok_and(|t| probes(t.family()))
}

fn probes(family: TaskFamily) -> bool {
    matches!(family, TaskFamily::FixedInterval | TaskFamily::PeakInterval)
}

/// [`PROBE_TASK`] for an agent trained on `task`, at TDs `tds`: the same parameters with
/// the soup never released and (unless `task` sets it) `max_timesteps = 2 × max TD +
/// PROBE_MARGIN`. An error (saying why) for tasks that [`can_probe`] refuses.
pub fn probe_task(task: &Task, tds: &[u32]) -> Result<Task, String> {
    if !probes(task.family()) {
        return Err(format!(
            "--probe plays peak-interval probe trials, for runs trained on FixedInterval-v0 or \
             PeakInterval-v0 (this run: {}); record it without --probe",
            task.id()
        ));
    }
    let build = || -> Result<Task, chronocooked_env::EnvError> {
        let mut probe = Task::new(PROBE_TASK)?;
        for (key, value) in task.values_set() {
            if key != "probe_factor" {
                probe.set_value(key, value.clone())?;
            }
        }
        probe.set("probe_factor", "0")?;
        if task.value_set("max_timesteps").is_none() {
            let longest = tds.iter().copied().max().unwrap_or(12);
            probe.set("max_timesteps", &(2 * longest + PROBE_MARGIN).to_string())?;
        }
        probe.config()?;
        Ok(probe)
    };
    build().map_err(|e| e.to_string())
}

/// The neural summary of every population of `dataset` (populations the summary cannot
/// analyse, e.g. without oven-on, are left out); `units_correspond` says whether unit `j`
/// is the same unit in every trial's agent (one network, or timing models of one model
/// and seed), `seed` seeds the category tests' surrogates.
pub fn population_summaries(
    dataset: &ActivityDataset,
    units_correspond: bool,
    seed: u64,
) -> Vec<NeuralSummary> {
    let mut opts = SummaryOptions {
        units_correspond,
        ..SummaryOptions::default()
    };
    opts.categories.seed = seed;
    dataset
        .meta
        .populations
        .iter()
        .filter_map(|p| neural_summary(dataset, Some(&p.name), &opts).ok())
        .collect()
}

/// The neural summary of a recorded activity dataset: `path` is an `activity.json` (from
/// `record`, or an evaluation folder's) or a folder holding one. Writes the summary beside
/// it (`activity.summary.json`, SHA-256-recorded) and returns its path and the summaries.
/// `units_correspond` and `seed` as in [`population_summaries`].
pub fn summarize_file(
    path: &std::path::Path,
    units_correspond: bool,
    seed: u64,
) -> Result<(std::path::PathBuf, Vec<NeuralSummary>), String> {
    let file = if path.is_dir() {
        path.join(crate::job_folder::ACTIVITY)
    } else {
        path.to_path_buf()
    };
    if !file.is_file() {
        return Err(format!(
            "{}: no activity dataset (an evaluation folder of an agent that returned activity, \
             or an activity.json from `record`)",
            file.display()
        ));
    }
    let folder = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let _lock = chronocooked_env::fs::FolderLock::acquire_shared_folder(&folder)
        .map_err(|e| e.to_string())?;
    let bytes = chronocooked_env::integrity::read_checked(&file).map_err(|e| e.to_string())?;
    let dataset =
        ActivityDataset::from_json(&bytes).map_err(|e| format!("{}: {e}", file.display()))?;
    let summaries = population_summaries(&dataset, units_correspond, seed);
    if summaries.is_empty() {
        return Err(format!(
            "{}: no population could be summarised (the summary needs trials with oven-on; \
             record fixed-interval agents on probe trials)",
            file.display()
        ));
    }
    let out = file.with_extension("summary.json");
    let json = serde_json::to_vec_pretty(&summaries).map_err(|e| e.to_string())?;
    chronocooked_env::integrity::write_recorded(&out, &json).map_err(|e| e.to_string())?;
    Ok((out, summaries))
}

/// Recomputes the dynamics signature ([`crate::neural::dynamics`]) of every population of
/// an existing `activity.summary.json` from its `activity.json` (`path`: either file or
/// their folder), leaving every other field as it was (the category tests are not rerun),
/// and rewrites the summary (SHA-256-recorded). For summaries made before the dynamics
/// view, or by an older version of it. Returns the populations refreshed.
pub fn refresh_dynamics(path: &std::path::Path) -> Result<usize, String> {
    use crate::neural::summary::{NeuralSummary, SummaryOptions, population_dynamics};
    let folder = if path.is_dir() {
        path.to_path_buf()
    } else {
        path.parent()
            .map(std::path::Path::to_path_buf)
            .unwrap_or_default()
    };
    let activity = folder.join(crate::job_folder::ACTIVITY);
    let summary = folder.join(crate::job_folder::ACTIVITY_SUMMARY);
    let _lock = chronocooked_env::fs::FolderLock::acquire_shared_folder(&folder)
        .map_err(|e| e.to_string())?;
    let bytes = chronocooked_env::integrity::read_checked(&activity).map_err(|e| e.to_string())?;
    let dataset =
        ActivityDataset::from_json(&bytes).map_err(|e| format!("{}: {e}", activity.display()))?;
    let text = chronocooked_env::integrity::read_checked(&summary).map_err(|e| e.to_string())?;
    let mut summaries: Vec<NeuralSummary> =
        serde_json::from_slice(&text).map_err(|e| format!("{}: {e}", summary.display()))?;
    let opts = SummaryOptions::default();
    for s in &mut summaries {
        let population = (s.population != "all").then_some(s.population.as_str());
        for t in &mut s.by_td {
            t.dynamics = population_dynamics(&dataset, population, t.td, &opts).ok();
        }
        s.dynamics = s.by_td.last().and_then(|t| t.dynamics);
    }
    let json = serde_json::to_vec_pretty(&summaries).map_err(|e| e.to_string())?;
    chronocooked_env::integrity::write_recorded(&summary, &json).map_err(|e| e.to_string())?;
    Ok(summaries.len())
}
