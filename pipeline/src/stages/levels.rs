//! The multi-timer curriculum's per-level policies evaluated as the paper's notebooks do
//! (`perforamce_metric_cl_exact.ipynb`, `..._cl_cat.ipynb`): the policy that left level `L`
//! (the final policy for the last level reached) plays, greedily from every start cell, each
//! TD it was trained on at that level, in that level's test setting:
//!
//! * level 0 (the warm-up): one timer, `TD[0]`, soup only takeable at `timer ≥ TD`, reduced
//!   reward 0.1, no buffers;
//! * level `L ≥ 1`: `L` timers, `TD[0..L]`, undercooking possible, no late buffer; exact
//!   curriculum: reduced reward 0, no early buffer; categorical curriculum (trained with an
//!   early buffer): reduced reward 0.1 and an early buffer of 2 steps, as the categorical
//!   notebook tests (its training used 3 and 0).
//!
//! Then, as the paper's multi-timer figures show it (an earlier version of the notebooks
//! swept every integer TD 1 … max(level's TDs) + 1: "Some additional out-of-distribution
//! (OOD) durations are also shown"), each level `L ≥ 1` policy in the same setting on the
//! TDs 1 … max(`TD[0..L]`) + 1 it was not trained on (value cue only: a categorical cue has
//! no code for an untrained TD) — after the trained TDs, so those keep their episodes. (The
//! final policy's own evaluation goes to max + 3, the lab's OOD range.) The analysis tells
//! them apart by the run's TD list.
//!
//! The growing curricula of the extensions (multi-anchor: 2 → 3 → 4 counters; multi-oven:
//! 1 → 2 → 3 ovens) are evaluated the same way: each level's policy plays its own level's
//! task (its counters or ovens) with that task's reference protocol — a run that stopped at
//! three counters is scored on three, as the extension notebooks do, beside the final
//! task's evaluation.
//!
//! Written as `levels.csv` ([`LevelEpisode`] rows) in the evaluation folder.

use crate::PipelineError;
use chronocooked_analysis::collect::{LEVELS_CSV, LevelEpisode, read_curve, write_level_episodes};
use chronocooked_analysis::{Condition, ConditionKind, Mode, reference_conditions, run_protocol};
use chronocooked_env::{CueMode, RewardMode, TaskParams};
use chronocooked_models::run_folder;
use chronocooked_training::ppo::agent::PpoAgent;
use chronocooked_training::run_dir::RunDir;
use std::path::Path;

/// Early buffer (steps) of the categorical notebook's test setting.
pub const CATEGORICAL_TEST_UNDER_BUFFER: u32 = 2;

/// The task overrides of level `level`'s test setting (appended to the run's own) and the
/// TDs it tests, for a run trained on `tds` with early buffer `under_buffer` and reduced
/// reward `reduced` (an exact run is tested with its own reduced reward: 0 in the paper's
/// code; a categorical one with the categorical notebook's 0.1).
pub fn level_test_setting(
    level: usize,
    tds: &[u32],
    under_buffer: u32,
    reduced: f32,
) -> (Vec<String>, Vec<u32>) {
    let categorical = under_buffer > 0;
    if level == 0 {
        let env = [
            "num_timers=1",
            "mode=lower_bounded",
            "reduced_reward=0.1",
            "under_buffer=0",
            "over_buffer=0",
        ];
        return (
            env.iter().map(|s| s.to_string()).collect(),
            tds.iter().take(1).copied().collect(),
        );
    }
    let n = level.min(tds.len());
    let (reduced, under) = if categorical {
        ("0.1".to_string(), CATEGORICAL_TEST_UNDER_BUFFER)
    } else {
        (reduced.to_string(), 0)
    };
    let env = vec![
        format!("num_timers={n}"),
        "mode=exact".into(),
        format!("reduced_reward={reduced}"),
        format!("under_buffer={under}"),
        "over_buffer=0".into(),
    ];
    (env, tds[..n].to_vec())
}

/// The untrained TDs level `level` is also tested on: 1 … max(`tds[..level]`) + 1 minus the
/// trained ones (none for the warm-up level 0 or without the value cue).
pub fn level_ood_tds(level: usize, tds: &[u32], value_cue: bool) -> Vec<u32> {
    if level == 0 || !value_cue {
        return Vec::new();
    }
    let trained = &tds[..level.min(tds.len())];
    let max = trained.iter().copied().max().unwrap_or(0);
    (1..=max + 1).filter(|t| !trained.contains(t)).collect()
}

