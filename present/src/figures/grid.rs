//! The paper's psychometric-curve grid: one panel per model (rows) and anchor pair
//! (columns) with every run's P(long) per probe as dots, the mean across runs, the logistic
//! fitted to the pooled counts, the anchors' arithmetic and geometric means and the
//! bisection point.

use super::draw::{Chart, FigureError, Series, atomic, draw_chart, err, figure_paths};
use chronocooked_analysis::behaviour::metrics::BisectionMetrics;
use chronocooked_analysis::behaviour::psychometric::{ProbeCounts, check_transition, fit_logistic};
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Panel width and height (pixels).
const PANEL: (u32, u32) = (420, 300);

/// Probe counts of several runs summed per probe duration.
pub fn pooled_counts(runs: &[&BisectionMetrics]) -> Vec<ProbeCounts> {
    let mut by_t: BTreeMap<u64, ProbeCounts> = BTreeMap::new();
    for b in runs {
        for p in &b.probes {
            let e = by_t.entry(p.t.to_bits()).or_insert(ProbeCounts {
                t: p.t,
                valid: 0,
                long: 0,
                failed: 0,
            });
            e.valid += p.valid;
            e.long += p.long;
            e.failed += p.failed;
        }
    }
    let mut v: Vec<ProbeCounts> = by_t.into_values().collect();
    v.sort_by(|a, b| a.t.total_cmp(&b.t));
    v
}

/// The chart of one panel: `runs` of `model` on one anchor pair.
pub fn panel_chart(model: &str, runs: &[&BisectionMetrics]) -> Chart {
    let (s, l) = runs.first().map_or((0, 0), |b| (b.short, b.long));
    let mut series: Vec<Series> = runs
        .iter()
        .enumerate()
        .map(|(i, b)| Series {
            label: if i == 0 { "runs".into() } else { String::new() },
            points: b.points(),
            line: false,
            color: 7,
        })
        .collect();
    let pooled = pooled_counts(runs);
    let mean: Vec<(f64, f64)> = pooled
        .iter()
        .map(|p| {
            let v: Vec<f64> = runs
                .iter()
                .flat_map(|b| b.probes.iter().zip(&b.p_long))
                .filter(|(q, v)| q.t == p.t && v.is_finite())
                .map(|(_, &v)| v)
                .collect();
            let m = if v.is_empty() {
                f64::NAN
            } else {
                v.iter().sum::<f64>() / v.len() as f64
            };
            (p.t, m)
        })
        .collect();
    series.push(Series {
        label: "mean".into(),
        points: mean,
        line: true,
        color: 0,
    });
    let mut markers = vec![
        (0.5 * f64::from(s + l), "AM".to_string()),
        ((f64::from(s) * f64::from(l)).sqrt(), "GM".to_string()),
    ];
    let mut title = format!("{model} · {s}–{l}");
    // The fit is drawn only when it passes the same transition test as the metrics.
    if let Ok(fit) = fit_logistic(&pooled)
        && check_transition(&pooled, &fit).is_ok()
    {
        let (t0, t1) = (
            pooled.first().map_or(0.0, |p| p.t),
            pooled.last().map_or(1.0, |p| p.t),
        );
        let curve = (0..=100)
            .map(|k| {
                let t = t0 + (t1 - t0) * f64::from(k) / 100.0;
                (t, 1.0 / (1.0 + (-(t - fit.bp) / fit.scale).exp()))
            })
            .collect();
        series.push(Series {
            label: "logistic fit".into(),
            points: curve,
            line: true,
            color: 3,
        });
        markers.push((fit.bp, "BP".to_string()));
        title = format!("{title} · BP {:.1}", fit.bp);
    }
    Chart {
        title,
        x_label: "probe duration (steps)".into(),
        y_label: "P(long)".into(),
        series,
        markers,
        y_range: Some((-0.05, 1.05)),
    }
}

/// Writes the grid for `rows` (model label, bisection metrics of its runs; shape
/// [`grid_shape`]) to
/// `<stem>.svg` / `<stem>.png`; rows without bisection runs are left out. Returns the files
/// written (none when no row has a bisection run).
pub fn psychometric_grid(
    stem: &Path,
    rows: &[(String, Vec<BisectionMetrics>)],
) -> Result<Vec<PathBuf>, FigureError> {
    let mut pairs: Vec<(u32, u32)> = rows
        .iter()
        .flat_map(|(_, b)| b.iter().map(|b| (b.short, b.long)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let models: Vec<&(String, Vec<BisectionMetrics>)> =
        rows.iter().filter(|(_, b)| !b.is_empty()).collect();
    if models.is_empty() {
        return Ok(vec![]);
    }
    let charts: Vec<Option<Chart>> = models
        .iter()
        .flat_map(|(model, runs)| {
            pairs.iter().map(move |&(s, l)| {
                let these: Vec<&BisectionMetrics> = runs
                    .iter()
                    .filter(|b| (b.short, b.long) == (s, l))
                    .collect();
                (!these.is_empty()).then(|| panel_chart(model, &these))
            })
        })
        .collect();
    write_panels(stem, grid_shape(models.len(), pairs.len()), &charts)
}

/// Panels most per row of a one-pair grid (models wrap into rows of this many).
pub const WRAP_COLUMNS: usize = 4;

/// `(rows, columns)` of the psychometric grid: models × anchor pairs, or — with one anchor
/// pair — the models wrapped into rows of up to [`WRAP_COLUMNS`] panels (row-major, so the
/// panel order is the same).
pub fn grid_shape(models: usize, pairs: usize) -> (usize, usize) {
    if pairs == 1 {
        let cols = models.clamp(1, WRAP_COLUMNS);
        (models.div_ceil(cols), cols)
    } else {
        (models, pairs)
    }
}

/// Writes `charts` (row-major; `None` leaves a panel empty) as a grid of `(rows, columns)`
/// panels of 420 × 300 pixels to `<stem>.svg` / `<stem>.png`; returns the files written.
pub fn write_panels(
    stem: &Path,
    grid: (usize, usize),
    charts: &[Option<Chart>],
) -> Result<Vec<PathBuf>, FigureError> {
    let (svg, png) = figure_paths(stem)?;
    let size = (PANEL.0 * grid.1 as u32, PANEL.1 * grid.0 as u32);
    atomic(&svg, |tmp| {
        let root = SVGBackend::new(tmp, size).into_drawing_area();
        draw_grid(&root, grid, charts, &svg)?;
        root.present().map_err(err(&svg))
    })?;
    atomic(&png, |tmp| {
        let root = BitMapBackend::new(tmp, size).into_drawing_area();
        draw_grid(&root, grid, charts, &png)?;
        root.present().map_err(err(&png))
    })?;
    Ok(vec![svg, png])
}

fn draw_grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    grid: (usize, usize),
    charts: &[Option<Chart>],
    path: &Path,
) -> Result<(), FigureError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err(path))?;
    for (area, chart) in root.split_evenly(grid).into_iter().zip(charts) {
        if let Some(c) = chart {
            draw_chart(area, c, path)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::grid_shape;

    #[test]
    fn one_anchor_pair_wraps_the_models_into_rows_of_four() {
        assert_eq!(grid_shape(7, 1), (2, 4));
        assert_eq!(grid_shape(3, 1), (1, 3));
        assert_eq!(grid_shape(1, 1), (1, 1));
        // Several pairs: models × pairs.
        assert_eq!(grid_shape(4, 6), (4, 6));
    }
}
