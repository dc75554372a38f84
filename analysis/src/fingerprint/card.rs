//! The fingerprint's files: `fingerprint.json` (the placement), `fingerprint.md`,
//! `fingerprint.html` (a card in the style of the report's mechanism cards, with the
//! placement) and `fingerprint.png` (the distance panel beside the card's panels).

use super::place::{Placement, REFERENCE_SOURCE};
use super::play::PROTOCOL;
use crate::figures::markup::{figure_file, page};
use crate::figures::{Chart, Series, write_chart_sized, write_panels};
use crate::job_folder;
use crate::mechanisms::{FEATURES, MechanismError};
use chronocooked_env::markdown::Table;
use maud::html;
use std::path::{Path, PathBuf};

fn fmt(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "–".into()
    }
}

fn range(r: Option<(f64, f64)>) -> String {
    r.map_or("–".into(), |(lo, hi)| format!("{lo:.2}–{hi:.2}"))
}

/// One sentence: what the placement says.
pub fn verdict(p: &Placement) -> String {
    let limit = |d: &crate::fingerprint::MechanismDistance| {
        d.limit.map_or("–".into(), |l| format!("{l:.2}"))
    };
    match (&p.nearest, p.distances.first()) {
        (Some(m), Some(d)) if p.identified => format!(
            "{} is identified as {m}: distance {} lies within {m}'s identification limit {} \
             (its own held-out seeds lie {} from it)",
            p.model,
            fmt(d.distance),
            limit(d),
            range(d.self_range)
        ),
        (Some(m), Some(d)) => format!(
            "{} is not identified: its nearest mechanism is {m} at distance {}, beyond {m}'s \
             identification limit {} (its own held-out seeds lie {} from it)",
            p.model,
            fmt(d.distance),
            limit(d),
            range(d.self_range)
        ),
        _ => format!(
            "{} shares no feature with the mechanisms: nothing to compare",
            p.model
        ),
    }
}

/// The distance panel: per mechanism (nearest first, one colour each) the agent's distance
/// to its fingerprint (dot) beside a bar from the nearest of the mechanism's own held-out
/// seeds to its identification limit.
fn distance_chart(p: &Placement) -> Chart {
    let mut series = Vec::new();
    for (i, d) in p.distances.iter().enumerate() {
        let x = i as f64;
        series.push(Series {
            label: d.mechanism.clone(),
            points: vec![(x, d.distance)],
            line: false,
            color: i,
        });
        if let (Some((lo, _)), Some(hi)) = (d.self_range, d.limit) {
            // The bar: a short line at x from lo to hi, drawn thick by three offsets.
            let pts = [-0.04, 0.0, 0.04]
                .iter()
                .flat_map(|dx| [(x + dx, lo), (x + dx, hi), (f64::NAN, f64::NAN)])
                .collect();
            series.push(Series {
                label: String::new(),
                points: pts,
                line: true,
                color: i,
            });
        }
    }
    let top = p
        .distances
        .iter()
        .flat_map(|d| [d.distance, d.limit.unwrap_or(0.0)])
        .filter(|v| v.is_finite())
        .fold(1.0f64, f64::max);
    Chart {
        title: format!("{}: distance to each mechanism", p.model),
        x_label: "mechanism, nearest first (bar: its own seeds up to its limit)".into(),
        y_label: "distance (seed SDs)".into(),
        series,
        markers: Vec::new(),
        y_range: Some((0.0, 1.3 * top)),
    }
}

fn markdown(p: &Placement) -> String {
    let mut md = format!("# Fingerprint of {}\n\n{}.\n\n", p.model, verdict(p));
    md += &format!(
        "Compared with {REFERENCE_SOURCE}; the reference names {} of its {} held-out \
         mechanism seeds as their own mechanism. Distance: RMS over the shared features of \
         the differences in units of each feature's seed-to-seed SD within a mechanism \
         (pooled over the mechanisms; 1 = one seed SD on every feature); \
         self-distance: the range of the mechanism's own held-out seeds' distances; limit: \
         the upper 99% prediction limit for a new seed's distance (identified within it); \
         bootstrap share: of {} resamples of the mechanisms' seeds, the share in which the \
         mechanism is the nearest.\n\n",
        p.reference_identification.0, p.reference_identification.1, p.resamples
    );
    let mut distances = Table::new([
        "mechanism",
        "distance",
        "self-distance",
        "limit",
        "bootstrap share",
    ]);
    for d in &p.distances {
        distances.row([
            d.mechanism.to_string(),
            fmt(d.distance),
            range(d.self_range),
            d.limit.map_or("–".into(), fmt),
            format!("{:.2}", d.bootstrap_share),
        ]);
    }
    md += &distances.render();
    let mut features = Table::new(["feature", "value"]);
    for f in FEATURES {
        features.row([
            f.to_string(),
            p.signature
                .get(f)
                .map_or("missing".into(), |v| format!("{v:.3}")),
        ]);
    }
    md += "\n";
    md += &features.render();
    if !p.missing.is_empty() {
        md += &format!("\nMissing features: {}.\n", p.missing.join(", "));
    }
    md
}

