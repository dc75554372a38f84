//! `claims.csv`: the paper's statements in words about fixed interval, the exact timer and
//! the multi-timer — made without a number (its exact-timer figure is empty in the source,
//! its FI and multi-timer figures have no table) — each tested on the lab's runs.
//!
//! Every test is a z on means over runs, with the comparison's threshold
//! ([`Z_AGREE`](super::compare::Z_AGREE) = 2): two models, `(a − b)/√(s_a²/n_a + s_b²/n_b)`;
//! one model against a fixed value `v`, `(a − v)/(s_a/√n_a)`. Verdicts:
//!
//! * `holds` — the data show what the statement says (`z` beyond the threshold in its
//!   direction; for "equally well" and "at the minimum", an equivalence test: the difference
//!   ± 2 standard errors within [`EQUIVALENCE_MARGIN`]);
//! * `contradicted` — they show the opposite (beyond the threshold the other way);
//! * `not shown` — neither (a difference too small, or too noisy, to tell);
//! * `n/a` — no test: a side without at least two runs. A "generally" verdict counts only
//!   the settings with a test.
//!
//! A fixed-interval run is summarised by its share of first oven checks at 0 (checking from
//! the oven's start) and its mean FOC / TD, over its episodes with a check. An exact-timer
//! run is summarised by its reward averaged over the test buffers (0, 25, 50
//! and 75% of TD on either side: the paper's figure's x-axis), each buffer the mean over the
//! start cells. The paper's CTRNN is the lab's reservoir CTRNN
//! ([`lab_model`](super::reference::lab_model)); the lab's trained CTRNN is tested beside it
//! in rows marked as not in the paper.

use super::collect::CompactJob;
use super::compare::{Z_AGREE, z_score};
use super::fi::{fi_runs, run_focs};
use super::multitimer::{LEVELS, MtCell, buffer_rewards, exact_timer_groups};
use super::reference::lab_model;
use super::spreads::{ConditionStat, condition_stats};
use crate::behaviour::aggregate::Spread;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write as _;

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
    /// The test's z (NaN where there is none).
    pub z: f64,
    /// `holds`, `contradicted`, `not shown` or `n/a`.
    pub verdict: String,
    /// A statement's verdict (`true`) or one setting behind a "generally" verdict.
    pub summary: bool,
}

/// Verdict of a one-directional statement from its z (positive: the statement's direction).
pub fn directional(z: f64) -> &'static str {
    if z.is_nan() {
        "n/a"
    } else if z > Z_AGREE {
        "holds"
    } else if z < -Z_AGREE {
        "contradicted"
    } else {
        "not shown"
    }
}

/// Reward difference within which two means count as "equally well" / "at the minimum":
/// one reduced reward (0.1), the task's own smallest step of reward.
pub const EQUIVALENCE_MARGIN: f64 = 0.1;

