//! Leaderboard data: finds evaluation folders under any set of run / sweep folders, groups
//! them into model rows (mean ± SD over runs), adds the neural summaries recorded next to
//! them and the constancy of the Weber fraction across bisection anchors.
//!
//! Folder conventions (what `sweep` writes, and what `eval`/`record` write when pointed
//! there): an evaluation folder holds `eval.json` + `records.jsonl`; its parent may hold
//! `activity.summary.json` (from `record --summary`), `neural_figures/` (heat maps) and
//! `run/figures/` (learning curve). A parent folder named `<model>~<variant>` labels the row.

use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_analysis::behaviour::foc::{FocStats, pool_foc_stats, scalar_property};
use chronocooked_analysis::behaviour::metrics::{BisectionMetrics, Metrics};
use chronocooked_analysis::behaviour::reproduction::ReproductionMetrics;
use chronocooked_analysis::columns::{
    UNC_ADAPTED, UNC_EPISODES_TO_ADAPT, WF_CV_ANCHORS, aggregate, headline, neural_columns,
};
use chronocooked_analysis::job_folder;
use chronocooked_analysis::neural::production::ProductionSpeed;
use chronocooked_analysis::neural::summary::NeuralSummary;
use chronocooked_analysis::records::{EVAL_INFO, RECORDS, read_eval_info};
use chronocooked_analysis::stats::robust::{BOOTSTRAP_RESAMPLES, iqm, stratified_bootstrap_ci};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One model's row.
#[derive(Debug, Clone)]
pub struct Row {
    /// Row label: the model name (with its variant label for sweep variants).
    pub model: String,
    /// Evaluation folders aggregated.
    pub runs: Vec<PathBuf>,
    /// Headline and neural spreads by column key.
    pub values: BTreeMap<String, Spread>,
    /// Bisection metrics of every run that has them (for the psychometric grid).
    pub bisection: Vec<BisectionMetrics>,
    /// Reproduction metrics of every run that has them (for the reproduction grid).
    pub reproduction: Vec<ReproductionMetrics>,
    /// The KiNeT speed after Set of every run whose neural summary has one (for the
    /// reproduction grid's speed panels).
    pub speed: Vec<Vec<ProductionSpeed>>,
    /// Fixed interval: first-oven-check statistics per TD, pooled over the row's runs
    /// (sorted by TD; empty without FI runs).
    pub foc: Vec<FocStats>,
    /// Interquartile mean and its stratified bootstrap 95% interval of every column with
    /// per-run values (headline and neural columns), with those values.
    pub robust: BTreeMap<String, Robust>,
    /// `Some(study)` for a committed baseline row read from compact study results
    /// (`results/<study>/jobs/`, see [`crate::report::baselines`]); `None` for a row of
    /// evaluation folders.
    pub baseline: Option<String>,
}

/// The few-run statistics of one column of a row (rliable's IQM and interval).
#[derive(Debug, Clone, PartialEq)]
pub struct Robust {
    /// Interquartile mean over the runs with a value.
    pub iqm: f64,
    /// Stratified percentile bootstrap 95% interval of the IQM (runs resampled within
    /// their task settings, [`BOOTSTRAP_RESAMPLES`] resamples, seed 0); `None` below 2 runs
    /// or when every task setting has one run.
    pub ci: Option<(f64, f64)>,
    /// The per-run values (NaN: the run lacks the metric), in run order.
    pub values: Vec<f64>,
}

/// The stratum of a run: the conditions it was evaluated on (task and TD of each), so runs
/// trained at different TDs or anchors are resampled separately.
fn stratum(m: &Metrics) -> String {
    let mut c: Vec<String> = m
        .conditions
        .iter()
        .map(|c| format!("{}:{}", c.task, c.td))
        .collect();
    c.sort();
    c.dedup();
    c.join(",")
}

/// The [`Robust`] statistics of every column with per-run values.
fn robust_columns(
    metrics: &[Metrics],
    neural: &[Option<&NeuralSummary>],
) -> BTreeMap<String, Robust> {
    let heads: Vec<BTreeMap<String, f64>> = metrics.iter().map(headline).collect();
    let strata: Vec<String> = metrics.iter().map(stratum).collect();
    let mut keys: Vec<String> = heads.iter().flat_map(|h| h.keys().cloned()).collect();
    keys.sort();
    keys.dedup();
    let mut columns: Vec<(String, Vec<f64>)> = keys
        .into_iter()
        .map(|k| {
            let v = heads
                .iter()
                .map(|h| h.get(&k).copied().unwrap_or(f64::NAN))
                .collect();
            (k, v)
        })
        .collect();
    if neural.iter().any(Option::is_some) {
        for (key, value) in neural_columns() {
            let v = neural.iter().map(|s| s.map_or(f64::NAN, value)).collect();
            columns.push((key.to_string(), v));
        }
    }
    columns
        .into_iter()
        .map(|(k, values)| {
            let ci = stratified_bootstrap_ci(&values, &strata, iqm, 0.95, BOOTSTRAP_RESAMPLES, 0);
            (
                k,
                Robust {
                    iqm: iqm(&values),
                    ci,
                    values,
                },
            )
        })
        .collect()
}

