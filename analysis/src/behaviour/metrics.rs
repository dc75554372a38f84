//! Behavioural metrics of an evaluation, computed from per-episode records alone (so they can
//! be recomputed without rerunning agents: same records → same JSON).

use crate::behaviour::foc::{FocStats, ScalarProperty, episode_foc, foc_stats, scalar_property};
use crate::behaviour::psychometric::{
    LogisticFit, ProbeCounts, bp_relative, check_transition, fit_with_ci,
};
use crate::records::{ConditionKind, EvalRecord};
use chronocooked_env::{Counter, Events, TaskParams};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Summary of one condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConditionSummary {
    /// Condition kind.
    pub kind: ConditionKind,
    /// Task id played.
    pub task: String,
    /// TD (steps).
    pub td: u32,
    /// PI factor / buffer fraction.
    pub factor: Option<f64>,
    /// Uncertainty: never-ready episodes.
    pub never_ready: Option<bool>,
    /// Episodes.
    pub episodes: usize,
    /// Full-reward deliveries / episodes.
    pub success_rate: f64,
    /// Mean episode reward.
    pub mean_reward: f64,
    /// Mean oven-off (pickup) timer over episodes with a pickup (NaN if none).
    pub mean_oven_off: f64,
}

/// Bisection metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BisectionMetrics {
    /// Short anchor S.
    pub short: u32,
    /// Long anchor L.
    pub long: u32,
    /// Counts per probe, in probe order.
    pub probes: Vec<ProbeCounts>,
    /// P(long) per probe (NaN: excluded by the >50%-failed rule).
    pub p_long: Vec<f64>,
    /// Correct choices on the two anchors among valid episodes.
    pub anchor_accuracy: f64,
    /// The logistic fit (with 95% bootstrap intervals), when it could be made.
    pub fit: Option<LogisticFit>,
    /// Why the fit failed, when it did.
    pub fit_error: Option<String>,
    /// BP / arithmetic mean of the anchors.
    pub bp_over_am: Option<f64>,
    /// BP / geometric mean of the anchors.
    pub bp_over_gm: Option<f64>,
}

impl BisectionMetrics {
    /// `(probe duration, P(long))` per probe (NaN where the exclusion rule applies).
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.probes
            .iter()
            .zip(&self.p_long)
            .map(|(p, &v)| (p.t, v))
            .collect()
    }
}

/// Fixed-interval metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FiMetrics {
    /// FOC statistics per TD.
    pub foc: Vec<FocStats>,
    /// Regressions across TDs (meaningful with ≥ 2 TDs).
    pub scalar: ScalarProperty,
}

/// Peak-interval response curve of one probe factor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PiCurve {
    /// Release factor (soup at factor × TD; 0 = never).
    pub factor: f64,
    /// Trained TD.
    pub td: u32,
    /// Oven checks per episode at each oven time 0, 1, … (among episodes whose oven was
    /// running then).
    pub rate: Vec<f64>,
    /// Gaussian(+baseline) fit of `rate` (peak time, spread, CV), when there is a peak.
    pub fit: Option<crate::behaviour::peak::GaussianFit>,
    /// Single-trial start/stop analysis averaged over the trials that responded:
    /// `[start, stop, middle, spread]` (steps of oven time), and the trials used.
    pub start_stop: Option<([f64; 4], usize)>,
}

/// Everything computed from one evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Model name.
    pub model: String,
    /// Episodes.
    pub episodes: usize,
    /// Full-reward deliveries over all episodes.
    pub success_rate: f64,
    /// Per-condition summaries.
    pub conditions: Vec<ConditionSummary>,
    /// FI (when FI conditions were played).
    pub fi: Option<FiMetrics>,
    /// Bisection (when bisection conditions were played).
    pub bisection: Option<BisectionMetrics>,
    /// PI curves.
    pub pi: Vec<PiCurve>,
    /// Multi-timer (when multi-timer conditions were played).
    pub multi_timer: Option<MultiTimerMetrics>,
    /// Dual task.
    pub dual: Option<DualMetrics>,
    /// Uncertainty task.
    pub uncertainty: Option<UncertaintyMetrics>,
    /// Multi-anchor categorization (when its conditions were played).
    #[serde(default)]
    pub multi_anchor: Option<crate::behaviour::categorization::MultiAnchorMetrics>,
    /// Multi-oven bisection (when its conditions were played).
    #[serde(default)]
    pub multi_oven: Option<crate::behaviour::concurrent::MultiOvenMetrics>,
    /// Temporal reproduction (when its conditions were played).
    #[serde(default)]
    pub reproduction: Option<crate::behaviour::reproduction::ReproductionMetrics>,
}

