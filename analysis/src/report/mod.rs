//! Leaderboard report from evaluation folders (`eval` outputs): one self-contained HTML page
//! (inline SVG figures, no external resources), Markdown and CSV. Rows = models (folders of
//! the same model are aggregated: mean ± SD over runs); columns = headline metrics.
//!
//! Submodules: [`leaderboard`] — rows and columns of the leaderboard; [`figures`] — the
//! SVG/PNG figures (plotters, bundled font).

pub mod baselines;
pub mod figures;
pub mod leaderboard;
pub mod mechanisms;

use crate::behaviour::aggregate::Spread;
pub use crate::report::leaderboard::{Row, load_metrics, load_rows, load_rows_from_runs};
use std::path::{Path, PathBuf};

/// What the `runs` column counts.
pub const RUNS_LEGEND: &str = "evaluation folders aggregated in the row (seeds, and task settings such as FI TDs); every other cell is the mean ± SD over the runs that have the metric";

/// What a row labelled `model (study)` is (rows with [`Row::baseline`]).
pub const BASELINE_LEGEND: &str = "rows labelled `model (study)` are committed baselines: the compact results of that study in the repository (results/<study>/jobs/, one run per job), grouped exactly as evaluation folders are";

/// What every column means and which direction is better.
pub const COLUMNS: [(&str, &str); 31] = [
    (
        "fi_success",
        "FI: full-reward deliveries at the trained TD (higher is better)",
    ),
    (
        "bisection_accuracy",
        "correct counter on the two anchors (higher is better)",
    ),
    ("bp", "bisection point of the logistic fit, steps"),
    (
        "bp_over_gm",
        "BP / geometric mean of the anchors (1 = geometric-mean bisection, as in animals)",
    ),
    ("bp_over_am", "BP / arithmetic mean of the anchors"),
    ("wf", "Weber fraction DL/BP (lower = sharper timing)"),
    (
        "wf_cv_anchors",
        "CV of the Weber fraction across anchor pairs (scalar timing: close to 0)",
    ),
    (
        "foc_over_td",
        "mean first oven check / TD (1 = checks exactly when the soup is ready)",
    ),
    (
        "foc_cv",
        "CV of the first oven check (scalar timing: constant across TDs)",
    ),
    ("r2_mean_vs_td", "R² of mean FOC vs TD (timing: close to 1)"),
    (
        "r2_sd_vs_mean",
        "R² of FOC SD vs mean (scalar property: close to 1)",
    ),
    (
        "pi_peak_over_td",
        "peak-interval response peak / TD (1 = peaks at the trained time)",
    ),
    ("pi_cv", "peak-interval spread / peak (lower = sharper)"),
    (
        "mt_reward",
        "multi-timer mean reward over TDs incl. OOD (higher is better)",
    ),
    ("mt_plateaus", "multi-timer timing plateaus (timers stored)"),
    (
        "dual_success",
        "dual task: soup delivered inside the reward window (higher is better)",
    ),
    ("dual_reward", "dual-task mean reward (soup + sink)"),
    (
        "unc_success",
        "uncertainty task: success with a normal oven (higher is better)",
    ),
    (
        "unc_button_use",
        "uncertainty task: button use when the oven never readies",
    ),
    (
        "unc_episodes_to_adapt",
        "uncertainty adaptation: episodes an agent trained without uncertainty plays until, in the last 100 episodes, 80% of the never-ready ovens are solved with the button and 80% of the normal ones without it (lower is better; runs that adapted)",
    ),
    (
        "unc_adapted",
        "uncertainty adaptation: fraction of runs that adapted within the budget (higher is better)",
    ),
    (
        "neural_units",
        "neural: units analysed in the primary population (constant units excluded), window 2 x TD after oven-on at the longest recorded TD",
    ),
    (
        "frac_ramp",
        "neural: fraction of ramps (time-locked, monotone fit R² ≥ 0.9); – below 10 units (counts in activity.summary.json)",
    ),
    (
        "frac_time_field",
        "neural: fraction of time fields (time-locked, one interior peak falling by half its range on both sides)",
    ),
    (
        "frac_oscillating",
        "neural: fraction of oscillating units (significant spectral peak with ≥ 2 cycles in the window, repeating autocorrelation)",
    ),
    (
        "frac_mixed",
        "neural: fraction of mixed units (time-locked with several or none of the three shapes)",
    ),
    (
        "frac_untuned",
        "neural: fraction of untuned units (not time-locked: circular-shift surrogate p > 0.05)",
    ),
    (
        "scaling",
        "neural: median per-unit temporal scaling factor from the shortest to the longest recorded TD (= TD ratio when activity stretches with the interval, 1 for a fixed clock)",
    ),
    (
        "speed_ratio",
        "neural: population trajectory speed at the longest TD over that at the shortest (= TD_short/TD_long when dynamics stretch)",
    ),
    (
        "sequentiality",
        "neural: sequentiality index (1 = tiling sequence, 0 = identical units)",
    ),
    (
        "decode_error",
        "neural: cross-validated ridge decoding error of elapsed time, steps (lower is better)",
    ),
];

