//! Leaderboard report from evaluation folders (`eval` outputs): one self-contained HTML page
//! (inline SVG figures, no external resources), Markdown and CSV. Rows = models (folders of
//! the same model are aggregated: mean ± SD over runs); columns = headline metrics.
//!
//! Submodules: [`leaderboard`] — rows and columns of the leaderboard; [`figures`] — the
//! SVG/PNG figures (plotters, bundled font); `markup` — the page shell and figures as maud
//! templates (maud escapes the text).

pub mod baselines;
pub use chronocooked_analysis::columns;
pub mod improvement;
pub mod leaderboard;
pub mod mechanisms;

use crate::figures::markup::{figure, figure_file, inline_svg};
pub use crate::report::improvement::write_improvement;
pub use crate::report::leaderboard::{Robust, Row, load_metrics, load_rows, load_rows_from_runs};
use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_env::markdown::Table;
use maud::{Markup, html};
use std::path::{Path, PathBuf};

/// What the `runs` column counts.
pub const RUNS_LEGEND: &str = "evaluation folders aggregated in the row (seeds, and task settings such as FI TDs); every other cell is the mean ± SD over the runs that have the metric and, for two or more runs, the interquartile mean (IQM: the mean of the middle 50% of the runs) with its 95% stratified bootstrap interval (runs resampled within their task settings; rliable, Agarwal et al. 2021)";

/// What a row labelled `model (study)` is (rows with [`Row::baseline`]).
pub const BASELINE_LEGEND: &str = "rows labelled `model (study)` are committed baselines: the compact results of that study in the repository (results/<study>/jobs/, one run per job), grouped exactly as evaluation folders are";

/// Short, readable header of a headline column (units in parentheses); its
/// [`columns::Column::doc`] is the full description, shown as the header's tooltip and in
/// the legend.
pub fn column_title(key: &str) -> &'static str {
    columns::column(key).map_or("other", |c| c.title)
}

fn cell(s: Option<&Spread>) -> String {
    match s {
        Some(s) if s.n > 1 && s.sd.is_finite() => format!("{:.3} ± {:.3}", s.mean, s.sd),
        Some(s) if s.mean.is_finite() => format!("{:.3}", s.mean),
        _ => "–".into(),
    }
}

/// The IQM and its bootstrap interval of a multi-run cell (`None` for fewer than 2 runs).
fn iqm_cell(r: Option<&Robust>) -> Option<String> {
    let r = r?;
    let (lo, hi) = r.ci?;
    Some(format!("IQM {:.3} [{lo:.3}, {hi:.3}]", r.iqm))
}

/// Runs per row and task whose behaviour figures are inlined in the HTML (the other runs
/// are named, their figures stay in their folders): a sweep's report stays readable and
/// small (the demo's ≤ 2 MB).
pub const FIGURE_RUNS: usize = 1;

/// One row's figures: the behaviour figures of its first [`FIGURE_RUNS`] runs per task, the
/// other runs named. (Its neural activity is in the "Mechanisms" section's card; every
/// population's heat map stays in the run's `neural_figures/`.)
fn row_figures_html(r: &Row) -> Result<Markup, String> {
    use crate::report::leaderboard::{behaviour_figures, figure_caption};
    let mut shown: Vec<(String, usize)> = Vec::new();
    let mut inlined: Vec<(String, Vec<Markup>)> = Vec::new();
    let mut named = Vec::new();
    for run in &r.runs {
        let task = eval_folder_task(run);
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
        let figures = behaviour_figures(run)
            .iter()
            .map(|svg| figure_file(svg, &figure_caption(svg), None))
            .collect::<Result<Vec<_>, _>>()?;
        inlined.push((run_caption(run), figures));
    }
    Ok(html! {
        @for (caption, figures) in &inlined {
            h3 { (caption) }
            @for f in figures { (f) }
        }
        @if !named.is_empty() {
            p { "Other runs (figures in their folders):" }
            ul { @for n in &named { li { (n) } } }
        }
    })
}

/// Task of an evaluation folder (from `eval.json`).
fn eval_folder_task(folder: &Path) -> String {
    chronocooked_analysis::records::read_eval_info(folder)
        .map(|info| info.task.id().to_string())
        .unwrap_or_else(|_| "unknown task".into())
}

/// Caption of one evaluation folder: its task and path.
fn run_caption(folder: &Path) -> String {
    format!("{} — {}", eval_folder_task(folder), folder.display())
}

