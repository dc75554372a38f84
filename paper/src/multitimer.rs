//! Multi-timer as the paper reports it: the curriculum level each run reached and the env
//! steps spent per level, the mean training reward while at each level (from the learning
//! curve), and the final policy's reward and oven-off time per TD — the trained TDs and every
//! other evaluated TD (out of distribution, as in the paper's figure) — as means over the 12
//! start cells, where a soup never taken counts as oven-off time −1, as in the notebook.
//! Runs that kept their curriculum levels' policies add each level's reward in that level's
//! test setting (`levels.csv`, the notebooks' per-level evaluation). Runs trained on one TD
//! are the exact timer ([`analyse_exact_timer`]): reward against the test buffer.

use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_analysis::collect::{CompactJob, LevelEpisode};
use chronocooked_analysis::records::ConditionKind;
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
    /// Mean reward of each level 0 … 5's own policy in that level's test setting, over its
    /// TDs and start cells (`None`: no policy kept for that level).
    #[serde(default)]
    pub level_eval: Vec<Option<f64>>,
    /// Each level 0 … 5's policy at every TD it was tested on, trained and untrained
    /// (empty for a level without a kept policy).
    #[serde(default)]
    pub level_curves: Vec<Vec<LevelTd>>,
    /// [`timers_stored`] of each level's curve (`None`: no policy kept for that level).
    #[serde(default)]
    pub level_timers: Vec<Option<usize>>,
}

/// One model under one curriculum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MtCell {
    /// Zoo model name.
    pub model: String,
    /// `exact` or `categorical`.
    pub curriculum: String,
    /// The trained TD list (steps), in curriculum order.
    #[serde(default)]
    pub tds: Vec<u32>,
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
    /// Each level's policy in its test setting, across the runs that kept one.
    #[serde(default)]
    pub level_eval: Vec<Spread>,
    /// Timers each level's policy stores ([`timers_stored`]), across the runs that kept one.
    #[serde(default)]
    pub level_timers: Vec<Spread>,
    /// Each level's policy's mean reward at the untrained TDs 1 … max + 1 of its level,
    /// across the runs that kept one.
    #[serde(default)]
    pub level_untrained_reward: Vec<Spread>,
}

/// The exact timer at one TD: reward against the test buffer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExactTimerCell {
    /// Zoo model name.
    pub model: String,
    /// Target duration (steps).
    pub td: u32,
    /// Runs.
    pub runs: usize,
    /// Per test buffer (fraction of TD on either side): the runs' mean rewards over the
    /// start cells (1 inside the window, the reduced reward outside, 0 never delivered).
    pub buffers: Vec<(f64, Spread)>,
}

/// `exact` (undercooking not tolerated) or `categorical` (an early buffer).
pub fn curriculum_of(job: &CompactJob) -> &'static str {
    match job.env_int("under_buffer") {
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

/// The TDs level `level` trains on: the warm-up the first TD, level `L ≥ 1` the first `L`.
pub fn level_tds(level: usize, tds: &[u32]) -> &[u32] {
    &tds[..level.max(1).min(tds.len())]
}

/// Mean reward of each level's own policy in that level's test setting, on the TDs it was
/// trained on (its episodes at untrained TDs are in [`level_curves_of`]).
fn level_eval_of(job: &CompactJob) -> Vec<Option<f64>> {
    let tds = trained_tds(job);
    (0..LEVELS)
        .map(|l| {
            let r: Vec<f64> = job
                .levels
                .iter()
                .filter(|e| e.level == l && level_tds(l, &tds).contains(&e.td))
                .map(|e| f64::from(e.reward))
                .collect();
            (!r.is_empty()).then(|| r.iter().sum::<f64>() / r.len() as f64)
        })
        .collect()
}

/// One level's policy at one tested TD, trained or not.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LevelTd {
    /// Tested TD (steps).
    pub td: u32,
    /// Whether the level trained on it.
    pub trained: bool,
    /// Mean reward over the start cells.
    pub reward: f64,
    /// Share of the start cells where the soup was taken.
    pub taken: f64,
    /// Mean oven-off time (steps) over the cells where it was taken (NaN: never).
    pub off_time: f64,
}

