//! Mechanism fingerprints: which timing mechanism does a trained agent resemble?
//!
//! Every finished job of a study's compact results (`results/<study>/jobs/<task>/<row>/seed<N>/`
//! with `job.json`, `metrics.json` and, for recorded jobs, `activity.summary.json`) gives
//! behavioural and neural signatures; per model and seed they form a [`Signature`] — a
//! vector of named features:
//!
//! * `foc_cv` — CV of the first oven check on fixed interval (mean over the trained TDs);
//! * `foc_cv_trend` — `ln(CV at the longest TD / CV at the shortest)`: 0 for scalar timing;
//! * `foc_over_td` — mean first check / TD;
//! * `pi_peak_over_td`, `pi_cv` — peak-interval response peak / TD and spread / peak (the
//!   2 × TD probe's Gaussian fit);
//! * `wf`, `bp_over_gm` — bisection Weber fraction and bisection point / geometric mean;
//! * `frac_ramp`, `frac_time_field`, `frac_oscillating` — the unit categories of the
//!   model's own timing populations on probe trials (value and RPE read-outs excluded),
//!   pooled over its recorded populations, from its fixed-interval jobs only (recorded on
//!   peak-interval probe trials); `decode_error_over_td` — the cross-validated ridge
//!   decoding error of elapsed time over TD;
//! * `scaling_index` — how the activity stretches between the shortest and the longest
//!   TD (1: with the interval, 0: a fixed clock), from the model × seed's fixed-interval
//!   runs recorded together (`<results>/scaling/<row>/seed<N>/`, written by
//!   `mechanisms --scaling-from SWEEP_OUT`): per timing population the geometry scaling
//!   index (no unit correspondence needed) or, where the geometry cannot tell (a straight
//!   ramp) and the units correspond, `ln(median unit factor) / ln(TD ratio)`; the
//!   unit-weighted mean over the populations.
//!
//! A model's fingerprint is the mean of its seeds' signatures. The distance between two
//! fingerprints is the root mean square, over the features both have, of their differences
//! in units of each feature's pooled within-mechanism SD — how far apart a feature's values
//! are for the seed-to-seed spread of one mechanism (a nearest-centroid classifier with a
//! diagonal pooled covariance: diagonal linear discriminant analysis, Dudoit, Fridlyand &
//! Speed 2002). A feature every mechanism shares (the Weber fraction, ≈ 0.12 for all) moves
//! every mechanism's distance alike and so does not decide the nearest; one they differ in
//! far beyond their seed spread (the unit categories) decides it. A distance of 1 is one
//! seed-to-seed SD on every feature. Each agent's
//! nearest mechanism is bootstrapped over seeds (seeds of every model resampled with
//! replacement): the fraction of resamples in which each mechanism is the nearest.

mod identify;
mod read;

pub use identify::{
    AgentVerdict, HeldOut, Identification, LIMIT_COVERAGE, SeedVerdict, identify, seed_verdicts,
};
pub use read::{
    CategoriesView, JobFiles, PopulationView, ScalingView, assemble, geometry_index_of_summary,
    scaling_index_of_summary, signatures,
};

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The features of the *unit view*, in table order: the behaviour, the unit categories,
/// the scaling index and the decoding error. The unit categories are properties of single
/// units and change when the units are mixed (another basis of the same dynamics); the
/// scaling index falls back on per-unit factors and the ridge decoder standardises each
/// unit. This view is basis-dependent.
pub const FEATURES: [&str; 12] = [
    "foc_cv",
    "foc_cv_trend",
    "foc_over_td",
    "pi_peak_over_td",
    "pi_cv",
    "wf",
    "bp_over_gm",
    "frac_ramp",
    "frac_time_field",
    "frac_oscillating",
    "scaling_index",
    "decode_error_over_td",
];

