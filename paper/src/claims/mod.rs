//! `claims.csv`: the paper's statements in words about fixed interval, the exact timer and
//! the multi-timer — made without a number (its exact-timer figure is empty in the source,
//! its FI and multi-timer figures have no table) — each tested on the lab's runs.
//!
//! Every test is on means over runs ([`MeanTest`], `stats.rs`): two models, `d = a − b`
//! with `se = √(s_a²/n_a + s_b²/n_b)`, Welch's t on Satterthwaite's degrees of freedom; one
//! model against a fixed value `v`, `d = a − v`, `se = s_a/√n_a`, t on `n_a − 1`; where every
//! run of a side is the same value, the exact randomisation (sign-flip) test. `z` = `d/se` is
//! reported beside the two-sided `p`. Verdicts:
//!
//! * `holds` — the data show what the statement says (`p` < [`SIGNIFICANCE`] with `d` in
//!   its direction; for "equally well" and "at the minimum", an equivalence test: the 95%
//!   interval `d ± t·se` within [`EQUIVALENCE_MARGIN`]);
//! * `contradicted` — they show the opposite (significant the other way; for equivalence,
//!   the whole interval beyond the margin);
//! * `not shown` — neither (a difference too small, or too noisy, to tell);
//! * `n/a` — no test: a side without at least two runs. A "generally" verdict counts only
//!   the settings with a test and needs at least [`MIN_SETTINGS`] of them.
//!
//! A fixed-interval run is summarised by its share of first oven checks at 0 (checking from
//! the oven's start) and its mean FOC / TD, over its episodes with a check. An exact-timer
//! run is summarised by its reward averaged over the test buffers (0, 25, 50
//! and 75% of TD on either side: the paper's figure's x-axis), each buffer the mean over the
//! start cells. The paper's CTRNN is the lab's reservoir CTRNN
//! ([`lab_model`]); the lab's trained CTRNN is tested beside it
//! in rows marked as not in the paper.
//!
//! One file per task family: `fi.rs`, `bisection.rs`, `exact.rs` (the exact timer),
//! `multitimer.rs`; here the row, the verdict rules and the shared tests.

use super::reference::lab_model;
use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_env::markdown::Table;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

mod bisection;
mod exact;
mod fi;
mod multitimer;
mod stats;

pub use bisection::bisection_claims;
pub use exact::{exact_timer_claims, exact_timer_run_means};
pub use fi::{fi_claims, fi_run_stat};
pub use multitimer::{capacity_claims, multitimer_claims, shift_claims};
pub use stats::{MeanTest, SIGNIFICANCE};

/// The minimum reward of a delivered soup in the exact timer (outside the window).
pub const REDUCED_REWARD: f64 = 0.1;

/// The shortest TD of the paper's exact-timer statements ("at the shortest target duration
/// (TD = 4)").
pub const PAPER_SHORTEST_TD: u32 = 4;

/// Reward over a curriculum level's trained TDs at which a run counts as performing them
/// (the curriculum's pass threshold for two to five timers).
pub const PERFORMS: f64 = 0.9;

/// One line of `claims.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// Short id of the statement (`exact_lstm_best`, …).
    pub claim: String,
    /// What the paper says (its words, shortened).
    pub statement: String,
    /// Where it is tested: task and TD, or TD list (steps).
    pub setting: String,
    /// The test applied.
    pub test: String,
    /// The lab's numbers behind the verdict (mean ± SD over runs, runs in brackets).
    pub lab: String,
    /// The test's `d/se` (NaN where there is none; ±∞ for a difference between sides whose
    /// runs each have one value).
    pub z: f64,
    /// The test's two-sided p (NaN where there is none).
    pub p: f64,
    /// `holds`, `contradicted`, `not shown` or `n/a`.
    pub verdict: String,
    /// A statement's verdict (`true`) or one setting behind a "generally" verdict.
    pub summary: bool,
}

/// Verdict of a one-directional statement from its test (`d` > 0: the statement's
/// direction): `holds` / `contradicted` when significant that way / the other way, `n/a`
/// without a test.
pub fn directional(t: Option<MeanTest>) -> &'static str {
    match t {
        None => "n/a",
        Some(t) if t.significant() && t.d > 0.0 => "holds",
        Some(t) if t.significant() && t.d < 0.0 => "contradicted",
        Some(_) => "not shown",
    }
}

/// Reward difference within which two means count as "equally well" / "at the minimum":
/// one reduced reward (0.1), the task's own smallest step of reward.
pub const EQUIVALENCE_MARGIN: f64 = 0.1;

