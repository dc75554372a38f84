//! The lab's numbers beside the paper's: one [`ComparisonRow`] per published number, with
//! two verdicts.
//!
//! **Old rule (`agree`)** — an interval around the lab's mean:
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
//!
//! **Discriminating rule (`agree_z`)** — `|z| ≤ 2` with
//! `z = (lab − paper) / √(lab_sd²/n + paper_sd²/n_paper)` ([`z_score`]): the difference over
//! the combined standard error of the two means. The paper's SD and run count
//! ([`PAPER_RUNS`]) enter only where the paper prints an SD for that number (WF and DL:
//! `se_from = lab+paper`); elsewhere (CV, R², the notebook's numbers) only the lab's
//! standard error (`se_from = lab`), which makes the rule stricter there. The `*_sd` rows
//! compare the two SDs on the log scale, `z = ln(lab_sd/paper_sd) / √(1/(2(n−1)) +
//! 1/(2(n_paper−1)))` ([`z_score_sd`], `se_from = sd`). Counts (`multitimer_runs_at_last_level`) have no z: the verdict is
//! exact equality (`se_from = exact`). Zero standard error: z = 0 when the numbers are equal,
//! ±∞ otherwise. The NaN, `n/a` and `both-nan` cases are those of the old rule.

use super::bisection::BisectionModel;
use super::fi::FiModel;
use super::multitimer::MtCell;
use super::reference::{
    PAPER_RUNS, PaperNumber, appendix_fi_numbers, appendix_numbers, lab_model,
    multitimer_2_10_numbers, numbers,
};
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
    /// `paper` (printed in the paper) or `notebook` (only in the notebook's output).
    pub source: String,
    /// The paper's number.
    pub paper: f64,
    /// The paper's SD over runs for this number (NaN where it prints none).
    pub paper_sd: f64,
    /// The paper's runs behind `paper_sd` (or behind the paper's SD in the `*_sd` rows; 0
    /// where it prints no SD).
    pub paper_n: usize,
    /// The lab's number (same statistic).
    pub lab_mean: f64,
    /// The lab's spread over runs.
    pub lab_sd: f64,
    /// Runs behind the lab's number.
    pub n: usize,
    /// `(lab − paper) / combined standard error` (NaN where undefined; see the module docs).
    pub z: f64,
    /// Which standard errors `z` uses: `lab+paper`, `lab`, `sd` or `exact`.
    pub se_from: String,
    /// Old rule: `yes`, `no`, `n/a` or `both-nan` (see the module docs).
    pub agree: String,
    /// Discriminating rule `|z| ≤ 2`: `yes`, `no`, `n/a` or `both-nan`.
    pub agree_z: String,
}

/// The threshold of the discriminating rule: agree when `|z| ≤ Z_AGREE`.
pub const Z_AGREE: f64 = 2.0;

/// `(lab − paper) / √(lab_sd²/n_lab + paper_sd²/n_paper)`; the paper's term is left out when
/// `paper_sd` is NaN or `n_paper` is 0. NaN when either value is NaN, when `n_lab < 2` or
/// the lab's SD is NaN; 0 when the standard error is 0 and the values are equal, ±∞ when it
/// is 0 and they differ.
pub fn z_score(
    lab: f64,
    lab_sd: f64,
    n_lab: usize,
    paper: f64,
    paper_sd: f64,
    n_paper: usize,
) -> f64 {
    if !lab.is_finite() || !paper.is_finite() || n_lab < 2 || !lab_sd.is_finite() {
        return f64::NAN;
    }
    let mut var = lab_sd * lab_sd / n_lab as f64;
    if paper_sd.is_finite() && n_paper > 0 {
        var += paper_sd * paper_sd / n_paper as f64;
    }
    let d = lab - paper;
    if var == 0.0 {
        return if d == 0.0 {
            0.0
        } else {
            d.signum() * f64::INFINITY
        };
    }
    d / var.sqrt()
}