/// The basis-free neural features of the *dynamics view*: the population trajectory's
/// signature ([`crate::neural::dynamics`], `dyn_<feature>`: mean over the model's timing
/// populations, weighted by their size, and over its fixed-interval jobs).
pub const DYNAMICS_NEURAL: [&str; 7] = [
    "dyn_dimension",
    "dyn_speed_trend",
    "dyn_turning",
    "dyn_straightness",
    "dyn_continuation",
    "dyn_spectral_radius",
    "dyn_rotation",
];

/// The features of the *dynamics view*, in table order: the behaviour and the basis-free
/// neural features. Every one is the same for any orthogonal mixing of a population's
/// units (tests mix each feature's input).
///
/// `dyn_scaling` (the geometry scaling index, basis-free too) is recorded beside them but
/// not compared: every mechanism whose geometry defines it is a fixed clock (index 0 within
/// the 1.01ᵏ grid of the search), it is undefined for drift-diffusion and Laplace (a
/// straight or a one-signed decaying path), so it has no seed spread to scale a distance
/// by — an agent with any other index would be hundreds of "seed SDs" from three mechanisms
/// on that feature alone and, as a missing feature is left out, nearer the two that lack
/// it (measured: `results/mechanisms-reference/dsa-crosscheck.md`).
pub const DYNAMICS_FEATURES: [&str; 14] = [
    "foc_cv",
    "foc_cv_trend",
    "foc_over_td",
    "pi_peak_over_td",
    "pi_cv",
    "wf",
    "bp_over_gm",
    "dyn_dimension",
    "dyn_speed_trend",
    "dyn_turning",
    "dyn_straightness",
    "dyn_continuation",
    "dyn_spectral_radius",
    "dyn_rotation",
];

/// Every feature a signature may hold (unit view, then the dynamics view's own), the
/// columns of `signatures.csv`.
pub const ALL_FEATURES: [&str; 20] = [
    "foc_cv",
    "foc_cv_trend",
    "foc_over_td",
    "pi_peak_over_td",
    "pi_cv",
    "wf",
    "bp_over_gm",
    "frac_ramp",
    "frac_time_field",
    "frac_oscillating",
    "scaling_index",
    "decode_error_over_td",
    "dyn_dimension",
    "dyn_speed_trend",
    "dyn_turning",
    "dyn_straightness",
    "dyn_continuation",
    "dyn_spectral_radius",
    "dyn_rotation",
    "dyn_scaling",
];

/// Which features a comparison reads: the two views of a fingerprint, each with its own
/// scale, distances, identification limits and verdicts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum View {
    /// Behaviour and single-unit categories ([`FEATURES`]): basis-dependent.
    Units,
    /// Behaviour and the population's dynamics ([`DYNAMICS_FEATURES`]): basis-free.
    Dynamics,
}

impl View {
    /// Both views, in display order.
    pub const ALL: [View; 2] = [View::Units, View::Dynamics];

    /// The view's features, in table order.
    pub fn features(self) -> &'static [&'static str] {
        match self {
            View::Units => &FEATURES,
            View::Dynamics => &DYNAMICS_FEATURES,
        }
    }

    /// Short key (`units`, `dynamics`): file and JSON names.
    pub fn key(self) -> &'static str {
        match self {
            View::Units => "units",
            View::Dynamics => "dynamics",
        }
    }

    /// The view's own features: those the other view does not read (single-unit
    /// categories and their scaling and decoding; the trajectory's `dyn_*`).
    pub fn own_features(self) -> Vec<&'static str> {
        let other = match self {
            View::Units => View::Dynamics,
            View::Dynamics => View::Units,
        };
        self.features()
            .iter()
            .copied()
            .filter(|f| !other.features().contains(f))
            .collect()
    }

    /// Whether any of `sigs` holds one of the view's own features: a study recorded before
    /// the dynamics view has none of its features, and a comparison in that view would be
    /// one of behaviour alone.
    pub fn recorded_in(self, sigs: &[Signature]) -> bool {
        let own = self.own_features();
        sigs.iter()
            .any(|s| own.iter().any(|f| s.features.contains_key(*f)))
    }

    /// Heading with what the view depends on.
    pub fn title(self) -> &'static str {
        match self {
            View::Units => "Unit view (basis-dependent: single-unit categories)",
            View::Dynamics => "Dynamics view (basis-free: population trajectory)",
        }
    }
}

