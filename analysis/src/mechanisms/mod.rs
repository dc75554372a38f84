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
//! mean of its seeds' signatures, and the distance between two fingerprints is the root mean
//! square of their standardised differences over the features both have. Each agent's
//! nearest mechanism is bootstrapped over seeds (seeds of every model resampled with
//! replacement): the fraction of resamples in which each mechanism is the nearest.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

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
const READOUTS: [&str; 3] = ["value", "rpe", "drift"];

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

fn read(path: &Path) -> Result<Value, MechanismError> {
    let text = std::fs::read_to_string(path).map_err(|e| MechanismError::File {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    serde_json::from_str(&text).map_err(|e| MechanismError::File {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

fn num(v: &Value) -> Option<f64> {
    v.as_f64().filter(|x| x.is_finite())
}

/// What one job contributes: `(feature, value)` pairs and the FI TD with its FOC CV.
#[derive(Default)]
struct JobFeatures {
    values: Vec<(&'static str, f64)>,
    fi_cv: Option<(u32, f64)>,
}

/// The features of one job; the neural ones only from fixed-interval (or peak-interval)
/// jobs, whose recordings are peak-interval probe trials with 2 × TD windows (`probe`).
fn job_features(dir: &Path, probe: bool) -> Result<JobFeatures, MechanismError> {
    let metrics = read(&dir.join("metrics.json"))?;
    let mut out = JobFeatures::default();
    if let Some(foc) = metrics["fi"]["foc"].as_array() {
        for f in foc {
            if let (Some(td), Some(mean), Some(cv)) =
                (f["td"].as_u64(), num(&f["mean"]), num(&f["cv"]))
            {
                out.values.push(("foc_cv", cv));
                out.values.push(("foc_over_td", mean / td as f64));
                out.fi_cv = Some((td as u32, cv));
            }
        }
    }
    if let Some(pi) = metrics["pi"].as_array() {
        for p in pi.iter().filter(|p| num(&p["factor"]) == Some(2.0)) {
            let td = p["td"].as_f64().unwrap_or(f64::NAN);
            if let Some(peak) = num(&p["fit"]["peak"]) {
                out.values.push(("pi_peak_over_td", peak / td));
            }
            if let Some(cv) = num(&p["fit"]["cv"]) {
                out.values.push(("pi_cv", cv));
            }
        }
    }
    let b = &metrics["bisection"];
    if let Some(wf) = num(&b["fit"]["wf"]) {
        out.values.push(("wf", wf));
    }
    if let (Some(bp), Some(s), Some(l)) = (num(&b["fit"]["bp"]), num(&b["short"]), num(&b["long"]))
    {
        out.values.push(("bp_over_gm", bp / (s * l).sqrt()));
    }
    let summary = dir.join("activity.summary.json");
    if probe && summary.is_file() {
        let pops = read(&summary)?;
        let (mut counts, mut units) = ([0.0f64; 3], 0.0);
        let mut decode = Vec::new();
        for p in pops.as_array().into_iter().flatten() {
            let name = p["population"].as_str().unwrap_or_default();
            if READOUTS.contains(&name) {
                continue;
            }
            let c = &p["categories"]["counts"];
            for (k, key) in ["ramp", "time_field", "oscillating"].iter().enumerate() {
                counts[k] += c[*key].as_f64().unwrap_or(0.0);
            }
            units += ["ramp", "time_field", "oscillating", "mixed", "untuned"]
                .iter()
                .map(|k| c[*k].as_f64().unwrap_or(0.0))
                .sum::<f64>();
            if let (Some(err), Some(td)) = (num(&p["decode_ridge"]), num(&p["td"])) {
                decode.push(err / td);
            }
        }
        if units > 0.0 {
            out.values.push(("frac_ramp", counts[0] / units));
            out.values.push(("frac_time_field", counts[1] / units));
            out.values.push(("frac_oscillating", counts[2] / units));
        }
        if !decode.is_empty() {
            out.values.push((
                "decode_error_over_td",
                decode.iter().sum::<f64>() / decode.len() as f64,
            ));
        }
    }
    Ok(out)
}

/// The scaling index of one model × seed's joint recording (`activity.summary.json` of
/// `record --summary` over runs at several TDs): per non-read-out population the geometry
/// index, else the per-unit one; weighted by units. `None` when no population has one.
fn scaling_index(summary: &Value) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for p in summary.as_array().into_iter().flatten() {
        let name = p["population"].as_str().unwrap_or_default();
        let s = &p["scaling"];
        if READOUTS.contains(&name) || s.is_null() {
            continue;
        }
        let ratio = num(&s["td_ratio"]).filter(|r| *r > 1.0);
        let index = num(&s["geometry_index"]).or_else(|| {
            let m = num(&s["median"]).filter(|m| *m > 0.0)?;
            Some(m.ln() / ratio?.ln())
        });
        let units = p["units"].as_f64().unwrap_or(0.0);
        if let Some(i) = index
            && units > 0.0
        {
            sum += units * i;
            weight += units;
        }
    }
    (weight > 0.0).then(|| sum / weight)
}

/// `(model, seed, scaling index)` of every joint recording under `<results>/scaling/`.
fn scaling_features(results: &Path) -> Result<Vec<(String, u64, f64)>, MechanismError> {
    let mut out = Vec::new();
    for model_dir in chronocooked_env::fs::real_subdirs(&results.join("scaling")) {
        for dir in chronocooked_env::fs::real_subdirs(&model_dir) {
            let (job, summary) = (dir.join("scaling.json"), dir.join("activity.summary.json"));
            if !job.is_file() || !summary.is_file() {
                continue;
            }
            let j = read(&job)?;
            let (Some(model), Some(seed)) = (j["model"].as_str(), j["seed"].as_u64()) else {
                return Err(MechanismError::File {
                    path: job,
                    message: "fields `model` and `seed` required".into(),
                });
            };
            if let Some(i) = scaling_index(&read(&summary)?) {
                out.push((model.to_string(), seed, i));
            }
        }
    }
    Ok(out)
}

/// Finished job folders (`job.json` + `metrics.json`) under `results` (its `jobs/` folder
/// when there is one), sorted; symbolic links are not followed.
fn job_dirs(results: &Path) -> Vec<PathBuf> {
    let root = if results.join("jobs").is_dir() {
        results.join("jobs")
    } else {
        results.to_path_buf()
    };
    let mut out = Vec::new();
    let mut stack = vec![root];
    while let Some(dir) = stack.pop() {
        if dir.join("job.json").is_file() && dir.join("metrics.json").is_file() {
            out.push(dir);
            continue;
        }
        for sub in chronocooked_env::fs::real_subdirs(&dir) {
            stack.push(sub);
        }
    }
    out.sort();
    out
}

/// The signature of every (model, seed) with a finished job under `results`.
pub fn signatures(results: &Path) -> Result<Vec<Signature>, MechanismError> {
    let dirs = job_dirs(results);
    if dirs.is_empty() {
        return Err(MechanismError::Empty(results.to_path_buf()));
    }
    type Key = (String, u64);
    let mut values: BTreeMap<Key, BTreeMap<&'static str, Vec<f64>>> = BTreeMap::new();
    let mut fi_cvs: BTreeMap<Key, Vec<(u32, f64)>> = BTreeMap::new();
    for dir in dirs {
        let job = read(&dir.join("job.json"))?;
        let model = job["row"]
            .as_str()
            .or(job["model"].as_str())
            .unwrap_or("unknown")
            .to_string();
        let key = (model, job["seed"].as_u64().unwrap_or(0));
        let probe = matches!(
            job["task"].as_str(),
            Some("FixedInterval-v0" | "PeakInterval-v0")
        );
        let f = job_features(&dir, probe)?;
        let slot = values.entry(key.clone()).or_default();
        for (name, v) in f.values {
            slot.entry(name).or_default().push(v);
        }
        if let Some(cv) = f.fi_cv {
            fi_cvs.entry(key).or_default().push(cv);
        }
    }
    for (model, seed, index) in scaling_features(results)? {
        if let Some(slot) = values.get_mut(&(model, seed)) {
            slot.entry("scaling_index").or_default().push(index);
        }
    }
    Ok(values
        .into_iter()
        .map(|(key, vals)| {
            let mut features: BTreeMap<String, f64> = vals
                .into_iter()
                .map(|(k, v)| (k.to_string(), v.iter().sum::<f64>() / v.len() as f64))
                .collect();
            if let Some(cvs) = fi_cvs.get(&key) {
                let short = cvs.iter().min_by_key(|c| c.0);
                let long = cvs.iter().max_by_key(|c| c.0);
                if let (Some(s), Some(l)) = (short, long)
                    && s.0 < l.0
                    && s.1 > 0.0
                    && l.1 > 0.0
                {
                    features.insert("foc_cv_trend".into(), (l.1 / s.1).ln());
                }
            }
            Signature {
                model: key.0,
                seed: key.1,
                features,
            }
        })
        .collect())
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
fn feature_sds(sigs: &[Signature]) -> BTreeMap<&'static str, f64> {
    per_feature(sigs.iter(), |s| {
        (s.sd.is_finite() && s.sd > 0.0).then_some(s.sd)
    })
}

/// Mean of each feature over `sigs` (features no signature has are absent).
fn mean_features(sigs: &[&Signature]) -> BTreeMap<&'static str, f64> {
    per_feature(sigs.iter().copied(), |s| (s.n > 0).then_some(s.mean))
}

/// RMS of the standardised differences over the features both fingerprints have (NaN when
/// they share none).
fn distance(
    a: &BTreeMap<&'static str, f64>,
    b: &BTreeMap<&'static str, f64>,
    sds: &BTreeMap<&'static str, f64>,
) -> f64 {
    let d: Vec<f64> = sds
        .iter()
        .filter_map(|(f, sd)| Some(((a.get(f)? - b.get(f)?) / sd).powi(2)))
        .collect();
    if d.is_empty() {
        f64::NAN
    } else {
        (d.iter().sum::<f64>() / d.len() as f64).sqrt()
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
    let sds = feature_sds(sigs);
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
                .map(|(m, mm)| (*m, distance(&am, mm, &sds)))
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
                distance: distance(&am, &mean_of(m), &sds),
                nearest_fraction: wins.get(&(a, m)).copied().unwrap_or(0) as f64
                    / resamples.max(1) as f64,
                seeds: (by_model[a].len(), by_model[m].len()),
            });
        }
    }
    out
}

/// The mechanism models of the lab's zoo, in table order.
pub const MECHANISMS: [&str; 5] = [
    "ddm",
    "sbf",
    "timecells-csc",
    "timecells-ms",
    "timecells-laplace",
];

/// What [`write_tables`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// `signatures.csv`, `mechanisms.csv`, `mechanisms.md`, `fingerprints.svg`/`.png`.
    pub files: Vec<PathBuf>,
    /// Signatures (model × seed).
    pub signatures: usize,
    /// Agents compared.
    pub agents: usize,
}

