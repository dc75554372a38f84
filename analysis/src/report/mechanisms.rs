//! The leaderboard's "Mechanisms" section: one signature card per model with recorded
//! fixed-interval runs, the fingerprint figure and each agent's nearest timing mechanism.
//!
//! A card shows the model's timing population (its largest population that is not a
//! read-out — value, RPE, learned drift) on peak-interval probe trials (`record --probe`,
//! windows of `2 × TD` steps after oven-on):
//!
//! * a heat map at the longest recorded TD, units min–max normalised and sorted by peak;
//! * three example units, one per category where it has them (time field, ramp,
//!   oscillating, mixed, untuned), as trial averages;
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

use crate::mechanisms::{JobFiles, MECHANISMS, Signature, assemble, compare};
use crate::neural::categories::{CATEGORIES, Category, UnitTests};
use crate::neural::geometry::{geometry_profile, geometry_scaling};
use crate::neural::oscillation::welch;
use crate::neural::summary::{
    SummaryOptions, TdClassification, WINDOW_ORIGIN, classify_td, neural_summary, recorded_tds,
};
use crate::report::figures::{Chart, Series, write_chart_sized, write_heatmap_sized};
use crate::report::leaderboard::Row;
use crate::report::{escape, figure_markup};
use chronocooked_models::ActivityDataset;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Populations that read the timing out rather than keep time.
const READOUTS: [&str; 3] = ["value", "rpe", "drift"];

/// Pixel size of a card's panels (four to a row at 1366 px).
const PANEL: (u32, u32) = (380, 280);

/// Colour of each category in the bar (ramp, time field, oscillating, mixed, untuned).
const CATEGORY_COLOURS: [&str; 5] = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#bbbbbb"];

/// One evaluation folder of a row: its task, seed and job folder.
struct RunInfo {
    eval: PathBuf,
    task: String,
    seed: u64,
}

