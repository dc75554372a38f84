//! Drawing primitives: line/point charts (psychometric curves, PI curves, FOC strips, reward
//! and oven-off vs TD, learning curves, decoder error) and activity heat maps, each written
//! as SVG and PNG with the bundled DejaVu Sans font.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

pub(super) fn ensure_font() {
    REGISTER.call_once(|| {
        // Registering the bundled font cannot fail for a valid TTF; a failure only means
        // text would be missing, which the figure tests would catch.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// A figure could not be drawn or written.
#[derive(Debug, thiserror::Error)]
#[error("figure {path}: {message}")]
pub struct FigureError {
    /// File being written.
    pub path: String,
    /// What went wrong.
    pub message: String,
}

/// One drawn series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label (empty: no legend entry).
    pub label: String,
    /// Points `(x, y)`; NaN points are skipped (and break lines).
    pub points: Vec<(f64, f64)>,
    /// Draw as a line (true) or as dots (false).
    pub line: bool,
    /// Palette index.
    pub color: usize,
}

/// A line/point chart.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Chart {
    /// Title.
    pub title: String,
    /// X-axis label.
    pub x_label: String,
    /// Y-axis label.
    pub y_label: String,
    /// Series in drawing order.
    pub series: Vec<Series>,
    /// Vertical reference lines `(x, label)` (e.g. AM, GM, BP).
    pub markers: Vec<(f64, String)>,
    /// Fixed y range (default: from the data).
    pub y_range: Option<(f64, f64)>,
}

fn color(i: usize) -> RGBColor {
    const P: [RGBColor; 8] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(127, 127, 127),
    ];
    P[i % P.len()]
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = chronocooked_analysis::neural::finite_range(values);
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 0.5, hi + 0.5);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

pub(super) fn err<E: std::fmt::Debug>(path: &Path) -> impl Fn(E) -> FigureError + '_ {
    move |e| FigureError {
        path: path.display().to_string(),
        message: format!("{e:?}"),
    }
}

/// Writes the figure file `path` atomically: `draw` renders into a temporary file beside it
/// (same extension), renamed over `path` once complete ([`chronocooked_env::fs`]).
pub(super) fn atomic(
    path: &Path,
    draw: impl FnOnce(&Path) -> Result<(), FigureError>,
) -> Result<(), FigureError> {
    let mut inner = None;
    let done = chronocooked_env::fs::write_atomic_with(path, |tmp| {
        draw(tmp).map_err(|e| {
            let m = e.message.clone();
            inner = Some(e);
            m
        })
    });
    match (done, inner) {
        (Ok(()), _) => Ok(()),
        (Err(_), Some(e)) => Err(e),
        (Err(e), None) => Err(err(path)(e)),
    }
}

/// The points of `s` with both coordinates finite (NaN marks a gap).
fn finite_points(s: &Series) -> Vec<(f64, f64)> {
    s.points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect()
}

/// The corner of the plot area the data crowds least, for the legend: every point and
/// points along each line segment are counted in a box of 40% × 35% of the axes at each
/// corner; ties go to the upper left, then upper right, lower left, lower right.
pub(super) fn legend_corner(chart: &Chart, x: (f64, f64), y: (f64, f64)) -> SeriesLabelPosition {
    let (w, h) = (x.1 - x.0, y.1 - y.0);
    if !(w > 0.0 && h > 0.0) {
        return SeriesLabelPosition::UpperLeft;
    }
    // (left?, top?) of each candidate corner, in order of preference.
    let corners = [(true, true), (false, true), (true, false), (false, false)];
    let mut counts = [0usize; 4];
    let mut count = |px: f64, py: f64| {
        let (u, v) = ((px - x.0) / w, (py - y.0) / h);
        for (k, (left, top)) in corners.iter().enumerate() {
            let in_x = if *left { u <= 0.4 } else { u >= 0.6 };
            let in_y = if *top { v >= 0.65 } else { v <= 0.35 };
            if in_x && in_y {
                counts[k] += 1;
            }
        }
    };
    for s in &chart.series {
        let pts = finite_points(s);
        for p in &pts {
            count(p.0, p.1);
        }
        if s.line {
            for seg in pts.windows(2) {
                for i in 1..10 {
                    let t = f64::from(i) / 10.0;
                    count(
                        seg[0].0 + t * (seg[1].0 - seg[0].0),
                        seg[0].1 + t * (seg[1].1 - seg[0].1),
                    );
                }
            }
        }
    }
    let best = (0..4).min_by_key(|&k| (counts[k], k)).unwrap_or(0);
    match corners[best] {
        (true, true) => SeriesLabelPosition::UpperLeft,
        (false, true) => SeriesLabelPosition::UpperRight,
        (true, false) => SeriesLabelPosition::LowerLeft,
        (false, false) => SeriesLabelPosition::LowerRight,
    }
}