/// Short, readable header of a headline column (units in parentheses); [`COLUMNS`] holds
/// the full description, shown as the header's tooltip and in the legend.
pub fn column_title(key: &str) -> &'static str {
    match key {
        "fi_success" | "dual_success" => "success",
        "bisection_accuracy" => "anchor accuracy",
        "bp" => "BP (steps)",
        "bp_over_gm" => "BP / GM",
        "bp_over_am" => "BP / AM",
        "wf" => "Weber fraction",
        "wf_cv_anchors" => "WF CV across pairs",
        "foc_over_td" => "first check / TD",
        "foc_cv" => "first-check CV",
        "r2_mean_vs_td" => "R² mean~TD",
        "r2_sd_vs_mean" => "R² SD~mean",
        "pi_peak_over_td" => "peak / TD",
        "pi_cv" => "spread / peak",
        "mt_reward" => "mean reward",
        "mt_plateaus" => "timers stored",
        "dual_reward" => "mean reward",
        "unc_success" => "success (normal oven)",
        "unc_button_use" => "button use (never ready)",
        "unc_episodes_to_adapt" => "episodes to adapt",
        "unc_adapted" => "runs adapted",
        "neural_units" => "units",
        "frac_ramp" => "ramps",
        "frac_time_field" => "time fields",
        "frac_oscillating" => "oscillating",
        "frac_mixed" => "mixed",
        "frac_untuned" => "untuned",
        "scaling" => "scaling (long/short)",
        "speed_ratio" => "speed ratio",
        "sequentiality" => "sequentiality",
        "decode_error" => "decoding error (steps)",
        _ => "other",
    }
}

fn cell(s: Option<&Spread>) -> String {
    match s {
        Some(s) if s.n > 1 && s.sd.is_finite() => format!("{:.3} ± {:.3}", s.mean, s.sd),
        Some(s) if s.mean.is_finite() => format!("{:.3}", s.mean),
        _ => "–".into(),
    }
}

pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The reports' style sheet: compact tables that fit a 1366 px window, figures as small
/// multiples two to a row (`figure.wide`: full width).
pub(crate) const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;max-width:1600px}table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #bbb;padding:3px 7px;text-align:right;white-space:nowrap;font-size:14px}th{background:#eee}td:first-child{text-align:left}h2.group{font-size:1.1em;margin:0.8em 0 0.3em}figure{display:inline-block;margin:0.5em;width:46%}figure.wide{width:96%}figure.panel{width:23.5%;margin:0.3em}figure.half{width:60%}figure svg,figure img{width:100%;height:auto}.card{border:1px solid #ccc;border-radius:4px;padding:0.3em 0.6em;margin:0.6em 0}.card h3{font-size:1em;margin:0.3em 0}.catbar{display:flex;width:100%;height:1.4em;font-size:12px;line-height:1.4em;color:#fff;overflow:hidden}.catbar span{white-space:nowrap;overflow:hidden;padding-left:3px;box-sizing:border-box}figcaption{font-size:13px}";

/// An SVG file as inline markup: the XML prolog and namespace URIs dropped (inline SVG in
/// HTML needs neither, and the page then holds no URL at all).
pub(crate) fn inline_svg(svg: &Path) -> Result<String, String> {
    let text = std::fs::read_to_string(svg).map_err(|e| format!("{}: {e}", svg.display()))?;
    let body = text.find("<svg").map_or(text.as_str(), |i| &text[i..]);
    Ok(body
        .replace(" xmlns=\"http://www.w3.org/2000/svg\"", "")
        .replace(" xmlns:xlink=\"http://www.w3.org/1999/xlink\"", ""))
}

/// Runs per row and task whose behaviour figures are inlined in the HTML (the other runs
/// are named, their figures stay in their folders): a sweep's report stays readable and
/// small (the demo's ≤ 2 MB).
pub const FIGURE_RUNS: usize = 1;