/// Populations that read the model's timing out rather than keep time (excluded from the
/// unit categories): the learner's value and reward-prediction error, the learned drift.
pub const READOUTS: [&str; 3] = ["value", "rpe", "drift"];

/// Why the fingerprints could not be made.
#[derive(Debug, thiserror::Error)]
pub enum MechanismError {
    /// A file could not be read or parsed.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
    /// No finished jobs under the results folder.
    #[error("no finished jobs (job.json + metrics.json) under {0}")]
    Empty(PathBuf),
}

impl MechanismError {
    /// A [`MechanismError::File`] error about `path`.
    pub fn at(path: &std::path::Path, message: impl ToString) -> Self {
        MechanismError::File {
            path: path.to_path_buf(),
            message: message.to_string(),
        }
    }
}

/// One model's signature from one training seed: feature name → value (missing = not
/// measured for that model, e.g. no bisection job).
#[derive(Debug, Clone, PartialEq)]
pub struct Signature {
    /// Model (the job's `row`, or its `model`).
    pub model: String,
    /// Training seed.
    pub seed: u64,
    /// Feature values.
    pub features: BTreeMap<String, f64>,
}

/// One statistic of every feature over `sigs` (`pick` reads it from the feature's spread;
/// `None` leaves the feature out).
fn per_feature<'a>(
    sigs: impl Iterator<Item = &'a Signature> + Clone,
    pick: impl Fn(crate::stats::Spread) -> Option<f64>,
) -> BTreeMap<&'static str, f64> {
    ALL_FEATURES
        .iter()
        .filter_map(|&f| {
            let values = sigs.clone().filter_map(|s| s.features.get(f).copied());
            pick(crate::stats::Spread::of(values)).map(|v| (f, v))
        })
        .collect()
}

/// SD of each feature over `sigs` (features with fewer than 2 values or no spread left out).
pub fn feature_sds<'a>(
    sigs: impl Iterator<Item = &'a Signature> + Clone,
) -> BTreeMap<&'static str, f64> {
    per_feature(sigs, |s| (s.sd.is_finite() && s.sd > 0.0).then_some(s.sd))
}

/// Mean of each feature over `sigs` (features no signature has are absent).
pub fn mean_features(sigs: &[&Signature]) -> BTreeMap<&'static str, f64> {
    per_feature(sigs.iter().copied(), |s| (s.n > 0).then_some(s.mean))
}

/// Floor of a feature's scale as a share of its SD over every mechanism signature. It only
/// matters for a feature that no mechanism varies from seed to seed (a category fraction
/// fixed by construction), whose pooled within-mechanism SD is 0: without it, any deviation
/// would be infinitely far. Leave-one-seed-out identification is the same for floors from
/// 0.0001 to 0.2 on both committed studies (40/40 and 20/20).
const SCALE_FLOOR: f64 = 0.05;

/// The pooled within-mechanism SD of each feature over the mechanism signatures `mechs`
/// (the SD of the seeds around their own mechanism's mean, pooled over the mechanisms),
/// floored at [`SCALE_FLOOR`] × the feature's SD over all of them. Features no two
/// signatures have, or with no spread at all, are left out.
fn within_sds(mechs: &[&Signature]) -> BTreeMap<&'static str, f64> {
    let mut by_model: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in mechs {
        by_model.entry(s.model.as_str()).or_default().push(s);
    }
    let total = feature_sds(mechs.iter().copied());
    let mut out = BTreeMap::new();
    for (f, total_sd) in total {
        let (mut ss, mut dof) = (0.0, 0usize);
        for seeds in by_model.values() {
            let xs: Vec<f64> = seeds
                .iter()
                .filter_map(|s| s.features.get(f).copied())
                .collect();
            if xs.len() >= 2 {
                let m = xs.iter().sum::<f64>() / xs.len() as f64;
                ss += xs.iter().map(|x| (x - m).powi(2)).sum::<f64>();
                dof += xs.len() - 1;
            }
        }
        let within = if dof > 0 {
            (ss / dof as f64).sqrt()
        } else {
            0.0
        };
        out.insert(f, within.max(SCALE_FLOOR * total_sd));
    }
    out
}

