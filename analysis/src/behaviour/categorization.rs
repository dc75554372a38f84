//! Multi-anchor categorization: the choice of every counter at every probe, the
//! reference's per-category error rate, a psychometric fit for every pair of neighbouring
//! anchors, and whether the Weber fraction is the same across boundaries (the scalar
//! property across categories).
//!
//! * **Choices.** Counter `c` (1…k) belongs to the `c`-th shortest active anchor; an
//!   episode without a delivery is a failure.
//! * **Category error rate** (the reference notebook's): a probe's category is the number
//!   `j` of anchors ≤ TD; category 0 accepts counter 1, category `j` (1 ≤ j < k) accepts
//!   counters `j` and `j + 1` (an anchor TD falls into the category above it, so both of
//!   its neighbours count as right), category `k` accepts counter `k`. Error = choices
//!   outside the accepted set / deliveries (failures excluded).
//! * **Boundaries.** For neighbouring anchors `a_i < a_{i+1}` the probes `a_i ≤ t ≤ a_{i+1}`
//!   give `P(upper | t)` among the deliveries to either of their two counters (other
//!   counters and failures are not choices between the two; the bisection exclusion rule
//!   applies to failures); the logistic fit of [`super::psychometric`] gives BP, DL and WF,
//!   and BP is compared with the pair's geometric (`√(a_i a_{i+1})`) and arithmetic means.
//! * **Constant WF.** The WFs of every fitted boundary with their 95% bootstrap intervals
//!   (`WF` interval = scale interval · ln 3 / BP); the WF is called constant when every
//!   pair of intervals overlaps.

use super::psychometric::{LogisticFit, ProbeCounts, check_transition, fit_with_ci};
use crate::records::{ConditionKind, EvalRecord};
use chronocooked_env::{Counter, Events};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Choices at one probe duration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CategoryCounts {
    /// Probe duration (steps).
    pub t: u32,
    /// Deliveries to counter 1…k.
    pub counters: Vec<u32>,
    /// Episodes without a delivery.
    pub failed: u32,
}

impl CategoryCounts {
    /// Episodes played at this probe.
    pub fn episodes(&self) -> u32 {
        self.counters.iter().sum::<u32>() + self.failed
    }

    /// Share of the episodes that chose each counter (failures in the denominator).
    pub fn proportions(&self) -> Vec<f64> {
        let n = f64::from(self.episodes().max(1));
        self.counters.iter().map(|&c| f64::from(c) / n).collect()
    }
}

/// The reference's error rate of one probe category.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CategoryError {
    /// Number of anchors ≤ the probe (0…k).
    pub category: usize,
    /// Counters accepted (1-based).
    pub accepted: Vec<u8>,
    /// Deliveries at the category's probes.
    pub choices: u32,
    /// Deliveries outside `accepted`.
    pub errors: u32,
    /// `errors / choices` (NaN without deliveries).
    pub rate: f64,
}

/// The psychometric boundary between two neighbouring anchors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Boundary {
    /// Shorter anchor (steps).
    pub lower: u32,
    /// Longer anchor (steps).
    pub upper: u32,
    /// `√(lower · upper)`.
    pub gm: f64,
    /// `(lower + upper) / 2`.
    pub am: f64,
    /// `P(upper)` counts per probe `lower ≤ t ≤ upper`.
    pub probes: Vec<ProbeCounts>,
    /// The logistic fit with 95% bootstrap intervals, when it could be made.
    pub fit: Option<LogisticFit>,
    /// Why not, when it could not.
    pub fit_error: Option<String>,
    /// 95% interval of the WF (from the scale's interval), when there is one.
    pub wf_ci: Option<(f64, f64)>,
    /// `geometric` or `arithmetic`: the mean BP is nearer to (None without a fit).
    pub nearer: Option<String>,
}

/// Whether the boundaries share one Weber fraction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WfConstancy {
    /// WF of every fitted boundary, in boundary order.
    pub wfs: Vec<f64>,
    /// Largest / smallest WF.
    pub ratio: f64,
    /// Every pair of WF intervals overlaps (None when an interval is missing).
    pub constant: Option<bool>,
}

/// Multi-anchor metrics of one evaluation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MultiAnchorMetrics {
    /// Active anchors (steps), counter order.
    pub anchors: Vec<u32>,
    /// Choices per probe, in probe order.
    pub probes: Vec<CategoryCounts>,
    /// Deliveries to the anchor's own counter at the anchor TDs, among deliveries.
    pub anchor_accuracy: f64,
    /// The reference's per-category error rates.
    pub category_errors: Vec<CategoryError>,
    /// One psychometric boundary per pair of neighbouring anchors.
    pub boundaries: Vec<Boundary>,
    /// Whether the WF is constant across boundaries (≥ 2 fitted boundaries).
    pub wf_constancy: Option<WfConstancy>,
}

/// The counter (1-based) an episode delivered to, `None` without a delivery.
fn chosen(r: &EvalRecord) -> Option<u8> {
    r.episode
        .infos
        .iter()
        .find(|i| i.events.has(Events::DELIVERY))
        .and_then(|i| i.counter)
        .map(Counter::number)
}

/// Counters accepted in category `j` of `k` anchors.
pub fn accepted(j: usize, k: usize) -> Vec<u8> {
    match j {
        0 => vec![1],
        j if j >= k => vec![k as u8],
        j => vec![j as u8, j as u8 + 1],
    }
}

