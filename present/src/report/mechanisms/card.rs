//! What a signature card shows, computed from a model's recorded fixed-interval runs.

use super::RunInfo;
use crate::report::leaderboard::Row;
use chronocooked_analysis::job_folder;
use chronocooked_analysis::mechanisms::{MECHANISMS, READOUTS};
use chronocooked_analysis::neural::categories::{Category, UnitTests};
use chronocooked_analysis::neural::oscillation::welch;
use chronocooked_analysis::neural::summary::{
    SummaryOptions, TdClassification, classify_td, neural_summary, recorded_tds,
};
use chronocooked_models::ActivityDataset;
use std::collections::BTreeMap;
use std::path::Path;

/// The activity dataset recorded next to an evaluation folder (`<job>/activity.json`).
fn load_activity(eval: &Path) -> Result<Option<ActivityDataset>, String> {
    let Some(path) = eval.parent().map(|p| p.join(job_folder::ACTIVITY)) else {
        return Ok(None);
    };
    if !path.is_file() {
        return Ok(None);
    }
    let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    ActivityDataset::from_json(&bytes)
        .map(Some)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// The largest population that is not a read-out (the first of equal size).
fn timing_population(ds: &ActivityDataset) -> Option<String> {
    ds.meta
        .populations
        .iter()
        .filter(|p| !READOUTS.contains(&p.name.as_str()) && p.size > 0)
        .rev()
        .max_by_key(|p| p.size)
        .map(|p| p.name.clone())
}

/// One seed's fixed-interval recordings of a model, merged (trials of every TD).
fn merged(datasets: Vec<ActivityDataset>) -> Option<ActivityDataset> {
    let mut it = datasets.into_iter();
    let mut first = it.next()?;
    for d in it {
        if d.meta.populations == first.meta.populations {
            first.trials.extend(d.trials);
        }
    }
    Some(first)
}

/// The scaling features of one seed's merged recording (as in the study's fingerprints):
/// `scaling_index` (geometry index per timing population, per-unit where the geometry
/// cannot tell and the units correspond — timing models of one seed) and `dyn_scaling`
/// (the geometry alone), where defined.
fn seed_scaling(ds: &ActivityDataset) -> Vec<(&'static str, f64)> {
    if recorded_tds(ds).len() < 2 {
        return Vec::new();
    }
    let opts = SummaryOptions {
        units_correspond: MECHANISMS.contains(&ds.meta.model.as_str()),
        ..SummaryOptions::default()
    };
    let summaries: Vec<_> = ds
        .meta
        .populations
        .iter()
        .filter(|p| !READOUTS.contains(&p.name.as_str()))
        .filter_map(|p| neural_summary(ds, Some(&p.name), &opts).ok())
        .collect();
    let view = chronocooked_analysis::mechanisms::PopulationView::all(&summaries);
    [
        (
            "scaling_index",
            chronocooked_analysis::mechanisms::scaling_index_of_summary(&view),
        ),
        (
            "dyn_scaling",
            chronocooked_analysis::mechanisms::geometry_index_of_summary(&view),
        ),
    ]
    .into_iter()
    .filter_map(|(f, v)| v.map(|v| (f, v)))
    .collect()
}

/// `(model, seed, feature, value)` of one seed's fixed-interval recordings.
pub(super) type SeedScaling = (String, u64, &'static str, f64);

/// What a card shows, computed from one seed's recordings.
pub(super) struct Card {
    pub(super) model: String,
    pub(super) population: String,
    pub(super) seed: u64,
    /// Classifications per recorded TD, shortest first.
    pub(super) by_td: Vec<TdClassification>,
    pub(super) scaling_index: Option<f64>,
}

/// `[window, varying units]` trial average of a classification's varying units.
pub(super) fn varying_average(c: &TdClassification) -> Vec<f64> {
    c.average_all
        .chunks_exact(c.size.max(1))
        .flat_map(|row| c.varying.iter().map(move |&j| row[j]))
        .collect()
}

/// Up to three example units: one per category in the order time field, ramp,
/// oscillating, mixed, beyond the window, untuned, then the next units of those categories.
pub(super) fn examples(tests: &[UnitTests]) -> Vec<&UnitTests> {
    let order = [
        Category::TimeField,
        Category::Ramp,
        Category::Oscillating,
        Category::Mixed,
        Category::BeyondWindow,
        Category::Untuned,
    ];
    let mut picked: Vec<&UnitTests> = order
        .iter()
        .filter_map(|c| tests.iter().find(|u| u.category == *c))
        .take(3)
        .collect();
    for u in tests {
        if picked.len() >= 3 {
            break;
        }
        if !picked.iter().any(|p| p.unit == u.unit) {
            picked.push(u);
        }
    }
    picked
}

/// Mean normalised single-trial spectrum of the varying units: `(cycles/step, power)`.
pub(super) fn population_spectrum(c: &TdClassification) -> Vec<(f64, f64)> {
    let cube = &c.cube;
    let mut sum: Vec<f64> = Vec::new();
    let mut freqs: Vec<f64> = Vec::new();
    let mut count = 0.0;
    for i in 0..cube.units() {
        for k in 0..cube.trials() {
            let x: Vec<f64> = (0..cube.time())
                .map(|t| cube.at(k, t, i))
                .take_while(|v| v.is_finite())
                .collect();
            if x.len() < cube.time().max(4) {
                continue;
            }
            let s = welch(&x, x.len(), 1.0);
            let total: f64 = s.power.iter().skip(1).sum();
            if total.is_nan() || total <= 0.0 {
                continue;
            }
            if sum.is_empty() {
                sum = vec![0.0; s.power.len()];
                freqs = s.freqs.clone();
            }
            for (acc, p) in sum.iter_mut().zip(&s.power).skip(1) {
                *acc += p / total;
            }
            count += 1.0;
        }
    }
    freqs
        .into_iter()
        .zip(sum)
        .skip(1)
        .map(|(f, p)| (f, p / count))
        .collect()
}

/// The card of a row: from the first seed whose fixed-interval recordings have the timing
/// population; the scaling index of every seed.
pub(super) fn card_and_scaling(
    row: &Row,
    runs: &[RunInfo],
) -> Result<(Option<Card>, Vec<SeedScaling>), String> {
    let mut by_seed: BTreeMap<u64, Vec<ActivityDataset>> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.task == "FixedInterval-v0") {
        if let Some(ds) = load_activity(&r.eval)? {
            by_seed.entry(r.seed).or_default().push(ds);
        }
    }
    let mut card = None;
    let mut scaling = Vec::new();
    for (seed, datasets) in by_seed {
        let Some(ds) = merged(datasets) else { continue };
        let features = seed_scaling(&ds);
        let index = features
            .iter()
            .find(|(f, _)| *f == "scaling_index")
            .map(|(_, v)| *v);
        for (f, v) in features {
            scaling.push((row.model.clone(), seed, f, v));
        }
        if card.is_some() {
            continue;
        }
        let Some(pop) = timing_population(&ds) else {
            continue;
        };
        let opts = SummaryOptions::default();
        let by_td: Vec<TdClassification> = recorded_tds(&ds)
            .into_iter()
            .filter_map(|td| classify_td(&ds, Some(&pop), td, &opts).ok())
            .filter(|c| !c.varying.is_empty())
            .collect();
        if !by_td.is_empty() {
            card = Some(Card {
                model: row.model.clone(),
                population: pop,
                seed,
                by_td,
                scaling_index: index,
            });
        }
    }
    Ok((card, scaling))
}