/// A figure as HTML: the SVG inline, or its PNG sibling (`stem.png`) as a base64 data URI
/// when that is smaller (heat maps: thousands of SVG rectangles, a few kB of PNG).
pub(crate) fn figure_markup(svg: &Path, caption: &str) -> Result<String, String> {
    use base64::Engine as _;
    let png = svg.with_extension("png");
    let svg_len = std::fs::metadata(svg)
        .map_err(|e| format!("{}: {e}", svg.display()))?
        .len();
    let png_len = std::fs::metadata(&png).map_or(u64::MAX, |m| m.len());
    let body = if png_len.saturating_mul(4) / 3 < svg_len {
        let bytes = std::fs::read(&png).map_err(|e| format!("{}: {e}", png.display()))?;
        format!(
            "<img alt=\"{}\" src=\"data:image/png;base64,{}\">",
            escape(caption),
            base64::engine::general_purpose::STANDARD.encode(bytes)
        )
    } else {
        inline_svg(svg)?
    };
    Ok(format!(
        "<figure>{body}<figcaption>{}</figcaption></figure>\n",
        escape(caption)
    ))
}

/// One row's figures: the behaviour figures of its first [`FIGURE_RUNS`] runs per task, the
/// other runs named. (Its neural activity is in the "Mechanisms" section's card; every
/// population's heat map stays in the run's `neural_figures/`.)
fn row_figures_html(r: &Row) -> Result<String, String> {
    use crate::report::leaderboard::{behaviour_figures, figure_caption};
    let mut html = String::new();
    let mut shown: Vec<(String, usize)> = Vec::new();
    let mut named = Vec::new();
    for run in &r.runs {
        let task = run_task(run);
        let count = match shown.iter_mut().find(|s| s.0 == task) {
            Some(s) => {
                s.1 += 1;
                s.1
            }
            None => {
                shown.push((task.clone(), 1));
                1
            }
        };
        if count > FIGURE_RUNS {
            named.push(run_caption(run));
            continue;
        }
        html += &format!("<h3>{}</h3>\n", escape(&run_caption(run)));
        for svg in behaviour_figures(run) {
            html += &figure_markup(&svg, &figure_caption(&svg))?;
        }
    }
    if !named.is_empty() {
        html += "<p>Other runs (figures in their folders):</p>\n<ul>\n";
        for n in named {
            html += &format!("<li>{}</li>\n", escape(&n));
        }
        html += "</ul>\n";
    }
    Ok(html)
}

/// Task of an evaluation folder (from `eval.json`).
fn run_task(folder: &Path) -> String {
    crate::records::read_eval_info(folder)
        .map(|info| info.task)
        .unwrap_or_else(|_| "unknown task".into())
}

/// Caption of one evaluation folder: its task and path.
fn run_caption(folder: &Path) -> String {
    format!("{} — {}", run_task(folder), folder.display())
}

/// Columns any row has, in [`COLUMNS`] order.
fn used_columns(rows: &[Row]) -> Vec<(&'static str, &'static str)> {
    COLUMNS
        .iter()
        .copied()
        .filter(|(k, _)| rows.iter().any(|r| r.values.contains_key(*k)))
        .collect()
}

/// The theme a headline column belongs to (the HTML report shows one table per theme).
pub fn column_group(key: &str) -> &'static str {
    match key {
        k if k == "fi_success" || k.starts_with("foc_") || k.starts_with("r2_") => "Fixed interval",
        k if k.starts_with("pi_") => "Peak interval",
        k if k.starts_with("bisection") || k.starts_with("bp") || k.starts_with("wf") => {
            "Bisection"
        }
        k if k.starts_with("mt_") => "Multi-timer",
        k if k.starts_with("dual_") => "Dual task",
        k if k.starts_with("unc_") => "Uncertainty",
        _ => "Neural activity",
    }
}

/// The used columns grouped by [`column_group`], groups in first-appearance order.
fn column_groups<'a>(cols: &[(&'a str, &str)]) -> Vec<(&'static str, Vec<&'a str>)> {
    let mut groups: Vec<(&'static str, Vec<&'a str>)> = Vec::new();
    for (k, _) in cols {
        let g = column_group(k);
        match groups.iter_mut().find(|(name, _)| *name == g) {
            Some((_, keys)) => keys.push(k),
            None => groups.push((g, vec![k])),
        }
    }
    groups
}

/// Rows of the per-TD fixed-interval table: (model, TD, episodes, mean FOC, FOC / TD, CV).
fn fi_by_td(rows: &[Row]) -> Vec<(String, u32, usize, String, String, String)> {
    let num = |x: f64| {
        if x.is_finite() {
            format!("{x:.2}")
        } else {
            "–".into()
        }
    };
    rows.iter()
        .flat_map(|r| {
            r.foc.iter().map(|f| {
                (
                    r.model.clone(),
                    f.td,
                    f.n,
                    num(f.mean),
                    num(f.mean / f64::from(f.td)),
                    num(f.cv),
                )
            })
        })
        .collect()
}