/// One evaluated run, ready to be grouped into a row: what an evaluation folder or a
/// compact study job contributes to the leaderboard.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// Row label the run belongs to.
    pub label: String,
    /// Where the run's results are (evaluation folder or compact job folder).
    pub path: PathBuf,
    /// Its behavioural metrics.
    pub metrics: Metrics,
    /// Neural summary of its primary population, when recorded.
    pub neural: Option<NeuralSummary>,
    /// Uncertainty adaptation measured with it: `Some(Some(n))` adapted after n episodes,
    /// `Some(None)` never adapted, `None` not measured.
    pub adapt: Option<Option<usize>>,
}

/// Recomputes the metrics of an `eval` folder from its `records.jsonl` and `eval.json`
/// (the records are the source of truth; metrics JSON writes NaN as null).
pub fn load_metrics(folder: &Path) -> Result<Metrics, String> {
    let path = folder.join(EVAL_INFO);
    if !path.is_file() && !folder.join(chronocooked_env::integrity::MANIFEST).is_file() {
        return Err(format!(
            "{}: no such file (not an `eval` output folder)",
            path.display()
        ));
    }
    chronocooked_analysis::records::check_complete_eval(folder)?;
    let info = read_eval_info(folder)?;
    let records = chronocooked_analysis::records::read_records(folder)
        .map_err(|e| format!("{e} (not an `eval` output folder)"))?;
    Ok(chronocooked_analysis::behaviour::metrics::compute_metrics(
        &info.model,
        &records,
        info.seed,
    ))
}

/// Whether `dir` is an `eval` output folder.
pub fn is_eval_folder(dir: &Path) -> bool {
    dir.join(EVAL_INFO).is_file() && dir.join(RECORDS).is_file()
}

/// Every evaluation folder at or below `roots` (sorted, each real folder once; symbolic
/// links below a root are not followed). Folders that cannot hold one (`export`,
/// `checkpoints`, `figures`, `report`, `slurm`) are not entered.
pub fn find_eval_folders(roots: &[PathBuf]) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        if is_eval_folder(dir) {
            out.push(dir.to_path_buf());
            return;
        }
        // Real sub-folders only: a symbolic link (a self-link, a loop) is never followed.
        let subs: Vec<PathBuf> = chronocooked_env::fs::real_subdirs(dir)
            .into_iter()
            .filter(|p| {
                !matches!(
                    p.file_name().and_then(|n| n.to_str()),
                    Some(
                        "export"
                            | "checkpoints"
                            | "figures"
                            | "neural_figures"
                            | "report"
                            | "slurm"
                    )
                )
            })
            .collect();
        for s in subs {
            walk(&s, out);
        }
    }
    let mut out = Vec::new();
    for r in roots {
        walk(r, &mut out);
    }
    out.sort();
    // Each real folder once, however many roots reach it.
    let mut seen = std::collections::BTreeSet::new();
    out.retain(|p| seen.insert(std::fs::canonicalize(p).unwrap_or_else(|_| p.clone())));
    out
}

/// Row label of an evaluation: the `row` of the sweep job it belongs to (`../job.json`:
/// the model plus its non-task variant settings), else the model name of `eval.json`.
fn row_label(folder: &Path, model: &str) -> String {
    folder
        .parent()
        .and_then(|p| optional_json::<job_folder::JobRecord>(&p.join(job_folder::JOB)))
        .and_then(|job| job.row)
        .unwrap_or_else(|| model.to_string())
}

/// An optional file beside an evaluation: `None` when absent; when present but unreadable,
/// also `None`, with a warning naming it (never ignored silently).
fn optional_json<T: serde::de::DeserializeOwned>(path: &Path) -> Option<T> {
    if !path.is_file() {
        return None;
    }
    // Checked against its SHA-256 record where the folder keeps one: an edited summary is
    // never shown as a result.
    let text = match chronocooked_env::integrity::read_checked(path) {
        Ok(bytes) => bytes,
        Err(e) => {
            eprintln!("warning: {e}; ignored");
            return None;
        }
    };
    match serde_json::from_slice(&text) {
        Ok(v) => Some(v),
        Err(e) => {
            eprintln!("warning: {}: {e}; ignored", path.display());
            None
        }
    }
}