/// Multi-timer metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultiTimerMetrics {
    /// `(TD, mean reward, mean oven-off time)` for every TD played (OOD included).
    pub by_td: Vec<(u32, f64, f64)>,
    /// `(TD, buffer fraction, mean reward)` of the exact-timer buffer conditions.
    pub by_buffer: Vec<(u32, f64, f64)>,
    /// Timers stored: distinct oven-off levels (mean oven-off rounded to a step) shared by at
    /// least two TDs, plus singleton levels at trained TDs — the plateaus of oven-off vs TD.
    pub plateaus: usize,
}

/// Dual-task metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DualMetrics {
    /// `(TD, mean reward, mean sink interactions, mean oven time when the agent last used
    /// the sink)`.
    pub by_td: Vec<(u32, f64, f64, f64)>,
}

/// Uncertainty-task metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UncertaintyMetrics {
    /// Success in normal episodes.
    pub success_normal: f64,
    /// Mean reward in never-ready episodes (the button pays a reduced reward).
    pub reward_never_ready: f64,
    /// Fraction of never-ready episodes in which the agent pressed the button.
    pub button_use: f64,
    /// Mean oven time of the button press (never-ready episodes that pressed it).
    pub press_time: f64,
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { s / n as f64 }
}

fn oven_off(r: &EvalRecord) -> Option<f64> {
    r.episode
        .infos
        .iter()
        .find(|i| i.events.has(Events::PICKUP))
        .map(|i| f64::from(i.timer_at_action))
}

/// Computes the metrics of `records` (bootstrap intervals seeded by `seed`).
pub fn compute_metrics(model: &str, records: &[EvalRecord], seed: u64) -> Metrics {
    // Conditions in first-seen order.
    let mut groups: Vec<(String, Vec<&EvalRecord>)> = Vec::new();
    for r in records {
        let key = serde_json::to_string(&r.condition).unwrap_or_default();
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, v)) => v.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let conditions = groups
        .iter()
        .map(|(_, v)| {
            let c = &v[0].condition;
            ConditionSummary {
                kind: c.kind,
                task: c.task.id().to_string(),
                td: c.td,
                factor: c.factor,
                never_ready: c.never_ready,
                episodes: v.len(),
                success_rate: mean(v.iter().map(|r| f64::from(u8::from(r.episode.success)))),
                mean_reward: mean(v.iter().map(|r| f64::from(r.episode.reward))),
                mean_oven_off: mean(v.iter().filter_map(|r| oven_off(r))),
            }
        })
        .collect();
    Metrics {
        model: model.to_string(),
        episodes: records.len(),
        success_rate: mean(
            records
                .iter()
                .map(|r| f64::from(u8::from(r.episode.success))),
        ),
        conditions,
        fi: fi_metrics(records),
        bisection: bisection_metrics(records, seed),
        pi: pi_curves(records),
        multi_timer: multi_timer_metrics(records),
        dual: dual_metrics(records),
        uncertainty: uncertainty_metrics(records),
        multi_anchor: crate::behaviour::categorization::multi_anchor_metrics(records, seed),
        multi_oven: crate::behaviour::concurrent::multi_oven_metrics(records, seed),
        reproduction: crate::behaviour::reproduction::reproduction_metrics(records),
    }
}

fn of_kind(records: &[EvalRecord], kind: ConditionKind) -> Vec<&EvalRecord> {
    records
        .iter()
        .filter(|r| r.condition.kind == kind)
        .collect()
}

fn by_td<'a>(recs: &[&'a EvalRecord]) -> BTreeMap<u32, Vec<&'a EvalRecord>> {
    let mut m: BTreeMap<u32, Vec<&EvalRecord>> = BTreeMap::new();
    for r in recs {
        m.entry(r.condition.td).or_default().push(r);
    }
    m
}

/// Number of oven-off plateaus in `(TD, mean oven-off)` pairs: distinct levels (rounded
/// to a step) reached by ≥ 2 TDs, plus levels reached by one trained TD (`trained`).
pub fn count_plateaus(points: &[(u32, f64)], trained: &[u32]) -> usize {
    let mut levels: BTreeMap<i64, (usize, bool)> = BTreeMap::new();
    for &(td, off) in points {
        if off.is_finite() {
            let e = levels.entry(off.round() as i64).or_insert((0, false));
            e.0 += 1;
            e.1 |= trained.contains(&td);
        }
    }
    levels.values().filter(|(n, t)| *n >= 2 || *t).count()
}