/// Verdict of an "equally well" statement on a difference of means (an equivalence test:
/// a non-significant difference alone is not evidence of equality): `holds` when the whole
/// 95% interval `d ± t·se` lies within ±`margin`; `contradicted` when the whole interval lies
/// beyond it and the difference is significant; else `not shown`; `n/a` without a test.
/// "At the minimum" is the same test on one model's mean minus the minimum.
pub fn equal(t: Option<MeanTest>, margin: f64) -> &'static str {
    let Some(t) = t else { return "n/a" };
    let half = t.half_width();
    if t.d.abs() + half <= margin + 1e-12 {
        "holds"
    } else if t.d.abs() - half > margin && t.significant() {
        "contradicted"
    } else {
        "not shown"
    }
}

/// Verdict of an "at most `margin` above" statement (one-sided equivalence, "at the
/// minimum"): `holds` when the 95% interval's upper end `d + t·se` is at most `margin` (below
/// it counts too); `contradicted` when its lower end is above `margin` and the difference is
/// significant; else `not shown`; `n/a` without a test.
pub fn at_most(t: Option<MeanTest>, margin: f64) -> &'static str {
    let Some(t) = t else { return "n/a" };
    let half = t.half_width();
    if t.d + half <= margin + 1e-12 {
        "holds"
    } else if t.d - half > margin && t.significant() {
        "contradicted"
    } else {
        "not shown"
    }
}

/// Verdict of a statement that no case out of `cases` goes against it: `n/a` without cases,
/// `holds` when none of them does (`against` = 0), else `contradicted`.
pub fn unless_any(cases: usize, against: usize) -> &'static str {
    match (cases, against) {
        (0, _) => "n/a",
        (_, 0) => "holds",
        _ => "contradicted",
    }
}

/// Settings (TDs, pairs, levels) a "generally" statement needs tested before it can hold or
/// be contradicted: one or two settings are a single observation, not a generality.
pub const MIN_SETTINGS: usize = 3;

/// Verdict of a "generally" statement from its per-setting verdicts: `n/a` without a
/// testable setting; `not shown` below [`MIN_SETTINGS`] tested; `holds` when it holds in
/// more than half the tested settings and is contradicted in none; `contradicted` when it is
/// contradicted in more than half; else `not shown`.
pub fn general<'a>(verdicts: impl IntoIterator<Item = &'a str>) -> &'static str {
    let v: Vec<&str> = verdicts.into_iter().filter(|v| *v != "n/a").collect();
    if v.is_empty() {
        return "n/a";
    }
    if v.len() < MIN_SETTINGS {
        return "not shown";
    }
    let holds = v.iter().filter(|v| **v == "holds").count();
    let against = v.iter().filter(|v| **v == "contradicted").count();
    if 2 * against > v.len() {
        "contradicted"
    } else if 2 * holds > v.len() && against == 0 {
        "holds"
    } else {
        "not shown"
    }
}

fn fmt_spread(s: &Spread) -> String {
    match s.n {
        0 => "no runs".into(),
        1 => format!("{:.2} (1)", s.mean),
        n => format!("{:.2} ± {:.2} ({n})", s.mean, s.sd),
    }
}

/// `(z, p)` of a test for a row (NaN without one).
fn z_p(t: Option<MeanTest>) -> (f64, f64) {
    t.map_or((f64::NAN, f64::NAN), |t| (t.z, t.p))
}

/// `d ± t·se` for a row's lab text (`–` without a test).
fn interval_text(t: Option<MeanTest>) -> String {
    t.map_or("–".into(), |t| {
        format!("{:.3} ± {:.3}", t.d, t.half_width())
    })
}

const LSTM: &str = "lstm125";
const CNN: &str = "cnn-mlp";
const TRAINED_CTRNN: &str = "ctrnn125";
/// The lab's trained CTRNN at the paper's larger size (the paper ran only reservoirs).
const TRAINED_CTRNN_256: &str = "ctrnn256";

fn paper_ctrnn() -> &'static str {
    lab_model("CTRNN125").unwrap_or("ctrnn-reservoir125")
}

/// The models LSTM125 is compared with ("the other two models"), with the lab's trained
/// CTRNN beside them.
fn others() -> [(&'static str, &'static str); 3] {
    [
        (paper_ctrnn(), "the paper's CTRNN125 (lab: reservoir)"),
        (CNN, "the CNN"),
        (
            TRAINED_CTRNN,
            "the lab's trained CTRNN125 (not in the paper)",
        ),
    ]
}