/// Each level 0 … 5's policy at every TD it was tested on, ascending (empty: not kept).
fn level_curves_of(job: &CompactJob) -> Vec<Vec<LevelTd>> {
    let tds = trained_tds(job);
    (0..LEVELS)
        .map(|l| {
            let mut at: BTreeMap<u32, Vec<&LevelEpisode>> = BTreeMap::new();
            for e in job.levels.iter().filter(|e| e.level == l) {
                at.entry(e.td).or_default().push(e);
            }
            at.into_iter()
                .map(|(td, eps)| {
                    let n = eps.len() as f64;
                    let taken: Vec<f64> = eps
                        .iter()
                        .filter(|e| e.oven_off_time >= 0)
                        .map(|e| f64::from(e.oven_off_time))
                        .collect();
                    LevelTd {
                        td,
                        trained: level_tds(l, &tds).contains(&td),
                        reward: eps.iter().map(|e| f64::from(e.reward)).sum::<f64>() / n,
                        taken: taken.len() as f64 / n,
                        off_time: if taken.is_empty() {
                            f64::NAN
                        } else {
                            taken.iter().sum::<f64>() / taken.len() as f64
                        },
                    }
                })
                .collect()
        })
        .collect()
}

/// Steps by which two oven-off plateaus must differ to count as two timers: oven-off times
/// are whole steps, so two timers differ by at least 1; means over start cells within half a
/// step of each other are one.
pub const PLATEAU_GAP: f64 = 0.5;

/// The paper's "number of distinct shifts" in a level's oven-off curve — how many timers the
/// policy stores: the mean oven-off times at the tested TDs where the soup was taken on at
/// least half the start cells, sorted, grouped from the smallest up, a group spanning at most
/// [`PLATEAU_GAP`] steps from its first value (no chaining: a curve that ramps in small steps
/// counts a timer per half step it climbs); the number of groups (0 when it is taken at no
/// TD). A TD where the soup is mostly never taken (the notebook's −1) holds no timer. A
/// policy that times every TD of 1 … 11 has 11; one that takes the soup at 2 below TD 3 and
/// at 5 from there on has 2 (the paper's CTRNN125 example: "it stores 2 timers").
pub fn timers_stored(curve: &[LevelTd]) -> usize {
    let mut off: Vec<f64> = curve
        .iter()
        .filter(|c| c.taken >= 0.5 && c.off_time.is_finite())
        .map(|c| c.off_time)
        .collect();
    off.sort_by(f64::total_cmp);
    let mut groups = 0;
    let mut start = f64::NEG_INFINITY;
    for v in off {
        if v - start > PLATEAU_GAP {
            groups += 1;
            start = v;
        }
    }
    groups
}