/// Verdict of an "equally well" statement on the difference `d` of two means with standard
/// error `se`: `contradicted` when `|d/se| > 2`; `holds` when the whole interval `d ± 2·se`
/// lies within ±[`EQUIVALENCE_MARGIN`] (an equivalence test: a non-significant difference
/// alone is not evidence of equality); else `not shown`; `n/a` without a standard error.
pub fn equal(d: f64, se: f64) -> &'static str {
    if d.is_nan() || se.is_nan() {
        "n/a"
    } else if d.abs() > Z_AGREE * se {
        "contradicted"
    } else if d.abs() + Z_AGREE * se <= EQUIVALENCE_MARGIN + 1e-12 {
        "holds"
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

/// Verdict of a "generally" statement from its per-setting verdicts: `holds` when it holds
/// in at least half the settings and is contradicted in none, `contradicted` when it is
/// contradicted in at least half, `n/a` without a testable setting, else `not shown`.
pub fn general<'a>(verdicts: impl IntoIterator<Item = &'a str>) -> &'static str {
    let v: Vec<&str> = verdicts.into_iter().filter(|v| *v != "n/a").collect();
    if v.is_empty() {
        return "n/a";
    }
    let holds = v.iter().filter(|v| **v == "holds").count();
    let against = v.iter().filter(|v| **v == "contradicted").count();
    if 2 * against >= v.len() {
        "contradicted"
    } else if 2 * holds >= v.len() && against == 0 {
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

/// Rewards are stored as `f32`: means closer than this are the same reward (0.1 as `f32`
/// is 1.5e-9 above 0.1, which over a zero SD would be an infinite z).
const SAME: f64 = 1e-6;

/// `(a − b, its standard error)` of two means over runs (NaN below two runs on a side).
fn difference(a: &Spread, b: &Spread) -> (f64, f64) {
    if a.n < 2 || b.n < 2 {
        return (f64::NAN, f64::NAN);
    }
    let se = (a.sd * a.sd / a.n as f64 + b.sd * b.sd / b.n as f64).sqrt();
    (a.mean - b.mean, se)
}

fn two_sample(a: &Spread, b: &Spread) -> f64 {
    if a.n < 2 || b.n < 2 {
        return f64::NAN;
    }
    if (a.mean - b.mean).abs() < SAME {
        return 0.0;
    }
    z_score(a.mean, a.sd, a.n, b.mean, b.sd, b.n)
}

fn against_value(a: &Spread, v: f64) -> f64 {
    if a.n < 2 {
        return f64::NAN;
    }
    if (a.mean - v).abs() < SAME {
        return 0.0;
    }
    z_score(a.mean, a.sd, a.n, v, f64::NAN, 0)
}

/// Per exact-timer (model, TD): each run's reward averaged over its test buffers.
pub fn exact_timer_run_means(jobs: &[CompactJob]) -> BTreeMap<(String, u32), Spread> {
    exact_timer_groups(jobs)
        .into_iter()
        .map(|((model, td), js)| {
            let runs = js.iter().filter_map(|j| {
                let b = buffer_rewards(j, td);
                (!b.is_empty()).then(|| b.iter().map(|x| x.1).sum::<f64>() / b.len() as f64)
            });
            ((model.to_string(), td), Spread::of(runs))
        })
        .collect()
}

const LSTM: &str = "lstm125";
const CNN: &str = "cnn-mlp";
const TRAINED_CTRNN: &str = "ctrnn125";

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

/// The exact timer's statements (the paper's Results, "For the exact timing case …").
pub fn exact_timer_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let means = exact_timer_run_means(jobs);
    if means.is_empty() {
        return Vec::new();
    }
    let empty = Spread::of([]);
    let get = |m: &str, td: u32| means.get(&(m.to_string(), td)).unwrap_or(&empty);
    let mut tds: Vec<u32> = means.keys().map(|k| k.1).collect();
    tds.sort_unstable();
    tds.dedup();
    let mut rows = Vec::new();

    // LSTM125 generally outperforms the other two models.
    for (other, name) in others() {
        per_setting_statement(
            &mut rows,
            "exact_lstm_best",
            &format!("LSTM125 generally outperforms {name}"),
            ("exact timer", "TD"),
            &format!("lstm125 − {other}, mean reward over buffers: z > 2"),
            &tds,
            |td| vec![*get(LSTM, td), *get(other, td)],
            |v| two_sample(&v[0], &v[1]),
        );
    }

    {
        let td = PAPER_SHORTEST_TD;
        // At the shortest TD, LSTM125 and CTRNN125 perform equally well.
        for (other, name) in ctrnns() {
            let (a, b) = (get(LSTM, td), get(other, td));
            let z = two_sample(a, b);
            let (d, se) = difference(a, b);
            rows.push(ClaimRow {
                claim: "exact_shortest_equal".into(),
                statement: format!("at the shortest TD, LSTM125 and {name} perform equally well"),
                setting: format!("exact timer, TD {td}"),
                test: format!(
                    "lstm125 − {other}, mean reward over buffers: d ± 2·se within ±{EQUIVALENCE_MARGIN} (|z| > 2: contradicted)"
                ),
                lab: format!(
                    "{} vs {}; d = {}",
                    fmt_spread(a),
                    fmt_spread(b),
                    if d.is_nan() { "–".into() } else { format!("{d:.3} ± {:.3}", Z_AGREE * se) }
                ),
                z,
                verdict: equal(d, se).into(),
                summary: true,
            });
        }
        // At the shortest TD the CNN earns above the minimum 0.1.
        let a = get(CNN, td);
        let z = against_value(a, REDUCED_REWARD);
        rows.push(ClaimRow {
            claim: "exact_cnn_above_min".into(),
            statement: "at the shortest TD the CNN earns above the minimum reward 0.1".into(),
            setting: format!("exact timer, TD {td}"),
            test: "cnn-mlp mean reward over buffers − 0.1: z > 2".into(),
            lab: fmt_spread(a),
            z,
            verdict: directional(z).into(),
            summary: true,
        });
        // … and that does not generalise to longer TDs.
        let mut per_td = Vec::new();
        for &long in tds.iter().filter(|t| **t > td) {
            let b = get(CNN, long);
            // At the longer TD the CNN is at the minimum: significantly above 0.1 goes
            // against it; its whole interval mean + 2·se within the equivalence margin of
            // 0.1 shows it; anything between does not tell.
            let z = against_value(b, REDUCED_REWARD);
            let upper = b.mean + Z_AGREE * b.sd / (b.n as f64).sqrt();
            let verdict = if z.is_nan() || b.n < 2 {
                "n/a"
            } else if z > Z_AGREE {
                "contradicted"
            } else if upper <= REDUCED_REWARD + EQUIVALENCE_MARGIN + 1e-12 {
                "holds"
            } else {
                "not shown"
            };
            per_td.push(verdict);
            rows.push(ClaimRow {
                claim: "exact_cnn_short_only".into(),
                statement: "the CNN's timing does not generalise to longer TDs".into(),
                setting: format!("exact timer, TD {long}"),
                test: format!(
                    "cnn-mlp mean reward over buffers: mean + 2·se ≤ 0.1 + {EQUIVALENCE_MARGIN} (z > 2 above 0.1: contradicted)"
                ),
                lab: fmt_spread(b),
                z,
                verdict: verdict.into(),
                summary: false,
            });
        }
        let against = per_td.iter().filter(|v| **v == "contradicted").count();
        let tested = per_td.iter().filter(|v| **v != "n/a").count();
        rows.push(ClaimRow {
            claim: "exact_cnn_short_only".into(),
            statement: "the CNN's timing does not generalise to longer TDs".into(),
            setting: "exact timer, every TD past the shortest".into(),
            test: "holds at every longer TD".into(),
            lab: format!(
                "{} of {tested} longer TDs at the minimum, {against} above it",
                per_td.iter().filter(|v| **v == "holds").count()
            ),
            z: f64::NAN,
            verdict: if per_td.contains(&"not shown") && against == 0 {
                "not shown"
            } else {
                unless_any(tested, against)
            }
            .into(),
            summary: true,
        });
    }
    rows
}