/// `z` of an SD against an SD on the log scale (the SD of a sample SD grows with the SD):
/// `ln(lab_sd / paper_sd) / √(1/(2(n_lab−1)) + 1/(2(n_paper−1)))` — the large-sample
/// standard error of `ln sd` is `1/√(2(n−1))`; the paper's term is left out when
/// `n_paper < 2`. ±∞ when exactly one SD is 0 (a printed 0.00 cannot be matched on a ratio
/// scale), 0 when both are; NaN when either is NaN or negative, or `n_lab < 2`.
pub fn z_score_sd(lab_sd: f64, n_lab: usize, paper_sd: f64, n_paper: usize) -> f64 {
    let ok = |x: f64| x.is_finite() && x >= 0.0;
    if n_lab < 2 || !ok(lab_sd) || !ok(paper_sd) {
        return f64::NAN;
    }
    match (lab_sd == 0.0, paper_sd == 0.0) {
        (true, true) => return 0.0,
        (true, false) => return f64::NEG_INFINITY,
        (false, true) => return f64::INFINITY,
        _ => {}
    }
    let mut v = 1.0 / (2.0 * (n_lab as f64 - 1.0));
    if n_paper >= 2 {
        v += 1.0 / (2.0 * (n_paper as f64 - 1.0));
    }
    (lab_sd / paper_sd).ln() / v.sqrt()
}

/// The discriminating verdict from a z and the two values: `both-nan`, `no` (only one
/// number), `n/a` (z undefined), else `yes` when `|z| ≤ Z_AGREE`.
pub fn agree_z(paper: f64, lab: f64, z: f64) -> String {
    match (paper.is_finite(), lab.is_finite()) {
        (false, false) => "both-nan".into(),
        (true, false) | (false, true) => "no".into(),
        _ if z.is_nan() => "n/a".into(),
        _ if z.abs() <= Z_AGREE + 1e-12 => "yes".into(),
        _ => "no".into(),
    }
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

/// The model a published number belongs to (its row or its column).
pub fn paper_model(p: &PaperNumber) -> &'static str {
    let is_model = |x: &str| ["CTRNN", "LSTM", "CNN"].iter().any(|m| x.starts_with(m));
    if is_model(p.row) { p.row } else { p.column }
}

/// The paper's SD of a per-run mean (the `*_sd` table beside `bisection_wf` / `_dl`), when
/// printed.
fn printed_sd(nums: &[PaperNumber], p: &PaperNumber) -> Option<f64> {
    let sd_table = match p.table {
        "bisection_wf" => "bisection_wf_sd",
        "bisection_dl" => "bisection_dl_sd",
        "appendix_wf" => "appendix_wf_sd",
        "appendix_dl" => "appendix_dl_sd",
        "multitimer_2_10_level_reward" => "multitimer_2_10_level_reward_sd",
        _ => return None,
    };
    nums.iter()
        .find(|q| q.table == sd_table && q.row == p.row && q.column == p.column)
        .map(|q| q.value)
        .filter(|v| v.is_finite())
}

/// Every comparison row the lab's results cover (rows whose model or condition the study
/// did not run are left out), each paper model against its faithful lab counterpart: the
/// main text's numbers, then the appendix's sizes 256 and 8 (bisection tables and the FI
/// notebook's numbers).
pub fn compare(fi: &[FiModel], bis: &[BisectionModel], mt: &[MtCell]) -> Vec<ComparisonRow> {
    let mut nums = numbers();
    nums.extend(appendix_numbers());
    nums.extend(appendix_fi_numbers());
    nums.extend(multitimer_2_10_numbers());
    compare_numbers(&nums, &|m| lab_model(m), fi, bis, mt)
}