/// The metrics of the multi-anchor records in `records` (`None` without any); `seed` seeds
/// the bootstrap.
pub fn multi_anchor_metrics(records: &[EvalRecord], seed: u64) -> Option<MultiAnchorMetrics> {
    let recs: Vec<&EvalRecord> = records
        .iter()
        .filter(|r| r.condition.kind == ConditionKind::MultiAnchor)
        .collect();
    let first = recs.first()?;
    let config = first.condition.task.config().ok()?;
    let anchors = config.params.active_anchors()?.to_vec();
    let k = anchors.len();
    let mut by_probe: BTreeMap<u32, CategoryCounts> = BTreeMap::new();
    for r in &recs {
        let c = by_probe
            .entry(r.condition.td)
            .or_insert_with(|| CategoryCounts {
                t: r.condition.td,
                counters: vec![0; k],
                failed: 0,
            });
        match chosen(r) {
            Some(i) if (1..=k as u8).contains(&i) => c.counters[i as usize - 1] += 1,
            _ => c.failed += 1,
        }
    }
    let probes: Vec<CategoryCounts> = by_probe.into_values().collect();
    let (mut right, mut total) = (0u32, 0u32);
    for (i, &a) in anchors.iter().enumerate() {
        if let Some(p) = probes.iter().find(|p| p.t == a) {
            right += p.counters[i];
            total += p.counters.iter().sum::<u32>();
        }
    }
    let category_errors = (0..=k)
        .map(|j| {
            let ok = accepted(j, k);
            let (mut choices, mut errors) = (0, 0);
            for p in probes
                .iter()
                .filter(|p| anchors.iter().filter(|&&a| a <= p.t).count() == j)
            {
                for (i, &n) in p.counters.iter().enumerate() {
                    choices += n;
                    if !ok.contains(&(i as u8 + 1)) {
                        errors += n;
                    }
                }
            }
            CategoryError {
                category: j,
                accepted: ok,
                choices,
                errors,
                rate: if choices > 0 {
                    f64::from(errors) / f64::from(choices)
                } else {
                    f64::NAN
                },
            }
        })
        .collect();
    let boundaries: Vec<Boundary> = anchors
        .windows(2)
        .enumerate()
        .map(|(i, w)| boundary(&probes, i, w[0], w[1], seed.wrapping_add(i as u64)))
        .collect();
    let wf_constancy = constancy(&boundaries);
    Some(MultiAnchorMetrics {
        anchors,
        probes,
        anchor_accuracy: if total > 0 {
            f64::from(right) / f64::from(total)
        } else {
            f64::NAN
        },
        category_errors,
        boundaries,
        wf_constancy,
    })
}

fn boundary(probes: &[CategoryCounts], i: usize, lower: u32, upper: u32, seed: u64) -> Boundary {
    let counts: Vec<ProbeCounts> = probes
        .iter()
        .filter(|p| (lower..=upper).contains(&p.t))
        .map(|p| ProbeCounts {
            t: f64::from(p.t),
            valid: p.counters[i] + p.counters[i + 1],
            long: p.counters[i + 1],
            failed: p.failed,
        })
        .collect();
    let (fit, fit_error) = match fit_with_ci(&counts, 0.95, 500, seed) {
        Ok(f) => match check_transition(&counts, &f) {
            Ok(()) => (Some(f), None),
            Err(why) => (None, Some(why)),
        },
        Err(e) => (None, Some(e.to_string())),
    };
    let (l, u) = (f64::from(lower), f64::from(upper));
    let (gm, am) = ((l * u).sqrt(), 0.5 * (l + u));
    let wf_ci = fit.as_ref().and_then(|f| {
        f.scale_ci
            .map(|(a, b)| (a * 3f64.ln() / f.bp, b * 3f64.ln() / f.bp))
    });
    let nearer = fit.as_ref().map(|f| {
        if (f.bp - gm).abs() <= (f.bp - am).abs() {
            "geometric".to_string()
        } else {
            "arithmetic".to_string()
        }
    });
    Boundary {
        lower,
        upper,
        gm,
        am,
        probes: counts,
        fit,
        fit_error,
        wf_ci,
        nearer,
    }
}

fn constancy(boundaries: &[Boundary]) -> Option<WfConstancy> {
    let fitted: Vec<&Boundary> = boundaries
        .iter()
        .filter(|b| b.fit.as_ref().is_some_and(|f| f.wf.is_finite()))
        .collect();
    if fitted.len() < 2 {
        return None;
    }
    let wfs: Vec<f64> = fitted
        .iter()
        .filter_map(|b| b.fit.as_ref().map(|f| f.wf))
        .collect();
    let max = wfs.iter().copied().fold(f64::MIN, f64::max);
    let min = wfs.iter().copied().fold(f64::MAX, f64::min);
    let cis: Option<Vec<(f64, f64)>> = fitted.iter().map(|b| b.wf_ci).collect();
    let constant = cis.map(|cis| {
        cis.iter()
            .all(|a| cis.iter().all(|b| a.0 <= b.1 && b.0 <= a.1))
    });
    Some(WfConstancy {
        wfs,
        ratio: max / min,
        constant,
    })
}
