//! `report.html` of a paper study: one self-contained page (inline SVG, no external
//! resources) with how many of the paper's numbers the lab reproduces per table, every
//! comparison row, and the study's figures in the paper's form.

use super::claims::{p_text, z_text};
use super::compare::ComparisonRow;
use super::study::PaperStudy;
use crate::agreement::Counts;
use crate::reference::APPENDIX_PREFIX;
use chronocooked_analysis::collect::{CollectError, err};
use chronocooked_present::figures::markup::{figure, inline_svg, page};
use maud::{Markup, html};
use std::path::{Path, PathBuf};

/// The figures the page shows, in order: (file stem, caption, full width).
const FIGURES: [(&str, &str, bool); 7] = [
    (
        "fi_foc",
        "Fixed interval: every first oven check per TD (dots, pooled over runs × start cells), the per-TD mean and FOC = TD",
        true,
    ),
    (
        "fi_scalar",
        "Mean FOC vs TD and SD vs mean FOC (scalar property), with each model's regression line",
        false,
    ),
    (
        "bisection_grid",
        "Bisection: run-averaged P(long) per probe for every model × anchor pair, the paper's least-squares fit and the lab's binomial maximum-likelihood fit; AM/GM = arithmetic/geometric mean of the anchors",
        true,
    ),
    (
        "wf_vs_ratio",
        "Weber fraction of the averaged curve against log2(L/S), per model with its regression line",
        false,
    ),
    (
        "multitimer",
        "Multi-timer: training reward per curriculum level (and, where the run kept them, each level's own policy in the notebook's test setting), the final policy's reward and oven-off time at every tested TD (vertical lines: trained TDs; the rest are out of distribution)",
        true,
    ),
    (
        "multitimer_levels",
        "Multi-timer, the paper's form: each curriculum level's policy (Timers = 1 … 5) on every TD 1 … its longest + 1 — mean reward and mean oven-off time (cells where the soup was taken) per model; the level's trained TDs marked",
        true,
    ),
    (
        "exact_timer",
        "Exact timer: reward against the test buffer (% of TD) per TD and model, ± SD over runs as dots; grey: the reduced reward 0.1 of any delivery (the paper's red dotted line)",
        true,
    ),
];

fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.3}")
    } else {
        "NaN".into()
    }
}

/// Per comparison table × source: (table, source, rows, agree under the old rule, agree
/// under the z rule, n/a or both NaN under the old rule).
fn agreement_by_table(rows: &[ComparisonRow]) -> Vec<(String, String, usize, usize, usize, usize)> {
    let mut out: Vec<(String, String, usize, usize, usize, usize)> = Vec::new();
    for r in rows {
        let i = match out.iter().position(|t| t.0 == r.table && t.1 == r.source) {
            Some(i) => i,
            None => {
                out.push((r.table.clone(), r.source.clone(), 0, 0, 0, 0));
                out.len() - 1
            }
        };
        let t = &mut out[i];
        t.2 += 1;
        t.3 += usize::from(r.agree == "yes");
        t.4 += usize::from(r.agree_z == "yes");
        t.5 += usize::from(r.agree != "yes" && r.agree != "no");
    }
    out
}

/// What the page's numbers mean (its first paragraph), after the number of jobs.
const INTRO: &str = " finished jobs. Old rule: a paper number agrees when it lies in the lab's 95% interval; z rule: |z| ≤ 2, z = difference over the combined standard error of the two means (";

/// The agreement per comparison table, counted over the numbers printed in the paper.
fn agreement_table(s: &PaperStudy) -> Markup {
    let by_table = agreement_by_table(&s.comparison);
    // The main text's printed numbers lead; the appendix's sizes 8 and 256 apart.
    let sum = |appendix: bool| {
        by_table
            .iter()
            .filter(|t| t.1 == "paper" && t.0.starts_with(APPENDIX_PREFIX) == appendix)
            .fold((0, 0, 0), |(n, y, z), t| (n + t.2, y + t.3, z + t.4))
    };
    let (n, yes, yes_z) = sum(false);
    let (an, ayes, ayes_z) = sum(true);
    html! {
        h2.group {
            "Numbers printed in the paper's main text: " (yes_z) " of " (n)
            " agree under the z rule (" (yes) " under the old rule)"
            @if an > 0 {
                "; appendix, sizes 8 and 256: " (ayes_z) " of " (an) " (" (ayes) ")"
            }
        }
        table {
            tr {
                th { "table" } th { "source" } th { "numbers" } th { "agree (old rule)" }
                th { "agree (z rule)" } th { "n/a or both NaN" }
            }
            @for (t, src, rows, a, z, o) in &by_table {
                tr { td { (t) } td { (src) } td { (rows) } td { (a) } td { (z) } td { (o) } }
            }
        }
    }
}