fn fmt(x: f64, digits: usize) -> String {
    if x.is_finite() {
        format!("{x:.digits$}")
    } else {
        "–".into()
    }
}

/// Reads the compact results under `results`, compares every agent with the
/// [`MECHANISMS`] (bootstrap of `resamples`, seeded) and writes into `out`:
/// `signatures.csv` (model, seed, every feature), `mechanisms.csv` (agent, mechanism,
/// distance, nearest fraction, seeds) and `mechanisms.md` (the fingerprints with seed
/// spreads, then per agent its distances and nearest mechanism).
pub fn write_tables(
    results: &Path,
    out: &Path,
    resamples: usize,
    seed: u64,
) -> Result<Written, MechanismError> {
    let sigs = signatures(results)?;
    let comparisons = compare(&sigs, &MECHANISMS, resamples, seed);
    let write = |name: &str, text: &str| {
        let p = out.join(name);
        chronocooked_env::fs::write_atomic(&p, text.as_bytes()).map_err(|e| {
            MechanismError::File {
                path: p.clone(),
                message: e.to_string(),
            }
        })?;
        Ok::<PathBuf, MechanismError>(p)
    };
    let mut csv = format!("model,seed,{}\n", FEATURES.join(","));
    for s in &sigs {
        let row: Vec<String> = FEATURES
            .iter()
            .map(|f| s.features.get(*f).map_or(String::new(), |v| v.to_string()))
            .collect();
        csv.push_str(&format!("{},{},{}\n", s.model, s.seed, row.join(",")));
    }
    let mut mcsv =
        String::from("agent,mechanism,distance,nearest_fraction,agent_seeds,mechanism_seeds\n");
    for c in &comparisons {
        mcsv.push_str(&format!(
            "{},{},{},{},{},{}\n",
            c.agent, c.mechanism, c.distance, c.nearest_fraction, c.seeds.0, c.seeds.1
        ));
    }
    // Markdown: fingerprints (mean ± SD over seeds), then the comparison.
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.dedup();
    let mut md = String::from("# Mechanism fingerprints\n\n");
    md.push_str(&format!(
        "Mean ± SD over training seeds (n). Features: {}.\n\n| model | n | {} |\n|---|---|{}\n",
        FEATURES.join(", "),
        FEATURES.join(" | "),
        "---|".repeat(FEATURES.len())
    ));
    for m in &models {
        let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == *m).collect();
        let cells: Vec<String> = FEATURES
            .iter()
            .map(|f| {
                let sp = crate::stats::Spread::of(
                    mine.iter().filter_map(|s| s.features.get(*f).copied()),
                );
                if sp.n == 0 {
                    "–".into()
                } else {
                    format!("{} ± {}", fmt(sp.mean, 3), fmt(sp.sd, 3))
                }
            })
            .collect();
        md.push_str(&format!(
            "| {m} | {} | {} |\n",
            mine.len(),
            cells.join(" | ")
        ));
    }
    md.push_str(&format!(
        "\n## Nearest mechanism\n\nDistance: RMS of feature differences in units of each \
         feature's SD over all signatures; nearest: the share of {resamples} bootstrap \
         resamples of the seeds in which the mechanism is the nearest.\n\n| agent | {} | nearest (bootstrap share) |\n|---|{}---|\n",
        MECHANISMS.join(" | "),
        "---|".repeat(MECHANISMS.len())
    ));
    let mut agents: Vec<&str> = comparisons.iter().map(|c| c.agent.as_str()).collect();
    agents.dedup();
    for a in &agents {
        let mine: Vec<&Comparison> = comparisons.iter().filter(|c| c.agent == *a).collect();
        let cells: Vec<String> = MECHANISMS
            .iter()
            .map(|m| {
                mine.iter()
                    .find(|c| c.mechanism == *m)
                    .map_or("–".into(), |c| fmt(c.distance, 2))
            })
            .collect();
        let best = mine
            .iter()
            .filter(|c| c.distance.is_finite())
            .min_by(|x, y| x.distance.total_cmp(&y.distance));
        let nearest = best.map_or("–".into(), |c| {
            format!("{} ({:.2})", c.mechanism, c.nearest_fraction)
        });
        md.push_str(&format!("| {a} | {} | {nearest} |\n", cells.join(" | ")));
    }
    let mut files = vec![
        write("signatures.csv", &csv)?,
        write("mechanisms.csv", &mcsv)?,
        write("mechanisms.md", &md)?,
    ];
    files.extend(fingerprint_figure(&sigs, &out.join("fingerprints"))?);
    Ok(Written {
        files,
        signatures: sigs.len(),
        agents: agents.len(),
    })
}

