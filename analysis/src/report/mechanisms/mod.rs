//! The leaderboard's "Mechanisms" section: one signature card per model with recorded
//! fixed-interval runs, the fingerprint figure and each agent's nearest timing mechanism.
//!
//! A card shows the model's timing population (its largest population that is not a
//! read-out — value, RPE, learned drift) on peak-interval probe trials (`record --probe`,
//! windows of `2 × TD` steps after oven-on):
//!
//! * a heat map at the longest recorded TD, units min–max normalised and sorted by peak;
//! * three example units, one per category where it has them (time field, ramp,
//!   oscillating, mixed, beyond the window, untuned), as trial averages;
//! * the population's power spectrum (each unit's single-trial periodogram normalised to
//!   unit power without the mean, then averaged);
//! * the temporal scaling between the shortest and the longest TD: the fit of the
//!   population geometry read at stretched times against the stretch factor
//!   ([`crate::neural::geometry`]; a peak at 1 = a fixed clock, at the TD ratio = activity
//!   that stretches with the interval);
//! * the unit categories as a bar (counts of the five exclusive categories).
//!
//! The fingerprint (features of [`crate::mechanisms`]) comes from the same runs: each
//! row's evaluation metrics, its neural summaries and the scaling index of each seed's
//! fixed-interval runs recorded at the shortest and the longest TD.

mod card;
mod card_html;
#[cfg(test)]
mod tests;

use crate::figures::markup::figure_file;
use crate::mechanisms::{JobFiles, MECHANISMS, Signature, View, assemble, compare};
use crate::records::{METRICS, read_eval_info};
use crate::report::leaderboard::Row;
use card::card_and_scaling;
use card_html::{card_charts, card_html};
use chronocooked_env::markdown::Table;
use maud::{Markup, html};
use std::path::{Path, PathBuf};

/// One evaluation folder of a row: its task, seed and job folder.
pub(super) struct RunInfo {
    pub(super) eval: PathBuf,
    pub(super) task: String,
    pub(super) seed: u64,
}

fn run_info(eval: &Path) -> RunInfo {
    let info = read_eval_info(eval).ok();
    RunInfo {
        eval: eval.to_path_buf(),
        task: info
            .as_ref()
            .map(|i| i.task.id().to_string())
            .unwrap_or_default(),
        seed: info.map_or(0, |i| i.seed),
    }
}

/// The eval folders of every row as the fingerprint's job files.
fn job_files(rows: &[Row]) -> (Vec<JobFiles>, Vec<Vec<RunInfo>>) {
    let mut jobs = Vec::new();
    let mut infos = Vec::new();
    for row in rows {
        let runs: Vec<RunInfo> = row.runs.iter().map(|e| run_info(e)).collect();
        for r in &runs {
            jobs.push(JobFiles {
                model: row.model.clone(),
                seed: r.seed,
                task: r.task.clone(),
                metrics: r.eval.join(METRICS),
                summary: r.eval.parent().map_or_else(PathBuf::new, |p| {
                    p.join(crate::job_folder::ACTIVITY_SUMMARY)
                }),
            });
        }
        infos.push(runs);
    }
    (jobs, infos)
}

/// The nearest-mechanism table (HTML, Markdown) of the agents among `sigs`; `None` when
/// no agent is among them.
fn nearest_tables(sigs: &[Signature]) -> Option<(Markup, String)> {
    let comparisons = compare(sigs, &MECHANISMS, 1000, 0, View::Units);
    let mut agents: Vec<&str> = comparisons.iter().map(|c| c.agent.as_str()).collect();
    agents.dedup();
    if agents.is_empty() {
        return None;
    }
    let mechs: Vec<&str> = MECHANISMS
        .iter()
        .copied()
        .filter(|m| comparisons.iter().any(|c| c.mechanism == *m))
        .collect();
    // Per agent: name, seeds, distance cell per mechanism, nearest label.
    let lines: Vec<(&str, usize, Vec<String>, String)> = agents
        .into_iter()
        .map(|a| {
            let mine: Vec<_> = comparisons.iter().filter(|c| c.agent == a).collect();
            let seeds = mine.first().map_or(0, |c| c.seeds.0);
            let cells = mechs
                .iter()
                .map(|m| {
                    let d = mine
                        .iter()
                        .find(|c| c.mechanism == *m)
                        .map_or(f64::NAN, |c| c.distance);
                    if d.is_finite() {
                        format!("{d:.2}")
                    } else {
                        "–".into()
                    }
                })
                .collect();
            (a, seeds, cells, crate::mechanisms::nearest_label(&mine))
        })
        .collect();
    let html = html! {
        table {
            tr {
                th { "agent" } th { "seeds" }
                @for m in &mechs { th { (m) } }
                th { "nearest (bootstrap share)" }
            }
            @for (a, seeds, cells, nearest) in &lines {
                tr {
                    td { (a) } td { (seeds) }
                    @for c in cells { td { (c) } }
                    td { (nearest) }
                }
            }
        }
    };
    let mut table = Table::new(
        ["agent".to_string(), "seeds".to_string()]
            .into_iter()
            .chain(mechs.iter().map(|m| m.to_string()))
            .chain(["nearest".to_string()]),
    );
    for (a, seeds, cells, nearest) in &lines {
        table.row(
            [a.to_string(), seeds.to_string()]
                .into_iter()
                .chain(cells.iter().cloned())
                .chain([nearest.clone()]),
        );
    }
    Some((html, table.render()))
}

