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
//!   ([`chronocooked_analysis::neural::geometry`]; a peak at 1 = a fixed clock, at the TD ratio = activity
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
use crate::report::leaderboard::Row;
use card::card_and_scaling;
use card_html::{card_charts, card_html};
use chronocooked_analysis::mechanisms::{JobFiles, Signature, View, assemble};
use chronocooked_analysis::records::{METRICS, read_eval_info};
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
                    p.join(chronocooked_analysis::job_folder::ACTIVITY_SUMMARY)
                }),
            });
        }
        infos.push(runs);
    }
    (jobs, infos)
}

/// Bootstrap resamples behind the report's placements.
const REPORT_RESAMPLES: usize = 1000;

/// One model of the report placed among the committed mechanisms in one view.
struct PlacedRow {
    model: String,
    view: View,
    seeds: usize,
    nearest: String,
    distance: f64,
    limit: Option<f64>,
    share: f64,
    identified: bool,
    /// Seeds identified (each seed placed on its own) and the mechanism they were
    /// identified with, most often first.
    seeds_identified: Vec<(String, usize)>,
}

/// Every model among `sigs` placed among the committed mechanism signatures
/// ([`crate::fingerprint::reference_signatures`]) in both views, as `chronocooked
/// fingerprint` places one agent: its seed mean, and each seed on its own.
fn placed_rows(sigs: &[Signature]) -> Vec<PlacedRow> {
    let reference = crate::fingerprint::reference_signatures();
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.sort_unstable();
    models.dedup();
    let mut rows = Vec::new();
    for m in models {
        let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == m).collect();
        let mean = Signature {
            model: m.to_string(),
            seed: 0,
            features: chronocooked_analysis::mechanisms::mean_features(&mine)
                .into_iter()
                .map(|(k, v)| (k.to_string(), v))
                .collect(),
        };
        for view in View::ALL {
            let p = crate::fingerprint::place(&mean, &reference, REPORT_RESAMPLES, 0, view);
            let Some(first) = p.distances.first() else {
                continue;
            };
            let mut ids: Vec<(String, usize)> = Vec::new();
            for s in &mine {
                let q = crate::fingerprint::place(s, &reference, 1, 0, view);
                if let (true, Some(n)) = (q.identified, q.nearest) {
                    match ids.iter_mut().find(|(x, _)| *x == n) {
                        Some(slot) => slot.1 += 1,
                        None => ids.push((n, 1)),
                    }
                }
            }
            ids.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
            rows.push(PlacedRow {
                model: m.to_string(),
                view,
                seeds: mine.len(),
                nearest: first.mechanism.clone(),
                distance: first.distance,
                limit: first.limit,
                share: first.bootstrap_share,
                identified: p.identified,
                seeds_identified: ids,
            });
        }
    }
    rows
}

