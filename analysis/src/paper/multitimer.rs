//! Multi-timer as the paper reports it: the curriculum level each run reached and the env
//! steps spent per level, the mean training reward while at each level (from the learning
//! curve), and the final policy's reward and oven-off time per TD — the trained TDs and every
//! other evaluated TD (out of distribution, as in the paper's figure) — as means over the 12
//! start cells, where a soup never taken counts as oven-off time −1, as in the notebook.

use super::collect::CompactJob;
use crate::behaviour::aggregate::Spread;
use crate::records::ConditionKind;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Levels of the paper's curriculum: 0 warm-up, then 1 … 5 timers.
pub const LEVELS: usize = 6;

/// One run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MtRun {
    /// Training seed.
    pub seed: u64,
    /// Highest level reached (0 … 5).
    pub level: usize,
    /// Env steps at which each reached level was entered.
    pub level_steps: Vec<u64>,
    /// Per trained TD: (TD, mean reward, mean oven-off time in steps, −1 for never taken).
    pub per_td: Vec<(u32, f64, f64)>,
    /// Per evaluated TD, trained or not: (TD, mean reward, mean oven-off time in steps).
    #[serde(default)]
    pub tested: Vec<(u32, f64, f64)>,
    /// Mean training-episode reward while the run was at each level 0 … 5 (the learning
    /// curve's samples at that level; `None` where no sample fell in it).
    #[serde(default)]
    pub level_reward: Vec<Option<f64>>,
}

/// One model under one curriculum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MtCell {
    /// Zoo model name.
    pub model: String,
    /// `exact` or `categorical`.
    pub curriculum: String,
    /// Every run.
    pub runs: Vec<MtRun>,
    /// Level reached across runs.
    pub level: Spread,
    /// Runs that reached the last level.
    pub reached_last: usize,
    /// Env steps spent in each level 0 … 4 by the runs that left it (mean ± SD).
    pub steps_in_level: Vec<Spread>,
    /// Per trained TD: (TD, reward across runs, oven-off time across runs).
    pub per_td: Vec<(u32, Spread, Spread)>,
    /// Per evaluated TD, trained or not: (TD, reward across runs, oven-off time across runs).
    #[serde(default)]
    pub tested: Vec<(u32, Spread, Spread)>,
    /// Training reward at each level 0 … 5 across the runs that have a sample there.
    #[serde(default)]
    pub level_reward: Vec<Spread>,
}

/// `exact` (undercooking not tolerated) or `categorical` (an early buffer).
pub fn curriculum_of(job: &CompactJob) -> &'static str {
    match job
        .env_value("under_buffer")
        .and_then(|v| v.parse::<u32>().ok())
    {
        Some(b) if b > 0 => "categorical",
        _ => "exact",
    }
}

/// The final policy's mean reward and oven-off time (steps, −1 for never taken) at each of
/// `tds` (TDs without evaluation episodes are skipped).
fn per_td_of(job: &CompactJob, tds: &[u32]) -> Vec<(u32, f64, f64)> {
    tds.iter()
        .filter_map(|&td| {
            let eps: Vec<_> = job
                .episodes
                .iter()
                .filter(|e| e.kind == ConditionKind::MultiTimer && e.td == td)
                .collect();
            let n = eps.len() as f64;
            (!eps.is_empty()).then(|| {
                (
                    td,
                    eps.iter().map(|e| f64::from(e.reward)).sum::<f64>() / n,
                    eps.iter().map(|e| f64::from(e.oven_off_time)).sum::<f64>() / n,
                )
            })
        })
        .collect()
}

/// Mean training reward of the learning-curve samples taken at each level 0 … 5.
fn level_reward_of(job: &CompactJob) -> Vec<Option<f64>> {
    (0..LEVELS)
        .map(|l| {
            let r: Vec<f64> = job
                .curve
                .iter()
                .filter(|c| c.curriculum_level == l && c.ep_return_mean.is_finite())
                .map(|c| c.ep_return_mean)
                .collect();
            (!r.is_empty()).then(|| r.iter().sum::<f64>() / r.len() as f64)
        })
        .collect()
}

fn run_of(job: &CompactJob) -> MtRun {
    let mut evaluated: Vec<u32> = job
        .episodes
        .iter()
        .filter(|e| e.kind == ConditionKind::MultiTimer)
        .map(|e| e.td)
        .collect();
    evaluated.sort_unstable();
    evaluated.dedup();
    let trained: Vec<u32> = job
        .env_value("tds")
        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![3, 6, 9, 12, 15]);
    let tested = per_td_of(job, &evaluated);
    MtRun {
        seed: job.job.seed,
        level: job.job.level_steps.len().saturating_sub(1),
        level_steps: job.job.level_steps.clone(),
        per_td: tested
            .iter()
            .filter(|x| trained.contains(&x.0))
            .copied()
            .collect(),
        tested,
        level_reward: level_reward_of(job),
    }
}

/// Per TD across runs: (TD, spread of the rewards, spread of the oven-off times).
fn spread_per_td(
    runs: &[MtRun],
    of: fn(&MtRun) -> &[(u32, f64, f64)],
) -> Vec<(u32, Spread, Spread)> {
    let mut tds: Vec<u32> = runs
        .iter()
        .flat_map(|r| of(r).iter().map(|x| x.0))
        .collect();
    tds.sort_unstable();
    tds.dedup();
    tds.into_iter()
        .map(|td| {
            let at = |r: &MtRun| of(r).iter().find(|x| x.0 == td).copied();
            (
                td,
                Spread::of(runs.iter().filter_map(|r| at(r).map(|x| x.1))),
                Spread::of(runs.iter().filter_map(|r| at(r).map(|x| x.2))),
            )
        })
        .collect()
}

/// Multi-timer analysis of every model and curriculum among `jobs`.
pub fn analyse_multitimer(jobs: &[CompactJob]) -> Vec<MtCell> {
    let mut groups: BTreeMap<(&str, &str), Vec<&CompactJob>> = BTreeMap::new();
    for j in jobs.iter().filter(|j| j.job.task == "MultiTimer-v0") {
        groups
            .entry((j.job.label(), curriculum_of(j)))
            .or_default()
            .push(j);
    }
    groups
        .into_iter()
        .map(|((model, curriculum), js)| {
            let runs: Vec<MtRun> = js.iter().map(|j| run_of(j)).collect();
            let steps_in_level = (0..LEVELS - 1)
                .map(|l| {
                    Spread::of(runs.iter().filter_map(|r| {
                        Some((r.level_steps.get(l + 1)? - r.level_steps.get(l)?) as f64)
                    }))
                })
                .collect();
            let level_reward = (0..LEVELS)
                .map(|l| Spread::of(runs.iter().filter_map(|r| *r.level_reward.get(l)?)))
                .collect();
            MtCell {
                model: model.to_string(),
                curriculum: curriculum.to_string(),
                level: Spread::of(runs.iter().map(|r| r.level as f64)),
                reached_last: runs.iter().filter(|r| r.level == LEVELS - 1).count(),
                steps_in_level,
                per_td: spread_per_td(&runs, |r| &r.per_td),
                tested: spread_per_td(&runs, |r| &r.tested),
                level_reward,
                runs,
            }
        })
        .collect()
}