/// Draws `chart` on `root` (the caller presents the area).
pub(super) fn draw_chart<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    chart: &Chart,
    path: &Path,
) -> Result<(), FigureError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err(path))?;
    let xs = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .chain(chart.markers.iter().map(|m| m.0));
    let (x0, x1) = range(xs);
    let (y0, y1) = chart.y_range.unwrap_or_else(|| {
        range(
            chart
                .series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1)),
        )
    });
    let mut c = ChartBuilder::on(&root)
        .caption(&chart.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(56)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err(path))?;
    c.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(err(path))?;
    for (x, label) in &chart.markers {
        let style = ShapeStyle::from(&BLACK.mix(0.5)).stroke_width(1);
        c.draw_series(LineSeries::new(vec![(*x, y0), (*x, y1)], style))
            .map_err(err(path))?;
        c.draw_series(std::iter::once(Text::new(
            label.clone(),
            (*x, y1 - 0.06 * (y1 - y0)),
            ("sans-serif", 13),
        )))
        .map_err(err(path))?;
    }
    for s in &chart.series {
        let col = color(s.color);
        let drawn = if s.line {
            // Split at NaN so gaps stay gaps.
            let mut parts: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
            for &(x, y) in &s.points {
                if x.is_finite() && y.is_finite() {
                    parts.last_mut().expect("non-empty").push((x, y));
                } else if !parts.last().expect("non-empty").is_empty() {
                    parts.push(Vec::new());
                }
            }
            let mut last = None;
            for p in parts.into_iter().filter(|p| !p.is_empty()) {
                last = Some(
                    c.draw_series(LineSeries::new(p, col.stroke_width(2)))
                        .map_err(err(path))?,
                );
            }
            last
        } else {
            let pts = finite_points(s);
            Some(
                c.draw_series(
                    pts.into_iter()
                        .map(|p| Circle::new(p, 3, col.mix(0.6).filled())),
                )
                .map_err(err(path))?,
            )
        };
        if let (Some(d), false) = (drawn, s.label.is_empty()) {
            d.label(s.label.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 16, y)], col.stroke_width(2))
            });
        }
    }
    if chart.series.iter().any(|s| !s.label.is_empty()) {
        c.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 13))
            .position(legend_corner(chart, (x0, x1), (y0, y1)))
            .draw()
            .map_err(err(path))?;
    }
    Ok(())
}

/// Readies a figure's files: the font registered, `stem`'s folder created; returns
/// `(<stem>.svg, <stem>.png)`.
pub(super) fn figure_paths(stem: &Path) -> Result<(PathBuf, PathBuf), FigureError> {
    ensure_font();
    if let Some(dir) = stem.parent() {
        std::fs::create_dir_all(dir).map_err(err(stem))?;
    }
    Ok((stem.with_extension("svg"), stem.with_extension("png")))
}

/// Writes `chart` to `<stem>.svg` and `<stem>.png` (800×520); returns both paths.
pub fn write_chart(stem: &Path, chart: &Chart) -> Result<Vec<PathBuf>, FigureError> {
    write_chart_sized(stem, chart, (800, 520))
}

/// [`write_chart`] at `size` (width, height in pixels), e.g. the report's small panels.
pub fn write_chart_sized(
    stem: &Path,
    chart: &Chart,
    size: (u32, u32),
) -> Result<Vec<PathBuf>, FigureError> {
    let (svg, png) = figure_paths(stem)?;
    atomic(&svg, |tmp| {
        let root = SVGBackend::new(tmp, size).into_drawing_area();
        draw_chart(root.clone(), chart, &svg)?;
        root.present().map_err(err(&svg))
    })?;
    atomic(&png, |tmp| {
        let root = BitMapBackend::new(tmp, size).into_drawing_area();
        draw_chart(root.clone(), chart, &png)?;
        root.present().map_err(err(&png))
    })?;
    Ok(vec![svg, png])
}

