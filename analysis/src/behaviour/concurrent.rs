//! Multi-oven bisection: each oven's psychometric curve, accuracy and fit, the
//! interference between ovens, and the order of deliveries.
//!
//! * **Per oven.** At every probe each oven's soup goes to the short counter, the long
//!   counter, or nowhere (a failure for that oven). `P(long)` among its deliveries and the
//!   logistic fit of [`super::psychometric`] give each oven's BP, DL and WF; accuracy is the
//!   share of its deliveries at S and L that went to the counter of its duration.
//! * **Interference** (simultaneous temporal processing, Meck & Church 1984): each oven's WF
//!   and BP against the same agent's one-oven curve (the protocol plays the one-oven task
//!   beside the trained one), `ΔWF = WF_oven − WF_single`, `ΔBP = BP_oven − BP_single`; and,
//!   in asynchronous mode, accuracy at the anchors by onset offset (the oven's start minus
//!   the first oven's start, in steps; the first oven starts at the put).
//! * **Order of deliveries**: the sequence of ovens whose soups were delivered, per episode.

use super::psychometric::{LogisticFit, ProbeCounts, bp_relative, check_transition, fit_with_ci};
use crate::records::{ConditionKind, EvalRecord};
use chronocooked_env::{Events, Info, OvenSet, TaskParams};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One oven's psychometric curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OvenCurve {
    /// Oven index (0 = the one that takes the onion).
    pub oven: usize,
    /// Counts per probe.
    pub probes: Vec<ProbeCounts>,
    /// P(long) per probe (NaN: excluded by the >50%-failed rule).
    pub p_long: Vec<f64>,
    /// Deliveries at S and L to the counter of the duration, among deliveries.
    pub accuracy: f64,
    /// The logistic fit with 95% bootstrap intervals, when it could be made.
    pub fit: Option<LogisticFit>,
    /// Why not, when it could not.
    pub fit_error: Option<String>,
    /// BP / geometric mean of S and L.
    pub bp_over_gm: Option<f64>,
}

/// One oven against the one-oven curve of the same agent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Interference {
    /// Oven index.
    pub oven: usize,
    /// `WF_oven − WF_single` (NaN where a fit is missing).
    pub d_wf: f64,
    /// `BP_oven − BP_single` (steps).
    pub d_bp: f64,
    /// `accuracy_oven − accuracy_single`.
    pub d_accuracy: f64,
}

/// Accuracy at the anchors by onset offset (asynchronous mode).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OffsetAccuracy {
    /// The oven's start minus the first oven's start (steps).
    pub offset: i32,
    /// Deliveries at S and L.
    pub n: usize,
    /// Their share at the counter of the oven's duration.
    pub accuracy: f64,
}

/// Multi-oven metrics of one evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultiOvenMetrics {
    /// Short anchor S (steps).
    pub short: u32,
    /// Long anchor L (steps).
    pub long: u32,
    /// Ovens of the evaluated task.
    pub ovens: usize,
    /// Asynchronous mode.
    pub asynchronous: bool,
    /// Every oven's curve.
    pub per_oven: Vec<OvenCurve>,
    /// The same agent on the one-oven task (when the protocol played it).
    pub single: Option<OvenCurve>,
    /// Each oven against `single`.
    pub interference: Vec<Interference>,
    /// Asynchronous mode: accuracy at the anchors by onset offset.
    pub by_offset: Vec<OffsetAccuracy>,
    /// `(order of ovens delivered, e.g. "1-0", episodes)`, most frequent first.
    pub orders: Vec<(String, usize)>,
}

/// The last step's per-oven state of an episode.
fn last(r: &EvalRecord) -> Option<&OvenSet> {
    r.episode.ovens.last()
}

/// The ovens in the order their soups were delivered, from every step's oven states
/// (`ovens`, one per step).
pub fn delivery_order(ovens: &[OvenSet]) -> Vec<usize> {
    let mut order = Vec::new();
    let mut before = [0u8; 3];
    for o in ovens {
        let n = o.n as usize;
        order.extend(
            before[..n]
                .iter()
                .zip(&o.delivered[..n])
                .enumerate()
                .filter(|(_, (b, d))| **b == 0 && **d != 0)
                .map(|(i, _)| i),
        );
        before = o.delivered;
    }
    order
}

/// Onset of every oven (step at whose end it started; −1 never): the first at the put, the
/// others at the put (synchronous) or at their on-times (asynchronous; 0 = at reset).
/// `infos` and `ovens` are one episode's steps.
pub fn onsets(infos: &[Info], ovens: &[OvenSet], asynchronous: bool) -> [i32; 3] {
    let put = infos
        .iter()
        .find(|i| i.events.has(Events::ONION_IN))
        .map_or(-1, |i| i.timestep as i32);
    let mut out = [-1; 3];
    let Some(first) = ovens.first() else {
        return out;
    };
    for (o, slot) in out.iter_mut().enumerate().take(first.n as usize) {
        *slot = if o == 0 || !asynchronous {
            put
        } else {
            first.on_time[o]
        };
    }
    out
}