/// One FI run's statistics: share of its FOCs at 0 and its mean FOC / TD, over its
/// episodes with a check (`None` for a run without one).
pub fn fi_run_stat(job: &CompactJob, td: u32) -> Option<(f64, f64)> {
    let f = run_focs(job, false);
    (!f.is_empty()).then(|| {
        let n = f.len() as f64;
        let zero = f.iter().filter(|x| **x == 0.0).count() as f64 / n;
        (zero, f.iter().sum::<f64>() / n / f64::from(td))
    })
}

/// A "generally" statement over settings (TDs, levels): one row per setting `unit x` of
/// `task` (`sides` gives the per-run statistic of
/// each side the test names, `z_of` the statement's z from them; `n/a` where a side has no
/// runs) and a verdict row over every setting by [`general`].
#[allow(clippy::too_many_arguments)]
fn per_setting_statement<T: Copy + std::fmt::Display>(
    rows: &mut Vec<ClaimRow>,
    claim: &str,
    statement: &str,
    (task, unit): (&str, &str),
    test: &str,
    tds: &[T],
    sides: impl Fn(T) -> Vec<Spread>,
    z_of: impl Fn(&[Spread]) -> f64,
) {
    let mut verdicts = Vec::new();
    for &td in tds {
        let v = sides(td);
        let z = z_of(&v);
        let verdict = if v.iter().any(|s| s.n == 0) {
            "n/a"
        } else {
            directional(z)
        };
        verdicts.push(verdict);
        rows.push(ClaimRow {
            claim: claim.into(),
            statement: statement.into(),
            setting: format!("{task}, {unit} {td}"),
            test: test.into(),
            lab: v.iter().map(fmt_spread).collect::<Vec<_>>().join(" vs "),
            z,
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
        test: format!("holds at ≥ half the {unit}s and contradicted at none"),
        lab: format!(
            "{} of {} {unit}s hold, {} contradicted",
            count("holds"),
            verdicts.len() - count("n/a"),
            count("contradicted")
        ),
        z: f64::NAN,
        verdict: general(verdicts.iter().copied()).into(),
        summary: true,
    }
}

/// The bisection statements (the paper's Results, "Bisection task"): "LSTM125 performs
/// better than its biologically plausible recurrent counterpart CTRNN125" and "for a higher
/// memory size (256) the two models have comparable performance", on the psychometric
/// curves' anchor accuracy (each kept run's share of correct answers at the two anchors:
/// `spreads::condition_stats`), per anchor pair; "comparable" is the equivalence test
/// ([`equal`]).
pub fn bisection_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let stats: Vec<ConditionStat> = condition_stats(jobs)
        .into_iter()
        .filter(|c| c.task == "Bisection-v0" && c.statistic == "anchor_accuracy")
        .collect();
    if stats.is_empty() {
        return Vec::new();
    }
    let mut pairs: Vec<&str> = stats.iter().map(|c| c.condition.as_str()).collect();
    pairs.sort_by_key(|p| {
        let (a, b) = p.split_once('-').unwrap_or((p, ""));
        (a.parse::<u32>().unwrap_or(0), b.parse::<u32>().unwrap_or(0))
    });
    pairs.dedup();
    let acc = |m: &str, pair: &str| {
        stats
            .iter()
            .find(|c| c.model == m && c.condition == pair)
            .map_or(Spread::of([]), |c| c.spread)
    };
    let task = "bisection";
    let mut rows = Vec::new();
    for (other, name) in ctrnns() {
        per_setting_statement(
            &mut rows,
            "bisection_lstm_better",
            &format!("LSTM125 performs better than {name}"),
            (task, "pair"),
            &format!("anchor accuracy per kept run, lstm125 − {other}: z > 2"),
            &pairs,
            |p| vec![acc(LSTM, p), acc(other, p)],
            |v| two_sample(&v[0], &v[1]),
        );
    }
    let (lstm256, ctrnn256) = (
        lab_model("LSTM256").unwrap_or("lstm256"),
        lab_model("CTRNN256").unwrap_or("ctrnn-reservoir256"),
    );
    let statement = "at size 256, LSTM256 and CTRNN256 (lab: reservoir) perform comparably";
    let mut verdicts = Vec::new();
    for &pair in &pairs {
        let (a, b) = (acc(lstm256, pair), acc(ctrnn256, pair));
        let (d, se) = difference(&a, &b);
        let verdict = equal(d, se);
        verdicts.push(verdict);
        rows.push(ClaimRow {
            claim: "bisection_256_comparable".into(),
            statement: statement.into(),
            setting: format!("{task}, pair {pair}"),
            test: format!(
                "anchor accuracy per kept run, {lstm256} − {ctrnn256}: d ± 2·se within ±{EQUIVALENCE_MARGIN}"
            ),
            lab: format!("{} vs {}", fmt_spread(&a), fmt_spread(&b)),
            z: two_sample(&a, &b),
            verdict: verdict.into(),
            summary: false,
        });
    }
    rows.push(general_row(
        "bisection_256_comparable",
        statement,
        (task, "pair"),
        &verdicts,
    ));
    rows
}

/// The fixed-interval statements (the paper's Results, "Fixed interval").
pub fn fi_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let runs = fi_runs(jobs);
    if runs.is_empty() {
        return Vec::new();
    }
    // Per-run statistic `stat` of (model, TD) across its runs.
    let across = |m: &str, td: u32, stat: fn((f64, f64)) -> f64| {
        let js = runs.get(m).and_then(|t| t.get(&td));
        Spread::of(
            js.into_iter()
                .flatten()
                .filter_map(|j| fi_run_stat(j, td).map(stat)),
        )
    };
    let zero = |s: (f64, f64)| s.0;
    let ratio = |s: (f64, f64)| s.1;
    let off = |s: (f64, f64)| (s.1 - 1.0).abs();
    let mut tds: Vec<u32> = runs.values().flat_map(|t| t.keys().copied()).collect();
    tds.sort_unstable();
    tds.dedup();
    let task = "fixed interval";
    let mut rows = Vec::new();
    per_setting_statement(
        &mut rows,
        "fi_cnn_foc_zero",
        "in most cases the CNN's first oven check is at 0 (checking from the start)",
        (task, "TD"),
        "cnn-mlp share of FOCs at 0 per run, against 0.5: z > 2",
        &tds,
        |td| vec![across(CNN, td, zero)],
        |v| against_value(&v[0], 0.5),
    );
    let reservoir = paper_ctrnn();
    for (other, name) in ctrnns() {
        per_setting_statement(
            &mut rows,
            "fi_lstm_closer",
            &format!("LSTM125's FOCs are closer to the TD than {name}'s"),
            (task, "TD"),
            &format!("|FOC/TD − 1| per run, {other} − lstm125: z > 2"),
            &tds,
            |td| vec![across(other, td, off), across(LSTM, td, off)],
            |v| two_sample(&v[0], &v[1]),
        );
        per_setting_statement(
            &mut rows,
            "fi_ctrnn_earlier",
            &format!("{name} checks the oven earlier than LSTM125"),
            (task, "TD"),
            &format!("FOC/TD per run, lstm125 − {other}: z > 2"),
            &tds,
            |td| vec![across(LSTM, td, ratio), across(other, td, ratio)],
            |v| two_sample(&v[0], &v[1]),
        );
    }
    let big = lab_model("CTRNN256").unwrap_or("ctrnn-reservoir256");
    per_setting_statement(
        &mut rows,
        "fi_ctrnn256_better",
        "at a higher memory size CTRNN256's FOCs improve on CTRNN125's (lab: reservoirs)",
        (task, "TD"),
        &format!("|FOC/TD − 1| per run, {reservoir} − {big}: z > 2"),
        &tds,
        |td| vec![across(reservoir, td, off), across(big, td, off)],
        |v| two_sample(&v[0], &v[1]),
    );
    rows
}