/// Evaluates every per-level policy the PPO run folder `run` kept into
/// `out/levels.csv`; returns the number of levels evaluated (`None`: the run is not a
/// multi-timer curriculum run, or kept no per-level policies). The kept levels must be
/// exactly those the learning curve passed through (first to last level): a gap (a run
/// resumed from a binary that kept none) or a stray file is an error naming the folder.
/// The last level's policy is the final one; when the final update entered that level, it
/// never collected a rollout there (as the paper's newest checkpoint of that level).
pub fn evaluate_levels(run: &Path, out: &Path, seed: u64) -> Result<Option<usize>, PipelineError> {
    if !run.join(run_folder::LEVELS).is_dir() {
        return Ok(None);
    }
    let dir = RunDir::open(run)?;
    let cfg = dir.config()?;
    if !cfg.curriculum.has_levels() {
        return Ok(None);
    }
    let levels = dir.saved_levels();
    if levels.is_empty() {
        return Ok(None);
    }
    let curve_path = run.join(run_folder::CURVES);
    let curve = read_curve(&curve_path).map_err(|e| PipelineError::Analysis(e.to_string()))?;
    let passed: Vec<usize> = match (curve.first(), curve.last()) {
        (Some(a), Some(b)) => (a.curriculum_level..=b.curriculum_level).collect(),
        _ => Vec::new(),
    };
    if levels != passed {
        return Err(PipelineError::Invalid(format!(
            "{}: holds the policies of curriculum levels {levels:?}, but {} passed levels \
             {passed:?} (a run resumed from a binary that kept no per-level policies, or a \
             stray file); retrain the run to evaluate its levels",
            run.join(run_folder::LEVELS).display(),
            curve_path.display()
        )));
    }
    if cfg.curriculum.growth().is_some() {
        let first = cfg.task.config()?.growth().map_or(0, |g| g.first);
        let mut rows = Vec::new();
        for &level in &levels {
            // The level's own task: `first + level` counters or ovens, as the trainer
            // built it, played with that task's reference protocol.
            let level_task = cfg.task.at_growth_size(first + level)?;
            let config = level_task.config()?;
            let mut agent = PpoAgent::load_level(run, level, &config)?;
            let conditions = reference_conditions(&level_task)?;
            let records = run_protocol(&mut agent, &conditions, Mode::Reference, seed)?;
            rows.extend(records.iter().map(|r| LevelEpisode::of(level, r)));
        }
        return write_levels(out, &rows).map(|()| Some(levels.len()));
    }
    let task = cfg.task.config()?;
    let TaskParams::MultiTimer {
        tds,
        under_buffer,
        mode,
        reduced_reward,
        cue,
        ..
    } = &task.params
    else {
        return Ok(None);
    };
    // A lower-bounded task has no early buffer to speak of: its levels test as exact.
    let under = if *mode == RewardMode::Exact {
        *under_buffer
    } else {
        0
    };
    let mut rows = Vec::new();
    for &level in &levels {
        let (extra, test_tds) = level_test_setting(level, tds, under, *reduced_reward);
        let level_task = cfg.task.with(&extra)?;
        let config = level_task.config()?;
        let mut agent = PpoAgent::load_level(run, level, &config)?;
        let conditions = |tds: &[u32]| -> Vec<Condition> {
            tds.iter()
                .map(|&td| Condition {
                    kind: ConditionKind::MultiTimer,
                    task: level_task.clone(),
                    td,
                    never_ready: None,
                    factor: None,
                    context: None,
                })
                .collect()
        };
        // Trained TDs first: their conditions keep the indices (and so the episode seeds)
        // they had before the untrained ones were added.
        let mut probe = test_tds;
        probe.extend(level_ood_tds(level, tds, *cue == CueMode::Value));
        let records = run_protocol(&mut agent, &conditions(&probe), Mode::Reference, seed)?;
        rows.extend(records.iter().map(|r| LevelEpisode::of(level, r)));
    }
    write_levels(out, &rows)?;
    Ok(Some(levels.len()))
}

/// Writes `out/levels.csv`.
fn write_levels(out: &Path, rows: &[LevelEpisode]) -> Result<(), PipelineError> {
    std::fs::create_dir_all(out)
        .map_err(|e| PipelineError::Analysis(format!("{}: {e}", out.display())))?;
    write_level_episodes(&out.join(LEVELS_CSV), rows)
        .map_err(|e| PipelineError::Analysis(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_level_tests_its_own_tds_in_the_notebooks_settings() {
        let tds = [2, 4, 6, 8, 10];
        let (env, t) = level_test_setting(0, &tds, 3, 0.0);
        assert_eq!(t, [2]);
        assert!(env.contains(&"mode=lower_bounded".to_string()));
        assert!(env.contains(&"reduced_reward=0.1".to_string()));
        let (env, t) = level_test_setting(3, &tds, 0, 0.0);
        assert_eq!(t, [2, 4, 6]);
        assert!(env.contains(&"reduced_reward=0".to_string()));
        assert!(env.contains(&"under_buffer=0".to_string()));
        let (env, t) = level_test_setting(5, &tds, 3, 0.0);
        assert_eq!(t, tds);
        assert!(env.contains(&"under_buffer=2".to_string()));
        assert!(env.contains(&"reduced_reward=0.1".to_string()));
        // An exact run trained with the text's reduced reward 0.1 is tested with it.
        let (env, t) = level_test_setting(1, &[4], 0, 0.1);
        assert_eq!(t, [4]);
        assert!(env.contains(&"reduced_reward=0.1".to_string()));
    }

    #[test]
    fn levels_past_the_warm_up_also_test_every_untrained_td_up_to_one_past_their_longest() {
        let tds = [2, 4, 6, 8, 10];
        assert_eq!(level_ood_tds(0, &tds, true), Vec::<u32>::new());
        assert_eq!(level_ood_tds(1, &tds, true), [1, 3]);
        assert_eq!(level_ood_tds(3, &tds, true), [1, 3, 5, 7]);
        assert_eq!(level_ood_tds(5, &tds, true), [1, 3, 5, 7, 9, 11]);
        // An unsorted list: up to one past the longest trained TD.
        assert_eq!(level_ood_tds(2, &[6, 3], true), [1, 2, 4, 5, 7]);
        assert_eq!(level_ood_tds(3, &tds, false), Vec::<u32>::new());
    }
}