/// The scale of a distance in one view: the pooled within-mechanism SD of each of the
/// view's features.
#[derive(Debug, Clone, PartialEq)]
pub struct Scale {
    sds: BTreeMap<&'static str, f64>,
}

impl Scale {
    /// The pooled within-mechanism SD of each of the view's features (the distance's units).
    pub fn sds(&self) -> &BTreeMap<&'static str, f64> {
        &self.sds
    }

    /// The within-mechanism SDs of `view`'s features over the signatures of the
    /// `mechanisms` among `sigs`.
    pub fn of(sigs: &[&Signature], mechanisms: &[&str], view: View) -> Self {
        let mechs: Vec<&Signature> = sigs
            .iter()
            .copied()
            .filter(|s| mechanisms.contains(&s.model.as_str()))
            .collect();
        let mut sds = within_sds(&mechs);
        sds.retain(|f, _| view.features().contains(f));
        Scale { sds }
    }
}

/// The RMS of the standardised differences over the features both fingerprints have:
/// `√(Σ z_f² / n)`, `z_f` the difference in feature `f`'s within-mechanism SDs (NaN when
/// they share no feature of the scale).
pub(crate) fn distance(
    a: &BTreeMap<&'static str, f64>,
    b: &BTreeMap<&'static str, f64>,
    scale: &Scale,
) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for (f, sd) in &scale.sds {
        let (Some(x), Some(y)) = (a.get(f), b.get(f)) else {
            continue;
        };
        sum += ((x - y) / sd).powi(2);
        n += 1;
    }
    if n > 0 {
        (sum / n as f64).sqrt()
    } else {
        f64::NAN
    }
}

/// The distance between two signatures in `view` (any two recorded agents, or seeds of
/// one), on the calibrated scale of the mechanisms: each feature in units of its pooled
/// within-mechanism SD over the [`MECHANISMS`] among `reference` — the scale of the
/// identification limits, so that a distance below a mechanism's limit is as near as two
/// seeds of one mechanism lie. NaN when they share no feature of the view.
pub fn signature_distance(
    a: &Signature,
    b: &Signature,
    reference: &[Signature],
    view: View,
) -> f64 {
    let refs: Vec<&Signature> = reference.iter().collect();
    let scale = Scale::of(&refs, &MECHANISMS, view);
    distance(&mean_features(&[a]), &mean_features(&[b]), &scale)
}

/// One pair of signatures and their distance (see [`signature_distance`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PairDistance {
    /// First signature: model and seed.
    pub a: (String, u64),
    /// Second signature.
    pub b: (String, u64),
    /// Their distance.
    pub distance: f64,
}

/// The distance of every pair of `sigs` (model × seed) in `view`, on the scale of the
/// mechanisms among `sigs` (see [`signature_distance`]).
pub fn pairwise(sigs: &[Signature], view: View) -> Vec<PairDistance> {
    let refs: Vec<&Signature> = sigs.iter().collect();
    let scale = Scale::of(&refs, &MECHANISMS, view);
    let means: Vec<BTreeMap<&'static str, f64>> =
        sigs.iter().map(|s| mean_features(&[s])).collect();
    let mut out = Vec::new();
    for i in 0..sigs.len() {
        for j in i + 1..sigs.len() {
            out.push(PairDistance {
                a: (sigs[i].model.clone(), sigs[i].seed),
                b: (sigs[j].model.clone(), sigs[j].seed),
                distance: distance(&means[i], &means[j], &scale),
            });
        }
    }
    out
}

