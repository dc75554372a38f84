//! Reading signatures: the behavioural and neural features of every finished job of a
//! study's compact results, or of a leaderboard's evaluation folders.

use super::{DYNAMICS_NEURAL, MechanismError, READOUTS, Signature};
use crate::job_folder;
use crate::neural::categories::CATEGORIES;
use crate::neural::dynamics::Dynamics;
use crate::neural::summary::NeuralSummary;
use crate::records::METRICS;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Reads a JSON file as `T`; errors name the file.
fn read<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, MechanismError> {
    let text = std::fs::read_to_string(path).map_err(|e| MechanismError::File {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    serde_json::from_str(&text).map_err(|e| MechanismError::File {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// What the signatures read of an evaluation's `metrics.json`, typed and tolerant of every
/// version the committed studies hold (a field a version lacks reads as absent; the full
/// type is [`crate::behaviour::metrics::Metrics`]).
#[derive(Debug, Default, Deserialize)]
struct MetricsView {
    #[serde(default)]
    fi: Option<FiView>,
    #[serde(default)]
    pi: Option<Vec<PiView>>,
    #[serde(default)]
    bisection: Option<BisectionView>,
}

#[derive(Debug, Default, Deserialize)]
struct FiView {
    #[serde(default)]
    foc: Option<Vec<FocView>>,
}

/// One TD's first-oven-check statistics.
#[derive(Debug, Deserialize)]
struct FocView {
    td: u32,
    mean: Option<f64>,
    cv: Option<f64>,
}

/// One peak-interval condition.
#[derive(Debug, Deserialize)]
struct PiView {
    #[serde(default)]
    factor: Option<f64>,
    #[serde(default)]
    td: Option<f64>,
    #[serde(default)]
    fit: Option<PiFitView>,
}

/// A peak-interval fit: its peak, CV and (newer files) its spread σ.
#[derive(Debug, Default, Deserialize)]
struct PiFitView {
    #[serde(default)]
    peak: Option<f64>,
    #[serde(default)]
    cv: Option<f64>,
    #[serde(default)]
    spread: Option<f64>,
}

/// Bisection: the anchors and the psychometric fit.
#[derive(Debug, Default, Deserialize)]
struct BisectionView {
    #[serde(default)]
    short: Option<f64>,
    #[serde(default)]
    long: Option<f64>,
    #[serde(default)]
    fit: Option<BisectionFitView>,
}

#[derive(Debug, Default, Deserialize)]
struct BisectionFitView {
    #[serde(default)]
    bp: Option<f64>,
    #[serde(default)]
    wf: Option<f64>,
}

/// What the signatures read of one population's neural summary (a list of them is an
/// `activity.summary.json`), typed and tolerant of every version the committed studies
/// hold; the full type is [`NeuralSummary`].
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct PopulationView {
    /// Population name (read-outs are left out of the signatures).
    #[serde(default)]
    pub population: String,
    /// Varying units analysed.
    #[serde(default)]
    pub units: f64,
    /// Constant units (left out of the unit analyses; counted in the population's size).
    #[serde(default)]
    pub constant_units: f64,
    /// TD of the primary window (steps).
    #[serde(default)]
    pub td: Option<f64>,
    /// Unit-category counts, by category name.
    #[serde(default)]
    pub categories: Option<CategoriesView>,
    /// Ridge decoding error of elapsed time (steps).
    #[serde(default)]
    pub decode_ridge: Option<f64>,
    /// The trajectory's basis-free features (written whole since they exist).
    #[serde(default)]
    pub dynamics: Option<Dynamics>,
    /// Temporal scaling between the shortest and the longest TD.
    #[serde(default)]
    pub scaling: Option<ScalingView>,
}

/// Unit-category counts.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct CategoriesView {
    /// Count per category name (`ramp`, `time_field`, …).
    #[serde(default)]
    pub counts: BTreeMap<String, f64>,
}

/// The signature feature `feature` (`dyn_dimension`, …) of a population's trajectory
/// features, if it has it.
fn dynamics_feature(d: &Dynamics, feature: &str) -> Option<f64> {
    match feature {
        "dyn_dimension" => d.dimension,
        "dyn_speed_trend" => d.speed_trend,
        "dyn_turning" => d.turning,
        "dyn_straightness" => d.straightness,
        "dyn_continuation" => d.continuation,
        "dyn_spectral_radius" => d.spectral_radius,
        "dyn_rotation" => d.rotation,
        _ => None,
    }
}

/// A population's temporal scaling.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct ScalingView {
    /// Longest over shortest TD.
    #[serde(default)]
    pub td_ratio: Option<f64>,
    /// The population geometry's scaling index.
    #[serde(default)]
    pub geometry_index: Option<f64>,
    /// Median per-unit scaling factor.
    #[serde(default)]
    pub median: Option<f64>,
}

impl PopulationView {
    /// The view of a summary computed now (the fields the signatures read).
    pub fn of(s: &NeuralSummary) -> Self {
        PopulationView {
            population: s.population.clone(),
            units: s.units as f64,
            constant_units: s.constant_units as f64,
            td: Some(f64::from(s.td)),
            categories: s.categories.as_ref().map(|c| CategoriesView {
                counts: CATEGORIES
                    .iter()
                    .map(|k| (k.name().to_string(), c.counts.get(*k) as f64))
                    .collect(),
            }),
            decode_ridge: s.decode_ridge,
            dynamics: s.dynamics,
            scaling: s.scaling.as_ref().map(|x| ScalingView {
                td_ratio: Some(x.td_ratio),
                geometry_index: x.geometry_index,
                median: x.median,
            }),
        }
    }

    /// Every population of a list of summaries computed now.
    pub fn all(summaries: &[NeuralSummary]) -> Vec<Self> {
        summaries.iter().map(Self::of).collect()
    }

    /// Reads an `activity.summary.json` (a list of population summaries).
    pub fn read(path: &Path) -> Result<Vec<Self>, MechanismError> {
        read(path)
    }
}

/// A finite value.
fn finite(v: Option<f64>) -> Option<f64> {
    v.filter(|x| x.is_finite())
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
    let metrics: MetricsView = read(metrics)?;
    let mut out = JobFeatures::default();
    for f in metrics.fi.iter().flat_map(|fi| fi.foc.iter().flatten()) {
        if let (Some(mean), Some(cv)) = (finite(f.mean), finite(f.cv)) {
            out.values.push(("foc_cv", cv));
            out.values.push(("foc_over_td", mean / f64::from(f.td)));
            out.fi_cv = Some((f.td, cv));
        }
    }
    for p in metrics
        .pi
        .iter()
        .flatten()
        .filter(|p| finite(p.factor) == Some(2.0))
    {
        let td = p.td.unwrap_or(f64::NAN);
        let window = 2.0 * td;
        // A fit wider than the 2 × TD window is not identified (older evaluations stored
        // such fits; `GaussianFit::identified_within`). Its spread is `σ`, or `cv · peak`
        // where only those were written.
        let fit = p.fit.as_ref();
        let (peak, cv) = (
            finite(fit.and_then(|f| f.peak)),
            finite(fit.and_then(|f| f.cv)),
        );
        let spread =
            finite(fit.and_then(|f| f.spread)).or_else(|| cv.zip(peak).map(|(c, m)| c * m));
        if spread.is_some_and(|s| s > window) {
            continue;
        }
        if let Some(peak) = peak {
            out.values.push(("pi_peak_over_td", peak / td));
        }
        if let Some(cv) = cv {
            out.values.push(("pi_cv", cv));
        }
    }
    if let Some(b) = &metrics.bisection {
        let fit = b.fit.as_ref();
        if let Some(wf) = finite(fit.and_then(|f| f.wf)) {
            out.values.push(("wf", wf));
        }
        if let (Some(bp), Some(s), Some(l)) = (
            finite(fit.and_then(|f| f.bp)),
            finite(b.short),
            finite(b.long),
        ) {
            out.values.push(("bp_over_gm", bp / (s * l).sqrt()));
        }
    }
    if probe && summary.is_file() {
        let pops = PopulationView::read(summary)?;
        let (mut counts, mut units) = ([0.0f64; 3], 0.0);
        let mut decode = Vec::new();
        // Dynamics features, weighted by population size (constant units included: how
        // many units vary is itself basis-dependent).
        let mut dynamics: BTreeMap<&'static str, (f64, f64)> = BTreeMap::new();
        for p in &pops {
            if READOUTS.contains(&p.population.as_str()) {
                continue;
            }
            let size = p.units + p.constant_units;
            for feature in DYNAMICS_NEURAL {
                if let Some(v) = finite(
                    p.dynamics
                        .as_ref()
                        .and_then(|d| dynamics_feature(d, feature)),
                ) && size > 0.0
                {
                    let slot = dynamics.entry(feature).or_insert((0.0, 0.0));
                    slot.0 += size * v;
                    slot.1 += size;
                }
            }
            let count = |name: &str| {
                p.categories
                    .as_ref()
                    .and_then(|c| c.counts.get(name).copied())
                    .unwrap_or(0.0)
            };
            for (k, key) in ["ramp", "time_field", "oscillating"].iter().enumerate() {
                counts[k] += count(key);
            }
            units += CATEGORIES.iter().map(|k| count(k.name())).sum::<f64>();
            if let (Some(err), Some(td)) = (finite(p.decode_ridge), finite(p.td)) {
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

/// The scaling index of one model × seed's joint recording (`activity.summary.json` of
/// `record --summary` over runs at several TDs): per non-read-out population the geometry
/// index, else the per-unit one; weighted by units. `None` when no population has one.
pub fn scaling_index_of_summary(summary: &[PopulationView]) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for p in summary {
        let Some(s) = &p.scaling else { continue };
        if READOUTS.contains(&p.population.as_str()) {
            continue;
        }
        let ratio = finite(s.td_ratio).filter(|r| *r > 1.0);
        let index = finite(s.geometry_index).or_else(|| {
            let m = finite(s.median).filter(|m| *m > 0.0)?;
            Some(m.ln() / ratio?.ln())
        });
        if let Some(i) = index
            && p.units > 0.0
        {
            sum += p.units * i;
            weight += p.units;
        }
    }
    (weight > 0.0).then(|| sum / weight)
}

/// The geometry scaling index of one model × seed's joint recording alone (no per-unit
/// fallback: the dynamics view's `dyn_scaling`), units-weighted over the non-read-out
/// populations that have one (weights: population size, constant units included).
pub fn geometry_index_of_summary(summary: &[PopulationView]) -> Option<f64> {
    let (mut sum, mut weight) = (0.0, 0.0);
    for p in summary {
        if READOUTS.contains(&p.population.as_str()) {
            continue;
        }
        let size = p.units + p.constant_units;
        if let Some(i) = finite(p.scaling.as_ref().and_then(|s| s.geometry_index))
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
            let j = job_folder::read_scaling(&job).map_err(|message| MechanismError::File {
                path: job.clone(),
                message,
            })?;
            let (model, seed) = (j.model.as_str(), j.seed);
            let summary = PopulationView::read(&summary)?;
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
        let job = job_folder::read_job(&dir).map_err(|message| MechanismError::File {
            path: dir.join(job_folder::JOB),
            message,
        })?;
        jobs.push(JobFiles {
            model: job.label().to_string(),
            seed: job.seed,
            task: job.task.id().to_string(),
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
        let summary: Vec<PopulationView> = serde_json::from_value(summary).unwrap();
        let i = scaling_index_of_summary(&summary).unwrap();
        assert!((i - (30.0 * 0.9 + 10.0 * 1.0) / 40.0).abs() < 1e-12, "{i}");
        assert_eq!(scaling_index_of_summary(&[]), None);
    }
}