/// The fingerprints as parallel coordinates: per model (seed mean) a line over the
/// features (x: the feature's index in [`FEATURES`], y: its value in SDs from the mean over
/// all signatures); SVG and PNG at `stem`.
fn fingerprint_figure(sigs: &[Signature], stem: &Path) -> Result<Vec<PathBuf>, MechanismError> {
    use crate::report::figures::{Chart, Series, write_chart};
    let sds = feature_sds(sigs);
    let all: Vec<&Signature> = sigs.iter().collect();
    let centre = mean_features(&all);
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.dedup();
    let series = models
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == *m).collect();
            let mean = mean_features(&mine);
            let points = FEATURES
                .iter()
                .enumerate()
                .filter_map(|(i, f)| {
                    Some((i as f64, (mean.get(f)? - centre.get(f)?) / sds.get(f)?))
                })
                .collect();
            Series {
                label: m.to_string(),
                points,
                line: true,
                color: k,
            }
        })
        .collect();
    let chart = Chart {
        title: "Mechanism fingerprints (seed means)".into(),
        x_label: format!(
            "feature (0 {} … {} {}, in the order of mechanisms.md)",
            FEATURES[0],
            FEATURES.len() - 1,
            FEATURES[FEATURES.len() - 1]
        ),
        y_label: "SDs from the mean of all signatures".into(),
        series,
        ..Chart::default()
    };
    write_chart(stem, &chart).map_err(|e| MechanismError::File {
        path: stem.to_path_buf(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sig(model: &str, seed: u64, f: &[(&str, f64)]) -> Signature {
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
    fn the_scaling_index_prefers_the_geometry_and_skips_readouts() {
        let summary = serde_json::json!([
            // Geometry defined: its index (0.9) counts with 30 units.
            {"population": "cells", "units": 30,
             "scaling": {"td_ratio": 2.0, "median": 1.0, "geometry_index": 0.9}},
            // Geometry undefined (a straight ramp): ln(2)/ln(2) = 1 from the unit factor.
            {"population": "accumulator", "units": 10,
             "scaling": {"td_ratio": 2.0, "median": 2.0, "geometry_index": null}},
            // Read-outs and populations without scaling are left out.
            {"population": "value", "units": 1,
             "scaling": {"td_ratio": 2.0, "median": 8.0, "geometry_index": 3.0}},
            {"population": "other", "units": 5, "scaling": null}
        ]);
        let i = scaling_index(&summary).unwrap();
        assert!((i - (30.0 * 0.9 + 10.0 * 1.0) / 40.0).abs() < 1e-12, "{i}");
        assert_eq!(scaling_index(&serde_json::json!([])), None);
    }

    #[test]
    fn distance_is_the_rms_of_standardised_differences_over_shared_features() {
        let a: BTreeMap<&str, f64> = [("wf", 0.1), ("foc_cv", 0.2)].into_iter().collect();
        let b: BTreeMap<&str, f64> = [("wf", 0.3)].into_iter().collect();
        let sds: BTreeMap<&str, f64> = [("wf", 0.1), ("foc_cv", 0.05)].into_iter().collect();
        // Only `wf` is shared: |0.1 − 0.3| / 0.1 = 2.
        assert!((distance(&a, &b, &sds) - 2.0).abs() < 1e-12);
        let none: BTreeMap<&str, f64> = BTreeMap::new();
        assert!(distance(&a, &none, &sds).is_nan());
    }
}