fn tds_label(tds: &[u32]) -> String {
    tds.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The five-timer curricula among `cells` (exact and categorical: the paper's figures do not
/// say which they show, so each statement is tested on both), as (curriculum, TD list).
fn five_timer_lists(cells: &[MtCell]) -> Vec<(&str, &[u32])> {
    let mut keys: Vec<(&str, &[u32])> = cells
        .iter()
        .filter(|c| c.tds.len() == LEVELS - 1)
        .map(|c| (c.curriculum.as_str(), c.tds.as_slice()))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// The cell of `model` under `curriculum` on `tds`.
fn cell_of<'a>(
    cells: &'a [MtCell],
    curriculum: &str,
    tds: &[u32],
    model: &str,
) -> Option<&'a MtCell> {
    cells
        .iter()
        .find(|c| c.curriculum == curriculum && c.tds == tds && c.model == model)
}

/// The multi-timer's statements ("While LSTM125 generally performs better than other models,
/// none of the models perform all the tasks successfully"), per five-timer curriculum: the
/// reward of each level's policy at its trained TDs (the figure's "Timers = L" panels) per
/// level, the curriculum level reached (`multitimer_lstm_further`, a coarser proxy), and
/// whether any run performs every timer — reached five timers with its five-timer policy
/// earning ≥ [`PERFORMS`] at each of the five trained TDs (in the notebooks' test setting
/// where the run kept its level policies, else the final policy in its training setting).
pub fn multitimer_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let mut rows = Vec::new();
    let levels: Vec<u32> = (1..LEVELS as u32).collect();
    for (curriculum, tds) in five_timer_lists(cells) {
        let cell = |m: &str| cell_of(cells, curriculum, tds, m);
        let task = format!("multi-timer {curriculum}, TDs {}", tds_label(tds));
        for (other, name) in others() {
            let reward = |m: &str, l: u32| {
                cell(m)
                    .and_then(|c| c.level_eval.get(l as usize).copied())
                    .unwrap_or(Spread::of([]))
            };
            per_setting_statement(
                &mut rows,
                "multitimer_lstm_best",
                &format!("LSTM125 generally performs better than {name}"),
                (&task, "level"),
                &format!(
                    "reward of each level's policy at its trained TDs, lstm125 − {other}: z > 2"
                ),
                &levels,
                |l| vec![reward(LSTM, l), reward(other, l)],
                |v| two_sample(&v[0], &v[1]),
            );
            let level = |m: &str| cell(m).map_or(Spread::of([]), |c| c.level);
            let (a, b) = (level(LSTM), level(other));
            let z = two_sample(&a, &b);
            rows.push(ClaimRow {
                claim: "multitimer_lstm_further".into(),
                statement: format!("LSTM125 gets further in the curriculum than {name} (a proxy of \"performs better\")"),
                setting: task.clone(),
                test: format!("lstm125 − {other}, curriculum level reached: z > 2"),
                lab: format!("{} vs {}", fmt_spread(&a), fmt_spread(&b)),
                z,
                verdict: if a.n == 0 || b.n == 0 { "n/a" } else { directional(z) }.into(),
                summary: true,
            });
        }
        let same: Vec<&MtCell> = cells
            .iter()
            .filter(|c| c.curriculum == curriculum && c.tds == tds)
            .collect();
        let total: usize = same.iter().map(|c| c.runs.len()).sum();
        let at_top: Vec<(&str, f64)> = same
            .iter()
            .flat_map(|c| {
                c.runs.iter().filter(|r| r.level == LEVELS - 1).map(|r| {
                    // The five-timer policy in the notebooks' test setting where the run
                    // kept it, else the final policy in the training setting.
                    let kept: Vec<f64> = r
                        .level_curves
                        .get(LEVELS - 1)
                        .map(|v| v.iter().filter(|p| p.trained).map(|p| p.reward).collect())
                        .unwrap_or_default();
                    let rewards = if kept.is_empty() {
                        r.per_td.iter().map(|x| x.1).collect()
                    } else {
                        kept
                    };
                    (
                        c.model.as_str(),
                        rewards.into_iter().fold(f64::INFINITY, f64::min),
                    )
                })
            })
            .collect();
        let performing: Vec<&str> = at_top
            .iter()
            .filter(|r| r.1 >= PERFORMS)
            .map(|r| r.0)
            .collect();
        rows.push(ClaimRow {
            claim: "multitimer_none_all".into(),
            statement: "none of the models perform all the tasks successfully".into(),
            setting: task,
            test: format!(
                "no run at five timers whose five-timer policy earns ≥ {PERFORMS} at each of the five TDs (notebooks' test setting)"
            ),
            lab: format!(
                "{} of {total} runs reach five timers, {} of them earn ≥ {PERFORMS} at every TD{}",
                at_top.len(),
                performing.len(),
                if performing.is_empty() { String::new() } else { format!(" ({})", performing.join(", ")) }
            ),
            z: f64::NAN,
            verdict: unless_any(total, performing.len()).into(),
            summary: true,
        });
    }
    rows
}