fn multi_timer_metrics(records: &[EvalRecord]) -> Option<MultiTimerMetrics> {
    let mt = of_kind(records, ConditionKind::MultiTimer);
    let buf = of_kind(records, ConditionKind::Buffer);
    if mt.is_empty() && buf.is_empty() {
        return None;
    }
    let reward = |v: &[&EvalRecord]| mean(v.iter().map(|r| f64::from(r.episode.reward)));
    let off = |v: &[&EvalRecord]| mean(v.iter().filter_map(|r| oven_off(r)));
    let by: Vec<(u32, f64, f64)> = by_td(&mt)
        .iter()
        .map(|(td, v)| (*td, reward(v), off(v)))
        .collect();
    let trained: Vec<u32> = buf.iter().map(|r| r.condition.td).collect();
    let mut by_buffer: Vec<(u32, f64, f64)> = Vec::new();
    for r in &buf {
        let key = (r.condition.td, r.condition.factor.unwrap_or(0.0));
        if !by_buffer.iter().any(|b| (b.0, b.1) == key) {
            let v: Vec<&EvalRecord> = buf
                .iter()
                .filter(|x| (x.condition.td, x.condition.factor.unwrap_or(0.0)) == key)
                .copied()
                .collect();
            by_buffer.push((key.0, key.1, reward(&v)));
        }
    }
    let plateaus = count_plateaus(&by.iter().map(|b| (b.0, b.2)).collect::<Vec<_>>(), &trained);
    Some(MultiTimerMetrics {
        by_td: by,
        by_buffer,
        plateaus,
    })
}

fn last_info(r: &EvalRecord) -> Option<&chronocooked_env::Info> {
    r.episode.infos.last()
}

fn dual_metrics(records: &[EvalRecord]) -> Option<DualMetrics> {
    let d = of_kind(records, ConditionKind::Dual);
    if d.is_empty() {
        return None;
    }
    let by = by_td(&d)
        .iter()
        .map(|(td, v)| {
            (
                *td,
                mean(v.iter().map(|r| f64::from(r.episode.reward))),
                mean(
                    v.iter()
                        .filter_map(|r| last_info(r))
                        .map(|i| f64::from(i.sink_count)),
                ),
                mean(
                    v.iter()
                        .filter_map(|r| last_info(r))
                        .filter(|i| i.last_sink_timer >= 0)
                        .map(|i| f64::from(i.last_sink_timer)),
                ),
            )
        })
        .collect();
    Some(DualMetrics { by_td: by })
}

fn uncertainty_metrics(records: &[EvalRecord]) -> Option<UncertaintyMetrics> {
    let u = of_kind(records, ConditionKind::Uncertainty);
    if u.is_empty() {
        return None;
    }
    let normal: Vec<&&EvalRecord> = u
        .iter()
        .filter(|r| r.condition.never_ready != Some(true))
        .collect();
    let never: Vec<&&EvalRecord> = u
        .iter()
        .filter(|r| r.condition.never_ready == Some(true))
        .collect();
    let press = |r: &EvalRecord| {
        r.episode
            .infos
            .iter()
            .find(|i| i.events.has(Events::BUTTON))
            .map(|i| f64::from(i.timer_at_action))
    };
    Some(UncertaintyMetrics {
        success_normal: mean(
            normal
                .iter()
                .map(|r| f64::from(u8::from(r.episode.success))),
        ),
        reward_never_ready: mean(never.iter().map(|r| f64::from(r.episode.reward))),
        button_use: mean(
            never
                .iter()
                .map(|r| f64::from(u8::from(press(r).is_some()))),
        ),
        press_time: mean(never.iter().filter_map(|r| press(r))),
    })
}

fn fi_metrics(records: &[EvalRecord]) -> Option<FiMetrics> {
    let mut by_td: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
    for r in records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::Fi)
    {
        let v = by_td.entry(r.condition.td).or_default();
        if let Some(f) = episode_foc(&r.episode) {
            v.push(f64::from(f));
        }
    }
    if by_td.is_empty() {
        return None;
    }
    let groups: Vec<(u32, Vec<f64>)> = by_td.into_iter().collect();
    let foc = foc_stats(&groups);
    let scalar = scalar_property(&foc);
    Some(FiMetrics { foc, scalar })
}

