//! `report.html` of a paper study: one self-contained page (inline SVG, no external
//! resources) with how many of the paper's numbers the lab reproduces per table, every
//! comparison row, and the study's figures in the paper's form.

use super::collect::{CollectError, err};
use super::compare::ComparisonRow;
use super::study::PaperStudy;
use crate::report::{STYLE, escape, inline_svg};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The figures the page shows, in order: (file stem, caption, full width).
const FIGURES: [(&str, &str, bool); 5] = [
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
        "Multi-timer: training reward per curriculum level, the final policy's reward and oven-off time at every tested TD (vertical lines: trained TDs; the rest are out of distribution)",
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

/// Writes `report.html` into `root`, inlining the figures found in `figures`; returns its path.
pub fn write_paper_report(
    root: &Path,
    s: &PaperStudy,
    figures: &Path,
) -> Result<PathBuf, CollectError> {
    let name = root
        .file_name()
        .map_or("study".into(), |n| n.to_string_lossy().to_string());
    let mut h = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{0}: the paper reproduced</title>\n<style>{STYLE}</style></head><body>\n<h1>{0}: the paper reproduced</h1>\n<p>{1} finished jobs. Old rule: a paper number agrees when it lies in the lab's 95% interval; z rule: |z| ≤ 2, z = difference over the combined standard error of the two means (<code>compare.rs</code>, <code>agreement.json</code> with its negative control); the full tables are in <code>tables.md</code>, the rows below in <code>comparison.csv</code>.</p>\n",
        escape(&name),
        s.jobs
    );
    let by_table = agreement_by_table(&s.comparison);
    let printed = by_table.iter().filter(|t| t.1 == "paper");
    let (n, yes, yes_z) = printed.fold((0, 0, 0), |(n, y, z), t| (n + t.2, y + t.3, z + t.4));
    let _ = writeln!(
        h,
        "<h2 class=\"group\">Numbers printed in the paper: {yes_z} of {n} agree under the z rule ({yes} under the old rule)</h2>\n<table>\n<tr><th>table</th><th>source</th><th>numbers</th><th>agree (old rule)</th><th>agree (z rule)</th><th>n/a or both NaN</th></tr>"
    );
    for (t, src, rows, a, z, o) in &by_table {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{rows}</td><td>{a}</td><td>{z}</td><td>{o}</td></tr>",
            escape(t),
            escape(src)
        );
    }
    h += "</table>\n<h2 class=\"group\">Negative control (matched = false) beside the faithful pairs: yes of (yes + no)</h2>\n<table>\n<tr><th>pairing</th><th>matched</th><th>source</th><th>old rule</th><th>z rule</th></tr>\n";
    let nc = &s.agreement.negative_control;
    for c in nc.iter().filter(|c| c.rule == "old") {
        let z = nc
            .iter()
            .find(|x| x.pairing == c.pairing && x.source == c.source && x.rule == "z");
        let cell = |k: &crate::paper::agreement::Counts| format!("{} of {}", k.yes, k.yes + k.no);
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(&c.pairing),
            c.matched,
            escape(&c.source),
            cell(&c.counts),
            z.map_or("–".into(), |z| cell(&z.counts))
        );
    }
    h += "</table>\n<h2 class=\"group\">Peak interval: uniform checking after the TD (pi.csv)</h2>\n<table>\n<tr><th>model</th><th>factor</th><th>curves</th><th>uniform</th><th>non-uniform</th><th>no checks</th><th>verdict</th></tr>\n";
    for v in &s.pi_verdicts {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(&v.model),
            v.factor,
            v.curves,
            v.uniform,
            v.non_uniform,
            v.no_checks,
            escape(&v.verdict)
        );
    }
    h += "</table>\n";
    for (stem, caption, wide) in FIGURES {
        let svg = figures.join(format!("{stem}.svg"));
        if !svg.is_file() {
            continue;
        }
        let body = inline_svg(&svg).map_err(|m| err(&svg, m))?;
        let class = if wide { " class=\"wide\"" } else { "" };
        let _ = writeln!(
            h,
            "<figure{class}>{body}<figcaption>{}</figcaption></figure>",
            escape(caption)
        );
    }
    h += "<h2 class=\"group\">Every comparison row</h2>\n<table>\n<tr><th>table</th><th>row</th><th>column</th><th>source</th><th>paper</th><th>paper SD</th><th>lab mean</th><th>lab SD</th><th>runs</th><th>z</th><th>agree (old)</th><th>agree (z)</th></tr>\n";
    for r in &s.comparison {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(&r.table),
            escape(&r.row),
            escape(&r.column),
            escape(&r.source),
            number(r.paper),
            number(r.paper_sd),
            number(r.lab_mean),
            number(r.lab_sd),
            r.n,
            number(r.z),
            escape(&r.agree),
            escape(&r.agree_z)
        );
    }
    h += "</table>\n</body></html>\n";
    let path = root.join("report.html");
    chronocooked_env::fs::write_atomic(&path, h.as_bytes()).map_err(|e| err(&path, e.error))?;
    Ok(path)
}