/// Neural summary of the primary population recorded next to an evaluation folder: the
/// population with the most units (first on ties: PPO `latent`, SBF `oscillators`, time
/// cells `time_cells`; DDM `accumulator`).
pub fn load_neural(folder: &Path) -> Option<NeuralSummary> {
    let all: Vec<NeuralSummary> =
        optional_json(&folder.parent()?.join(job_folder::ACTIVITY_SUMMARY))?;
    let max = all.iter().map(|s| s.units).max()?;
    all.into_iter().find(|s| s.units == max)
}

/// Episodes to adapt measured next to an evaluation folder (`../adapt/adapt.json` from
/// `adapt`): `Some(n)` adapted after n episodes, `None` inside means it never adapted.
pub fn load_adaptation(folder: &Path) -> Option<Option<usize>> {
    /// What the leaderboard reads of an adaptation's `adapt.json` (written by the training
    /// crate's `AdaptResult`).
    #[derive(serde::Deserialize)]
    struct Adapted {
        /// Episodes until adapted; `null` when the run never adapted.
        episodes_to_adapt: Option<usize>,
    }
    let a: Adapted = optional_json(&folder.parent()?.join("adapt").join("adapt.json"))?;
    Some(a.episodes_to_adapt)
}

/// Coefficient of variation of the mean Weber fraction across anchor pairs (needs runs on
/// at least two different anchor pairs with a fit; `None` otherwise).
pub fn wf_constancy(bisection: &[BisectionMetrics]) -> Option<f64> {
    let mut by_pair: BTreeMap<(u32, u32), Vec<f64>> = BTreeMap::new();
    for b in bisection {
        if let Some(f) = &b.fit
            && f.wf.is_finite()
        {
            by_pair.entry((b.short, b.long)).or_default().push(f.wf);
        }
    }
    if by_pair.len() < 2 {
        return None;
    }
    let s = Spread::of(by_pair.values().map(|v| Spread::of(v.iter().copied()).mean));
    Some(s.sd / s.mean)
}

/// Loads every folder's metrics (and neural summary) and groups them into rows
/// (input order of first appearance kept).
pub fn load_rows(folders: &[PathBuf]) -> Result<Vec<Row>, String> {
    let mut results = Vec::with_capacity(folders.len());
    for f in folders {
        // An evaluation another process is still writing is never read half-written.
        chronocooked_env::fs::ensure_not_being_written(f).map_err(|e| e.to_string())?;
        let metrics = load_metrics(f)?;
        results.push(RunResult {
            label: row_label(f, &metrics.model),
            path: f.clone(),
            neural: load_neural(f),
            adapt: load_adaptation(f),
            metrics,
        });
    }
    Ok(group_rows(results))
}