fn draw_heatmap<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    rows: &[Vec<f64>],
    path: &Path,
) -> Result<(), FigureError>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(err(path))?;
    let n = rows.len().max(1);
    let t = rows.first().map_or(1, Vec::len).max(1);
    let mut c = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(56)
        .build_cartesian_2d(0..t, 0..n)
        .map_err(err(path))?;
    c.configure_mesh()
        .disable_mesh()
        .x_desc("time since oven on (steps)")
        .y_desc("unit (sorted by peak time)")
        .label_style(("sans-serif", 14))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(err(path))?;
    c.draw_series(rows.iter().enumerate().flat_map(|(i, row)| {
        row.iter().enumerate().map(move |(j, &v)| {
            let v = if v.is_finite() {
                v.clamp(0.0, 1.0)
            } else {
                0.0
            };
            let col = HSLColor(0.66 - 0.66 * v, 0.9, 0.15 + 0.45 * v);
            Rectangle::new([(j, i), (j + 1, i + 1)], col.filled())
        })
    }))
    .map_err(err(path))?;
    root.present().map_err(err(path))?;
    Ok(())
}

/// Most rows a heat map draws; larger populations (e.g. 1,000 SBF oscillators) are shown as
/// this many bands, each the mean of adjacent units in peak-time order (keeps the SVG small).
pub const MAX_HEATMAP_ROWS: usize = 200;

/// Averages consecutive rows into at most `max` bands (rows unchanged when there are fewer).
fn bin_rows(rows: Vec<Vec<f64>>, max: usize) -> Vec<Vec<f64>> {
    if rows.len() <= max {
        return rows;
    }
    let n = rows.len();
    (0..max)
        .map(|b| {
            let (lo, hi) = (b * n / max, ((b + 1) * n / max).max(b * n / max + 1));
            let width = rows[lo].len();
            (0..width)
                .map(|t| rows[lo..hi].iter().map(|r| r[t]).sum::<f64>() / (hi - lo) as f64)
                .collect()
        })
        .collect()
}

/// Heat map of a `[time, units]` trial average, each unit min–max normalised and units
/// sorted by peak time (the usual time-cell sequence plot); SVG and PNG.
pub fn write_heatmap(
    stem: &Path,
    title: &str,
    avg: &[f64],
    units: usize,
) -> Result<Vec<PathBuf>, FigureError> {
    write_heatmap_sized(stem, title, avg, units, (800, 520))
}

/// [`write_heatmap`] at `size` (width, height in pixels).
pub fn write_heatmap_sized(
    stem: &Path,
    title: &str,
    avg: &[f64],
    units: usize,
    size: (u32, u32),
) -> Result<Vec<PathBuf>, FigureError> {
    ensure_font();
    if let Some(dir) = stem.parent() {
        std::fs::create_dir_all(dir).map_err(err(stem))?;
    }
    let time = avg.len() / units.max(1);
    let mut rows: Vec<(usize, Vec<f64>)> = (0..units)
        .map(|i| {
            let col: Vec<f64> = (0..time).map(|t| avg[t * units + i]).collect();
            let (lo, hi) = chronocooked_analysis::neural::finite_range(col.iter().copied());
            let norm: Vec<f64> = col
                .iter()
                .map(|&v| if hi > lo { (v - lo) / (hi - lo) } else { 0.0 })
                .collect();
            (chronocooked_analysis::neural::argmax(&norm), norm)
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    let rows = bin_rows(rows.into_iter().map(|r| r.1).collect(), MAX_HEATMAP_ROWS);
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    atomic(&svg, |tmp| {
        draw_heatmap(
            SVGBackend::new(tmp, size).into_drawing_area(),
            title,
            &rows,
            &svg,
        )
    })?;
    atomic(&png, |tmp| {
        draw_heatmap(
            BitMapBackend::new(tmp, size).into_drawing_area(),
            title,
            &rows,
            &png,
        )
    })?;
    Ok(vec![svg, png])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(points: Vec<(f64, f64)>, line: bool) -> Series {
        Series {
            label: "s".into(),
            points,
            line,
            color: 0,
        }
    }

    #[test]
    fn the_legend_goes_to_the_emptiest_corner() {
        let axes = ((0.0, 10.0), (0.0, 10.0));
        let chart = |series| Chart {
            series,
            ..Chart::default()
        };
        let pos = |c: &Chart| format!("{:?}", legend_corner(c, axes.0, axes.1));
        // A rising line leaves the upper left free (the default).
        let rising = chart(vec![line(vec![(0.0, 0.0), (10.0, 10.0)], true)]);
        assert_eq!(pos(&rising), "UpperLeft");
        // A falling line crosses the upper left and the lower right.
        let falling = chart(vec![line(vec![(0.0, 10.0), (10.0, 0.0)], true)]);
        assert_eq!(pos(&falling), "UpperRight");
        // …and dots in the upper right leave the lower left.
        let mut both = falling.clone();
        both.series.push(line(vec![(9.0, 9.0), (8.0, 9.5)], false));
        assert_eq!(pos(&both), "LowerLeft");
    }
}
