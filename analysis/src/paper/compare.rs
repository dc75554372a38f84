//! The lab's numbers beside the paper's: one [`ComparisonRow`] per published number, with
//! the agreement rule of `RESULTS.md`.
//!
//! * Means (CV, FOC mean, R², WF, DL, levels): the lab's value is the paper's statistic
//!   computed the paper's way (pooled, or mean over runs for the per-run tables) and its
//!   spread the SD of the same statistic over runs. The paper's value agrees when it lies
//!   in `lab ± t₀.₉₇₅,ₙ₋₁ · sd · √(1/n + 1/4)` — the 95% interval of a difference between
//!   two means of runs with the lab's spread (the paper's tables come from 4 runs).
//! * SDs over runs (`*_sd` tables): the paper's SD agrees when it lies in the χ² 95%
//!   interval of the lab's SD.
//! * `n/a` when the lab has fewer than two runs with a value (or, for the R² rows, fewer than
//!   three TDs); `both-nan` when paper and lab
//!   both have no number; `no` when only one of them has one.

use super::bisection::BisectionModel;
use super::fi::FiModel;
use super::multitimer::MtCell;
use super::reference::{MODELS, PaperNumber, lab_model, numbers};
use crate::behaviour::aggregate::Spread;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};

/// One line of `comparison.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComparisonRow {
    /// Table.
    pub table: String,
    /// Row.
    pub row: String,
    /// Column.
    pub column: String,
    /// The paper's number.
    pub paper: f64,
    /// The lab's number (same statistic).
    pub lab_mean: f64,
    /// The lab's spread over runs.
    pub lab_sd: f64,
    /// Runs behind the lab's number.
    pub n: usize,
    /// `yes`, `no`, `n/a` or `both-nan` (see the module docs).
    pub agree: String,
}

/// Agreement of a paper mean with a lab mean ± SD over `n` runs.
pub fn agree_mean(paper: f64, lab: f64, sd: f64, n: usize) -> String {
    match (paper.is_finite(), lab.is_finite()) {
        (false, false) => return "both-nan".into(),
        (true, false) | (false, true) => return "no".into(),
        _ => {}
    }
    if n < 2 || !sd.is_finite() {
        return "n/a".into();
    }
    let t = StudentsT::new(0.0, 1.0, (n - 1) as f64)
        .map(|d| d.inverse_cdf(0.975))
        .unwrap_or(f64::NAN);
    let half = t * sd * (1.0 / n as f64 + 0.25).sqrt();
    if (paper - lab).abs() <= half + 1e-12 {
        "yes".into()
    } else {
        "no".into()
    }
}

/// Agreement of a paper SD with a lab SD over `n` runs (χ² interval).
pub fn agree_sd(paper: f64, lab_sd: f64, n: usize) -> String {
    match (paper.is_finite(), lab_sd.is_finite()) {
        (false, false) => return "both-nan".into(),
        (true, false) | (false, true) => return if n < 2 { "n/a".into() } else { "no".into() },
        _ => {}
    }
    let df = (n - 1) as f64;
    let Ok(chi) = ChiSquared::new(df) else {
        return "n/a".into();
    };
    let lo = lab_sd * (df / chi.inverse_cdf(0.975)).sqrt();
    let hi = lab_sd * (df / chi.inverse_cdf(0.025)).sqrt();
    if paper >= lo - 1e-12 && paper <= hi + 1e-12 {
        "yes".into()
    } else {
        "no".into()
    }
}

fn paper_model(p: &PaperNumber) -> &'static str {
    MODELS
        .iter()
        .map(|(m, _)| *m)
        .find(|m| *m == p.row || *m == p.column)
        .unwrap_or("")
}

/// Every comparison row the lab's results cover (rows whose model or condition the study
/// did not run are left out).
pub fn compare(fi: &[FiModel], bis: &[BisectionModel], mt: &[MtCell]) -> Vec<ComparisonRow> {
    let mut out = Vec::new();
    for p in numbers() {
        let Some(lab) = lab_model(paper_model(&p)) else {
            continue;
        };
        let fi_m = fi.iter().find(|m| m.model == lab);
        let fi_cell = |td: &str| {
            let td: u32 = td.parse().ok()?;
            fi_m?.cells.iter().find(|c| c.td == td)
        };
        let bis_cell = |anchor: &str| {
            let (s, l) = anchor.split_once('-')?;
            let (s, l): (u32, u32) = (s.parse().ok()?, l.parse().ok()?);
            bis.iter()
                .find(|m| m.model == lab)?
                .cells
                .iter()
                .find(|c| c.short == s && c.long == l)
        };
        let mean_row = |v: f64, s: Spread| (v, s.sd, s.n, agree_mean(p.value, v, s.sd, s.n));
        let value = match p.table {
            "fi_cv" => fi_cell(p.row).map(|c| mean_row(c.pooled.cv, c.run_cv)),
            "fi_foc_mean_notebook" => fi_cell(p.row).map(|c| mean_row(c.pooled.mean, c.run_mean)),
            "fi_foc_sd_notebook" => fi_cell(p.row).map(|c| {
                (
                    c.pooled.sd,
                    c.run_sd.sd,
                    c.run_sd.n,
                    agree_mean(p.value, c.pooled.sd, c.run_sd.sd, c.run_sd.n),
                )
            }),
            "fi_r2" | "fi_r2_notebook" => fi_m.map(|m| {
                let mut row = if p.column == "mean_vs_td" {
                    mean_row(m.scalar.r2_mean_vs_td, m.run_r2_mean_vs_td)
                } else {
                    mean_row(m.scalar.r2_sd_vs_mean, m.run_r2_sd_vs_mean)
                };
                // A regression over fewer than three TDs says nothing yet.
                if m.cells.len() < 3 {
                    row.3 = "n/a".into();
                }
                row
            }),
            "bisection_wf" => bis_cell(p.row).map(|c| mean_row(c.wf.mean, c.wf)),
            "bisection_dl" => bis_cell(p.row).map(|c| mean_row(c.dl.mean, c.dl)),
            "bisection_wf_sd" => bis_cell(p.row).map(|c| {
                (
                    c.wf.sd,
                    f64::NAN,
                    c.wf.n,
                    agree_sd(p.value, c.wf.sd, c.wf.n),
                )
            }),
            "bisection_dl_sd" => bis_cell(p.row).map(|c| {
                (
                    c.dl.sd,
                    f64::NAN,
                    c.dl.n,
                    agree_sd(p.value, c.dl.sd, c.dl.n),
                )
            }),
            "multitimer_level" => mt
                .iter()
                .find(|c| c.model == lab && c.curriculum == p.column)
                .map(|c| mean_row(c.level.mean, c.level)),
            "multitimer_runs_at_last_level" => mt
                .iter()
                .find(|c| c.model == lab && c.curriculum == p.column)
                .map(|c| {
                    let v = c.reached_last as f64;
                    let ok = if v == p.value { "yes" } else { "no" };
                    (v, f64::NAN, c.runs.len(), ok.to_string())
                }),
            _ => None,
        };
        if let Some((lab_mean, lab_sd, n, agree)) = value {
            out.push(ComparisonRow {
                table: p.table.into(),
                row: p.row.into(),
                column: p.column.into(),
                paper: p.value,
                lab_mean,
                lab_sd,
                n,
                agree,
            });
        }
    }
    out
}