/// Writes `fingerprint.md`, `fingerprint.html`, `fingerprint.png` and, last, `fingerprint.json`
/// (panel files in `card/`) into `dir`, the folder the agent's protocol conditions were
/// written to (its fixed-interval recordings make the card); returns the files.
pub fn write_fingerprint(dir: &Path, p: &Placement) -> Result<Vec<PathBuf>, MechanismError> {
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        chronocooked_env::fs::write_atomic(&path, bytes)
            .map_err(|e| MechanismError::at(&path, e.error))?;
        Ok::<PathBuf, MechanismError>(path)
    };
    let mut files = Vec::new();
    let json = serde_json::json!({
        "placement": p,
        "verdict": verdict(p),
        "reference": REFERENCE_SOURCE,
        "features": FEATURES,
    });
    let text = serde_json::to_string_pretty(&json).map_err(|e| MechanismError::at(dir, e))? + "\n";
    files.push(write("fingerprint.md", markdown(p).as_bytes())?);
    let panels_dir = dir.join("card");
    let fi_evals: Vec<PathBuf> = PROTOCOL
        .iter()
        .filter(|c| c.probe_td.is_some())
        .map(|c| dir.join(c.name).join(job_folder::EVAL))
        .filter(|e| e.is_dir())
        .collect();
    let card = crate::report::mechanisms::agent_card(
        &p.model,
        &fi_evals,
        &panels_dir,
        p.signature.get("scaling_index").copied(),
    )
    .map_err(|e| MechanismError::at(&panels_dir, e))?;
    let chart = distance_chart(p);
    let distance_files = write_chart_sized(&panels_dir.join("distances"), &chart, (560, 360))
        .map_err(|e| MechanismError::at(&panels_dir, e))?;
    let distance_figure = figure_file(
        &distance_files[0],
        "distance to each mechanism's fingerprint (dots) beside bars from the nearest of the \
         mechanism's own held-out seeds to its identification limit (the upper 99% \
         prediction limit for a new seed): a dot within its bar is as near as an unseen \
         seed of that mechanism",
        Some("half"),
    )
    .map_err(|e| MechanismError::at(&panels_dir, e))?;
    let body = html! {
        p { (verdict(p)) "." }
        p { (format!("Compared with {REFERENCE_SOURCE}: {} of {} held-out mechanism seeds named as their own mechanism.", p.reference_identification.0, p.reference_identification.1)) }
        table {
            tr { th { "mechanism" } th { "distance" } th { "self-distance" } th { "limit" } th { "bootstrap share" } }
            @for d in &p.distances {
                tr {
                    td { (d.mechanism) } td { (fmt(d.distance)) } td { (range(d.self_range)) }
                    td { (d.limit.map_or("–".into(), fmt)) }
                    td { (format!("{:.2}", d.bootstrap_share)) }
                }
            }
        }
        (distance_figure)
        @if let Some((markup, _)) = &card { (markup) }
        @else { p { "No neural card: the agent recorded no activity with a varying timing population on the probe trials." } }
        table {
            tr { th { "feature" } th { "value" } }
            @for f in FEATURES {
                tr { td { (f) } td { (p.signature.get(f).map_or("missing".into(), |v| format!("{v:.3}"))) } }
            }
        }
    };
    let html_page = page(&format!("Fingerprint — {}", p.model), body);
    files.push(write("fingerprint.html", html_page.as_bytes())?);
    let mut charts = vec![Some(chart)];
    if let Some((_, panels)) = card {
        charts.extend(panels.into_iter().map(|(_, c, _)| Some(c)));
    }
    let png = write_panels(&dir.join("fingerprint"), (1, charts.len()), &charts)
        .map_err(|e| MechanismError::at(dir, e))?;
    files.extend(png);
    // The placement last: a folder with `fingerprint.json` is a complete fingerprint.
    files.push(write("fingerprint.json", text.as_bytes())?);
    Ok(files)
}
