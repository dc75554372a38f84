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
//! Features are standardised by their SD over every signature, a model's fingerprint is the
//! mean of its seeds' signatures, and the distance between two fingerprints is the weighted
//! root mean square of their standardised differences over the features both have. A
//! feature's weight is how well it tells the mechanisms apart, `F / (1 + F)` with `F`
//! Fisher's ratio of the variance between the mechanisms' means to the pooled variance of
//! their seeds: a feature every mechanism shares (the Weber fraction, ≈ 0.12 for all)
//! hardly counts, so an agent's Weber fraction does not decide which mechanism it is
//! nearest; the unit categories count fully. Each agent's
//! nearest mechanism is bootstrapped over seeds (seeds of every model resampled with
//! replacement): the fraction of resamples in which each mechanism is the nearest.

mod identify;
mod read;
mod tables;

pub use identify::{AgentVerdict, HeldOut, Identification, identify};
pub use read::{JobFiles, assemble, scaling_index_of_summary, signatures};
pub use tables::{Written, fingerprint_figure, write_tables};

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The features of a signature, in table order.
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

/// Populations that read the model's timing out rather than keep time (excluded from the
/// unit categories): the learner's value and reward-prediction error, the learned drift.
pub(crate) const READOUTS: [&str; 3] = ["value", "rpe", "drift"];

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
    FEATURES
        .iter()
        .filter_map(|&f| {
            let values = sigs.clone().filter_map(|s| s.features.get(f).copied());
            pick(crate::stats::Spread::of(values)).map(|v| (f, v))
        })
        .collect()
}

/// SD of each feature over `sigs` (features with fewer than 2 values or no spread left out).
pub(crate) fn feature_sds<'a>(
    sigs: impl Iterator<Item = &'a Signature> + Clone,
) -> BTreeMap<&'static str, f64> {
    per_feature(sigs, |s| (s.sd.is_finite() && s.sd > 0.0).then_some(s.sd))
}

/// Mean of each feature over `sigs` (features no signature has are absent).
pub(crate) fn mean_features(sigs: &[&Signature]) -> BTreeMap<&'static str, f64> {
    per_feature(sigs.iter().copied(), |s| (s.n > 0).then_some(s.mean))
}

/// How much each feature tells the mechanisms apart: with `F` the variance of the
/// mechanisms' means over the pooled variance of their seeds (Fisher's discriminant
/// ratio), the weight `F / (1 + F)` — near 1 for a feature the mechanisms differ in far
/// beyond their seed-to-seed spread (the unit categories), near 0 for one they share (the
/// Weber fraction: every mechanism ≈ 0.12). Features seen in fewer than two mechanisms are
/// left out.
fn feature_weights(mechs: &[&Signature]) -> BTreeMap<&'static str, f64> {
    let mut by_model: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in mechs {
        by_model.entry(s.model.as_str()).or_default().push(s);
    }
    let mut out = BTreeMap::new();
    for f in FEATURES {
        let groups: Vec<Vec<f64>> = by_model
            .values()
            .map(|v| {
                v.iter()
                    .filter_map(|s| s.features.get(f).copied())
                    .collect::<Vec<f64>>()
            })
            .filter(|v| !v.is_empty())
            .collect();
        if groups.len() < 2 {
            continue;
        }
        let means: Vec<f64> = groups
            .iter()
            .map(|g| g.iter().sum::<f64>() / g.len() as f64)
            .collect();
        let between = crate::stats::Spread::of(means.iter().copied()).sd.powi(2);
        let (mut ss, mut dof) = (0.0, 0usize);
        for (g, m) in groups.iter().zip(&means) {
            ss += g.iter().map(|x| (x - m).powi(2)).sum::<f64>();
            dof += g.len() - 1;
        }
        let within = if dof > 0 { ss / dof as f64 } else { f64::NAN };
        let weight = if between.is_nan() || between <= 0.0 {
            0.0
        } else if within.is_nan() || within <= 0.0 {
            1.0
        } else {
            let ratio = between / within;
            ratio / (1.0 + ratio)
        };
        out.insert(f, weight);
    }
    out
}

/// The scale of a distance: each feature's SD and its weight.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Scale {
    sds: BTreeMap<&'static str, f64>,
    weights: BTreeMap<&'static str, f64>,
}

impl Scale {
    /// SDs over `sigs`, weights from the signatures of the `mechanisms` among them.
    pub(crate) fn of(sigs: &[&Signature], mechanisms: &[&str]) -> Self {
        let mechs: Vec<&Signature> = sigs
            .iter()
            .copied()
            .filter(|s| mechanisms.contains(&s.model.as_str()))
            .collect();
        Scale {
            sds: feature_sds(sigs.iter().copied()),
            weights: feature_weights(&mechs),
        }
    }
}