/// The comparison rows of `nums`, each paper model `m` against the lab model `lab_of(m)`
/// (none: the number is left out) — [`compare`] with the faithful pairing, the negative
/// control of `agreement.json` with deliberately wrong ones.
pub fn compare_numbers(
    nums: &[PaperNumber],
    lab_of: &dyn Fn(&str) -> Option<&'static str>,
    fi: &[FiModel],
    bis: &[BisectionModel],
    mt: &[MtCell],
) -> Vec<ComparisonRow> {
    let mut out = Vec::new();
    for p in nums {
        let Some(lab) = lab_of(paper_model(p)) else {
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
        // The multi-timer cell of `lab` under `curriculum` on the table's TD list.
        let mt_cell = |table: &str, curriculum: &str| {
            let tds: &[u32] = if table.starts_with("multitimer_2_10") {
                &[2, 4, 6, 8, 10]
            } else {
                &[3, 6, 9, 12, 15]
            };
            mt.iter()
                .find(|c| c.model == lab && c.curriculum == curriculum && c.tds == tds)
        };
        let paper_sd = printed_sd(nums, p);
        let (psd, pn) = paper_sd.map_or((f64::NAN, 0), |sd| (sd, PAPER_RUNS));
        let se_from = if paper_sd.is_some() {
            "lab+paper"
        } else {
            "lab"
        };
        // (lab value, lab SD, runs, old verdict, z, se_from)
        let mean_row = |v: f64, sd: f64, n: usize| {
            (
                v,
                sd,
                n,
                agree_mean(p.value, v, sd, n),
                z_score(v, sd, n, p.value, psd, pn),
                se_from,
            )
        };
        let sd_row = |sd: f64, n: usize| {
            (
                sd,
                f64::NAN,
                n,
                agree_sd(p.value, sd, n),
                z_score_sd(sd, n, p.value, PAPER_RUNS),
                "sd",
            )
        };
        let value = match p.table {
            "fi_cv" => fi_cell(p.row).map(|c| mean_row(c.pooled.cv, c.run_cv.sd, c.run_cv.n)),
            "fi_foc_mean_notebook" | "appendix_fi_foc_mean_notebook" => {
                fi_cell(p.row).map(|c| mean_row(c.pooled.mean, c.run_mean.sd, c.run_mean.n))
            }
            "fi_foc_sd_notebook" => {
                fi_cell(p.row).map(|c| mean_row(c.pooled.sd, c.run_sd.sd, c.run_sd.n))
            }
            "fi_r2" | "fi_r2_notebook" | "appendix_fi_r2_notebook" => fi_m.map(|m| {
                let (v, s) = if p.column == "mean_vs_td" {
                    (m.scalar.r2_mean_vs_td, m.run_r2_mean_vs_td)
                } else {
                    (m.scalar.r2_sd_vs_mean, m.run_r2_sd_vs_mean)
                };
                let mut row = mean_row(v, s.sd, s.n);
                // A regression over fewer than three TDs says nothing yet.
                if m.cells.len() < 3 {
                    row.3 = "n/a".into();
                    row.4 = f64::NAN;
                }
                row
            }),
            "bisection_wf" | "appendix_wf" => {
                bis_cell(p.row).map(|c| mean_row(c.wf.mean, c.wf.sd, c.wf.n))
            }
            "bisection_dl" | "appendix_dl" => {
                bis_cell(p.row).map(|c| mean_row(c.dl.mean, c.dl.sd, c.dl.n))
            }
            "bisection_wf_sd" | "appendix_wf_sd" => {
                bis_cell(p.row).map(|c| sd_row(c.wf.sd, c.wf.n))
            }
            "bisection_dl_sd" | "appendix_dl_sd" => {
                bis_cell(p.row).map(|c| sd_row(c.dl.sd, c.dl.n))
            }
            "multitimer_level" | "multitimer_2_10_level" => {
                mt_cell(p.table, p.column).map(|c| mean_row(c.level.mean, c.level.sd, c.level.n))
            }
            "multitimer_2_10_level_reward" => p
                .column
                .rsplit_once(" level ")
                .and_then(|(curriculum, level)| {
                    let level: usize = level.parse().ok()?;
                    mt_cell(p.table, curriculum)?.level_eval.get(level).copied()
                })
                .filter(|x| x.n > 0)
                .map(|x| mean_row(x.mean, x.sd, x.n)),
            "multitimer_runs_at_last_level" | "multitimer_2_10_runs_at_last_level" => {
                mt_cell(p.table, p.column).map(|c| {
                    let v = c.reached_last as f64;
                    let ok = if v == p.value { "yes" } else { "no" };
                    (v, f64::NAN, c.runs.len(), ok.to_string(), f64::NAN, "exact")
                })
            }
            _ => None,
        };
        if let Some((lab_mean, lab_sd, n, agree, z, se_from)) = value {
            // Counts compare exactly; a row the old rule cannot judge (fewer than two runs, or
            // an R² over fewer than three TDs) has no z verdict either.
            let agree_z = if se_from == "exact" || agree == "n/a" {
                agree.clone()
            } else {
                agree_z(p.value, lab_mean, z)
            };
            let (paper_sd, paper_n) = match se_from {
                "lab+paper" => (psd, pn),
                "sd" => (f64::NAN, PAPER_RUNS),
                _ => (f64::NAN, 0),
            };
            out.push(ComparisonRow {
                table: p.table.into(),
                row: p.row.into(),
                column: p.column.into(),
                source: p.source.as_str().into(),
                paper: p.value,
                paper_sd,
                paper_n,
                lab_mean,
                lab_sd,
                n,
                z,
                se_from: se_from.into(),
                agree,
                agree_z,
            });
        }
    }
    out
}
