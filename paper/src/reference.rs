//! The paper's published numbers that the paper-core study covers: its tables (FI CV, FI
//! R², bisection WF and DL for CTRNN125 / LSTM125) and the numbers printed in its
//! notebooks (pooled FI FOC means and SDs, R² as the notebook prints it now, multi-timer
//! levels reached), with where each comes from ([`Source`]: the paper's tables in
//! `chronocooked-paper.tex`, or only the notebook's output). NaN = the paper prints NaN.

/// One published number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperNumber {
    /// Table name (`fi_cv`, `bisection_wf`, …).
    pub table: &'static str,
    /// Row (TD, anchor pair `S-L`, model).
    pub row: &'static str,
    /// Column (the paper's model name, or the statistic).
    pub column: &'static str,
    /// The value.
    pub value: f64,
    /// Printed in the paper, or only in the authors' notebook output.
    pub source: Source,
}

/// Where a published number is printed.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Hash,
    Serialize,
    Deserialize,
    strum::IntoStaticStr,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum Source {
    /// A table of the paper (`chronocooked-paper.tex`).
    Paper,
    /// Only the output cells of the authors' notebooks (`docs/paper-protocol.md` §4).
    Notebook,
}

impl Source {
    /// `paper` or `notebook` (the `source` column of `comparison.csv`).
    pub fn as_str(self) -> &'static str {
        self.into()
    }
}

/// Training runs behind each of the paper's per-run means and SDs (WF, DL): logs 1–4 of
/// the authors' scripts (`docs/paper-protocol.md` §2.2; the paper does not print how many of
/// them survived its exclusion rule, so 4 is an upper bound).
pub const PAPER_RUNS: usize = 4;

const N: f64 = f64::NAN;
use Source::{Notebook, Paper};
use serde::{Deserialize, Serialize};

/// The paper's model names and the lab's faithful counterparts (the paper's CTRNN is an
/// untrained reservoir: see docs/training.md).
pub const MODELS: [(&str, &str); 3] = [
    ("CTRNN125", "ctrnn-reservoir125"),
    ("LSTM125", "lstm125"),
    ("CNN", "cnn-mlp"),
];

/// Prefix of the tables that hold the appendix's sizes 8 and 256 (counted apart from the
/// main text's tables).
pub const APPENDIX_PREFIX: &str = "appendix_";

/// The appendix's sizes (`tab:wf_supp`, `tab:dl_supp`) and the lab's faithful counterparts.
pub const APPENDIX_MODELS: [(&str, &str); 4] = [
    ("CTRNN256", "ctrnn-reservoir256"),
    ("LSTM256", "lstm256"),
    ("CTRNN8", "ctrnn-reservoir8"),
    ("LSTM8", "lstm8"),
];

/// The lab model of a paper model name (main text or appendix).
pub fn lab_model(paper: &str) -> Option<&'static str> {
    MODELS
        .iter()
        .chain(&APPENDIX_MODELS)
        .find(|(p, _)| *p == paper)
        .map(|(_, l)| *l)
}