fn run_info(eval: &Path) -> RunInfo {
    let info: serde_json::Value = std::fs::read_to_string(eval.join("eval.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or_default();
    RunInfo {
        eval: eval.to_path_buf(),
        task: info["task"].as_str().unwrap_or_default().to_string(),
        seed: info["seed"].as_u64().unwrap_or(0),
    }
}

/// The activity dataset recorded next to an evaluation folder (`<job>/activity.json`).
fn load_activity(eval: &Path) -> Result<Option<ActivityDataset>, String> {
    let Some(path) = eval.parent().map(|p| p.join("activity.json")) else {
        return Ok(None);
    };
    if !path.is_file() {
        return Ok(None);
    }
    let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    ActivityDataset::from_json(&bytes)
        .map(Some)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// The largest population that is not a read-out (the first of equal size).
fn timing_population(ds: &ActivityDataset) -> Option<String> {
    ds.meta
        .populations
        .iter()
        .filter(|p| !READOUTS.contains(&p.name.as_str()) && p.size > 0)
        .rev()
        .max_by_key(|p| p.size)
        .map(|p| p.name.clone())
}

/// One seed's fixed-interval recordings of a model, merged (trials of every TD).
fn merged(datasets: Vec<ActivityDataset>) -> Option<ActivityDataset> {
    let mut it = datasets.into_iter();
    let mut first = it.next()?;
    for d in it {
        if d.meta.populations == first.meta.populations {
            first.trials.extend(d.trials);
        }
    }
    Some(first)
}

/// The scaling index of one seed's merged recording (as in the study's fingerprints:
/// geometry index per timing population, per-unit where the geometry cannot tell and the
/// units correspond — timing models of one seed).
fn seed_scaling(ds: &ActivityDataset) -> Option<f64> {
    if recorded_tds(ds).len() < 2 {
        return None;
    }
    let opts = SummaryOptions {
        units_correspond: MECHANISMS.contains(&ds.meta.model.as_str()),
        ..SummaryOptions::default()
    };
    let summaries: Vec<_> = ds
        .meta
        .populations
        .iter()
        .filter(|p| !READOUTS.contains(&p.name.as_str()))
        .filter_map(|p| neural_summary(ds, Some(&p.name), &opts).ok())
        .collect();
    let json = serde_json::to_value(&summaries).ok()?;
    crate::mechanisms::scaling_index_of_summary(&json)
}

/// `(model, seed, scaling index)` of one seed's fixed-interval recordings.
type SeedScaling = (String, u64, f64);

/// What a card shows, computed from one seed's recordings.
struct Card {
    model: String,
    population: String,
    seed: u64,
    /// Classifications per recorded TD, shortest first.
    by_td: Vec<TdClassification>,
    scaling_index: Option<f64>,
}

/// `[window, varying units]` trial average of a classification's varying units.
fn varying_average(c: &TdClassification) -> Vec<f64> {
    c.average_all
        .chunks_exact(c.size.max(1))
        .flat_map(|row| c.varying.iter().map(move |&j| row[j]))
        .collect()
}

/// Up to three example units: one per category in the order time field, ramp,
/// oscillating, mixed, untuned, then the next units of those categories.
fn examples(tests: &[UnitTests]) -> Vec<&UnitTests> {
    let order = [
        Category::TimeField,
        Category::Ramp,
        Category::Oscillating,
        Category::Mixed,
        Category::Untuned,
    ];
    let mut picked: Vec<&UnitTests> = order
        .iter()
        .filter_map(|c| tests.iter().find(|u| u.category == *c))
        .take(3)
        .collect();
    for u in tests {
        if picked.len() >= 3 {
            break;
        }
        if !picked.iter().any(|p| p.unit == u.unit) {
            picked.push(u);
        }
    }
    picked
}

/// Mean normalised single-trial spectrum of the varying units: `(cycles/step, power)`.
fn population_spectrum(c: &TdClassification) -> Vec<(f64, f64)> {
    let cube = &c.cube;
    let mut sum: Vec<f64> = Vec::new();
    let mut freqs: Vec<f64> = Vec::new();
    let mut count = 0.0;
    for i in 0..cube.units {
        for k in 0..cube.trials {
            let x: Vec<f64> = (0..cube.time)
                .map(|t| cube.at(k, t, i))
                .take_while(|v| v.is_finite())
                .collect();
            if x.len() < cube.time.max(4) {
                continue;
            }
            let s = welch(&x, x.len(), 1.0);
            let total: f64 = s.power.iter().skip(1).sum();
            if total.is_nan() || total <= 0.0 {
                continue;
            }
            if sum.is_empty() {
                sum = vec![0.0; s.power.len()];
                freqs = s.freqs.clone();
            }
            for (acc, p) in sum.iter_mut().zip(&s.power).skip(1) {
                *acc += p / total;
            }
            count += 1.0;
        }
    }
    freqs
        .into_iter()
        .zip(sum)
        .skip(1)
        .map(|(f, p)| (f, p / count))
        .collect()
}

/// The card of a row: from the first seed whose fixed-interval recordings have the timing
/// population; the scaling index of every seed.
fn card_and_scaling(
    row: &Row,
    runs: &[RunInfo],
) -> Result<(Option<Card>, Vec<SeedScaling>), String> {
    let mut by_seed: BTreeMap<u64, Vec<ActivityDataset>> = BTreeMap::new();
    for r in runs.iter().filter(|r| r.task == "FixedInterval-v0") {
        if let Some(ds) = load_activity(&r.eval)? {
            by_seed.entry(r.seed).or_default().push(ds);
        }
    }
    let mut card = None;
    let mut scaling = Vec::new();
    for (seed, datasets) in by_seed {
        let Some(ds) = merged(datasets) else { continue };
        let index = seed_scaling(&ds);
        if let Some(i) = index {
            scaling.push((row.model.clone(), seed, i));
        }
        if card.is_some() {
            continue;
        }
        let Some(pop) = timing_population(&ds) else {
            continue;
        };
        let opts = SummaryOptions::default();
        let by_td: Vec<TdClassification> = recorded_tds(&ds)
            .into_iter()
            .filter_map(|td| classify_td(&ds, Some(&pop), td, &opts).ok())
            .filter(|c| !c.varying.is_empty())
            .collect();
        if !by_td.is_empty() {
            card = Some(Card {
                model: row.model.clone(),
                population: pop,
                seed,
                by_td,
                scaling_index: index,
            });
        }
    }
    Ok((card, scaling))
}

fn panel(stem: &Path, chart: &Chart, caption: &str) -> Result<String, String> {
    let files = write_chart_sized(stem, chart, PANEL).map_err(|e| e.to_string())?;
    figure_markup(&files[0], caption).map(|h| h.replace("<figure>", "<figure class=\"panel\">"))
}

/// The category bar of a classification (HTML: widths proportional to the counts).
fn category_bar(c: &TdClassification) -> String {
    let Ok(tests) = &c.tests else {
        return String::from("<p>categories undefined (too few trials)</p>\n");
    };
    let total = tests.len().max(1) as f64;
    let mut html = String::from("<div class=\"catbar\">");
    for (k, cat) in CATEGORIES.iter().enumerate() {
        let n = tests.iter().filter(|u| u.category == *cat).count();
        if n == 0 {
            continue;
        }
        html += &format!(
            "<span style=\"width:{:.1}%;background:{}\" title=\"{} {n}\">{} {n}</span>",
            100.0 * n as f64 / total,
            CATEGORY_COLOURS[k],
            cat.name(),
            cat.name()
        );
    }
    html + "</div>\n"
}

fn card_html(card: &Card, dir: &Path) -> Result<String, String> {
    let long = card.by_td.last().expect("a card has a TD");
    let short = &card.by_td[0];
    let tds: Vec<String> = card.by_td.iter().map(|c| c.td.to_string()).collect();
    let mut html = format!(
        "<div class=\"card\"><h3>{} — {} ({} varying of {} units at TD {}; seed {}; TDs {})</h3>\n",
        escape(&card.model),
        escape(&card.population),
        long.varying.len(),
        long.size,
        long.td,
        card.seed,
        tds.join(", ")
    );
    html += &category_bar(long);
    let stem = |name: &str| dir.join(format!("{}-{name}", card.model));
    // Heat map.
    let heat = write_heatmap_sized(
        &stem("heatmap"),
        &format!("TD {} probe trials", long.td),
        &varying_average(long),
        long.varying.len(),
        PANEL,
    )
    .map_err(|e| e.to_string())?;
    html += &figure_markup(
        &heat[0],
        "units sorted by peak time, each min–max normalised",
    )?
    .replace("<figure>", "<figure class=\"panel\">");
    // Example units.
    let avg = long.cube.average();
    let units = long.cube.units;
    let series: Vec<Series> = match &long.tests {
        Ok(tests) => examples(tests)
            .into_iter()
            .enumerate()
            .map(|(k, u)| Series {
                label: format!("unit {} ({})", long.varying[u.unit], u.category.name()),
                points: (0..long.window)
                    .map(|t| (t as f64 + WINDOW_ORIGIN, avg[t * units + u.unit]))
                    .collect(),
                line: true,
                color: k,
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    let chart = Chart {
        title: "example units".into(),
        x_label: "steps since oven on".into(),
        y_label: "activity (trial mean)".into(),
        series,
        markers: vec![(f64::from(long.td), "TD".into())],
        y_range: None,
    };
    html += &panel(
        &stem("units"),
        &chart,
        "example units, one per category it has",
    )?;
    // Spectrum.
    let spectrum = population_spectrum(long);
    let chart = Chart {
        title: "spectrum".into(),
        x_label: "frequency (cycles / step)".into(),
        y_label: "share of power".into(),
        series: vec![Series {
            label: String::new(),
            points: spectrum,
            line: true,
            color: 0,
        }],
        markers: vec![(1.0 / f64::from(long.td), "1/TD".into())],
        y_range: None,
    };
    html += &panel(
        &stem("spectrum"),
        &chart,
        "mean single-trial power spectrum of the units",
    )?;
    // Scaling.
    if card.by_td.len() >= 2 {
        let ratio = f64::from(long.td) / f64::from(short.td);
        let profile = geometry_profile(
            &short.average_all,
            short.size,
            &long.average_all,
            long.size,
            WINDOW_ORIGIN,
        );
        let g = geometry_scaling(
            &short.average_all,
            short.size,
            &long.average_all,
            long.size,
            ratio,
            WINDOW_ORIGIN,
        );
        let chart = Chart {
            title: format!("scaling TD {} → {}", short.td, long.td),
            x_label: "stretch factor s".into(),
            y_label: "geometry fit R²".into(),
            series: vec![Series {
                label: String::new(),
                points: profile,
                line: true,
                color: 1,
            }],
            markers: vec![(1.0, "fixed".into()), (ratio, "scales".into())],
            y_range: None,
        };
        let caption = format!(
            "population geometry at TD {} read at stretched times vs TD {}: best s {}; \
             model's scaling index {}",
            long.td,
            short.td,
            g.map_or("undefined (the geometry cannot tell)".into(), |g| format!(
                "{:.2}",
                g.factor
            )),
            card.scaling_index
                .map_or("undefined".into(), |i| format!("{i:.2}"))
        );
        html += &panel(&stem("scaling"), &chart, &caption)?;
    }
    Ok(html + "</div>\n")
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
                metrics: r.eval.join("metrics.json"),
                summary: r
                    .eval
                    .parent()
                    .map_or_else(PathBuf::new, |p| p.join("activity.summary.json")),
            });
        }
        infos.push(runs);
    }
    (jobs, infos)
}

/// The nearest-mechanism table (HTML, Markdown) of the agents among `sigs`.
fn nearest_tables(sigs: &[Signature]) -> (String, String) {
    let comparisons = compare(sigs, &MECHANISMS, 1000, 0);
    let mut agents: Vec<&str> = comparisons.iter().map(|c| c.agent.as_str()).collect();
    agents.dedup();
    if agents.is_empty() {
        return (String::new(), String::new());
    }
    let mechs: Vec<&str> = MECHANISMS
        .iter()
        .copied()
        .filter(|m| comparisons.iter().any(|c| c.mechanism == *m))
        .collect();
    let mut html = String::from("<table>\n<tr><th>agent</th><th>seeds</th>");
    let mut md = String::from("| agent | seeds |");
    for m in &mechs {
        html += &format!("<th>{}</th>", escape(m));
        md += &format!(" {m} |");
    }
    html += "<th>nearest (bootstrap share)</th></tr>\n";
    md += &format!(" nearest |\n|---|---|{}---|\n", "---|".repeat(mechs.len()));
    for a in agents {
        let mine: Vec<_> = comparisons.iter().filter(|c| c.agent == a).collect();
        let seeds = mine.first().map_or(0, |c| c.seeds.0);
        html += &format!("<tr><td>{}</td><td>{seeds}</td>", escape(a));
        md += &format!("| {a} | {seeds} |");
        for m in &mechs {
            let d = mine
                .iter()
                .find(|c| c.mechanism == *m)
                .map_or(f64::NAN, |c| c.distance);
            let cell = if d.is_finite() {
                format!("{d:.2}")
            } else {
                "–".into()
            };
            html += &format!("<td>{cell}</td>");
            md += &format!(" {cell} |");
        }
        let nearest = crate::mechanisms::nearest_label(&mine);
        html += &format!("<td>{}</td></tr>\n", escape(&nearest));
        md += &format!(" {nearest} |\n");
    }
    (html + "</table>\n", md)
}

/// The "Mechanisms" section of the leaderboard (HTML, Markdown) for `rows`; its figures go
/// to `<out>/mechanisms/`. Empty strings when no row has recorded fixed-interval runs.
pub fn mechanisms_section(rows: &[Row], out: &Path) -> Result<(String, String), String> {
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
        return Ok((String::new(), String::new()));
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    // Fingerprints of the models with a card (recorded neural activity): the oracle and
    // the random agent are bounds, not mechanisms to place.
    let carded: Vec<JobFiles> = jobs
        .into_iter()
        .filter(|j| cards.iter().any(|c| c.model == j.model))
        .collect();
    let sigs = assemble(&carded, &scaling).map_err(|e| e.to_string())?;
    let mut html = String::from(
        "<h2>Mechanisms</h2>\n<p>How each model keeps time, on peak-interval probe trials \
         (soup withheld, windows of 2 × TD steps after oven-on): its timing population's \
         unit categories (bar: counts of the exclusive categories ramp, time field, \
         oscillating, mixed, untuned), heat map, example units, power spectrum and temporal \
         scaling between its shortest and longest TD (a peak at s = 1: a clock at a fixed \
         speed; at the TD ratio: activity that stretches with the interval). Below the \
         cards: each model's fingerprint and each agent's distance to every timing \
         mechanism.</p>\n",
    );
    let mut md = String::from("\n## Mechanisms\n\n");
    for card in &cards {
        html += &card_html(card, &dir)?;
    }
    let (table_html, table_md) = nearest_tables(&sigs);
    let fig = crate::mechanisms::fingerprint_figure(&sigs, &dir.join("fingerprints"))
        .map_err(|e| e.to_string())?;
    if let Some(svg) = fig
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        let names: Vec<String> = crate::mechanisms::FEATURES
            .iter()
            .enumerate()
            .map(|(i, f)| format!("{i} {f}"))
            .collect();
        html += &figure_markup(
            svg,
            &format!(
                "fingerprints: each model's features (seed means) in SDs from the mean of \
                 all signatures; features: {}",
                names.join(", ")
            ),
        )?
        .replace("<figure>", "<figure class=\"half\">");
    }
    if !table_html.is_empty() {
        html += "<h3>Nearest timing mechanism</h3>\n<p>Distance: RMS over the shared \
                 features of the difference in units of each feature's SD over all \
                 signatures (models × seeds); nearest: the share of 1,000 bootstrap \
                 resamples of the seeds in which it is the nearest. With one seed per \
                 model the share is 1 by construction: run more seeds for a test.</p>\n";
        html += &table_html;
        md += "Nearest timing mechanism (distance in feature SDs):\n\n";
        md += &table_md;
    }
    md += "\n| model | population | scaling index |\n|---|---|---|\n";
    for c in &cards {
        md += &format!(
            "| {} | {} | {} |\n",
            c.model,
            c.population,
            c.scaling_index.map_or("–".into(), |i| format!("{i:.2}"))
        );
    }
    Ok((html, md))
}

#[cfg(test)]
mod tests {
    use super::*;
    use chronocooked_models::Marker;
    use chronocooked_models::activity::{ActivityMeta, Event, Population, Trial};
    use rand::{Rng, SeedableRng};

    /// A recording at `td` of a population `cells` (unit activity `f(unit, τ, td)`, τ =
    /// steps since oven-on) plus a `value` read-out, 16 noisy trials, oven-on at step 2.
    fn dataset(
        model: &str,
        td: u32,
        units: usize,
        f: &dyn Fn(usize, f64, f64) -> f64,
    ) -> ActivityDataset {
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(u64::from(td));
        let steps = 2 + 2 * td as usize + 4;
        let trials = (0..16)
            .map(|_| {
                let mut activity = Vec::with_capacity(steps * (units + 1));
                for s in 0..steps {
                    let tau = s as f64 - 2.0;
                    for u in 0..units {
                        let v = if tau >= 0.0 {
                            f(u, tau, f64::from(td))
                        } else {
                            0.0
                        };
                        activity.push((v + 0.03 * (rng.random::<f64>() - 0.5)) as f32);
                    }
                    activity.push((tau / f64::from(td)) as f32);
                }
                Trial {
                    td,
                    start: (1, 1),
                    steps,
                    activity,
                    events: vec![Event {
                        step: 2,
                        marker: Marker::OvenOn,
                    }],
                    reward: 0.0,
                    success: false,
                }
            })
            .collect();
        let mut meta = ActivityMeta::new(model, "PeakInterval-v0", &[], 0);
        meta.populations = vec![
            Population {
                name: "cells".into(),
                size: units,
            },
            Population {
                name: "value".into(),
                size: 1,
            },
        ];
        ActivityDataset { meta, trials }
    }

    /// Evaluation folders (eval.json only: the card needs task and seed) with the dataset
    /// beside each, as a sweep lays them out.
    fn row(root: &Path, model: &str, sets: Vec<ActivityDataset>) -> Row {
        let mut runs = Vec::new();
        for ds in sets {
            let job = root.join(format!("{model}-{}", ds.trials[0].td));
            std::fs::create_dir_all(job.join("eval")).unwrap();
            std::fs::write(
                job.join("eval/eval.json"),
                r#"{"task": "FixedInterval-v0", "seed": 0}"#,
            )
            .unwrap();
            std::fs::write(job.join("eval/metrics.json"), "{}").unwrap();
            std::fs::write(job.join("activity.json"), serde_json::to_vec(&ds).unwrap()).unwrap();
            runs.push(job.join("eval"));
        }
        Row {
            model: model.into(),
            runs,
            values: BTreeMap::new(),
            bisection: Vec::new(),
            foc: Vec::new(),
            baseline: None,
        }
    }

    fn stretched(u: usize, tau: f64, td: f64) -> f64 {
        let peak = td * (0.25 + 0.25 * u as f64);
        (-(tau - peak).powi(2) / (2.0 * (0.2 * peak).powi(2))).exp()
    }

    fn oscillator(u: usize, tau: f64, _td: f64) -> f64 {
        (2.0 * std::f64::consts::PI * (0.12 + 0.05 * u as f64) * tau).sin()
    }

    #[test]
    fn cards_show_the_stretching_sequence_and_the_fixed_clock_for_what_they_are() {
        let root = std::env::temp_dir().join(format!("cc-mech-card-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let seq = row(
            &root,
            "seq",
            vec![
                dataset("seq", 6, 6, &stretched),
                dataset("seq", 12, 6, &stretched),
            ],
        );
        let osc = row(
            &root,
            "osc",
            vec![
                dataset("osc", 6, 5, &oscillator),
                dataset("osc", 12, 5, &oscillator),
            ],
        );
        let infos = |r: &Row| r.runs.iter().map(|e| run_info(e)).collect::<Vec<_>>();
        let (card, scaling) = card_and_scaling(&seq, &infos(&seq)).unwrap();
        let card = card.unwrap();
        // The read-out is not the timing population; both TDs are on the card.
        assert_eq!(card.population, "cells");
        assert_eq!(card.by_td.iter().map(|c| c.td).collect::<Vec<_>>(), [6, 12]);
        let tests = card.by_td[1].tests.as_ref().unwrap();
        let fields = tests
            .iter()
            .filter(|u| u.category == Category::TimeField)
            .count();
        assert!(fields >= 4, "{tests:?}");
        // Fields at fixed fractions of TD: the geometry stretches by the TD ratio.
        let s = scaling[0].2;
        assert!((s - 1.0).abs() < 0.15, "sequence scaling index {s}");
        let (card, scaling) = card_and_scaling(&osc, &infos(&osc)).unwrap();
        let tests = card.unwrap().by_td[1].tests.clone().unwrap();
        assert!(
            tests
                .iter()
                .filter(|u| u.category == Category::Oscillating)
                .count()
                >= 3
        );
        assert!(
            scaling[0].2.abs() < 0.15,
            "oscillator scaling index {}",
            scaling[0].2
        );
        // The section: a card per model with its four panels and the category bar.
        let out = root.join("report");
        let (html, md) = mechanisms_section(&[seq, osc], &out).unwrap();
        assert!(html.starts_with("<h2>Mechanisms</h2>"));
        assert_eq!(html.matches("<div class=\"card\">").count(), 2);
        assert_eq!(html.matches("<figure class=\"panel\">").count(), 8);
        assert!(html.contains("title=\"time_field ") && html.contains("title=\"oscillating "));
        for name in [
            "seq-heatmap",
            "seq-units",
            "seq-spectrum",
            "seq-scaling",
            "fingerprints",
        ] {
            assert!(
                out.join("mechanisms").join(format!("{name}.svg")).is_file(),
                "{name}"
            );
        }
        assert!(
            md.contains("| seq | cells |") && md.contains("| osc | cells |"),
            "{md}"
        );
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn a_report_without_recordings_has_no_section() {
        let root = std::env::temp_dir().join(format!("cc-mech-none-{}", std::process::id()));
        let r = row(&root, "none", Vec::new());
        assert_eq!(
            mechanisms_section(&[r], &root).unwrap(),
            (String::new(), String::new())
        );
        assert!(!root.join("mechanisms").exists());
        let _ = std::fs::remove_dir_all(&root);
    }
}