/// The TD list a multi-timer job trained on (the task's default list when not set).
pub fn trained_tds(job: &CompactJob) -> Vec<u32> {
    job.env_ints("tds").unwrap_or_else(|| vec![3, 6, 9, 12, 15])
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
    let trained = trained_tds(job);
    let tested = per_td_of(job, &evaluated);
    let curves = level_curves_of(job);
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
        level_eval: level_eval_of(job),
        level_timers: curves
            .iter()
            .map(|c| (!c.is_empty()).then(|| timers_stored(c)))
            .collect(),
        level_curves: curves,
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

/// Multi-timer analysis of every model, curriculum and TD list among `jobs` (jobs trained
/// on one TD are the exact timer's, see [`analyse_exact_timer`]).
pub fn analyse_multitimer(jobs: &[CompactJob]) -> Vec<MtCell> {
    let mut groups: BTreeMap<(&str, &str, Vec<u32>), Vec<&CompactJob>> = BTreeMap::new();
    for j in jobs.iter().filter(|j| j.job.task.id() == "MultiTimer-v0") {
        let tds = trained_tds(j);
        if tds.len() < 2 {
            continue;
        }
        groups
            .entry((j.job.label(), curriculum_of(j), tds))
            .or_default()
            .push(j);
    }
    groups
        .into_iter()
        .map(|((model, curriculum, tds), js)| {
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
            let level_eval = (0..LEVELS)
                .map(|l| Spread::of(runs.iter().filter_map(|r| *r.level_eval.get(l)?)))
                .collect();
            let level_timers = (0..LEVELS)
                .map(|l| {
                    Spread::of(
                        runs.iter()
                            .filter_map(|r| r.level_timers.get(l).copied().flatten())
                            .map(|n| n as f64),
                    )
                })
                .collect();
            let level_untrained_reward = (0..LEVELS)
                .map(|l| {
                    Spread::of(runs.iter().filter_map(|r| {
                        let v: Vec<f64> = r
                            .level_curves
                            .get(l)?
                            .iter()
                            .filter(|c| !c.trained)
                            .map(|c| c.reward)
                            .collect();
                        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
                    }))
                })
                .collect();
            MtCell {
                level_timers,
                level_untrained_reward,
                model: model.to_string(),
                curriculum: curriculum.to_string(),
                tds,
                level_eval,
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

/// The exact timer: every multi-timer job trained on a single TD, per model and TD, its
/// reward under each test buffer (the evaluation's `buffer` conditions: soup taken within
/// TD ± buffer pays 1, outside it the reduced reward, never delivered 0), as the mean over
/// the start cells per run, then mean ± SD over runs.
pub fn analyse_exact_timer(jobs: &[CompactJob]) -> Vec<ExactTimerCell> {
    exact_timer_groups(jobs)
        .into_iter()
        .map(|((model, td), js)| {
            let per_run: Vec<Vec<(f64, f64)>> = js.iter().map(|j| buffer_rewards(j, td)).collect();
            let mut fracs: Vec<f64> = per_run.iter().flatten().map(|b| b.0).collect();
            fracs.sort_by(f64::total_cmp);
            fracs.dedup();
            let buffers = fracs
                .into_iter()
                .map(|f| {
                    let runs = per_run
                        .iter()
                        .filter_map(|r| r.iter().find(|b| b.0 == f).map(|b| b.1));
                    (f, Spread::of(runs))
                })
                .collect();
            ExactTimerCell {
                model: model.to_string(),
                td,
                runs: js.len(),
                buffers,
            }
        })
        .collect()
}

/// The exact-timer jobs (multi-timer jobs trained on a single TD) grouped by (model, TD).
pub fn exact_timer_groups(jobs: &[CompactJob]) -> BTreeMap<(&str, u32), Vec<&CompactJob>> {
    let mut groups: BTreeMap<(&str, u32), Vec<&CompactJob>> = BTreeMap::new();
    for j in jobs.iter().filter(|j| j.job.task.id() == "MultiTimer-v0") {
        if let [td] = trained_tds(j)[..] {
            groups.entry((j.job.label(), td)).or_default().push(j);
        }
    }
    groups
}

/// One run's mean reward over the start cells under each test buffer at `td`:
/// `(buffer as a fraction of TD, mean reward)`, by increasing buffer (empty when the run has
/// no `buffer` episodes at `td`).
pub fn buffer_rewards(job: &CompactJob, td: u32) -> Vec<(f64, f64)> {
    let mut by_frac: BTreeMap<u64, (f64, f64, usize)> = BTreeMap::new();
    for e in job
        .episodes
        .iter()
        .filter(|e| e.kind == ConditionKind::Buffer && e.td == td)
    {
        if let Some(f) = e.factor {
            let slot = by_frac.entry(f.to_bits()).or_insert((f, 0.0, 0));
            slot.1 += f64::from(e.reward);
            slot.2 += 1;
        }
    }
    let mut v: Vec<(f64, f64)> = by_frac
        .into_values()
        .map(|(f, sum, n)| (f, sum / n as f64))
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}
