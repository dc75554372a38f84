//! Temporal reproduction: each context's (prior × gain) productions `tp` against the sample
//! intervals `ts`, their summary (regression slope, BIAS, √VAR, RMSE, Weber fraction of
//! [`crate::reproduction`]) and, at gain 1, the Bayesian observer that fits them best
//! (maximum likelihood over BLS, MAP and ML with whole-step productions).
//!
//! A production is the `tp` of the episode's pickup (steps from Set to the response,
//! `info.oven_off_time`); episodes without a pickup are failures (too late, or never).

use crate::records::{ConditionKind, EvalRecord};
use crate::reproduction::{Prior, Record, Rounding, fit_observers, summarize};
use chronocooked_env::Events;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The observer fit of one context.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObserverChoice {
    /// The observer of largest likelihood (`BLS`, `MAP`, `ML`).
    pub best: String,
    /// Its measurement Weber fraction.
    pub wm: f64,
    /// Its production Weber fraction.
    pub wp: f64,
    /// `(observer, log-likelihood)` of every observer.
    pub log_likelihoods: Vec<(String, f64)>,
}

/// One context's productions and summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContextSummary {
    /// Prior index (the task's `priors`).
    pub prior: u8,
    /// Gain `g`.
    pub gain: f64,
    /// Episodes played.
    pub episodes: usize,
    /// Episodes without a production.
    pub failures: usize,
    /// `(ts, mean tp, SD of tp, productions)` per sample interval.
    pub by_ts: Vec<(u32, f64, f64, usize)>,
    /// `(ts, mean tp / (g·ts))`: 1 is veridical.
    pub ratio: Vec<(u32, f64)>,
    /// OLS slope of tp on ts (< g: regression to the mean).
    pub slope: Option<f64>,
    /// BIAS (steps) against the target `g·ts` (at gain 1, Jazayeri & Shadlen's against `ts`).
    pub bias: Option<f64>,
    /// √VAR (steps).
    pub sqrt_var: Option<f64>,
    /// RMSE (steps) against the target `g·ts`.
    pub rmse: Option<f64>,
    /// Mean over ts of SD/mean of tp.
    pub weber: Option<f64>,
    /// The best Bayesian observer (gain 1, ≥ 2 productions at ≥ 2 intervals).
    pub observer: Option<ObserverChoice>,
}

/// Reproduction metrics of one evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReproductionMetrics {
    /// One summary per context, in (prior, gain) order.
    pub contexts: Vec<ContextSummary>,
}

/// The production `tp` of an episode (`None` without a pickup).
pub fn production(r: &EvalRecord) -> Option<u32> {
    r.episode
        .infos
        .iter()
        .find(|i| i.events.has(Events::PICKUP))
        .map(|i| i.oven_off_time.max(0) as u32)
}

/// The metrics of the reproduction records in `records` (`None` without any).
pub fn reproduction_metrics(records: &[EvalRecord]) -> Option<ReproductionMetrics> {
    let mut by_context: BTreeMap<(u8, u8), Vec<&EvalRecord>> = BTreeMap::new();
    for r in records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::Reproduction)
    {
        let [p, g] = r.condition.context.unwrap_or([0, 0]);
        by_context.entry((p, g)).or_default().push(r);
    }
    if by_context.is_empty() {
        return None;
    }
    let contexts = by_context
        .into_iter()
        .map(|((prior, _), recs)| context_summary(prior, &recs))
        .collect();
    Some(ReproductionMetrics { contexts })
}

fn context_summary(prior: u8, recs: &[&EvalRecord]) -> ContextSummary {
    let gain = recs[0].condition.factor.unwrap_or(1.0);
    let mut by_ts: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
    let mut failures = 0;
    for r in recs {
        match production(r) {
            Some(tp) => by_ts.entry(r.condition.td).or_default().push(f64::from(tp)),
            None => failures += 1,
        }
    }
    let stats: Vec<(u32, f64, f64, usize)> = by_ts
        .iter()
        .map(|(&ts, v)| {
            let n = v.len() as f64;
            let mean = v.iter().sum::<f64>() / n;
            let var = if v.len() > 1 {
                v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
            } else {
                0.0
            };
            (ts, mean, var.sqrt(), v.len())
        })
        .collect();
    let ratio = stats
        .iter()
        .map(|&(ts, mean, ..)| (ts, mean / (gain * f64::from(ts))))
        .collect();
    let points: Vec<Record> = by_ts
        .iter()
        .flat_map(|(&ts, v)| {
            v.iter().map(move |&tp| Record {
                ts: f64::from(ts),
                tp,
            })
        })
        .collect();
    // Summarised against the target `g·ts`, so BIAS and RMSE measure the error of the
    // production the context asks for (against `ts` a perfect gain of 1.5 would read as a
    // BIAS of half the prior's mean); the slope is reported per step of `ts` (`g` when
    // veridical).
    let targets: Vec<Record> = points
        .iter()
        .map(|r| Record {
            ts: gain * r.ts,
            tp: r.tp,
        })
        .collect();
    let summary = summarize(&targets).ok();
    let observer = ((gain - 1.0).abs() < 1e-9)
        .then(|| observer_choice(recs, &points))
        .flatten();
    ContextSummary {
        prior,
        gain,
        episodes: recs.len(),
        failures,
        by_ts: stats,
        ratio,
        slope: summary.as_ref().map(|s| s.slope * gain),
        bias: summary.as_ref().map(|s| s.bias),
        sqrt_var: summary.as_ref().map(|s| s.sqrt_var()),
        rmse: summary.as_ref().map(|s| s.rmse),
        weber: summary.as_ref().map(|s| s.weber),
        observer,
    }
}

/// The prior the observers assume: the task's prior of this context (every whole step).
fn observer_choice(recs: &[&EvalRecord], points: &[Record]) -> Option<ObserverChoice> {
    let c = &recs.first()?.condition;
    let rsg = c.task.config().ok()?.ready_set_go().ok()??;
    let &(lo, hi) = rsg.priors.get(c.context.map_or(0, |x| x[0]) as usize)?;
    let values: Vec<f64> = (lo..=hi).map(f64::from).collect();
    let prior = Prior::new(&values).ok()?;
    let report = fit_observers(points, &prior, Rounding::WholeSteps).ok()?;
    let best = report.best_fit();
    Some(ObserverChoice {
        best: best.observer.name().to_string(),
        wm: best.wm,
        wp: best.wp,
        log_likelihoods: report
            .fits
            .iter()
            .map(|f| (f.observer.name().to_string(), f.log_likelihood))
            .collect(),
    })
}
