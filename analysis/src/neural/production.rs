//! Timing by speed in recorded activity: the KiNeT analysis ([`crate::neural::speed`]) on a
//! reproduction dataset's mean trajectories after Set, one condition per sample interval
//! `ts`, separately for every context (prior × gain) of the task.
//!
//! * **Trials.** Those with a Set marker ([`Marker::Set`]) and a reproduction context;
//!   grouped by context, then by `ts` (the trial's `td`).
//! * **Trajectory of one `ts`.** Its states at production times `t = 0, 1, …` (step
//!   `Set + 1 + t`: the first step after the Set flash, as every other alignment), averaged
//!   over the condition's trials that still run at that step, for `T` steps: `T` is the
//!   median production of the condition's trials that responded (steps from the Set step
//!   to the pickup; Remington et al. 2018 analysed Set → Go), cut where no trial runs any
//!   more. A `ts` with no response, or shorter than the analysis needs, is left out.
//! * **Dimensions.** The population's units that are finite at every step used (a unit
//!   the agent did not write is NaN) and vary somewhere in the context.
//! * **Analysis.** [`kinet_speed`] with the default options (reference: the middle `ts`);
//!   the context needs ≥ 2 such conditions.

use crate::neural::speed::{ConditionTrajectory, SpeedOptions, kinet_speed};
use chronocooked_models::{ActivityDataset, Marker};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The KiNeT analysis of one context's productions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProductionSpeed {
    /// Index of the context's prior (in the task's `priors`).
    pub prior: u8,
    /// Index of the context's gain (in the task's `gains`).
    pub gain: u8,
    /// Dimensions analysed (units of the population that vary and are always finite).
    pub units: usize,
    /// The reference condition's `ts` (steps).
    pub reference_ts: u32,
    /// One entry per analysed `ts`, ascending.
    pub conditions: Vec<ProductionCondition>,
    /// `−` slope of ln speed on ln ts: ≈ 1 when the trajectories are time-stretched copies
    /// (timing by speed), ≈ 0 for a clock of fixed speed.
    pub scaling_index: Option<f64>,
    /// Spearman correlation of `ts` with the states at Set projected on the shortest →
    /// longest axis (the initial condition ordered by `ts`).
    pub initial_order: Option<f64>,
    /// Spearman correlation of `ts` with the mean signed distance to the reference.
    pub distance_order: Option<f64>,
}

/// One `ts` of a context.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProductionCondition {
    /// Sample interval (steps).
    pub ts: u32,
    /// Trials averaged.
    pub trials: usize,
    /// Trajectory length `T` (steps after Set).
    pub steps: usize,
    /// Speed relative to the reference (1 for the reference; `None` when undefined).
    pub relative_speed: Option<f64>,
    /// Mean signed distance to the reference over the matched window (state units).
    pub mean_signed_distance: Option<f64>,
}

/// The median of `v` (non-empty), the lower middle for an even count.
fn lower_median(mut v: Vec<usize>) -> usize {
    v.sort_unstable();
    v[(v.len() - 1) / 2]
}

/// The KiNeT analysis of `population` (every unit when `None`) in every context of
/// `dataset` with ≥ 2 analysable `ts`, ordered by prior then gain. Empty for a dataset
/// without reproduction trials or an unknown population.
pub fn production_speed(
    dataset: &ActivityDataset,
    population: Option<&str>,
) -> Vec<ProductionSpeed> {
    let n = dataset.meta.n_units();
    let cols = match population {
        Some(p) => match dataset.meta.range(p) {
            Some(r) => r,
            None => return Vec::new(),
        },
        None => 0..n,
    };
    let options = SpeedOptions::default();
    let min_time = crate::neural::speed::MIN_TIME + 2 * options.edge_margin;
    // context → ts → trials (index, Set step, production if the agent responded).
    type ByTs = BTreeMap<u32, Vec<(usize, usize, Option<usize>)>>;
    let mut contexts: BTreeMap<(u8, u8), ByTs> = BTreeMap::new();
    for (k, t) in dataset.trials.iter().enumerate() {
        let (Some(ctx), Some(set)) = (t.reproduction, t.first(Marker::Set)) else {
            continue;
        };
        let tp = t
            .events
            .iter()
            .find(|e| e.marker == Marker::Pickup && e.step > set)
            .map(|e| (e.step - set) as usize);
        contexts
            .entry((ctx.prior, ctx.gain))
            .or_default()
            .entry(t.td)
            .or_default()
            .push((k, set as usize, tp));
    }
    let mut out = Vec::new();
    for ((prior, gain), by_ts) in contexts {
        // Mean trajectory [T, population] of every analysable ts.
        let mut means: Vec<(u32, usize, usize, Vec<f64>)> = Vec::new();
        for (ts, trials) in by_ts {
            let productions: Vec<usize> = trials.iter().filter_map(|t| t.2).collect();
            if productions.is_empty() {
                continue;
            }
            let want = lower_median(productions);
            let mut states = Vec::new();
            let mut time = 0;
            for step in 0..want {
                let mut sum = vec![0.0; cols.len()];
                let mut count = 0usize;
                for &(k, set, _) in &trials {
                    let trial = &dataset.trials[k];
                    let at = set + 1 + step;
                    if at < trial.steps {
                        let row = &trial.activity[at * n..(at + 1) * n];
                        for (s, &v) in sum.iter_mut().zip(&row[cols.clone()]) {
                            *s += f64::from(v);
                        }
                        count += 1;
                    }
                }
                if count == 0 {
                    break;
                }
                states.extend(sum.iter().map(|s| s / count as f64));
                time += 1;
            }
            if time >= min_time {
                means.push((ts, trials.len(), time, states));
            }
        }
        if means.len() < 2 {
            continue;
        }
        // Units finite everywhere and varying somewhere in the context.
        let width = cols.len();
        let keep: Vec<usize> = (0..width)
            .filter(|&j| {
                let mut values = means
                    .iter()
                    .flat_map(|(_, _, time, s)| (0..*time).map(move |t| s[t * width + j]));
                let Some(first) = values.next() else {
                    return false;
                };
                let mut varies = false;
                for v in values {
                    if !v.is_finite() {
                        return false;
                    }
                    varies |= v != first;
                }
                first.is_finite() && varies
            })
            .collect();
        if keep.is_empty() {
            continue;
        }
        let conditions: Vec<ConditionTrajectory> = means
            .iter()
            .map(|(ts, _, time, s)| ConditionTrajectory {
                ts: f64::from(*ts),
                time: *time,
                dims: keep.len(),
                states: (0..*time)
                    .flat_map(|t| keep.iter().map(move |&j| s[t * width + j]))
                    .collect(),
            })
            .collect();
        let Ok(analysis) = kinet_speed(&conditions, options) else {
            continue;
        };
        out.push(ProductionSpeed {
            prior,
            gain,
            units: keep.len(),
            reference_ts: means[analysis.reference].0,
            conditions: means
                .iter()
                .zip(&analysis.conditions)
                .map(|((ts, trials, time, _), c)| ProductionCondition {
                    ts: *ts,
                    trials: *trials,
                    steps: *time,
                    relative_speed: c.relative_speed,
                    mean_signed_distance: c.mean_signed_distance,
                })
                .collect(),
            scaling_index: analysis.scaling_index,
            initial_order: analysis.initial_order,
            distance_order: analysis.distance_order,
        });
    }
    out
}