/// The placement table (HTML, Markdown) of the models among `sigs`, both views side by
/// side; `None` when there is none.
fn placement_tables(sigs: &[Signature]) -> Option<(Markup, String)> {
    let rows = placed_rows(sigs);
    if rows.is_empty() {
        return None;
    }
    let fmt = |x: f64| {
        if x.is_finite() {
            format!("{x:.2}")
        } else {
            "–".into()
        }
    };
    let cells = |r: &PlacedRow| {
        let identified: usize = r.seeds_identified.iter().map(|x| x.1).sum();
        [
            r.nearest.clone(),
            fmt(r.distance),
            r.limit.map_or("–".into(), fmt),
            if r.identified {
                "identified"
            } else {
                "not identified"
            }
            .to_string(),
            format!("{:.2}", r.share),
            if identified == 0 {
                format!("0/{}", r.seeds)
            } else {
                format!(
                    "{identified}/{} ({})",
                    r.seeds,
                    r.seeds_identified
                        .iter()
                        .map(|(m, n)| format!("{m} {n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            },
        ]
    };
    let mut models: Vec<&str> = rows.iter().map(|r| r.model.as_str()).collect();
    models.dedup();
    let of = |m: &str, v: View| rows.iter().find(|r| r.model == m && r.view == v);
    let heads = [
        "nearest",
        "distance",
        "limit",
        "verdict",
        "share",
        "seeds identified",
    ];
    let html = html! {
        table {
            tr {
                th rowspan="2" { "model" }
                th colspan="6" { (View::Units.title()) }
                th colspan="6" { (View::Dynamics.title()) }
                th rowspan="2" { "views" }
            }
            tr { @for _ in 0..2 { @for h in heads { th { (h) } } } }
            @for m in &models {
                tr {
                    td { (m) }
                    @for v in View::ALL {
                        @if let Some(r) = of(m, v) { @for c in cells(r) { td { (c) } } }
                        @else { @for _ in 0..6 { td { "–" } } }
                    }
                    @let say = agreement(of(m, View::Units), of(m, View::Dynamics));
                    // One word in the cell (the table fits 1,366 px); the difference is
                    // spelt out under the table.
                    td title=(say) { (say.split(':').next().unwrap_or_default()) }
                }
            }
        }
        @for m in &models {
            @let say = agreement(of(m, View::Units), of(m, View::Dynamics));
            @if say.starts_with("disagree") {
                p { (m) ": the views " (say) "." }
            }
        }
    };
    let mut table = Table::new(["model", "view"].into_iter().chain(heads));
    for r in &rows {
        table.row(
            [r.model.clone(), r.view.key().to_string()]
                .into_iter()
                .chain(cells(r)),
        );
    }
    let mut md = table.render();
    for m in &models {
        let say = agreement(of(m, View::Units), of(m, View::Dynamics));
        if say.starts_with("disagree") {
            md += &format!("\n{m}: the views {say}.\n");
        }
    }
    Some((html, md))
}

/// Whether the two views give the same verdict (`agree`), or how they differ.
fn agreement(units: Option<&PlacedRow>, dynamics: Option<&PlacedRow>) -> String {
    match (units, dynamics) {
        (Some(u), Some(d)) if u.nearest == d.nearest && u.identified == d.identified => {
            "agree".into()
        }
        (Some(u), Some(d)) => format!(
            "disagree: units {} {}, dynamics {} {}",
            if u.identified {
                "identified as"
            } else {
                "nearest"
            },
            u.nearest,
            if d.identified {
                "identified as"
            } else {
                "nearest"
            },
            d.nearest
        ),
        _ => "one view only".into(),
    }
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

/// How the placement table is read (the paragraph above it), from the constants the
/// placement uses.
fn nearest_legend() -> String {
    format!(
        "Each model's seed mean is placed among the committed mechanism signatures ({}) as \
         `chronocooked fingerprint` places one agent, in two views: the unit view (features: \
         {}) reads single-unit categories, which depend on the basis of the units; the \
         dynamics view (features: {}) reads the population trajectory, the same in any \
         orthogonal basis. Distance: RMS over the view's shared features of the difference \
         in units of each feature's seed-to-seed SD within a mechanism, pooled over the \
         mechanisms (1 = one seed SD on every feature). Limit: the nearest mechanism's \
         identification limit, the upper {:.0}% prediction limit for one new seed's distance \
         (leave one seed out); a model is identified only within it. Share: of {} bootstrap \
         resamples of the mechanisms' seeds, the share in which that mechanism is the \
         nearest. Seeds identified: each seed placed on its own.",
        crate::fingerprint::REFERENCE_SOURCE,
        View::Units.features().join(", "),
        View::Dynamics.features().join(", "),
        100.0 * chronocooked_analysis::mechanisms::LIMIT_COVERAGE,
        REPORT_RESAMPLES
    )
}

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
    let nearest = placement_tables(&sigs);
    // The report's own models beside the committed mechanisms' seeds (never among this
    // report's one-seed runs of the mechanisms): the same reference the table below places
    // them against.
    let fig = crate::mechanisms::placed_fingerprint_figure(
        &sigs,
        &crate::fingerprint::reference_signatures(),
        &dir.join("fingerprints"),
    )
    .map_err(|e| e.to_string())?;
    let fingerprint = match fig
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        Some(svg) => Some(figure_file(
            svg,
            crate::mechanisms::PLACED_FINGERPRINT_CAPTION,
            Some("wide"),
        )?),
        None => None,
    };
    let html = html! {
        h2 { "Mechanisms" }
        p { (MECHANISMS_INTRO) }
        @for card in &card_markup { (card) }
        @if let Some(f) = &fingerprint { (f) }
        @if let Some((table, _)) = &nearest {
            h3 { "Nearest timing mechanism, in two views" }
            p { (nearest_legend()) }
            (table)
        }
    };
    let mut md = String::from("\n## Mechanisms\n\n");
    if let Some((_, table_md)) = &nearest {
        md += "Nearest timing mechanism, in two views (distance in seed-to-seed SDs of the \
               committed mechanisms; limit: the nearest mechanism's identification limit):\n\n";
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
