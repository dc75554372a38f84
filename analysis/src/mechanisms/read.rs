//! Reading signatures: the behavioural and neural features of every finished job of a
//! study's compact results, or of a leaderboard's evaluation folders.

use super::{MechanismError, READOUTS, Signature};
use crate::job_folder;
use crate::records::METRICS;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

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

pub(crate) fn num(v: &Value) -> Option<f64> {
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
fn job_features(
    metrics: &Path,
    summary: &Path,
    probe: bool,
) -> Result<JobFeatures, MechanismError> {
    let metrics = read(metrics)?;
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
            let window = 2.0 * td;
            // A fit wider than the 2 × TD window is not identified (older evaluations
            // stored such fits; `GaussianFit::identified_within`). Its spread is `σ`, or
            // `cv · peak` where only those were written.
            let fit = &p["fit"];
            let spread = num(&fit["spread"])
                .or_else(|| num(&fit["cv"]).zip(num(&fit["peak"])).map(|(c, m)| c * m));
            if spread.is_some_and(|s| s > window) {
                continue;
            }
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
    if probe && summary.is_file() {
        let pops = read(summary)?;
        let (mut counts, mut units) = ([0.0f64; 3], 0.0);
        let mut decode = Vec::new();
        // Dynamics features, weighted by population size (constant units included: how
        // many units vary is itself basis-dependent).
        let mut dynamics: BTreeMap<&'static str, (f64, f64)> = BTreeMap::new();
        for p in pops.as_array().into_iter().flatten() {
            let name = p["population"].as_str().unwrap_or_default();
            if READOUTS.contains(&name) {
                continue;
            }
            let size =
                p["units"].as_f64().unwrap_or(0.0) + p["constant_units"].as_f64().unwrap_or(0.0);
            for (feature, key) in DYNAMICS_KEYS {
                if let Some(v) = num(&p["dynamics"][key])
                    && size > 0.0
                {
                    let slot = dynamics.entry(feature).or_insert((0.0, 0.0));
                    slot.0 += size * v;
                    slot.1 += size;
                }
            }
            let c = &p["categories"]["counts"];
            for (k, key) in ["ramp", "time_field", "oscillating"].iter().enumerate() {
                counts[k] += c[*key].as_f64().unwrap_or(0.0);
            }
            units += crate::neural::categories::CATEGORIES
                .iter()
                .map(|k| c[k.name()].as_f64().unwrap_or(0.0))
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
        for (feature, (sum, weight)) in dynamics {
            out.values.push((feature, sum / weight));
        }
    }
    Ok(out)
}

/// Signature feature ← field of a population summary's `dynamics`.
const DYNAMICS_KEYS: [(&str, &str); 7] = [
    ("dyn_dimension", "dimension"),
    ("dyn_speed_trend", "speed_trend"),
    ("dyn_turning", "turning"),
    ("dyn_straightness", "straightness"),
    ("dyn_continuation", "continuation"),
    ("dyn_spectral_radius", "spectral_radius"),
    ("dyn_rotation", "rotation"),
];

/// The scaling index of one model × seed's joint recording (`activity.summary.json` of
/// `record --summary` over runs at several TDs): per non-read-out population the geometry
/// index, else the per-unit one; weighted by units. `None` when no population has one.
pub fn scaling_index_of_summary(summary: &Value) -> Option<f64> {
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

/// The geometry scaling index of one model × seed's joint recording alone (no per-unit
/// fallback: the dynamics view's `dyn_scaling`), units-weighted over the non-read-out
/// populations that have one (weights: population size, constant units included).
pub fn geometry_index_of_summary(summary: &Value) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for p in summary.as_array().into_iter().flatten() {
        let name = p["population"].as_str().unwrap_or_default();
        if READOUTS.contains(&name) {
            continue;
        }
        let size = p["units"].as_f64().unwrap_or(0.0) + p["constant_units"].as_f64().unwrap_or(0.0);
        if let Some(i) = num(&p["scaling"]["geometry_index"])
            && size > 0.0
        {
            sum += size * i;
            weight += size;
        }
    }
    (weight > 0.0).then(|| sum / weight)
}

/// `(model, seed, feature, value)` of every joint recording under `<results>/scaling/`:
/// `scaling_index` and, where the geometry tells, `dyn_scaling`.
fn scaling_features(
    results: &Path,
) -> Result<Vec<(String, u64, &'static str, f64)>, MechanismError> {
    let mut out = Vec::new();
    for model_dir in chronocooked_env::fs::real_subdirs(&results.join("scaling")) {
        for dir in chronocooked_env::fs::real_subdirs(&model_dir) {
            let (job, summary) = (
                dir.join(job_folder::SCALING),
                dir.join(job_folder::ACTIVITY_SUMMARY),
            );
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
            let summary = read(&summary)?;
            if let Some(i) = scaling_index_of_summary(&summary) {
                out.push((model.to_string(), seed, "scaling_index", i));
            }
            if let Some(i) = geometry_index_of_summary(&summary) {
                out.push((model.to_string(), seed, "dyn_scaling", i));
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
        if dir.join(job_folder::JOB).is_file() && dir.join(METRICS).is_file() {
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
    // A folder that `paper collect` is writing, or left unfinished, is never read: its
    // signatures would be of some jobs only.
    crate::results_folder::check_complete(results).map_err(|message| MechanismError::File {
        path: results.to_path_buf(),
        message,
    })?;
    let dirs = job_dirs(results);
    if dirs.is_empty() {
        return Err(MechanismError::Empty(results.to_path_buf()));
    }
    let mut jobs = Vec::new();
    for dir in dirs {
        let job = read(&dir.join(job_folder::JOB))?;
        let model = job["row"]
            .as_str()
            .or(job["model"].as_str())
            .unwrap_or("unknown")
            .to_string();
        jobs.push(JobFiles {
            model,
            seed: job["seed"].as_u64().unwrap_or(0),
            task: job["task"].as_str().unwrap_or_default().to_string(),
            metrics: dir.join(METRICS),
            summary: dir.join(job_folder::ACTIVITY_SUMMARY),
        });
    }
    let scaling = scaling_features(results)?;
    assemble(&jobs, &scaling)
}

/// The files of one finished job: its metrics and (for recorded jobs) its neural summary.
#[derive(Debug, Clone, PartialEq)]
pub struct JobFiles {
    /// Model (row) name.
    pub model: String,
    /// Training seed.
    pub seed: u64,
    /// Task id (the neural features come from fixed- and peak-interval jobs only).
    pub task: String,
    /// `metrics.json` (the evaluation's metrics).
    pub metrics: PathBuf,
    /// `activity.summary.json` (need not exist).
    pub summary: PathBuf,
}

/// One signature per (model, seed) of `jobs`, the scaling features `(model, seed, feature,
/// value)` (`scaling_index`, `dyn_scaling`) added where given.
pub fn assemble(
    jobs: &[JobFiles],
    scaling: &[(String, u64, &'static str, f64)],
) -> Result<Vec<Signature>, MechanismError> {
    type Key = (String, u64);
    let mut values: BTreeMap<Key, BTreeMap<&'static str, Vec<f64>>> = BTreeMap::new();
    let mut fi_cvs: BTreeMap<Key, Vec<(u32, f64)>> = BTreeMap::new();
    for job in jobs {
        let key = (job.model.clone(), job.seed);
        let probe = matches!(job.task.as_str(), "FixedInterval-v0" | "PeakInterval-v0");
        let f = job_features(&job.metrics, &job.summary, probe)?;
        let slot = values.entry(key.clone()).or_default();
        for (name, v) in f.values {
            slot.entry(name).or_default().push(v);
        }
        if let Some(cv) = f.fi_cv {
            fi_cvs.entry(key).or_default().push(cv);
        }
    }
    for (model, seed, feature, value) in scaling {
        if let Some(slot) = values.get_mut(&(model.clone(), *seed)) {
            slot.entry(feature).or_default().push(*value);
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

#[cfg(test)]
mod tests {
    use super::*;

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
        let i = scaling_index_of_summary(&summary).unwrap();
        assert!((i - (30.0 * 0.9 + 10.0 * 1.0) / 40.0).abs() < 1e-12, "{i}");
        assert_eq!(scaling_index_of_summary(&serde_json::json!([])), None);
    }
}