/// Groups runs into rows by label (order of first appearance kept): every headline column
/// as mean ± SD over the row's runs, the neural columns, the scalar-property regressions
/// over the row's FI runs at different TDs, adaptation and the Weber-fraction constancy.
/// Evaluation folders and committed baselines go through this one function.
pub fn group_rows(results: Vec<RunResult>) -> Vec<Row> {
    struct Group {
        label: String,
        runs: Vec<PathBuf>,
        metrics: Vec<Metrics>,
        neural: Vec<NeuralSummary>,
        /// Per run, the index of its neural summary in `neural`.
        neural_of_run: Vec<Option<usize>>,
        adapt: Vec<Option<usize>>,
    }
    let mut groups: Vec<Group> = Vec::new();
    for r in results {
        let idx = match groups.iter().position(|g| g.label == r.label) {
            Some(i) => i,
            None => {
                groups.push(Group {
                    label: r.label.clone(),
                    runs: vec![],
                    metrics: vec![],
                    neural: vec![],
                    neural_of_run: vec![],
                    adapt: vec![],
                });
                groups.len() - 1
            }
        };
        let g = &mut groups[idx];
        g.adapt.extend(r.adapt);
        g.runs.push(r.path);
        g.neural_of_run
            .push(r.neural.is_some().then_some(g.neural.len()));
        g.neural.extend(r.neural);
        g.metrics.push(r.metrics);
    }
    groups
        .into_iter()
        .map(|g| {
            let mut values = aggregate(&g.metrics);
            let per_run_neural: Vec<Option<&NeuralSummary>> = g
                .neural_of_run
                .iter()
                .map(|i| i.map(|i| &g.neural[i]))
                .collect();
            let robust = robust_columns(&g.metrics, &per_run_neural);
            if !g.neural.is_empty() {
                for (key, value) in neural_columns() {
                    let v = g.neural.iter().map(value);
                    values.insert(key.into(), Spread::of(v));
                }
            }
            // FI runs trained at different TDs: the scalar-property regressions across them.
            let foc: Vec<FocStats> = g
                .metrics
                .iter()
                .filter_map(|m| m.fi.as_ref())
                .flat_map(|f| f.foc.iter().cloned())
                .collect();
            let pooled = pool_foc_stats(&foc);
            if pooled.len() >= 2 {
                let sp = scalar_property(&pooled);
                for (key, v) in [
                    ("r2_mean_vs_td", sp.r2_mean_vs_td),
                    ("r2_sd_vs_mean", sp.r2_sd_vs_mean),
                ] {
                    if values.get(key).is_none_or(|s| s.n == 0) {
                        values.insert(key.into(), Spread::of([v]));
                    }
                }
            }
            if !g.adapt.is_empty() {
                let eps = g.adapt.iter().map(|a| a.map_or(f64::NAN, |n| n as f64));
                values.insert(UNC_EPISODES_TO_ADAPT.into(), Spread::of(eps));
                let adapted = g.adapt.iter().map(|a| f64::from(u8::from(a.is_some())));
                values.insert(UNC_ADAPTED.into(), Spread::of(adapted));
            }
            let bisection: Vec<BisectionMetrics> = g
                .metrics
                .iter()
                .filter_map(|m| m.bisection.clone())
                .collect();
            if let Some(c) = wf_constancy(&bisection) {
                values.insert(WF_CV_ANCHORS.into(), Spread::of([c]));
            }
            let reproduction = g
                .metrics
                .iter()
                .filter_map(|m| m.reproduction.clone())
                .collect();
            let speed = g
                .neural
                .iter()
                .map(|s| s.production_speed.clone())
                .filter(|s| !s.is_empty())
                .collect();
            Row {
                model: g.label,
                runs: g.runs,
                values,
                bisection,
                reproduction,
                speed,
                foc: pooled,
                robust,
                baseline: None,
            }
        })
        .collect()
}

/// Rows of every evaluation folder found at or below `roots` (run folders, sweep outputs,
/// or evaluation folders themselves).
pub fn load_rows_from_runs(roots: &[PathBuf]) -> Result<Vec<Row>, String> {
    for r in roots {
        if !r.is_dir() {
            return Err(format!("{}: no such folder", r.display()));
        }
    }
    load_rows(&find_eval_folders(roots))
}

fn sorted_entries(d: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(d)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.sort();
    v
}

fn is_svg(p: &Path) -> bool {
    p.extension().is_some_and(|e| e == "svg")
}

/// Behaviour figure files (`.svg`) of an evaluation folder: its own `figures/` and the
/// learning curve of its run (`../run/figures/`), sorted within each folder.
pub fn behaviour_figures(folder: &Path) -> Vec<PathBuf> {
    let mut dirs = vec![folder.join("figures")];
    if let Some(parent) = folder.parent() {
        dirs.push(parent.join(job_folder::RUN).join("figures"));
    }
    dirs.iter()
        .flat_map(|d| sorted_entries(d))
        .filter(|p| p.is_file() && is_svg(p))
        .collect()
}

/// Neural figure files (`.svg`) recorded beside an evaluation folder (`../neural_figures/`:
/// the heat maps, then each population's signature figures in `<population>/`).
pub fn neural_figures(folder: &Path) -> Vec<PathBuf> {
    let Some(parent) = folder.parent() else {
        return Vec::new();
    };
    let mut all = Vec::new();
    for p in sorted_entries(&parent.join("neural_figures")) {
        if p.is_dir() {
            all.extend(sorted_entries(&p).into_iter().filter(|q| is_svg(q)));
        } else if is_svg(&p) {
            all.push(p);
        }
    }
    all
}

/// Caption of a figure file: its name, prefixed by its population folder when it sits in
/// one (`accumulator/by_td`, `lstm/decoding`).
pub fn figure_caption(svg: &Path) -> String {
    let stem = svg.file_stem().unwrap_or_default().to_string_lossy();
    let parent = svg
        .parent()
        .and_then(|p| p.file_name())
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    if parent.is_empty() || parent == "figures" || parent == "neural_figures" {
        stem.to_string()
    } else {
        format!("{parent}/{stem}")
    }
}