fn curve(recs: &[&EvalRecord], oven: usize, short: u32, long: u32, seed: u64) -> OvenCurve {
    let mut by: BTreeMap<u32, ProbeCounts> = BTreeMap::new();
    let (mut right, mut total) = (0u32, 0u32);
    for r in recs {
        let Some(end) = last(r) else { continue };
        let td = end.td[oven];
        let c = by.entry(td).or_insert(ProbeCounts {
            t: f64::from(td),
            valid: 0,
            long: 0,
            failed: 0,
        });
        match end.delivered[oven] {
            0 => c.failed += 1,
            d => {
                c.valid += 1;
                c.long += u32::from(d == 2);
                if td == short || td == long {
                    total += 1;
                    right += u32::from((d == 2) == (td == long));
                }
            }
        }
    }
    let probes: Vec<ProbeCounts> = by.into_values().collect();
    let p_long = probes.iter().map(ProbeCounts::p_long).collect();
    let (fit, fit_error) = match fit_with_ci(&probes, 0.95, 500, seed) {
        Ok(f) => match check_transition(&probes, &f) {
            Ok(()) => (Some(f), None),
            Err(why) => (None, Some(why)),
        },
        Err(e) => (None, Some(e.to_string())),
    };
    let bp_over_gm = fit
        .as_ref()
        .map(|f| bp_relative(f.bp, f64::from(short), f64::from(long)).1);
    OvenCurve {
        oven,
        probes,
        p_long,
        accuracy: if total > 0 {
            f64::from(right) / f64::from(total)
        } else {
            f64::NAN
        },
        fit,
        fit_error,
        bp_over_gm,
    }
}

/// The metrics of the multi-oven records in `records` (`None` without any): the curves of
/// the task with the most ovens, and the one-oven curve when it was played too.
pub fn multi_oven_metrics(records: &[EvalRecord], seed: u64) -> Option<MultiOvenMetrics> {
    let mut by_n: BTreeMap<usize, (Vec<&EvalRecord>, u32, u32, bool)> = BTreeMap::new();
    for r in records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::MultiOven)
    {
        let Ok(cfg) = r.condition.task.config() else {
            continue;
        };
        if let TaskParams::MultiOven {
            short,
            long,
            ovens,
            asynchronous,
        } = cfg.params
        {
            by_n.entry(ovens as usize)
                .or_insert_with(|| (Vec::new(), short, long, asynchronous))
                .0
                .push(r);
        }
    }
    let (&ovens, (recs, short, long, asynchronous)) = by_n.iter().next_back()?;
    let (short, long, asynchronous) = (*short, *long, *asynchronous);
    let per_oven: Vec<OvenCurve> = (0..ovens)
        .map(|o| curve(recs, o, short, long, seed.wrapping_add(o as u64)))
        .collect();
    let single = (ovens > 1)
        .then(|| by_n.get(&1))
        .flatten()
        .map(|(r, ..)| curve(r, 0, short, long, seed.wrapping_add(7)));
    let wf = |c: &OvenCurve| c.fit.as_ref().map_or(f64::NAN, |f| f.wf);
    let bp = |c: &OvenCurve| c.fit.as_ref().map_or(f64::NAN, |f| f.bp);
    let interference = single
        .as_ref()
        .map(|s| {
            per_oven
                .iter()
                .map(|c| Interference {
                    oven: c.oven,
                    d_wf: wf(c) - wf(s),
                    d_bp: bp(c) - bp(s),
                    d_accuracy: c.accuracy - s.accuracy,
                })
                .collect()
        })
        .unwrap_or_default();
    let mut offsets: BTreeMap<i32, (usize, usize)> = BTreeMap::new();
    let mut orders: BTreeMap<String, usize> = BTreeMap::new();
    for r in recs {
        let ovens_at = &r.episode.ovens;
        let Some(end) = ovens_at.last() else { continue };
        let order: Vec<String> = delivery_order(ovens_at)
            .iter()
            .map(|o| o.to_string())
            .collect();
        *orders.entry(order.join("-")).or_default() += 1;
        if !asynchronous {
            continue;
        }
        let on = onsets(&r.episode.infos, ovens_at, asynchronous);
        if on[0] < 0 {
            continue;
        }
        for o in 1..ovens {
            let td = end.td[o];
            let d = end.delivered[o];
            if (td == short || td == long) && d != 0 && on[o] >= 0 {
                let e = offsets.entry(on[o] - on[0]).or_default();
                e.0 += 1;
                e.1 += usize::from((d == 2) == (td == long));
            }
        }
    }
    let mut orders: Vec<(String, usize)> = orders.into_iter().collect();
    orders.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    Some(MultiOvenMetrics {
        short,
        long,
        ovens,
        asynchronous,
        per_oven,
        single,
        interference,
        by_offset: offsets
            .into_iter()
            .map(|(offset, (n, right))| OffsetAccuracy {
                offset,
                n,
                accuracy: right as f64 / n as f64,
            })
            .collect(),
        orders,
    })
}
