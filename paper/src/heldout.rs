//! The held-out check (issues #15 and #29): a grid job rerun with a seed the study never
//! used should land inside the study's reported spread — the 95% prediction interval of one
//! new run of its condition ([`super::spreads::NewRunRange`], `ranges.csv`).
//!
//! Each held-out job is analysed on its own exactly as the study analyses its runs (the
//! notebook's exclusion rule and fit failures included), so its value of each statistic is
//! the one a study run with that seed would have contributed.

use super::spreads::{condition_stats, prediction_interval};
use chronocooked_analysis::collect::CompactJob;
use chronocooked_env::markdown::Table;
use serde::{Deserialize, Serialize};
use std::fmt;
use thiserror::Error;

/// Where one held-out statistic landed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum HeldOutVerdict {
    /// Inside the study's 95% range for a new run.
    Inside,
    /// Outside it.
    Outside,
    /// The held-out run has no value (excluded by the paper's rule, or its fit failed).
    NoValue,
    /// The study has fewer than two runs with a value for this condition: no range.
    NoRange,
}

impl fmt::Display for HeldOutVerdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            HeldOutVerdict::Inside => "inside",
            HeldOutVerdict::Outside => "outside",
            HeldOutVerdict::NoValue => "no value",
            HeldOutVerdict::NoRange => "no range",
        })
    }
}

/// One statistic of one held-out job against the study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeldOutCheck {
    /// The held-out job's id.
    pub id: String,
    /// Its seed.
    pub seed: u64,
    /// Task id.
    pub task: String,
    /// Model label.
    pub model: String,
    /// Condition: `TD 12` or the anchor pair `4-12`.
    pub condition: String,
    /// `foc_mean`, `foc_cv` (FI; steps) or `anchor_accuracy`, `wf`, `dl`, `bp` (bisection;
    /// `dl`, `bp` in steps).
    pub statistic: String,
    /// The held-out run's value (NaN when it has none).
    pub value: f64,
    /// The study's runs with a value.
    pub n: usize,
    /// The study's runs of the condition, with a value or not (a held-out run without a
    /// value is unlike the study when most of these have one).
    pub runs: usize,
    /// Their mean.
    pub mean: f64,
    /// Their SD.
    pub sd: f64,
    /// Lower end of the study's 95% range for a new run.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// (value − mean) / sd: how many study SDs from the study's mean.
    pub sds_from_mean: f64,
    /// Where it landed.
    pub verdict: HeldOutVerdict,
}

/// Why the held-out check cannot run.
#[derive(Debug, Error, PartialEq)]
pub enum HeldOutError {
    /// A "held-out" job's seed is one of the study's runs of the same condition: it is not
    /// held out.
    #[error(
        "held-out job {id}: seed {seed} is already one of the study's runs of this condition ({study_id}); a held-out check needs a seed the study never used"
    )]
    SeedInStudy {
        /// The held-out job.
        id: String,
        /// Its seed.
        seed: u64,
        /// The study's job with the same condition and seed.
        study_id: String,
    },
    /// No fixed-interval or bisection job among the held-out results.
    #[error(
        "no fixed-interval or bisection job among the held-out results: nothing to check (the check covers FixedInterval-v0 and Bisection-v0 jobs)"
    )]
    NothingToCheck,
}

fn same_condition(a: &CompactJob, b: &CompactJob) -> bool {
    a.job.task == b.job.task && a.job.label() == b.job.label()
}

/// Checks every FI and bisection statistic of each held-out job against the study's 95%
/// range for one new run of the same condition (task, model label, condition).
pub fn check_held_out(
    study: &[CompactJob],
    held_out: &[CompactJob],
) -> Result<Vec<HeldOutCheck>, HeldOutError> {
    let study_stats = condition_stats(study);
    let mut out = Vec::new();
    for h in held_out {
        if let Some(s) = study
            .iter()
            .find(|s| s.job.seed == h.job.seed && same_condition(s, h))
        {
            return Err(HeldOutError::SeedInStudy {
                id: h.job.id.clone(),
                seed: h.job.seed,
                study_id: s.job.id.clone(),
            });
        }
        for stat in condition_stats(std::slice::from_ref(h)) {
            let study_stat = study_stats.iter().find(|s| {
                s.task == stat.task
                    && s.model == stat.model
                    && s.condition == stat.condition
                    && s.statistic == stat.statistic
            });
            let value = if stat.spread.n == 1 {
                stat.spread.mean
            } else {
                f64::NAN
            };
            let (n, runs, mean, sd, (lo, hi)) = match study_stat {
                Some(s) => (
                    s.spread.n,
                    s.runs,
                    s.spread.mean,
                    s.spread.sd,
                    prediction_interval(&s.spread),
                ),
                None => (0, 0, f64::NAN, f64::NAN, (f64::NAN, f64::NAN)),
            };
            let verdict = if !value.is_finite() {
                HeldOutVerdict::NoValue
            } else if !(lo.is_finite() && hi.is_finite()) {
                HeldOutVerdict::NoRange
            } else if (lo..=hi).contains(&value) {
                HeldOutVerdict::Inside
            } else {
                HeldOutVerdict::Outside
            };
            out.push(HeldOutCheck {
                id: h.job.id.clone(),
                seed: h.job.seed,
                task: stat.task,
                model: stat.model,
                condition: stat.condition,
                statistic: stat.statistic.into(),
                value,
                n,
                runs,
                mean,
                sd,
                lo,
                hi,
                sds_from_mean: if sd > 0.0 {
                    (value - mean) / sd
                } else {
                    f64::NAN
                },
                verdict,
            });
        }
    }
    if out.is_empty() {
        return Err(HeldOutError::NothingToCheck);
    }
    Ok(out)
}

/// Writes the checks as CSV (one row per held-out job × statistic) to `path`, atomically.
pub fn write_held_out_csv(
    path: &std::path::Path,
    checks: &[HeldOutCheck],
) -> Result<(), chronocooked_analysis::collect::CollectError> {
    chronocooked_analysis::collect::write_csv(path, checks)
}

fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3}")
    } else {
        "–".into()
    }
}

/// The checks as a Markdown table (job, statistic, held-out value, study mean ± SD with its
/// runs that have a value of all its runs, the 95% range for a new run, SDs from the mean,
/// verdict) and a count line.
pub fn held_out_markdown(checks: &[HeldOutCheck]) -> String {
    let mut table = Table::new([
        "job",
        "statistic",
        "held-out run",
        "study (mean ± SD; runs with a value of all)",
        "95% range for a new run",
        "SDs from mean",
        "verdict",
    ])
    .right([2, 5]);
    for c in checks {
        table.row([
            c.id.clone(),
            c.statistic.to_string(),
            num(c.value),
            format!("{} ± {} ({} of {})", num(c.mean), num(c.sd), c.n, c.runs),
            format!("{} … {}", num(c.lo), num(c.hi)),
            if c.sds_from_mean.is_finite() {
                format!("{:+.1}", c.sds_from_mean)
            } else {
                "–".into()
            },
            c.verdict.to_string(),
        ]);
    }
    let mut s = table.render();
    let count = |v| checks.iter().filter(|c| c.verdict == v).count();
    s.push_str(&format!(
        "\n{} inside, {} outside, {} without a held-out value, {} without a study range\n",
        count(HeldOutVerdict::Inside),
        count(HeldOutVerdict::Outside),
        count(HeldOutVerdict::NoValue),
        count(HeldOutVerdict::NoRange)
    ));
    s
}