/// Columns any row has, in [`columns::COLUMNS`] order: (key, description).
fn used_columns(rows: &[Row]) -> Vec<(&'static str, &'static str)> {
    columns::COLUMNS
        .iter()
        .map(|c| (c.key, c.doc))
        .filter(|(k, _)| rows.iter().any(|r| r.values.contains_key(*k)))
        .collect()
}

/// The theme a headline column belongs to (the HTML report shows one table per theme).
pub fn column_group(key: &str) -> &'static str {
    columns::column(key).map_or(columns::NEURAL_POPULATION, |c| c.group)
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

fn fi_by_td_html(rows: &[Row]) -> Markup {
    let lines = fi_by_td(rows);
    html! {
        @if !lines.is_empty() {
            h2.group { "Fixed interval per TD" }
            p { (FI_BY_TD) }
            table {
                tr {
                    th { "model" } th { "TD (steps)" } th { "episodes" }
                    th { "mean FOC (steps)" } th { "FOC / TD" } th { "FOC CV" }
                }
                @for (m, td, n, mean, ratio, cv) in &lines {
                    tr { td { (m) } td { (td) } td { (n) } td { (mean) } td { (ratio) } td { (cv) } }
                }
            }
        }
    }
}

/// The headline metrics as one table per theme (each narrow enough for a 1366 px window),
/// a row per model that has a metric of the theme.
fn theme_tables(rows: &[Row], cols: &[(&str, &str)]) -> Markup {
    let what = |k: &str| cols.iter().find(|(c, _)| *c == k).map_or("", |(_, w)| *w);
    html! {
        @for (group, keys) in column_groups(cols) {
            h2.group { (group) }
            table {
                tr {
                    th { "model" } th { "runs" }
                    @for k in &keys { th title=(what(k)) { (column_title(k)) } }
                }
                @for r in rows.iter().filter(|r| keys.iter().any(|k| r.values.contains_key(*k))) {
                    tr {
                        td { (r.model) } td { (r.runs.len()) }
                        @for k in &keys {
                            td {
                                (cell(r.values.get(*k)))
                                @if let Some(i) = iqm_cell(r.robust.get(*k)) { br; small { (i) } }
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The legend of the columns (`runs`, each used column, the baselines when shown).
fn columns_legend(cols: &[(&str, &str)], baselines: bool) -> Markup {
    html! {
        h2 { "Columns" }
        dl {
            dt { code { "runs" } } dd { (RUNS_LEGEND) }
            @for (k, what) in cols {
                dt { (column_title(k)) " (" code { (k) } ")" } dd { (what) }
            }
            @if baselines { dt { "baselines" } dd { (BASELINE_LEGEND) } }
        }
    }
}

/// Caption of the reproduction grid.
const REPRODUCTION_CAPTION: &str = "Per model (runs pooled): left, mean production tp against the sample interval ts, one colour per prior × gain, the best Bayesian observer's predicted mean (line, its mean wm and wp over the runs that chose it) and tp = g·ts; right, KiNeT's relative speed of the population trajectory after Set against ts (mean over runs), with the time-stretched answer ts_ref/ts and the fixed-speed clock 1";

/// Caption of the psychometric grid.
const GRID_CAPTION: &str = "P(long) per probe: grey dots = runs, blue = mean over runs, red = logistic fit of the pooled counts; AM/GM = arithmetic/geometric mean of the anchors, BP = bisection point";

fn fi_by_td_markdown(rows: &[Row]) -> String {
    let lines = fi_by_td(rows);
    if lines.is_empty() {
        return String::new();
    }
    let mut table = Table::new([
        "model",
        "TD (steps)",
        "episodes",
        "mean FOC (steps)",
        "FOC / TD",
        "FOC CV",
    ])
    .right(1..6);
    for (m, td, n, mean, ratio, cv) in lines {
        table.row([
            m.to_string(),
            td.to_string(),
            n.to_string(),
            mean.to_string(),
            ratio.to_string(),
            cv.to_string(),
        ]);
    }
    format!("\n## Fixed interval per TD\n\n{FI_BY_TD}\n\n{table}")
}

fn has_extension(files: &[PathBuf], ext: &str) -> bool {
    files
        .iter()
        .any(|p| p.extension().is_some_and(|e| e == ext))
}

/// The first SVG of a figure's `files`, ready to inline (`None` without one).
fn inline_svg_of(files: &[PathBuf]) -> Result<Option<Markup>, String> {
    match files
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        Some(svg) => Ok(Some(inline_svg(svg)?)),
        None => Ok(None),
    }
}

/// Writes `report.html`, `report.md` and `report.csv` into `out`.
pub fn write_report(rows: &[Row], out: &Path) -> Result<Vec<PathBuf>, String> {
    // One writer per report folder; a killed writer's temporary files are removed.
    let _lock = chronocooked_env::fs::FolderLock::acquire(out).map_err(|e| e.to_string())?;
    chronocooked_env::fs::remove_temp_files(&out.join("figures"));
    let cols = used_columns(rows);
    // CSV: mean and SD columns.
    let mut header = vec!["model".to_string(), "baseline".into(), "runs".to_string()];
    for (k, _) in &cols {
        header.push(k.to_string());
        header.push(format!("{k}_sd"));
        for suffix in ["iqm", "iqm_lo", "iqm_hi"] {
            header.push(format!("{k}_{suffix}"));
        }
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
                match r.robust.get(*k) {
                    Some(x) => {
                        let (lo, hi) = x.ci.unwrap_or((f64::NAN, f64::NAN));
                        line.extend([x.iqm, lo, hi].map(|v| v.to_string()));
                    }
                    None => line.extend([String::new(), String::new(), String::new()]),
                }
            }
            line
        })
        .collect();
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    let csv = crate::export::csv_text(&header, &table)?;
    // Markdown.
    let mut leaderboard = Table::new(
        ["model".to_string(), "runs".to_string()]
            .into_iter()
            .chain(cols.iter().map(|(k, _)| k.to_string())),
    );
    for r in rows {
        leaderboard.row(
            [r.model.clone(), r.runs.len().to_string()]
                .into_iter()
                .chain(cols.iter().map(|(k, _)| {
                    let mut c = cell(r.values.get(*k));
                    if let Some(i) = iqm_cell(r.robust.get(*k)) {
                        c += &format!("; {i}");
                    }
                    c
                })),
        );
    }
    let mut md = format!("# Chronocooked leaderboard\n\n{leaderboard}");
    md += "\n## Columns\n\n";
    md += &format!("* `runs`: {RUNS_LEGEND}\n");
    if rows.iter().any(|r| r.baseline.is_some()) {
        md += &format!("* {BASELINE_LEGEND}\n");
    }
    for (k, what) in &cols {
        md += &format!("* `{k}`: {what}\n");
    }
    // HTML with inline SVG figures.
    let baselines = rows.iter().any(|r| r.baseline.is_some());
    let (mech_html, mech_md) = mechanisms::mechanisms_section(rows, out)?;
    md += &fi_by_td_markdown(rows);
    md += &mech_md;
    let grid_rows: Vec<(
        String,
        Vec<chronocooked_analysis::behaviour::metrics::BisectionMetrics>,
    )> = rows
        .iter()
        .map(|r| (r.model.clone(), r.bisection.clone()))
        .collect();
    let grid = crate::figures::psychometric_grid(&out.join("psychometric_grid"), &grid_rows)
        .map_err(|e| e.to_string())?;
    let grid_svg = inline_svg_of(&grid)?;
    let reproduction_rows: Vec<_> = rows
        .iter()
        .map(|r| crate::figures::reproduction::ReproductionRuns {
            model: &r.model,
            metrics: &r.reproduction,
            speed: &r.speed,
        })
        .collect();
    let reproduction = crate::figures::reproduction::reproduction_grid(
        &out.join("reproduction_grid"),
        &reproduction_rows,
    )
    .map_err(|e| e.to_string())?;
    let reproduction_svg = inline_svg_of(&reproduction)?;
    let row_figures = rows
        .iter()
        .filter(|r| r.baseline.is_none())
        .map(|r| Ok((r.model.as_str(), row_figures_html(r)?)))
        .collect::<Result<Vec<_>, String>>()?;
    let html = crate::figures::markup::page(
        "Chronocooked leaderboard",
        html! {
            (mech_html)
            (theme_tables(rows, &cols))
            (fi_by_td_html(rows))
            (columns_legend(&cols, baselines))
            @if let Some(svg) = grid_svg {
                h2 { "Psychometric curves (bisection)" }
                (figure(svg, GRID_CAPTION, Some("wide")))
            }
            @if let Some(svg) = reproduction_svg {
                h2 { "Temporal reproduction" }
                (figure(svg, REPRODUCTION_CAPTION, Some("wide")))
            }
            @for (model, figures) in row_figures {
                h2 { (model) }
                (figures)
            }
        },
    );
    if has_extension(&grid, "png") {
        md += "\n## Psychometric curves\n\n![psychometric grid](psychometric_grid.png)\n";
    }
    if has_extension(&reproduction, "png") {
        md += "\n## Temporal reproduction\n\n![reproduction grid](reproduction_grid.png)\n";
    }
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
    files.extend(reproduction);
    Ok(files)
}