fn bisection_metrics(records: &[EvalRecord], seed: u64) -> Option<BisectionMetrics> {
    let bis: Vec<&EvalRecord> = records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::Bisection)
        .collect();
    let first = bis.first()?;
    let (short, long) = match first.condition.task.config().ok()?.params {
        TaskParams::Bisection { short, long } => (short, long),
        _ => return None,
    };
    let mut counts: BTreeMap<u32, ProbeCounts> = BTreeMap::new();
    for r in &bis {
        let c = counts.entry(r.condition.td).or_insert(ProbeCounts {
            t: f64::from(r.condition.td),
            valid: 0,
            long: 0,
            failed: 0,
        });
        let delivered = r
            .episode
            .infos
            .iter()
            .find(|i| i.events.has(Events::DELIVERY))
            .and_then(|i| i.counter);
        match delivered {
            Some(Counter::Long) => {
                c.valid += 1;
                c.long += 1;
            }
            Some(_) => c.valid += 1,
            None => c.failed += 1,
        }
    }
    let probes: Vec<ProbeCounts> = counts.into_values().collect();
    let p_long = probes.iter().map(ProbeCounts::p_long).collect();
    let anchor = |t: u32, want_long: bool| {
        probes
            .iter()
            .find(|p| p.t == f64::from(t))
            .map(|p| (if want_long { p.long } else { p.valid - p.long }, p.valid))
    };
    let (mut right, mut total) = (0, 0);
    for (t, l) in [(short, false), (long, true)] {
        if let Some((a, b)) = anchor(t, l) {
            right += a;
            total += b;
        }
    }
    let (fit, fit_error) = match fit_with_ci(&probes, 0.95, 500, seed) {
        Ok(f) => match check_transition(&probes, &f) {
            Ok(()) => (Some(f), None),
            Err(why) => (None, Some(why)),
        },
        Err(e) => (None, Some(e.to_string())),
    };
    let rel = fit
        .as_ref()
        .map(|f| bp_relative(f.bp, f64::from(short), f64::from(long)));
    Some(BisectionMetrics {
        short,
        long,
        probes,
        p_long,
        anchor_accuracy: if total > 0 {
            f64::from(right) / f64::from(total)
        } else {
            f64::NAN
        },
        fit,
        fit_error,
        bp_over_am: rel.map(|r| r.0),
        bp_over_gm: rel.map(|r| r.1),
    })
}

fn pi_curves(records: &[EvalRecord]) -> Vec<PiCurve> {
    let mut out: Vec<PiCurve> = Vec::new();
    let mut denom: Vec<Vec<f64>> = Vec::new();
    let mut trials: Vec<Vec<Vec<f64>>> = Vec::new();
    for r in records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::Pi)
    {
        let factor = r.condition.factor.unwrap_or(0.0);
        let idx = match out
            .iter()
            .position(|c| c.factor == factor && c.td == r.condition.td)
        {
            Some(i) => i,
            None => {
                out.push(PiCurve {
                    factor,
                    td: r.condition.td,
                    rate: Vec::new(),
                    fit: None,
                    start_stop: None,
                });
                trials.push(Vec::new());
                denom.push(Vec::new());
                out.len() - 1
            }
        };
        let mut responses: Vec<f64> = Vec::new();
        for (a, info) in r.episode.actions.iter().zip(&r.episode.infos) {
            if info.timer_at_action < 0 {
                continue;
            }
            let tt = info.timer_at_action as usize;
            if responses.len() <= tt {
                responses.resize(tt + 1, 0.0);
            }
            if *a == 5 && info.events.has(Events::OVEN_CHECK) {
                responses[tt] += 1.0;
            }
            let t = info.timer_at_action as usize;
            let curve = &mut out[idx].rate;
            if curve.len() <= t {
                curve.resize(t + 1, 0.0);
                denom[idx].resize(t + 1, 0.0);
            }
            denom[idx][t] += 1.0;
            if *a == 5 && info.events.has(Events::OVEN_CHECK) {
                curve[t] += 1.0;
            }
        }
        trials[idx].push(responses);
    }
    for ((c, d), tr) in out.iter_mut().zip(&denom).zip(&trials) {
        c.rate
            .iter_mut()
            .zip(d)
            .for_each(|(v, n)| *v = if *n > 0.0 { *v / n } else { f64::NAN });
        c.fit = crate::behaviour::peak::fit_gaussian(&c.rate);
        let ss: Vec<crate::behaviour::peak::StartStop> = tr
            .iter()
            .filter_map(|x| crate::behaviour::peak::start_stop(x))
            .collect();
        if !ss.is_empty() {
            let n = ss.len() as f64;
            let m = |f: &dyn Fn(&crate::behaviour::peak::StartStop) -> f64| {
                ss.iter().map(f).sum::<f64>() / n
            };
            c.start_stop = Some((
                [
                    m(&|s| s.start as f64),
                    m(&|s| s.stop as f64),
                    m(&|s| s.middle),
                    m(&|s| s.spread as f64),
                ],
                ss.len(),
            ));
        }
    }
    out
}