/// The weighted RMS of the standardised differences over the features both fingerprints
/// have: `√(Σ w_f z_f² / Σ w_f)`, `z_f` the difference in SDs of feature `f` (NaN when they
/// share no weighted feature).
pub(crate) fn distance(
    a: &BTreeMap<&'static str, f64>,
    b: &BTreeMap<&'static str, f64>,
    scale: &Scale,
) -> f64 {
    let (mut sum, mut weight) = (0.0, 0.0);
    for (f, sd) in &scale.sds {
        let (Some(x), Some(y), Some(w)) = (a.get(f), b.get(f), scale.weights.get(f)) else {
            continue;
        };
        sum += w * ((x - y) / sd).powi(2);
        weight += w;
    }
    if weight > 0.0 {
        (sum / weight).sqrt()
    } else {
        f64::NAN
    }
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

/// Compares every model not in `mechanisms` with every model in it: distances of the
/// seed-mean fingerprints and the bootstrap support of the nearest (`resamples` resamples
/// of every model's seeds, seeded by `seed`).
pub fn compare(
    sigs: &[Signature],
    mechanisms: &[&str],
    resamples: usize,
    seed: u64,
) -> Vec<Comparison> {
    let scale = Scale::of(&sigs.iter().collect::<Vec<_>>(), mechanisms);
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
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut wins: BTreeMap<(&str, &str), usize> = BTreeMap::new();
    for _ in 0..resamples {
        let mut draw = |m: &str| {
            let s = &by_model[m];
            let pick: Vec<&Signature> = (0..s.len())
                .map(|_| s[rng.random_range(0..s.len())])
                .collect();
            mean_features(&pick)
        };
        let mech_means: Vec<(&str, BTreeMap<&str, f64>)> =
            mechs.iter().map(|&m| (m, draw(m))).collect();
        for &a in &agents {
            let am = draw(a);
            let nearest = mech_means
                .iter()
                .map(|(m, mm)| (*m, distance(&am, mm, &scale)))
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

    /// A signature of `model`'s seed `seed` with features `f` (shared with `identify`'s tests).
    pub(super) fn sig(model: &str, seed: u64, f: &[(&str, f64)]) -> Signature {
        Signature {
            model: model.into(),
            seed,
            features: f.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        }
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
        let c = compare(&s, &["ramp", "cells"], 200, 1);
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
    fn distance_is_the_weighted_rms_of_standardised_differences_over_shared_features() {
        let a: BTreeMap<&str, f64> = [("wf", 0.1), ("foc_cv", 0.2)].into_iter().collect();
        let b: BTreeMap<&str, f64> = [("wf", 0.3), ("foc_cv", 0.1)].into_iter().collect();
        let scale = Scale {
            sds: [("wf", 0.1), ("foc_cv", 0.05)].into_iter().collect(),
            weights: [("wf", 0.75), ("foc_cv", 0.25)].into_iter().collect(),
        };
        // z = 2 (wf) and 2 (foc_cv): √((0.75·4 + 0.25·4) / 1) = 2.
        assert!((distance(&a, &b, &scale) - 2.0).abs() < 1e-12);
        // Only `wf` shared: |0.1 − 0.3| / 0.1 = 2 whatever its weight.
        let c: BTreeMap<&str, f64> = [("wf", 0.3)].into_iter().collect();
        assert!((distance(&a, &c, &scale) - 2.0).abs() < 1e-12);
        // z = 4 on a weight-0.25 feature, 0 on a weight-0.75 one: √(0.25·16) = 2.
        let d: BTreeMap<&str, f64> = [("wf", 0.1), ("foc_cv", 0.0)].into_iter().collect();
        assert!((distance(&a, &d, &scale) - 2.0).abs() < 1e-12);
        let none: BTreeMap<&str, f64> = BTreeMap::new();
        assert!(distance(&a, &none, &scale).is_nan());
    }

    /// Fisher weights by hand: two mechanisms, two seeds each. Feature `wf`: means 0.1 and
    /// 0.3 (between variance 0.02), seeds ±0.01 around them (within variance 0.0002):
    /// F = 100, weight 100/101. Feature `foc_cv`: means 0.2 and 0.2: weight 0. Feature
    /// `pi_cv`: 0.1/0.1 and 0.3/0.3 (no spread within): weight 1.
    #[test]
    fn features_are_weighted_by_how_far_apart_the_mechanisms_are_for_their_spread() {
        let s = [
            sig("ddm", 0, &[("wf", 0.09), ("foc_cv", 0.1), ("pi_cv", 0.1)]),
            sig("ddm", 1, &[("wf", 0.11), ("foc_cv", 0.3), ("pi_cv", 0.1)]),
            sig("sbf", 0, &[("wf", 0.29), ("foc_cv", 0.3), ("pi_cv", 0.3)]),
            sig("sbf", 1, &[("wf", 0.31), ("foc_cv", 0.1), ("pi_cv", 0.3)]),
        ];
        let w = feature_weights(&s.iter().collect::<Vec<_>>());
        assert!((w["wf"] - 100.0 / 101.0).abs() < 1e-9, "{w:?}");
        assert_eq!(w["foc_cv"], 0.0);
        assert_eq!(w["pi_cv"], 1.0);
        assert!(!w.contains_key("frac_ramp"));
    }
}