/// One agent compared with one mechanism.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// The agent (a model that is not a mechanism).
    pub agent: String,
    /// The mechanism.
    pub mechanism: String,
    /// Distance of the seed-mean fingerprints (standardised RMS).
    pub distance: f64,
    /// Fraction of bootstrap resamples (over seeds) in which this mechanism is the nearest.
    pub nearest_fraction: f64,
    /// Seeds of the agent and of the mechanism.
    pub seeds: (usize, usize),
}

/// Compares every model not in `mechanisms` with every model in it in `view`: distances
/// of the seed-mean fingerprints and the bootstrap support of the nearest (`resamples`
/// resamples of every model's seeds, seeded by `seed`).
pub fn compare(
    sigs: &[Signature],
    mechanisms: &[&str],
    resamples: usize,
    seed: u64,
    view: View,
) -> Vec<Comparison> {
    let scale = Scale::of(&sigs.iter().collect::<Vec<_>>(), mechanisms, view);
    let mut by_model: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in sigs {
        by_model.entry(s.model.as_str()).or_default().push(s);
    }
    let mechs: Vec<&str> = by_model
        .keys()
        .copied()
        .filter(|m| mechanisms.contains(m))
        .collect();
    let agents: Vec<&str> = by_model
        .keys()
        .copied()
        .filter(|m| !mechanisms.contains(m))
        .collect();
    let mean_of = |m: &str| mean_features(&by_model[m]);
    // The bootstrap on dense rows of the scale's features (NaN = missing): the same draws
    // and means as `mean_features` and `distance`, without a map per resample.
    let features: Vec<&'static str> = scale.sds.keys().copied().collect();
    let sds: Vec<f64> = features.iter().map(|f| scale.sds[f]).collect();
    let dense: BTreeMap<&str, Vec<Vec<f64>>> = by_model
        .iter()
        .map(|(m, seeds)| {
            let rows = seeds
                .iter()
                .map(|s| {
                    features
                        .iter()
                        .map(|f| s.features.get(*f).copied().unwrap_or(f64::NAN))
                        .collect()
                })
                .collect();
            (*m, rows)
        })
        .collect();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut wins: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    let (mut sum, mut count) = (vec![0.0; features.len()], vec![0usize; features.len()]);
    for _ in 0..resamples {
        let mut draw = |m: &str| {
            let rows = &dense[m];
            sum.iter_mut().for_each(|x| *x = 0.0);
            count.iter_mut().for_each(|x| *x = 0);
            for _ in 0..rows.len() {
                let row = &rows[rng.random_range(0..rows.len())];
                for (k, v) in row.iter().enumerate() {
                    if v.is_finite() {
                        sum[k] += v;
                        count[k] += 1;
                    }
                }
            }
            sum.iter()
                .zip(&count)
                .map(|(s, &n)| if n > 0 { s / n as f64 } else { f64::NAN })
                .collect::<Vec<f64>>()
        };
        let mech_means: Vec<(&str, Vec<f64>)> = mechs.iter().map(|&m| (m, draw(m))).collect();
        for &a in &agents {
            let am = draw(a);
            let nearest = mech_means
                .iter()
                .map(|(m, mm)| (*m, dense_distance(&am, mm, &sds)))
                .filter(|(_, d)| d.is_finite())
                .min_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((m, _)) = nearest {
                *wins.entry((a, m)).or_default() += 1;
            }
        }
    }
    let mut out = Vec::new();
    for &a in &agents {
        let am = mean_of(a);
        for &m in &mechs {
            out.push(Comparison {
                agent: a.to_string(),
                mechanism: m.to_string(),
                distance: distance(&am, &mean_of(m), &scale),
                nearest_fraction: wins.get(&(a, m)).copied().unwrap_or(0) as f64
                    / resamples.max(1) as f64,
                seeds: (by_model[a].len(), by_model[m].len()),
            });
        }
    }
    out
}

/// [`distance`] on dense rows: the RMS of `(a − b) / sd` over the features both have (NaN
/// when none).
fn dense_distance(a: &[f64], b: &[f64], sds: &[f64]) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for ((x, y), sd) in a.iter().zip(b).zip(sds) {
        if x.is_finite() && y.is_finite() {
            sum += ((x - y) / sd).powi(2);
            n += 1;
        }
    }
    if n > 0 {
        (sum / n as f64).sqrt()
    } else {
        f64::NAN
    }
}

