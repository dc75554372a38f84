//! The fingerprint's files: `fingerprint.json` (the placements in both views),
//! `fingerprint.md`, `fingerprint.html` (the two views side by side, then a card in the
//! style of the report's mechanism cards) and `fingerprint.png` (the distance panels of
//! both views beside the card's panels).

use super::play::PROTOCOL;
use crate::figures::markup::{figure_file, page};
use crate::figures::{Chart, Series, write_chart_sized, write_panels};
use chronocooked_analysis::fingerprint::{Fingerprint, Placement, REFERENCE_SOURCE};
use chronocooked_analysis::job_folder;
use chronocooked_analysis::mechanisms::{MechanismError, Signature};
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

/// One sentence: what the placement says, in its view.
pub fn verdict(p: &Placement) -> String {
    format!("{} view: {}", p.view.key(), bare_verdict(p))
}

/// Whether the two views agree, as a sentence (says which view says what where not).
pub fn agreement(f: &Fingerprint) -> String {
    let say = |p: &Placement| match (&p.nearest, p.identified) {
        (Some(m), true) => format!("identified as {m}"),
        (Some(m), false) => format!("not identified (nearest {m})"),
        (None, _) => "no verdict".to_string(),
    };
    if f.views_agree() {
        format!("The two views agree: {}", say(&f.dynamics))
    } else {
        format!(
            "The two views disagree: the unit view says {}, the dynamics view {}. Unit \
             categories change with the basis of the units; the dynamics view does not",
            say(&f.units),
            say(&f.dynamics)
        )
    }
}

fn bare_verdict(p: &Placement) -> String {
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
            "{} shares no feature with the mechanisms: nothing to compare. Every feature is \
             measured on timed responses (the oven started, then a check, a delivery or a \
             choice) and on the activity of trials that have them; an agent that never starts \
             the timer, such as one trained on a short budget, has none (the zoo's and the \
             reference preset's agents do)",
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
        title: format!("{} view: distance to each mechanism", p.view.key()),
        x_label: "mechanism, nearest first (bar: its own seeds up to its limit)".into(),
        y_label: "distance (seed SDs)".into(),
        series,
        markers: Vec::new(),
        y_range: Some((0.0, 1.3 * top)),
    }
}

