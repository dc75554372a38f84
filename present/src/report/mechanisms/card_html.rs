//! A signature card as HTML: category bar and four figure panels.

use super::card::{Card, examples, population_spectrum, varying_average};
use crate::figures::markup::figure_file;
use crate::figures::{Chart, Series, write_chart_sized, write_heatmap_sized};
use chronocooked_analysis::neural::categories::CATEGORIES;
use chronocooked_analysis::neural::geometry::{geometry_profile, geometry_scaling};
use chronocooked_analysis::neural::summary::{TdClassification, WINDOW_ORIGIN};
use maud::{Markup, html};
use std::path::Path;

/// Pixel size of a card's panels (four to a row at 1366 px).
const PANEL: (u32, u32) = (380, 280);

/// Colour of each category in the bar, in [`CATEGORIES`] order (ramp, time field,
/// oscillating, mixed, untuned, beyond the window: a paler time-field blue).
const CATEGORY_COLOURS: [&str; CATEGORIES.len()] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#bbbbbb", "#aec7e8",
];

fn panel(stem: &Path, chart: &Chart, caption: &str) -> Result<Markup, String> {
    let files = write_chart_sized(stem, chart, PANEL).map_err(|e| e.to_string())?;
    figure_file(&files[0], caption, Some("panel"))
}

/// The category bar of a classification (HTML: widths proportional to the counts).
fn category_bar(c: &TdClassification) -> Markup {
    let Ok(tests) = &c.tests else {
        return html! { p { "categories undefined (too few trials)" } };
    };
    let total = tests.len().max(1) as f64;
    let counts: Vec<(usize, usize)> = CATEGORIES
        .iter()
        .enumerate()
        .map(|(k, cat)| (k, tests.iter().filter(|u| u.category == *cat).count()))
        .filter(|&(_, n)| n > 0)
        .collect();
    html! {
        div.catbar {
            @for (k, n) in counts {
                @let name = CATEGORIES[k].name();
                span style=(format!("width:{:.1}%;background:{}", 100.0 * n as f64 / total, CATEGORY_COLOURS[k]))
                    title=(format!("{name} {n}")) { (name) " " (n) }
            }
        }
    }
}

/// The line-chart panels of a card — example units, spectrum and (with two TDs) the
/// scaling profile — as `(file name, chart, caption)`.
pub(crate) fn card_charts(card: &Card) -> Vec<(&'static str, Chart, String)> {
    let long = card.by_td.last().expect("a card has a TD");
    let short = &card.by_td[0];
    let mut out = Vec::new();
    // Example units.
    let avg = long.cube.average();
    let units = long.cube.units();
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
    out.push((
        "units",
        chart,
        "example units, one per category it has".to_string(),
    ));
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
    out.push((
        "spectrum",
        chart,
        "mean single-trial power spectrum of the units".to_string(),
    ));
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
        out.push(("scaling", chart, caption));
    }
    out
}

/// A model's signature card: heading, category bar and the four panels (heat map,
/// example units, spectrum, and the scaling profile when two TDs were recorded); the
/// panels' files go to `dir`.
pub(super) fn card_html(card: &Card, dir: &Path) -> Result<Markup, String> {
    let long = card.by_td.last().expect("a card has a TD");
    let tds: Vec<String> = card.by_td.iter().map(|c| c.td.to_string()).collect();
    let heading = format!(
        "{} — {} ({} varying of {} units at TD {}; seed {}; TDs {})",
        card.model,
        card.population,
        long.varying.len(),
        long.size,
        long.td,
        card.seed,
        tds.join(", ")
    );
    let mut panels = Vec::new();
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
    panels.push(figure_file(
        &heat[0],
        "units sorted by peak time, each min–max normalised",
        Some("panel"),
    )?);
    for (name, chart, caption) in card_charts(card) {
        panels.push(panel(&stem(name), &chart, &caption)?);
    }
    Ok(html! {
        div.card {
            h3 { (heading) }
            (category_bar(long))
            @for p in &panels { (p) }
        }
    })
}
