//! Fixed interval as the paper analyses it: first oven checks pooled over runs × start
//! cells per (model, TD) — mean, SD, CV — and the scalar-property regressions across TDs;
//! beside them the lab's per-run statistics (mean ± SD over runs).

use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_analysis::behaviour::foc::{FocStats, ScalarProperty, foc_stats, scalar_property};
use chronocooked_analysis::collect::{CompactJob, EpisodeRow};
use chronocooked_analysis::records::ConditionKind;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// FOC statistics of one model at one TD.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FiCell {
    /// Target duration (steps).
    pub td: u32,
    /// Runs evaluated.
    pub runs: usize,
    /// Pooled over runs × start cells with the notebook's rule (a run's remaining cells are
    /// skipped after its first episode without a FOC).
    pub pooled: FocStats,
    /// Pooled over every episode with a FOC (no skipping).
    pub pooled_all: FocStats,
    /// As `pooled`, with the lab's FOC convention (`FocConvention::Checks`: an interact run
    /// from the onion put counts as a check at step 1, where the paper's code reports 0) —
    /// the measured effect of the paper's convention.
    #[serde(default)]
    pub pooled_checks: Option<FocStats>,
    /// Mean FOC per run, across runs.
    pub run_mean: Spread,
    /// SD of FOC per run, across runs.
    pub run_sd: Spread,
    /// CV per run, across runs.
    pub run_cv: Spread,
    /// Mean FOC / TD per run, across runs.
    pub run_ratio: Spread,
    /// The pooled FOCs (paper rule), for figures.
    pub focs: Vec<f64>,
}

/// One model's FI results across TDs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FiModel {
    /// Zoo model name.
    pub model: String,
    /// Per TD, ascending.
    pub cells: Vec<FiCell>,
    /// Regressions on the pooled statistics (the paper's R² table).
    pub scalar: ScalarProperty,
    /// The same regressions per run, across runs.
    pub run_r2_mean_vs_td: Spread,
    /// R² of SD vs mean per run, across runs.
    pub run_r2_sd_vs_mean: Spread,
}

/// FOCs of one run's FI episodes in start-cell order; with `notebook_break` the list stops
/// at the first episode without a FOC (the notebook's "did not converge" rule).
pub fn run_focs(job: &CompactJob, notebook_break: bool) -> Vec<f64> {
    run_focs_by(job, notebook_break, |e| e.foc)
}

/// [`run_focs`] with the FOC read by `foc` (e.g. the lab's convention, `foc_checks`).
fn run_focs_by(
    job: &CompactJob,
    notebook_break: bool,
    foc: fn(&EpisodeRow) -> Option<i32>,
) -> Vec<f64> {
    let mut eps: Vec<_> = job
        .episodes
        .iter()
        .filter(|e| e.kind == ConditionKind::Fi)
        .collect();
    eps.sort_by_key(|e| (e.row, e.col));
    let mut out = Vec::new();
    for e in eps {
        match foc(e) {
            Some(f) => out.push(f64::from(f)),
            None if notebook_break => break,
            None => {}
        }
    }
    out
}

/// The FI jobs among `jobs` by model, then TD (steps).
pub fn fi_runs(jobs: &[CompactJob]) -> BTreeMap<&str, BTreeMap<u32, Vec<&CompactJob>>> {
    let mut by_model: BTreeMap<&str, BTreeMap<u32, Vec<&CompactJob>>> = BTreeMap::new();
    for j in jobs
        .iter()
        .filter(|j| j.job.task.id() == "FixedInterval-v0")
    {
        let Some(td) = j.env_int("td") else {
            continue;
        };
        by_model
            .entry(j.job.label())
            .or_default()
            .entry(td)
            .or_default()
            .push(j);
    }
    by_model
}

/// FI analysis of every model among `jobs` (jobs of other tasks are ignored).
pub fn analyse_fi(jobs: &[CompactJob]) -> Vec<FiModel> {
    fi_runs(jobs)
        .into_iter()
        .map(|(model, tds)| {
            let mut cells = Vec::new();
            let mut per_seed: BTreeMap<u64, Vec<FocStats>> = BTreeMap::new();
            for (td, runs) in tds {
                let paper: Vec<f64> = runs.iter().flat_map(|j| run_focs(j, true)).collect();
                let all: Vec<f64> = runs.iter().flat_map(|j| run_focs(j, false)).collect();
                let checks: Vec<f64> = runs
                    .iter()
                    .flat_map(|j| run_focs_by(j, true, |e| e.foc_checks))
                    .collect();
                let per_run: Vec<FocStats> = runs
                    .iter()
                    .map(|j| {
                        let s = foc_stats(&[(td, run_focs(j, false))]).remove(0);
                        per_seed.entry(j.job.seed).or_default().push(s.clone());
                        s
                    })
                    .collect();
                cells.push(FiCell {
                    td,
                    runs: runs.len(),
                    pooled: foc_stats(&[(td, paper.clone())]).remove(0),
                    pooled_all: foc_stats(&[(td, all)]).remove(0),
                    pooled_checks: Some(foc_stats(&[(td, checks)]).remove(0)),
                    run_mean: Spread::of(per_run.iter().map(|s| s.mean)),
                    run_sd: Spread::of(per_run.iter().map(|s| s.sd)),
                    run_cv: Spread::of(per_run.iter().map(|s| s.cv)),
                    run_ratio: Spread::of(per_run.iter().map(|s| s.mean / f64::from(td))),
                    focs: paper,
                });
            }
            let pooled: Vec<FocStats> = cells.iter().map(|c| c.pooled.clone()).collect();
            let per_run: Vec<ScalarProperty> =
                per_seed.values().map(|s| scalar_property(s)).collect();
            FiModel {
                model: model.to_string(),
                scalar: scalar_property(&pooled),
                run_r2_mean_vs_td: Spread::of(per_run.iter().map(|s| s.r2_mean_vs_td)),
                run_r2_sd_vs_mean: Spread::of(per_run.iter().map(|s| s.r2_sd_vs_mean)),
                cells,
            }
        })
        .collect()
}