/// The nearest mechanism among one agent's comparisons as `mechanism (bootstrap share)`,
/// `–` when no distance is defined.
pub fn nearest_label(mine: &[&Comparison]) -> String {
    mine.iter()
        .filter(|c| c.distance.is_finite())
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .map_or("–".into(), |c| {
            format!("{} ({:.2})", c.mechanism, c.nearest_fraction)
        })
}

/// The mechanism models of the lab's zoo, in table order.
pub const MECHANISMS: [&str; 5] = [
    "ddm",
    "sbf",
    "timecells-csc",
    "timecells-ms",
    "timecells-laplace",
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairwise distances by hand: two mechanisms (two seeds each) give the scale (pooled
    /// within SD of `dyn_turning` √((4·0.1²)/2) = 0.1414, above the floor 0.05 × 0.589);
    /// the unit-view feature `frac_ramp` is not read by the dynamics view. Agents a and b
    /// differ by 0.1 in turning: 0.707 seed SDs.
    #[test]
    fn pairwise_distances_are_on_the_mechanisms_scale_of_the_view() {
        let s = vec![
            sig("ddm", 0, &[("dyn_turning", 0.9)]),
            sig("ddm", 1, &[("dyn_turning", 1.1)]),
            sig("sbf", 0, &[("dyn_turning", -0.1)]),
            sig("sbf", 1, &[("dyn_turning", 0.1)]),
            sig("a", 0, &[("dyn_turning", 0.5), ("frac_ramp", 0.0)]),
            sig("b", 0, &[("dyn_turning", 0.6), ("frac_ramp", 1.0)]),
        ];
        let p = pairwise(&s, View::Dynamics);
        assert_eq!(p.len(), 15);
        let ab = p.iter().find(|p| p.a.0 == "a" && p.b.0 == "b").unwrap();
        assert!((ab.distance - 0.1 / 0.02f64.sqrt()).abs() < 1e-9, "{ab:?}");
        let d = signature_distance(&s[4], &s[5], &s, View::Dynamics);
        assert!((d - ab.distance).abs() < 1e-12);
        // The unit view has no shared feature with a scale here (frac_ramp has no
        // mechanism spread): undefined.
        assert!(signature_distance(&s[4], &s[5], &s, View::Units).is_nan());
    }

    /// A signature of `model`'s seed `seed` with features `f` (shared with `identify`'s tests).
    pub(super) fn sig(model: &str, seed: u64, f: &[(&str, f64)]) -> Signature {
        Signature {
            model: model.into(),
            seed,
            features: f.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        }
    }

    /// A view is recorded when some signature holds one of its own features: behaviour
    /// alone (shared by both views) or `dyn_scaling` (recorded, not compared) does not make
    /// the dynamics view; one `dyn_turning` does.
    #[test]
    fn a_view_is_recorded_only_with_its_own_features() {
        assert_eq!(View::Dynamics.own_features().len(), 7);
        assert!(!View::Units.own_features().contains(&"wf"));
        let old = vec![
            sig("ddm", 0, &[("wf", 0.1), ("frac_ramp", 1.0)]),
            sig("sbf", 0, &[("wf", 0.1), ("dyn_scaling", 0.0)]),
        ];
        assert!(View::Units.recorded_in(&old));
        assert!(!View::Dynamics.recorded_in(&old));
        let mut new = old.clone();
        new.push(sig("ddm", 1, &[("dyn_turning", 0.3)]));
        assert!(View::Dynamics.recorded_in(&new));
        assert!(!View::Units.recorded_in(&[sig("x", 0, &[("wf", 0.1)])]));
    }

    #[test]
    fn an_agent_with_a_mechanisms_signature_is_nearest_to_it() {
        // Two mechanisms far apart in two features; the agent's seeds scatter around the
        // ramp's values: its distance to the ramp is smaller and every resample agrees.
        let mut s = Vec::new();
        for k in 0..4 {
            let e = 0.01 * k as f64;
            s.push(sig("ramp", k, &[("frac_ramp", 1.0 - e), ("wf", 0.1 + e)]));
            s.push(sig("cells", k, &[("frac_ramp", 0.1 + e), ("wf", 0.2 - e)]));
            s.push(sig(
                "agent",
                k,
                &[("frac_ramp", 0.95 - e), ("wf", 0.11 + e)],
            ));
        }
        let c = compare(&s, &["ramp", "cells"], 200, 1, View::Units);
        let get = |m: &str| {
            c.iter()
                .find(|x| x.agent == "agent" && x.mechanism == m)
                .unwrap()
        };
        assert!(get("ramp").distance < get("cells").distance, "{c:?}");
        assert_eq!(get("ramp").nearest_fraction, 1.0);
        assert_eq!(get("cells").nearest_fraction, 0.0);
        assert_eq!(get("ramp").seeds, (4, 4));
    }

    #[test]
    fn distance_is_the_rms_of_standardised_differences_over_shared_features() {
        let a: BTreeMap<&str, f64> = [("wf", 0.1), ("foc_cv", 0.2)].into_iter().collect();
        let b: BTreeMap<&str, f64> = [("wf", 0.3), ("foc_cv", 0.1)].into_iter().collect();
        let scale = Scale {
            sds: [("wf", 0.1), ("foc_cv", 0.025)].into_iter().collect(),
        };
        // z = 2 (wf) and 4 (foc_cv): √((4 + 16) / 2) = √10.
        assert!((distance(&a, &b, &scale) - 10f64.sqrt()).abs() < 1e-12);
        // Only `wf` shared: |0.1 − 0.3| / 0.1 = 2.
        let c: BTreeMap<&str, f64> = [("wf", 0.3)].into_iter().collect();
        assert!((distance(&a, &c, &scale) - 2.0).abs() < 1e-12);
        let none: BTreeMap<&str, f64> = BTreeMap::new();
        assert!(distance(&a, &none, &scale).is_nan());
    }

    /// Within-mechanism SDs by hand: two mechanisms, two seeds each. Feature `wf`: seeds
    /// 0.09/0.11 and 0.29/0.31, each ±0.01 around its mechanism's mean: pooled SD
    /// √((2·0.0001 + 2·0.0001) / 2) = √0.0002. Feature `foc_cv`: 0.1/0.3 twice: √0.02.
    /// Feature `pi_cv`: 0.1/0.1 and 0.3/0.3 (no spread within): the floor, `SCALE_FLOOR` ×
    /// the SD of the four values.
    #[test]
    fn features_are_scaled_by_the_seed_spread_within_a_mechanism() {
        let s = [
            sig("ddm", 0, &[("wf", 0.09), ("foc_cv", 0.1), ("pi_cv", 0.1)]),
            sig("ddm", 1, &[("wf", 0.11), ("foc_cv", 0.3), ("pi_cv", 0.1)]),
            sig("sbf", 0, &[("wf", 0.29), ("foc_cv", 0.3), ("pi_cv", 0.3)]),
            sig("sbf", 1, &[("wf", 0.31), ("foc_cv", 0.1), ("pi_cv", 0.3)]),
        ];
        let sds = within_sds(&s.iter().collect::<Vec<_>>());
        assert!((sds["wf"] - 0.0002f64.sqrt()).abs() < 1e-12, "{sds:?}");
        assert!((sds["foc_cv"] - 0.02f64.sqrt()).abs() < 1e-12, "{sds:?}");
        // SD of (0.1, 0.1, 0.3, 0.3): √(4 · 0.01 / 3).
        let total = (0.04f64 / 3.0).sqrt();
        assert!(
            (sds["pi_cv"] - SCALE_FLOOR * total).abs() < 1e-12,
            "{sds:?}"
        );
        assert!(!sds.contains_key("frac_ramp"));
    }
}