/// Caption of the per-TD fixed-interval table.
const FI_BY_TD: &str = "The first oven check (FOC, steps after the onion went in; the paper's convention), pooled over the row's runs and start cells. FOC / TD near 1: the agent checks when the soup is ready; near 0: it checks at once (no timing).";

fn fi_by_td_html(rows: &[Row]) -> String {
    let lines = fi_by_td(rows);
    if lines.is_empty() {
        return String::new();
    }
    let mut h = format!(
        "<h2 class=\"group\">Fixed interval per TD</h2>\n<p>{}</p>\n<table>\n<tr><th>model</th><th>TD (steps)</th><th>episodes</th><th>mean FOC (steps)</th><th>FOC / TD</th><th>FOC CV</th></tr>\n",
        escape(FI_BY_TD)
    );
    for (m, td, n, mean, ratio, cv) in lines {
        h += &format!(
            "<tr><td>{}</td><td>{td}</td><td>{n}</td><td>{mean}</td><td>{ratio}</td><td>{cv}</td></tr>\n",
            escape(&m)
        );
    }
    h + "</table>\n"
}

fn fi_by_td_markdown(rows: &[Row]) -> String {
    let lines = fi_by_td(rows);
    if lines.is_empty() {
        return String::new();
    }
    let mut md = format!(
        "\n## Fixed interval per TD\n\n{FI_BY_TD}\n\n| model | TD (steps) | episodes | mean FOC (steps) | FOC / TD | FOC CV |\n|---|---:|---:|---:|---:|---:|\n"
    );
    for (m, td, n, mean, ratio, cv) in lines {
        md += &format!("| {m} | {td} | {n} | {mean} | {ratio} | {cv} |\n");
    }
    md
}