/// The negative control (unmatched pairings) beside the faithful ones, per rule.
fn negative_control_table(s: &PaperStudy) -> Markup {
    let nc = &s.agreement.negative_control;
    let cell = |k: &Counts| format!("{} of {}", k.yes, k.yes + k.no);
    html! {
        h2.group {
            "Negative control (matched = false) beside the faithful pairs: yes of (yes + no)"
        }
        table {
            tr { th { "pairing" } th { "matched" } th { "source" } th { "old rule" } th { "z rule" } }
            @for c in nc.iter().filter(|c| c.rule == "old" && c.counts.rows > 0) {
                @let z = nc
                    .iter()
                    .find(|x| x.pairing == c.pairing && x.source == c.source && x.rule == "z");
                tr {
                    td { (c.pairing) } td { (c.matched) } td { (c.source) } td { (cell(&c.counts)) }
                    td { (z.map_or("–".into(), |z| cell(&z.counts))) }
                }
            }
        }
    }
}

/// The peak-interval verdicts (`pi.csv`).
fn pi_table(s: &PaperStudy) -> Markup {
    html! {
        h2.group { "Peak interval: uniform checking after the TD (pi.csv)" }
        table {
            tr {
                th { "model" } th { "factor" } th { "curves" } th { "uniform" }
                th { "non-uniform" } th { "no checks" } th { "verdict" }
            }
            @for v in &s.pi_verdicts {
                tr {
                    td { (v.model) } td { (v.factor) } td { (v.curves) } td { (v.uniform) }
                    td { (v.non_uniform) } td { (v.no_checks) } td { (v.verdict) }
                }
            }
        }
    }
}

/// The paper's statements in words, tested (`claims.csv`; the verdict rows).
fn claims_table(s: &PaperStudy) -> Markup {
    html! {
        h2.group { "The paper's statements in words, tested (claims.csv)" }
        table.text {
            tr {
                th { "statement" } th { "setting" } th { "test" } th { "lab" } th { "z" }
                th { "p" } th { "verdict" }
            }
            @for r in s.claims.iter().filter(|r| r.summary) {
                tr {
                    td { (r.statement) } td { (r.setting) } td { (r.test) } td { (r.lab) }
                    td { (z_text(r.z)) } td { (p_text(r.p)) } td { (r.verdict) }
                }
            }
        }
    }
}

/// Every comparison row (`comparison.csv`).
fn comparison_table(s: &PaperStudy) -> Markup {
    html! {
        h2.group { "Every comparison row" }
        table {
            tr {
                th { "table" } th { "row" } th { "column" } th { "source" } th { "paper" }
                th { "paper SD" } th { "lab mean" } th { "lab SD" } th { "runs" } th { "z" }
                th { "agree (old)" } th { "agree (z)" }
            }
            @for r in &s.comparison {
                tr {
                    td { (r.table) } td { (r.row) } td { (r.column) } td { (r.source) }
                    td { (number(r.paper)) } td { (number(r.paper_sd)) }
                    td { (number(r.lab_mean)) } td { (number(r.lab_sd)) } td { (r.n) }
                    td { (number(r.z)) } td { (r.agree) } td { (r.agree_z) }
                }
            }
        }
    }
}

/// Writes `report.html` into `root`, inlining the figures found in `figures`; returns its path.
pub fn write_paper_report(
    root: &Path,
    s: &PaperStudy,
    figures: &Path,
) -> Result<PathBuf, CollectError> {
    let name = root
        .file_name()
        .map_or("study".into(), |n| n.to_string_lossy().to_string());
    let mut shown = Vec::new();
    for (stem, caption, wide) in FIGURES {
        let svg = figures.join(format!("{stem}.svg"));
        if svg.is_file() {
            let body = inline_svg(&svg).map_err(|m| err(&svg, m))?;
            shown.push(figure(body, caption, wide.then_some("wide")));
        }
    }
    let h = page(
        &format!("{name}: the paper reproduced"),
        html! {
            p {
                (s.jobs) (INTRO) code { "compare.rs" } ", " code { "agreement.json" }
                " with its negative control); the full tables are in " code { "tables.md" }
                ", the rows below in " code { "comparison.csv" } "."
            }
            (agreement_table(s))
            (negative_control_table(s))
            @if !s.pi_verdicts.is_empty() { (pi_table(s)) }
            @if !s.claims.is_empty() { (claims_table(s)) }
            @for f in &shown { (f) }
            (comparison_table(s))
        },
    );
    let path = root.join("report.html");
    chronocooked_env::fs::write_atomic(&path, h.as_bytes()).map_err(|e| err(&path, e.error))?;
    Ok(path)
}
