//! How much the spread over runs changed with more repeats (issue #29 item 2): every
//! condition's per-run statistics computed on the study's first four seeds (the paper's run
//! count: logs 1–4) and on every run, side by side (`spreads.csv`).
//!
//! Fixed interval: each run's mean first oven check and its CV; bisection: each run's Weber
//! fraction, difference limen and bisection point. A condition appears once it has more
//! runs than the first four seeds.

use super::bisection::analyse_bisection;
use super::fi::analyse_fi;
use chronocooked_analysis::collect::CompactJob;
use chronocooked_analysis::stats::Spread;
use serde::{Deserialize, Serialize};

/// The seeds of the paper-core study's first repeats (the paper's logs 1–4).
pub const FIRST_SEEDS: [u64; 4] = [1, 2, 3, 4];

/// One statistic of one condition on the first four seeds and on every run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpreadChange {
    /// Task id.
    pub task: String,
    /// Model label.
    pub model: String,
    /// Condition: `TD 12` or the anchor pair `4-12`.
    pub condition: String,
    /// `foc_mean`, `foc_cv` (FI) or `wf`, `dl`, `bp` (bisection).
    pub statistic: String,
    /// Mean over the first four seeds' runs.
    pub mean_first: f64,
    /// SD over them.
    pub sd_first: f64,
    /// Runs with a value among them.
    pub n_first: usize,
    /// Mean over every run.
    pub mean_all: f64,
    /// SD over every run.
    pub sd_all: f64,
    /// Runs with a value.
    pub n_all: usize,
}

fn row(
    task: &str,
    model: &str,
    condition: String,
    statistic: &str,
    a: Spread,
    b: Spread,
) -> SpreadChange {
    SpreadChange {
        task: task.into(),
        model: model.into(),
        condition,
        statistic: statistic.into(),
        mean_first: a.mean,
        sd_first: a.sd,
        n_first: a.n,
        mean_all: b.mean,
        sd_all: b.sd,
        n_all: b.n,
    }
}

/// The spread of every FI and bisection statistic on the first four seeds and on all runs,
/// for the conditions that have more runs than those.
pub fn spread_changes(jobs: &[CompactJob]) -> Vec<SpreadChange> {
    let first: Vec<CompactJob> = jobs
        .iter()
        .filter(|j| FIRST_SEEDS.contains(&j.job.seed))
        .cloned()
        .collect();
    let mut out = Vec::new();
    let (fi_a, fi_b) = (analyse_fi(&first), analyse_fi(jobs));
    for m in &fi_b {
        for c in &m.cells {
            let Some(a) = fi_a
                .iter()
                .find(|x| x.model == m.model)
                .and_then(|x| x.cells.iter().find(|y| y.td == c.td))
            else {
                continue;
            };
            if c.runs <= a.runs {
                continue;
            }
            let cond = format!("TD {}", c.td);
            let t = "FixedInterval-v0";
            out.push(row(
                t,
                &m.model,
                cond.clone(),
                "foc_mean",
                a.run_mean,
                c.run_mean,
            ));
            out.push(row(t, &m.model, cond, "foc_cv", a.run_cv, c.run_cv));
        }
    }
    let (bis_a, bis_b) = (analyse_bisection(&first), analyse_bisection(jobs));
    for m in &bis_b {
        for c in &m.cells {
            let Some(a) = bis_a.iter().find(|x| x.model == m.model).and_then(|x| {
                x.cells
                    .iter()
                    .find(|y| y.short == c.short && y.long == c.long)
            }) else {
                continue;
            };
            if c.runs.len() <= a.runs.len() {
                continue;
            }
            let cond = format!("{}-{}", c.short, c.long);
            let t = "Bisection-v0";
            out.push(row(t, &m.model, cond.clone(), "wf", a.wf, c.wf));
            out.push(row(t, &m.model, cond.clone(), "dl", a.dl, c.dl));
            out.push(row(t, &m.model, cond, "bp", a.bp, c.bp));
        }
    }
    out
}