fn rows(
    source: Source,
    table: &'static str,
    column: &'static str,
    keys: &[&'static str],
    values: &[f64],
) -> Vec<PaperNumber> {
    keys.iter()
        .zip(values)
        .map(|(&row, &value)| PaperNumber {
            table,
            row,
            column,
            value,
            source,
        })
        .collect()
}

/// FI target durations.
pub const TDS: [&str; 6] = ["4", "6", "9", "12", "18", "24"];
/// Bisection anchor pairs in the paper's table order.
pub const ANCHORS: [&str; 6] = ["6-8", "4-8", "6-12", "4-12", "6-18", "4-18"];

/// Every number, in table order.
pub fn numbers() -> Vec<PaperNumber> {
    let mut v = Vec::new();
    // Paper, Table "Coefficient of Variation" (FI).
    v.extend(rows(
        Paper,
        "fi_cv",
        "CTRNN125",
        &TDS,
        &[N, N, 1.14, 2.34, 0.27, 0.05],
    ));
    v.extend(rows(
        Paper,
        "fi_cv",
        "LSTM125",
        &TDS,
        &[0.42, 0.41, 0.33, 0.27, 0.11, 0.24],
    ));
    // Paper, Table "R²" (FI scalar property).
    v.extend(rows(
        Paper,
        "fi_r2",
        "mean_vs_td",
        &["CTRNN125", "LSTM125"],
        &[0.9, 0.97],
    ));
    v.extend(rows(
        Paper,
        "fi_r2",
        "sd_vs_mean",
        &["CTRNN125", "LSTM125"],
        &[0.02, 0.43],
    ));
    // FI notebook (current outputs), pooled FOC means and SDs, and R².
    v.extend(rows(
        Notebook,
        "fi_foc_mean_notebook",
        "LSTM125",
        &TDS,
        &[3.98, 5.63, 9.02, 11.46, 18.19, 22.75],
    ));
    v.extend(rows(
        Notebook,
        "fi_foc_mean_notebook",
        "CTRNN125",
        &TDS,
        &[2.52, 3.71, 2.86, 7.14, 13.03, 18.92],
    ));
    v.extend(rows(
        Notebook,
        "fi_foc_mean_notebook",
        "CNN",
        &TDS,
        &[0.06, 0.06, 0.81, 0.00, 0.75, 0.81],
    ));
    v.extend(rows(
        Notebook,
        "fi_foc_sd_notebook",
        "LSTM125",
        &TDS,
        &[0.53, 1.23, 0.96, 2.13, 2.43, 2.72],
    ));
    v.extend(rows(
        Notebook,
        "fi_foc_sd_notebook",
        "CTRNN125",
        &TDS,
        &[1.44, 1.88, 3.21, 3.61, 3.70, 4.25],
    ));
    v.extend(rows(
        Notebook,
        "fi_r2_notebook",
        "mean_vs_td",
        &["CTRNN125", "LSTM125"],
        &[0.95, 1.00],
    ));
    v.extend(rows(
        Notebook,
        "fi_r2_notebook",
        "sd_vs_mean",
        &["CTRNN125", "LSTM125"],
        &[0.62, 0.85],
    ));
    // Paper, Tables "Weber fraction" and "Difference limen" (mean and SD over runs).
    v.extend(rows(
        Paper,
        "bisection_wf",
        "CTRNN125",
        &ANCHORS,
        &[N, N, 0.05, 0.04, 0.04, 0.06],
    ));
    v.extend(rows(
        Paper,
        "bisection_wf",
        "LSTM125",
        &ANCHORS,
        &[0.04, 0.09, 0.07, 0.13, 0.15, 0.14],
    ));
    v.extend(rows(
        Paper,
        "bisection_wf_sd",
        "CTRNN125",
        &ANCHORS,
        &[N, N, 0.06, 0.05, 0.00, 0.00],
    ));
    v.extend(rows(
        Paper,
        "bisection_wf_sd",
        "LSTM125",
        &ANCHORS,
        &[0.05, 0.03, 0.01, 0.02, 0.04, 0.06],
    ));
    v.extend(rows(
        Paper,
        "bisection_dl",
        "CTRNN125",
        &ANCHORS,
        &[N, N, 0.46, 0.26, 0.48, 0.59],
    ));
    v.extend(rows(
        Paper,
        "bisection_dl",
        "LSTM125",
        &ANCHORS,
        &[0.29, 0.50, 0.62, 1.04, 1.69, 1.19],
    ));
    v.extend(rows(
        Paper,
        "bisection_dl_sd",
        "CTRNN125",
        &ANCHORS,
        &[N, N, 0.53, 0.33, 0.02, 0.08],
    ));
    v.extend(rows(
        Paper,
        "bisection_dl_sd",
        "LSTM125",
        &ANCHORS,
        &[0.30, 0.12, 0.10, 0.28, 0.23, 0.42],
    ));
    // Multi-timer notebook (TDs 3, 6, …, 15): CTRNN125 exact "never left env0" (4 runs);
    // no LSTM125 exact run reached the 5-timer level. The exact CTRNN script starts training
    // at env1 (one timer, undercooking possible) while its level counter starts at 0
    // (`docs/paper-protocol.md` §5.10), so its "env0" is the one-timer level: level 1 in the
    // code's env numbering, which the lab's levels follow (0 = warm-up).
    v.extend(rows(
        Notebook,
        "multitimer_level",
        "exact",
        &["CTRNN125"],
        &[1.0],
    ));
    v.extend(rows(
        Notebook,
        "multitimer_runs_at_last_level",
        "exact",
        &["LSTM125"],
        &[0.0],
    ));
    v
}

/// The multi-timer notebooks' numbers on the TD list 2, 4, 6, 8, 10 (`docs/paper-protocol.md`
/// §4; the lab's study: `sweeps/paper-multitimer.toml`), every one a notebook output:
/// * `multitimer_2_10_level`, exact CTRNN125: its logs reached the script's `env1` and
///   stayed; the exact CTRNN script starts at `env1` under level counter 0, so counter 1 is
///   the one-timer level again: level 1 in the lab's numbering (0 = warm-up).
/// * `multitimer_2_10_runs_at_last_level`: no exact LSTM125 or CNN run reached five timers;
///   categorical LSTM125 and CTRNN125 reached them on all 4 logs.
/// * `multitimer_2_10_level_reward` (+ `_sd`): categorical LSTM125, each level's checkpoint
///   in its test setting, mean and SD over logs 1–4 of the printed per-log rewards (levels
///   2–5: 0.85/0.79/0.82/0.82, 0.96/0.95/0.83/0.83, 0.94/0.85/0.89/0.94, 0.92/0.00/0.84/0.89;
///   the protocol notes that some of these tables come from an older version that also
///   tested untrained TDs).
pub fn multitimer_2_10_numbers() -> Vec<PaperNumber> {
    let mut v = Vec::new();
    v.extend(rows(
        Notebook,
        "multitimer_2_10_level",
        "exact",
        &["CTRNN125"],
        &[1.0],
    ));
    v.extend(rows(
        Notebook,
        "multitimer_2_10_runs_at_last_level",
        "exact",
        &["LSTM125", "CNN"],
        &[0.0, 0.0],
    ));
    v.extend(rows(
        Notebook,
        "multitimer_2_10_runs_at_last_level",
        "categorical",
        &["LSTM125", "CTRNN125"],
        &[4.0, 4.0],
    ));
    let per_log: [(&'static str, [f64; 4]); 4] = [
        ("categorical level 2", [0.85, 0.79, 0.82, 0.82]),
        ("categorical level 3", [0.96, 0.95, 0.83, 0.83]),
        ("categorical level 4", [0.94, 0.85, 0.89, 0.94]),
        ("categorical level 5", [0.92, 0.00, 0.84, 0.89]),
    ];
    for (column, logs) in per_log {
        let s = chronocooked_analysis::stats::Spread::of(logs);
        v.extend(rows(
            Notebook,
            "multitimer_2_10_level_reward",
            column,
            &["LSTM125"],
            &[s.mean],
        ));
        v.extend(rows(
            Notebook,
            "multitimer_2_10_level_reward_sd",
            column,
            &["LSTM125"],
            &[s.sd],
        ));
    }
    v
}

/// The appendix's Weber fraction and difference limen tables at sizes 256 and 8
/// (`tab:wf_supp`, `tab:dl_supp`: mean and SD over runs per anchor pair; the 6-8 row and
/// every size-8 entry are printed as NaN) as tables `appendix_wf`, `appendix_wf_sd`,
/// `appendix_dl` and `appendix_dl_sd` (kept apart from the main text's `bisection_*` tables
/// so that each is counted on its own in `agreement.json`).
pub fn appendix_numbers() -> Vec<PaperNumber> {
    let mut v = Vec::new();
    v.extend(rows(
        Paper,
        "appendix_wf",
        "CTRNN256",
        &ANCHORS,
        &[N, 0.29, 0.03, 0.11, 0.06, 0.07],
    ));
    v.extend(rows(
        Paper,
        "appendix_wf",
        "LSTM256",
        &ANCHORS,
        &[N, 0.08, 0.06, 0.09, 0.14, 0.18],
    ));
    v.extend(rows(
        Paper,
        "appendix_wf_sd",
        "CTRNN256",
        &ANCHORS,
        &[N, 0.34, 0.02, 0.03, 0.04, 0.00],
    ));
    v.extend(rows(
        Paper,
        "appendix_wf_sd",
        "LSTM256",
        &ANCHORS,
        &[N, 0.01, 0.01, 0.03, 0.09, 0.02],
    ));
    v.extend(rows(
        Paper,
        "appendix_dl",
        "CTRNN256",
        &ANCHORS,
        &[N, 0.68, 0.28, 0.63, 0.73, 0.46],
    ));
    v.extend(rows(
        Paper,
        "appendix_dl",
        "LSTM256",
        &ANCHORS,
        &[N, 0.46, 0.50, 0.70, 1.30, 1.75],
    ));
    v.extend(rows(
        Paper,
        "appendix_dl_sd",
        "CTRNN256",
        &ANCHORS,
        &[N, 0.61, 0.20, 0.18, 0.45, 0.06],
    ));
    v.extend(rows(
        Paper,
        "appendix_dl_sd",
        "LSTM256",
        &ANCHORS,
        &[N, 0.06, 0.07, 0.24, 0.95, 0.04],
    ));
    for model in ["CTRNN8", "LSTM8"] {
        for table in [
            "appendix_wf",
            "appendix_wf_sd",
            "appendix_dl",
            "appendix_dl_sd",
        ] {
            v.extend(rows(Paper, table, model, &ANCHORS, &[N; 6]));
        }
    }
    v
}

/// The size-8 numbers: the appendix's WF and DL entries (all printed as NaN) and the FI
/// notebook's pooled FOC means and R² of LSTM8 and CTRNN8 (`docs/paper-protocol.md` §4;
/// "–" there = NaN here), for the size control of `agreement.json` (paper size 8 against
/// the lab's size 256, or its size 125 where 256 has not run).
pub fn size8_numbers() -> Vec<PaperNumber> {
    let mut v: Vec<PaperNumber> = appendix_numbers()
        .into_iter()
        .filter(|p| ["CTRNN8", "LSTM8"].contains(&p.column))
        .collect();
    v.extend(appendix_fi_numbers().into_iter().filter(|p| {
        [p.row, p.column]
            .iter()
            .any(|m| ["CTRNN8", "LSTM8"].contains(m))
    }));
    v
}

/// The FI notebook's pooled FOC means and R² at sizes 8 and 256 (source notebook, tables
/// `appendix_fi_foc_mean_notebook` and `appendix_fi_r2_notebook`; `docs/paper-protocol.md`
/// §4; "–" there = NaN here).
pub fn appendix_fi_numbers() -> Vec<PaperNumber> {
    let mut v = Vec::new();
    v.extend(rows(
        Notebook,
        "appendix_fi_foc_mean_notebook",
        "LSTM256",
        &TDS,
        &[3.96, 5.90, 8.67, 11.96, 17.13, 23.73],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_foc_mean_notebook",
        "CTRNN256",
        &TDS,
        &[1.97, 4.56, 6.78, 8.83, 12.53, 16.92],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_r2_notebook",
        "mean_vs_td",
        &["CTRNN256", "LSTM256"],
        &[0.99, 1.00],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_r2_notebook",
        "sd_vs_mean",
        &["CTRNN256", "LSTM256"],
        &[0.79, 0.98],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_foc_mean_notebook",
        "LSTM8",
        &TDS,
        &[3.39, 3.92, 5.59, 12.50, N, 10.85],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_foc_mean_notebook",
        "CTRNN8",
        &TDS,
        &[0.0, 0.0, 7.58, 6.17, 5.44, N],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_r2_notebook",
        "mean_vs_td",
        &["CTRNN8", "LSTM8"],
        &[0.44, 0.57],
    ));
    v.extend(rows(
        Notebook,
        "appendix_fi_r2_notebook",
        "sd_vs_mean",
        &["CTRNN8", "LSTM8"],
        &[0.35, 0.35],
    ));
    v
}

/// The human reference the paper sets WF-vs-log2(L/S) against: (r, p).
pub const HUMAN_WF_VS_RATIO: (f64, f64) = (0.323, 0.04);