/// Writes `report.html`, `report.md` and `report.csv` into `out`.
pub fn write_report(rows: &[Row], out: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let cols = used_columns(rows);
    // CSV: mean and SD columns.
    let mut header = vec!["model".to_string(), "baseline".into(), "runs".to_string()];
    for (k, _) in &cols {
        header.push(k.to_string());
        header.push(format!("{k}_sd"));
    }
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let baseline = r.baseline.clone().unwrap_or_default();
            let mut line = vec![r.model.clone(), baseline, r.runs.len().to_string()];
            for (k, _) in &cols {
                match r.values.get(*k) {
                    Some(s) => line.extend([s.mean.to_string(), s.sd.to_string()]),
                    None => line.extend([String::new(), String::new()]),
                }
            }
            line
        })
        .collect();
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let csv = crate::export::csv_text(&header, &table)?;
    // Markdown.
    let mut md = String::from("# Chronocooked leaderboard\n\n| model | runs |");
    for (k, _) in &cols {
        md += &format!(" {k} |");
    }
    md += "\n|---|---|";
    md += &"---|".repeat(cols.len());
    md.push('\n');
    for r in rows {
        md += &format!("| {} | {} |", r.model, r.runs.len());
        for (k, _) in &cols {
            md += &format!(" {} |", cell(r.values.get(*k)));
        }
        md.push('\n');
    }
    md += "\n## Columns\n\n";
    md += &format!("* `runs`: {RUNS_LEGEND}\n");
    if rows.iter().any(|r| r.baseline.is_some()) {
        md += &format!("* {BASELINE_LEGEND}\n");
    }
    for (k, what) in &cols {
        md += &format!("* `{k}`: {what}\n");
    }
    // HTML with inline SVG figures; the headline metrics as one table per theme, each
    // narrow enough for a 1366 px window.
    let mut html = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Chronocooked leaderboard</title>\n",
    );
    html += &format!("<style>{STYLE}</style></head><body>\n<h1>Chronocooked leaderboard</h1>\n");
    let (mech_html, mech_md) = mechanisms::mechanisms_section(rows, out)?;
    html += &mech_html;
    for (group, keys) in column_groups(&cols) {
        html +=
            &format!("<h2 class=\"group\">{group}</h2>\n<table>\n<tr><th>model</th><th>runs</th>");
        for k in &keys {
            let what = cols.iter().find(|(c, _)| c == k).map_or("", |(_, w)| *w);
            html += &format!(
                "<th title=\"{}\">{}</th>",
                escape(what),
                escape(column_title(k))
            );
        }
        html += "</tr>\n";
        for r in rows {
            if !keys.iter().any(|k| r.values.contains_key(*k)) {
                continue;
            }
            html += &format!("<tr><td>{}</td><td>{}</td>", escape(&r.model), r.runs.len());
            for k in &keys {
                html += &format!("<td>{}</td>", cell(r.values.get(*k)));
            }
            html += "</tr>\n";
        }
        html += "</table>\n";
    }
    html += &fi_by_td_html(rows);
    md += &fi_by_td_markdown(rows);
    md += &mech_md;
    html += "<h2>Columns</h2>\n<dl>\n";
    html += &format!(
        "<dt><code>runs</code></dt><dd>{}</dd>\n",
        escape(RUNS_LEGEND)
    );
    for (k, what) in &cols {
        html += &format!(
            "<dt>{} (<code>{k}</code>)</dt><dd>{}</dd>\n",
            escape(column_title(k)),
            escape(what)
        );
    }
    if rows.iter().any(|r| r.baseline.is_some()) {
        html += &format!("<dt>baselines</dt><dd>{}</dd>\n", escape(BASELINE_LEGEND));
    }
    html += "</dl>\n";
    let grid_rows: Vec<(String, Vec<crate::behaviour::metrics::BisectionMetrics>)> = rows
        .iter()
        .map(|r| (r.model.clone(), r.bisection.clone()))
        .collect();
    let grid =
        crate::report::figures::psychometric_grid(&out.join("psychometric_grid"), &grid_rows)
            .map_err(|e| e.to_string())?;
    if let Some(svg) = grid
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        html += "<h2>Psychometric curves (bisection)</h2>\n";
        html += &format!(
            "<figure class=\"wide\">{}<figcaption>P(long) per probe: grey dots = runs, blue = mean over runs, red = logistic fit of the pooled counts; AM/GM = arithmetic/geometric mean of the anchors, BP = bisection point</figcaption></figure>\n",
            inline_svg(svg)?
        );
    }
    for r in rows.iter().filter(|r| r.baseline.is_none()) {
        html += &format!("<h2>{}</h2>\n", escape(&r.model));
        html += &row_figures_html(r)?;
    }
    if grid
        .iter()
        .any(|p| p.extension().is_some_and(|e| e == "png"))
    {
        md += "\n## Psychometric curves\n\n![psychometric grid](psychometric_grid.png)\n";
    }
    html += "</body></html>\n";
    let mut files = Vec::new();
    for (name, text) in [
        ("report.html", html),
        ("report.md", md),
        ("report.csv", csv),
    ] {
        let p = out.join(name);
        chronocooked_env::fs::write_atomic(&p, text.as_bytes()).map_err(|e| e.to_string())?;
        files.push(p);
    }
    files.extend(grid);
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_headline_column_has_a_short_distinct_title_within_its_theme() {
        for (k, _) in COLUMNS {
            let t = column_title(k);
            assert_ne!(t, "other", "{k} has no title");
            assert!(
                t.chars().count() <= 24,
                "{k}: title {t:?} too long for the table"
            );
            let clash = COLUMNS
                .iter()
                .filter(|(o, _)| column_group(o) == column_group(k) && column_title(o) == t)
                .count();
            assert_eq!(
                clash,
                1,
                "{k}: title {t:?} repeats within {}",
                column_group(k)
            );
        }
        assert_eq!(escape("a \"b\" <c>"), "a &quot;b&quot; &lt;c&gt;");
    }

    #[test]
    fn a_figure_is_embedded_in_its_smaller_form() {
        let dir = std::env::temp_dir().join(format!("cc-figure-markup-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let big_svg = format!("<svg>{}</svg>", "<rect/>".repeat(2000));
        // A heat map: large SVG, small PNG → the PNG as data.
        std::fs::write(dir.join("heat.svg"), &big_svg).unwrap();
        std::fs::write(dir.join("heat.png"), [1u8, 2, 3]).unwrap();
        let m = figure_markup(&dir.join("heat.svg"), "heat <map>").unwrap();
        assert!(
            m.contains("<img alt=\"heat &lt;map&gt;\" src=\"data:image/png;base64,AQID\">"),
            "{m}"
        );
        // A line chart: small SVG, large PNG → the SVG inline.
        std::fs::write(dir.join("line.svg"), "<svg><path/></svg>").unwrap();
        std::fs::write(dir.join("line.png"), vec![0u8; 5000]).unwrap();
        let m = figure_markup(&dir.join("line.svg"), "line").unwrap();
        assert!(
            m.contains("<svg><path/></svg>") && !m.contains("<img"),
            "{m}"
        );
        // No PNG beside it: the SVG.
        std::fs::write(dir.join("only.svg"), &big_svg).unwrap();
        assert!(
            figure_markup(&dir.join("only.svg"), "x")
                .unwrap()
                .contains("<svg>")
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