/// The CTRNNs a statement about "CTRNN125" is tested on, with their names in the rows: the
/// paper's (the lab's reservoir) and the lab's trained one.
fn ctrnns() -> [(&'static str, &'static str); 2] {
    [
        (paper_ctrnn(), "CTRNN125 (lab: reservoir)"),
        (
            TRAINED_CTRNN,
            "the lab's trained CTRNN125 (not in the paper)",
        ),
    ]
}

/// A "generally" statement over settings (TDs, levels): one row per setting `unit x` of
/// `task` (`sides` gives the per-run statistic of
/// each side the test names, `test_of` the statement's test from them, `d` > 0 in its
/// direction; `n/a` where a side has no runs) and a verdict row over every setting by
/// [`general`].
#[allow(clippy::too_many_arguments)]
fn per_setting_statement<T: Copy + std::fmt::Display>(
    rows: &mut Vec<ClaimRow>,
    claim: &str,
    statement: &str,
    (task, unit): (&str, &str),
    test: &str,
    tds: &[T],
    sides: impl Fn(T) -> Vec<Spread>,
    test_of: impl Fn(&[Spread]) -> Option<MeanTest>,
) {
    let mut verdicts = Vec::new();
    for &td in tds {
        let v = sides(td);
        let t = test_of(&v);
        let verdict = if v.iter().any(|s| s.n == 0) {
            "n/a"
        } else {
            directional(t)
        };
        let (z, p) = z_p(t);
        verdicts.push(verdict);
        rows.push(ClaimRow {
            claim: claim.into(),
            statement: statement.into(),
            setting: format!("{task}, {unit} {td}"),
            test: test.into(),
            lab: v.iter().map(fmt_spread).collect::<Vec<_>>().join(" vs "),
            z,
            p,
            verdict: verdict.into(),
            summary: false,
        });
    }
    rows.push(general_row(claim, statement, (task, unit), &verdicts));
}

/// The verdict row of a "generally" statement over every setting (`unit`s of `task`) from
/// the settings' `verdicts` ([`general`]).
fn general_row(
    claim: &str,
    statement: &str,
    (task, unit): (&str, &str),
    verdicts: &[&str],
) -> ClaimRow {
    let count = |v: &str| verdicts.iter().filter(|x| **x == v).count();
    ClaimRow {
        claim: claim.into(),
        statement: statement.into(),
        setting: format!("{task}, every {unit}"),
        test: format!(
            "holds at more than half the tested {unit}s (at least {MIN_SETTINGS}) and contradicted at none"
        ),
        lab: format!(
            "{} of {} {unit}s hold, {} contradicted{}",
            count("holds"),
            verdicts.len() - count("n/a"),
            count("contradicted"),
            match count("n/a") {
                0 => String::new(),
                k => format!(" ({k} untested: a side below two runs)"),
            }
        ),
        z: f64::NAN,
        p: f64::NAN,
        verdict: general(verdicts.iter().copied()).into(),
        summary: true,
    }
}

fn tds_label(tds: &[u32]) -> String {
    tds.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Markdown: the summary rows (and single-setting statements) with their verdicts.
pub fn claims_markdown(m: &mut String, rows: &[ClaimRow]) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        m,
        "\n## The paper's statements in words, tested (`claims.csv`)\n\nMeans over runs: Welch's t (the exact randomisation test where each side's runs share one value), two-sided p < 0.05; z = d/se. \"Equally well\" and \"at the minimum\": the 95% interval of the difference within 0.1. A \"generally\" verdict needs at least 3 tested settings (each TD, pair or level behind it is a row of `claims.csv`).\n"
    );
    let mut table =
        Table::new(["statement", "setting", "test", "lab", "z", "p", "verdict"]).right([4, 5]);
    for r in rows.iter().filter(|r| r.summary) {
        table.row([
            r.statement.to_string(),
            r.setting.to_string(),
            r.test.to_string(),
            r.lab.to_string(),
            z_text(r.z),
            p_text(r.p),
            r.verdict.to_string(),
        ]);
    }
    m.push_str(&table.render());
}

/// A p for tables: 3 decimals (`< 0.001` below), `–` for none.
pub fn p_text(p: f64) -> String {
    if p.is_nan() {
        "–".into()
    } else if p < 0.001 {
        "< 0.001".into()
    } else {
        format!("{p:.3}")
    }
}

/// A z for tables: 2 decimals, `–` for none, `±∞`.
pub fn z_text(z: f64) -> String {
    if z.is_finite() {
        format!("{z:.2}")
    } else if z.is_nan() {
        "–".into()
    } else if z > 0.0 {
        "+∞".into()
    } else {
        "−∞".into()
    }
}
