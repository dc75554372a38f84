//! Multi-timer as the paper reports it: the curriculum level each run reached and the env
//! steps spent per level, and the final policy's reward and oven-off time per trained TD
//! (mean over the 12 start cells; a soup never taken counts as −1, as in the notebook).

use super::collect::CompactJob;
use crate::behaviour::aggregate::Spread;
use crate::evaluation::protocol::ConditionKind;
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
    /// Per trained TD: (TD, mean reward, mean oven-off time with −1 for never taken).
    pub per_td: Vec<(u32, f64, f64)>,
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
    /// Per TD: (TD, reward across runs, oven-off time across runs).
    pub per_td: Vec<(u32, Spread, Spread)>,
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
            let runs: Vec<MtRun> = js
                .iter()
                .map(|j| {
                    let mut tds: Vec<u32> = j
                        .episodes
                        .iter()
                        .filter(|e| e.kind == ConditionKind::MultiTimer)
                        .map(|e| e.td)
                        .collect();
                    tds.sort_unstable();
                    tds.dedup();
                    let trained: Vec<u32> = j
                        .env_value("tds")
                        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
                        .unwrap_or_else(|| vec![3, 6, 9, 12, 15]);
                    let per_td = trained
                        .iter()
                        .filter(|td| tds.contains(td))
                        .map(|&td| {
                            let eps: Vec<_> = j
                                .episodes
                                .iter()
                                .filter(|e| e.kind == ConditionKind::MultiTimer && e.td == td)
                                .collect();
                            let n = eps.len().max(1) as f64;
                            (
                                td,
                                eps.iter().map(|e| f64::from(e.reward)).sum::<f64>() / n,
                                eps.iter().map(|e| f64::from(e.oven_off_time)).sum::<f64>() / n,
                            )
                        })
                        .collect();
                    MtRun {
                        seed: j.job.seed,
                        level: j.job.level_steps.len().saturating_sub(1),
                        level_steps: j.job.level_steps.clone(),
                        per_td,
                    }
                })
                .collect();
            let steps_in_level = (0..LEVELS - 1)
                .map(|l| {
                    Spread::of(runs.iter().filter_map(|r| {
                        Some((r.level_steps.get(l + 1)? - r.level_steps.get(l)?) as f64)
                    }))
                })
                .collect();
            let mut tds: Vec<u32> = runs
                .iter()
                .flat_map(|r| r.per_td.iter().map(|x| x.0))
                .collect();
            tds.sort_unstable();
            tds.dedup();
            let per_td = tds
                .into_iter()
                .map(|td| {
                    let get = |f: fn(&(u32, f64, f64)) -> f64| {
                        Spread::of(
                            runs.iter()
                                .flat_map(|r| r.per_td.iter().filter(|x| x.0 == td).map(f)),
                        )
                    };
                    (td, get(|x| x.1), get(|x| x.2))
                })
                .collect();
            MtCell {
                model: model.to_string(),
                curriculum: curriculum.to_string(),
                level: Spread::of(runs.iter().map(|r| r.level as f64)),
                reached_last: runs.iter().filter(|r| r.level == LEVELS - 1).count(),
                steps_in_level,
                per_td,
                runs,
            }
        })
        .collect()
}