/// "CTRNN125 generally shows more shifts than LSTM125" (the multi-timer's oven-off curves,
/// each level's policy on every TD 1 … its longest + 1): per curriculum and five-TD list, the
/// timers each level's policy stores ([`timers_stored`](super::multitimer::timers_stored)),
/// CTRNN − LSTM per level 1 … 5 with the runs that kept that level, then over the levels.
/// The paper's figures do not say which curriculum they show, so both are tested.
pub fn shift_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let mut rows = Vec::new();
    let levels: Vec<u32> = (1..LEVELS as u32).collect();
    for (curriculum, tds) in five_timer_lists(cells) {
        let timers = |m: &str, level: u32| {
            cell_of(cells, curriculum, tds, m)
                .and_then(|c| c.level_timers.get(level as usize).copied())
                .unwrap_or(Spread::of([]))
        };
        let task = format!("multi-timer {curriculum}, TDs {}", tds_label(tds));
        for (ctrnn, name) in ctrnns() {
            per_setting_statement(
                &mut rows,
                "multitimer_ctrnn_more_shifts",
                &format!("{name} generally shows more shifts (timers stored) than LSTM125"),
                (&task, "level"),
                &format!("timers stored per run, {ctrnn} − lstm125: z > 2"),
                &levels,
                |l| vec![timers(ctrnn, l), timers(LSTM, l)],
                |v| two_sample(&v[0], &v[1]),
            );
        }
    }
    rows
}