/// Where one more run of a condition is expected to land: the 95% prediction interval of a
/// single new run from the study's runs, `mean ± t₀.₉₇₅,ₙ₋₁ · sd · √(1 + 1/n)` (normal runs).
/// A held-out seed's run is checked against this, not against mean ± SD (which a new run
/// leaves about a third of the time).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NewRunRange {
    /// Task id.
    pub task: String,
    /// Model label.
    pub model: String,
    /// Condition: `TD 12` or the anchor pair `4-12`.
    pub condition: String,
    /// `foc_mean`, `foc_cv` (FI) or `anchor_accuracy`, `wf`, `dl`, `bp` (bisection).
    pub statistic: String,
    /// Runs with a value.
    pub n: usize,
    /// Runs of the condition, with a value or not (excluded by the paper's rule, fit
    /// failed); 0 in files written before it existed.
    #[serde(default)]
    pub runs: usize,
    /// Mean over them.
    pub mean: f64,
    /// SD over them.
    pub sd: f64,
    /// Lower end of the 95% prediction interval.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

/// The 95% prediction interval of one new run from `s` (NaN ends below two runs).
pub fn prediction_interval(s: &Spread) -> (f64, f64) {
    if s.n < 2 || !s.sd.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let t = statrs::distribution::StudentsT::new(0.0, 1.0, (s.n - 1) as f64)
        .map(|d| statrs::distribution::ContinuousCDF::inverse_cdf(&d, 0.975))
        .unwrap_or(f64::NAN);
    let half = t * s.sd * (1.0 + 1.0 / s.n as f64).sqrt();
    (s.mean - half, s.mean + half)
}

fn range(c: ConditionStat) -> NewRunRange {
    let s = c.spread;
    let (lo, hi) = prediction_interval(&s);
    NewRunRange {
        task: c.task,
        model: c.model,
        condition: c.condition,
        statistic: c.statistic.into(),
        n: s.n,
        runs: c.runs,
        mean: s.mean,
        sd: s.sd,
        lo,
        hi,
    }
}

/// One per-run statistic of one condition over a set of runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ConditionStat {
    /// Task id.
    pub task: String,
    /// Model label.
    pub model: String,
    /// Condition: `TD 12` or the anchor pair `4-12`.
    pub condition: String,
    /// `foc_mean`, `foc_cv` (FI) or `anchor_accuracy`, `wf`, `dl`, `bp` (bisection).
    pub statistic: &'static str,
    /// Runs of the condition (with a value or not).
    pub runs: usize,
    /// The statistic over the runs (runs the paper's rules exclude, or whose fit fails,
    /// have no value).
    pub spread: Spread,
}

/// Every FI and bisection statistic per condition over `jobs`: FI each run's mean first
/// oven check and its CV; bisection each run's anchor accuracy (runs the notebook keeps),
/// WF, DL and bisection point.
pub fn condition_stats(jobs: &[CompactJob]) -> Vec<ConditionStat> {
    let mut out = Vec::new();
    let mut push = |task: &str, model: &str, condition: &str, runs, statistic, spread| {
        out.push(ConditionStat {
            task: task.into(),
            model: model.into(),
            condition: condition.into(),
            statistic,
            runs,
            spread,
        })
    };
    for m in analyse_fi(jobs) {
        for c in &m.cells {
            let cond = format!("TD {}", c.td);
            let t = "FixedInterval-v0";
            push(t, &m.model, &cond, c.runs, "foc_mean", c.run_mean);
            push(t, &m.model, &cond, c.runs, "foc_cv", c.run_cv);
        }
    }
    for m in analyse_bisection(jobs) {
        for c in &m.cells {
            let cond = format!("{}-{}", c.short, c.long);
            let t = "Bisection-v0";
            let runs = c.runs.len();
            push(
                t,
                &m.model,
                &cond,
                runs,
                "anchor_accuracy",
                c.anchor_accuracy,
            );
            push(t, &m.model, &cond, runs, "wf", c.wf);
            push(t, &m.model, &cond, runs, "dl", c.dl);
            push(t, &m.model, &cond, runs, "bp", c.bp);
        }
    }
    out
}

/// The new-run range of every FI and bisection statistic with at least two runs.
pub fn new_run_ranges(jobs: &[CompactJob]) -> Vec<NewRunRange> {
    condition_stats(jobs)
        .into_iter()
        .filter(|c| c.spread.n >= 2)
        .map(range)
        .collect()
}