fn view_markdown(p: &Placement) -> String {
    let mut md = format!(
        "## {}\n\n{}.\n\nThe reference names {} of its {} held-out mechanism seeds as their own \
         mechanism in this view.\n\n",
        p.view.title(),
        bare_verdict(p),
        p.reference_identification.0,
        p.reference_identification.1
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
    for f in p.view.features() {
        features.row([
            f.to_string(),
            p.signature
                .get(*f)
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

fn markdown(f: &Fingerprint) -> String {
    let mut md = format!("# Fingerprint of {}\n\n{}.\n\n", f.model(), agreement(f));
    md += &format!(
        "Compared with {REFERENCE_SOURCE}. Distance: RMS over the view's shared features of \
         the differences in units of each feature's seed-to-seed SD within a mechanism \
         (pooled over the mechanisms; 1 = one seed SD on every feature); \
         self-distance: the range of the mechanism's own held-out seeds' distances; limit: \
         the upper 99% prediction limit for a new seed's distance (identified within it); \
         bootstrap share: of {} resamples of the mechanisms' seeds, the share in which the \
         mechanism is the nearest. The unit view reads single-unit categories, which change \
         when the units are mixed; the dynamics view reads the population trajectory's \
         basis-free signature, the same in any orthogonal basis.\n\n",
        f.units.resamples
    );
    for p in f.views() {
        md += &view_markdown(p);
        md += "\n";
    }
    md
}

/// Writes `fingerprint.md`, `fingerprint.html`, `fingerprint.png` and, last, `fingerprint.json`
/// (panel files in `card/`) into `dir`, the folder the agent's protocol conditions were
/// written to (its fixed-interval recordings make the card); returns the files.
pub fn write_fingerprint(dir: &Path, f: &Fingerprint) -> Result<Vec<PathBuf>, MechanismError> {
    let p = &f.units;
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        chronocooked_env::fs::write_atomic(&path, bytes)
            .map_err(|e| MechanismError::at(&path, e.error))?;
        Ok::<PathBuf, MechanismError>(path)
    };
    let mut files = Vec::new();
    let json = serde_json::json!({
        "units": f.units,
        "dynamics": f.dynamics,
        "verdicts": {"units": verdict(&f.units), "dynamics": verdict(&f.dynamics)},
        "views_agree": f.views_agree(),
        "agreement": agreement(f),
        "reference": REFERENCE_SOURCE,
        "features": {
            "units": chronocooked_analysis::mechanisms::View::Units.features(),
            "dynamics": chronocooked_analysis::mechanisms::View::Dynamics.features(),
        },
    });
    let text = serde_json::to_string_pretty(&json).map_err(|e| MechanismError::at(dir, e))? + "\n";
    files.push(write("fingerprint.md", markdown(f).as_bytes())?);
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
    let charts_of_views: Vec<Chart> = f.views().iter().map(|p| distance_chart(p)).collect();
    let mut view_blocks = Vec::new();
    for (p, chart) in f.views().into_iter().zip(&charts_of_views) {
        let files = write_chart_sized(
            &panels_dir.join(format!("distances-{}", p.view.key())),
            chart,
            (560, 360),
        )
        .map_err(|e| MechanismError::at(&panels_dir, e))?;
        let figure = figure_file(
            &files[0],
            "distance to each mechanism's fingerprint (dots) beside bars from the nearest of \
             the mechanism's own held-out seeds to its identification limit (the upper 99% \
             prediction limit for a new seed): a dot within its bar is as near as an unseen \
             seed of that mechanism",
            None,
        )
        .map_err(|e| MechanismError::at(&panels_dir, e))?;
        view_blocks.push(html! {
            div style="flex: 1 1 560px; min-width: 0" {
                h2 { (p.view.title()) }
                p { (bare_verdict(p)) "." }
                p { (format!("{} of {} held-out mechanism seeds named as their own mechanism in this view.", p.reference_identification.0, p.reference_identification.1)) }
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
                (figure)
                table {
                    tr { th { "feature" } th { "value" } }
                    @for feat in p.view.features() {
                        tr { td { (feat) } td { (p.signature.get(*feat).map_or("missing".into(), |v| format!("{v:.3}"))) } }
                    }
                }
            }
        });
    }
    let body = html! {
        p { strong { (agreement(f)) "." } }
        p { (format!("Compared with {REFERENCE_SOURCE}."))
            " The unit view reads single-unit categories, which change when the units are mixed (another basis of the same dynamics); the dynamics view reads the population trajectory's basis-free signature." }
        div style="display: flex; flex-wrap: wrap; gap: 1.5em" {
            @for b in &view_blocks { (b) }
        }
        @if let Some((markup, _)) = &card { (markup) }
        @else { p { "No neural card: the agent recorded no activity with a varying timing population on the probe trials." } }
    };
    let html_page = page(&format!("Fingerprint — {}", p.model), body);
    files.push(write("fingerprint.html", html_page.as_bytes())?);
    let mut charts: Vec<Option<Chart>> = charts_of_views.into_iter().map(Some).collect();
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

/// The agent's signature as a fingerprint folder's `fingerprint.json` records it (its unit
/// view's model and features; both views place the same signature), read typed: what a
/// pairwise distance between two recorded agents needs. Errors name the file.
pub fn read_signature(dir: &Path) -> Result<Signature, String> {
    #[derive(serde::Deserialize)]
    struct File {
        units: Recorded,
    }
    #[derive(serde::Deserialize)]
    struct Recorded {
        #[serde(default)]
        model: Option<String>,
        signature: std::collections::BTreeMap<String, Option<f64>>,
    }
    let path = dir.join("fingerprint.json");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        format!(
            "{}: {e} (a folder written by `fingerprint`)",
            path.display()
        )
    })?;
    let file: File = serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(Signature {
        model: file.units.model.unwrap_or_else(|| "agent".into()),
        seed: 0,
        features: file
            .units
            .signature
            .into_iter()
            .filter_map(|(k, v)| v.map(|x| (k, x)))
            .collect(),
    })
}