/// "None of the models demonstrate a strong capacity to store multiple intervals or
/// generalize reliably to OOD durations": per five-timer curriculum, a model goes against it
/// when its five-timer policies (the runs that kept level 5), averaged over those runs, earn
/// at least [`PERFORMS`] at every one of the five trained TDs (stores the intervals) or at
/// every untrained TD 1 … 11 (generalises).
pub fn capacity_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let top = LEVELS - 1;
    five_timer_lists(cells)
        .into_iter()
        .map(|(curriculum, tds)| {
            // Per model with five-timer policies: (model, runs, worst trained-TD mean,
            // worst untrained-TD mean).
            let at_top: Vec<(&str, usize, f64, f64)> = cells
                .iter()
                .filter(|c| c.curriculum == curriculum && c.tds == tds)
                .filter_map(|c| {
                    let curves: Vec<_> = c
                        .runs
                        .iter()
                        .filter_map(|r| r.level_curves.get(top).filter(|v| !v.is_empty()))
                        .collect();
                    if curves.is_empty() {
                        return None;
                    }
                    let mut at: BTreeMap<(bool, u32), Vec<f64>> = BTreeMap::new();
                    for p in curves.iter().flat_map(|v| v.iter()) {
                        at.entry((p.trained, p.td)).or_default().push(p.reward);
                    }
                    let worst = |trained: bool| {
                        at.iter()
                            .filter(|((t, _), _)| *t == trained)
                            .map(|(_, v)| v.iter().sum::<f64>() / v.len() as f64)
                            .fold(f64::NAN, f64::min)
                    };
                    Some((c.model.as_str(), curves.len(), worst(true), worst(false)))
                })
                .collect();
            let strong: Vec<&str> = at_top
                .iter()
                .filter(|x| x.2 >= PERFORMS || x.3 >= PERFORMS)
                .map(|x| x.0)
                .collect();
            let lab = at_top
                .iter()
                .map(|(m, n, t, u)| format!("{m} {t:.2} / {u:.2} ({n})"))
                .collect::<Vec<_>>()
                .join("; ");
            ClaimRow {
                claim: "multitimer_no_strong_capacity".into(),
                statement: "none of the models store multiple intervals strongly or generalise reliably to OOD durations".into(),
                setting: format!("multi-timer {curriculum}, TDs {}", tds_label(tds)),
                test: format!(
                    "no model's five-timer policies earn ≥ {PERFORMS} at every trained TD, or at every untrained TD (lab: worst trained / worst untrained TD)"
                ),
                lab: if lab.is_empty() {
                    "no run kept a five-timer policy".into()
                } else if strong.is_empty() {
                    lab
                } else {
                    format!("{lab}; against: {}", strong.join(", "))
                },
                z: f64::NAN,
                verdict: unless_any(at_top.len(), strong.len()).into(),
                summary: true,
            }
        })
        .collect()
}

/// Markdown: the summary rows (and single-setting statements) with their verdicts.
pub fn claims_markdown(m: &mut String, rows: &[ClaimRow]) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        m,
        "\n## The paper's statements in words, tested (`claims.csv`)\n\nz on means over runs, threshold 2; \"equally well\" and \"at the minimum\": the difference ± 2 SE within 0.1 (each TD or level behind a \"generally\" verdict is a row of `claims.csv`).\n"
    );
    let _ = writeln!(m, "| statement | setting | test | lab | z | verdict |");
    let _ = writeln!(m, "|---|---|---|---|---:|---|");
    for r in rows.iter().filter(|r| r.summary) {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} | {} |",
            r.statement,
            r.setting,
            r.test,
            r.lab,
            z_text(r.z),
            r.verdict
        );
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