/// A card's line-chart panels: `(file name, chart, caption)`.
pub type CardPanels = Vec<(&'static str, crate::figures::Chart, String)>;

/// The signature card of one agent from its fixed-interval evaluation folders `fi_evals`
/// (each with the probe recording `activity.json` beside it, as in a study's job folders
/// or a fingerprint's condition folders): the card's HTML (panel files written to `dir`)
/// and its line-chart panels `(file name, chart, caption)`. `None` when no recording has a
/// timing population with varying units. `scaling_index`, when given, is the agent's own
/// (e.g. its fingerprint's, whose units may correspond across TDs) and replaces the card's
/// geometry-only one.
pub fn agent_card(
    model: &str,
    fi_evals: &[PathBuf],
    dir: &Path,
    scaling_index: Option<f64>,
) -> Result<Option<(Markup, CardPanels)>, String> {
    let row = Row {
        model: model.to_string(),
        runs: fi_evals.to_vec(),
        values: Default::default(),
        bisection: Vec::new(),
        reproduction: Vec::new(),
        speed: Vec::new(),
        foc: Vec::new(),
        robust: Default::default(),
        baseline: None,
    };
    let runs: Vec<RunInfo> = fi_evals.iter().map(|e| run_info(e)).collect();
    let (card, _) = card_and_scaling(&row, &runs)?;
    let Some(mut card) = card else {
        return Ok(None);
    };
    card.scaling_index = scaling_index.or(card.scaling_index);
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    Ok(Some((card_html(&card, dir)?, card_charts(&card))))
}

/// What the "Mechanisms" section shows (its first paragraph).
const MECHANISMS_INTRO: &str = "How each model keeps time, on peak-interval probe trials \
     (soup withheld, windows of 2 × TD steps after oven-on): its timing population's \
     unit categories (bar: counts of the exclusive categories ramp, time field, \
     oscillating, mixed, untuned and beyond the window: a field that peaks after it), \
     heat map, example units, power spectrum and temporal \
     scaling between its shortest and longest TD (a peak at s = 1: a clock at a fixed \
     speed; at the TD ratio: activity that stretches with the interval). Below the \
     cards: each model's fingerprint and each agent's distance to every timing \
     mechanism.";

/// How the nearest-mechanism table is read (the paragraph above it).
const NEAREST_LEGEND: &str = "Distance: RMS over the shared \
     features of the difference in units of each feature's SD over all \
     signatures (models × seeds), each feature weighted by how well it tells the \
     timing mechanisms apart (F/(1+F), F = variance between their means over the \
     pooled variance of their seeds); nearest: the share of 1,000 bootstrap \
     resamples of the seeds in which it is the nearest. With one seed per \
     model the share is 1 by construction: run more seeds for a test.";

/// The "Mechanisms" section of the leaderboard (HTML, Markdown) for `rows`; its figures go
/// to `<out>/mechanisms/`. Empty strings when no row has recorded fixed-interval runs.
pub fn mechanisms_section(rows: &[Row], out: &Path) -> Result<(Markup, String), String> {
    let dir = out.join("mechanisms");
    let (jobs, infos) = job_files(rows);
    let mut cards = Vec::new();
    let mut scaling = Vec::new();
    for (row, runs) in rows.iter().zip(&infos) {
        let (card, s) = card_and_scaling(row, runs)?;
        cards.extend(card);
        scaling.extend(s);
    }
    if cards.is_empty() {
        return Ok((html! {}, String::new()));
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    // Fingerprints of the models with a card (recorded neural activity): the oracle and
    // the random agent are bounds, not mechanisms to place.
    let carded: Vec<JobFiles> = jobs
        .into_iter()
        .filter(|j| cards.iter().any(|c| c.model == j.model))
        .collect();
    let sigs = assemble(&carded, &scaling).map_err(|e| e.to_string())?;
    let card_markup = cards
        .iter()
        .map(|card| card_html(card, &dir))
        .collect::<Result<Vec<_>, _>>()?;
    let nearest = nearest_tables(&sigs);
    let fig = crate::mechanisms::fingerprint_figure(&sigs, &dir.join("fingerprints"))
        .map_err(|e| e.to_string())?;
    let fingerprint = match fig
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        Some(svg) => {
            let names: Vec<String> = crate::mechanisms::FEATURES
                .iter()
                .enumerate()
                .map(|(i, f)| format!("{i} {f}"))
                .collect();
            let caption = format!(
                "fingerprints: each model's features (seed means) in SDs from the mean of \
                 all signatures; features: {}",
                names.join(", ")
            );
            Some(figure_file(svg, &caption, Some("half"))?)
        }
        None => None,
    };
    let html = html! {
        h2 { "Mechanisms" }
        p { (MECHANISMS_INTRO) }
        @for card in &card_markup { (card) }
        @if let Some(f) = &fingerprint { (f) }
        @if let Some((table, _)) = &nearest {
            h3 { "Nearest timing mechanism" }
            p { (NEAREST_LEGEND) }
            (table)
        }
    };
    let mut md = String::from("\n## Mechanisms\n\n");
    if let Some((_, table_md)) = &nearest {
        md += "Nearest timing mechanism (distance in feature SDs):\n\n";
        md += table_md;
    }
    let mut table = Table::new(["model", "population", "scaling index"]);
    for c in &cards {
        table.row([
            c.model.clone(),
            c.population.clone(),
            c.scaling_index.map_or("–".into(), |i| format!("{i:.2}")),
        ]);
    }
    md += "\n";
    md += &table.render();
    Ok((html, md))
}
