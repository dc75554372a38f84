//! Figures (plotters; every figure written as SVG and PNG with the bundled DejaVu Sans font,
//! so no system fonts are needed): line/point charts (psychometric curves, PI curves, FOC
//! strips, reward and oven-off vs TD, learning curves, decoder error) and activity heat maps.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::{Path, PathBuf};
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

fn ensure_font() {
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
    let (lo, hi) = crate::neural::finite_range(values);
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 0.5, hi + 0.5);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

fn err<E: std::fmt::Debug>(path: &Path) -> impl Fn(E) -> FigureError + '_ {
    move |e| FigureError {
        path: path.display().to_string(),
        message: format!("{e:?}"),
    }
}

fn draw_chart<DB: DrawingBackend>(
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
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
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
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(err(path))?;
    }
    root.present().map_err(err(path))?;
    Ok(())
}

/// Writes `chart` to `<stem>.svg` and `<stem>.png` (800×520); returns both paths.
pub fn write_chart(stem: &Path, chart: &Chart) -> Result<Vec<PathBuf>, FigureError> {
    ensure_font();
    if let Some(dir) = stem.parent() {
        std::fs::create_dir_all(dir).map_err(err(stem))?;
    }
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    draw_chart(
        SVGBackend::new(&svg, (800, 520)).into_drawing_area(),
        chart,
        &svg,
    )?;
    draw_chart(
        BitMapBackend::new(&png, (800, 520)).into_drawing_area(),
        chart,
        &png,
    )?;
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

/// Heat map of a `[time, units]` trial average, each unit min–max normalised and units
/// sorted by peak time (the usual time-cell sequence plot); SVG and PNG.
pub fn write_heatmap(
    stem: &Path,
    title: &str,
    avg: &[f64],
    units: usize,
) -> Result<Vec<PathBuf>, FigureError> {
    ensure_font();
    if let Some(dir) = stem.parent() {
        std::fs::create_dir_all(dir).map_err(err(stem))?;
    }
    let time = avg.len() / units.max(1);
    let mut rows: Vec<(usize, Vec<f64>)> = (0..units)
        .map(|i| {
            let col: Vec<f64> = (0..time).map(|t| avg[t * units + i]).collect();
            let (lo, hi) = crate::neural::finite_range(col.iter().copied());
            let norm: Vec<f64> = col
                .iter()
                .map(|&v| if hi > lo { (v - lo) / (hi - lo) } else { 0.0 })
                .collect();
            (crate::neural::argmax(&norm), norm)
        })
        .collect();
    rows.sort_by_key(|r| r.0);
    let rows: Vec<Vec<f64>> = rows.into_iter().map(|r| r.1).collect();
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    draw_heatmap(
        SVGBackend::new(&svg, (800, 520)).into_drawing_area(),
        title,
        &rows,
        &svg,
    )?;
    draw_heatmap(
        BitMapBackend::new(&png, (800, 520)).into_drawing_area(),
        title,
        &rows,
        &png,
    )?;
    Ok(vec![svg, png])
}

/// The standard figures of one evaluation into `dir` (SVG + PNG each): psychometric curve
/// (bisection), FOC strip per TD (FI), PI response curves with their Gaussian fits,
/// reward and oven-off time vs TD (multi-timer). Returns the files written.
pub fn eval_figures(
    dir: &Path,
    metrics: &crate::metrics::Metrics,
    records: &[crate::protocol::EvalRecord],
) -> Result<Vec<PathBuf>, FigureError> {
    let mut out = Vec::new();
    let model = &metrics.model;
    if let Some(b) = &metrics.bisection {
        let mut series = vec![Series {
            label: "P(long)".into(),
            points: b
                .probes
                .iter()
                .zip(&b.p_long)
                .map(|(p, &v)| (p.t, v))
                .collect(),
            line: false,
            color: 0,
        }];
        let mut markers = vec![
            (f64::from(b.short), "S".to_string()),
            (f64::from(b.long), "L".to_string()),
            (0.5 * f64::from(b.short + b.long), "AM".to_string()),
            (
                (f64::from(b.short) * f64::from(b.long)).sqrt(),
                "GM".to_string(),
            ),
        ];
        if let Some(f) = &b.fit {
            let t0 = b.probes.first().map_or(0.0, |p| p.t);
            let t1 = b.probes.last().map_or(1.0, |p| p.t);
            let pts = (0..=200)
                .map(|k| {
                    let t = t0 + (t1 - t0) * f64::from(k) / 200.0;
                    let p = if f.scale > 0.0 {
                        1.0 / (1.0 + (-(t - f.bp) / f.scale).exp())
                    } else {
                        f64::from(u8::from(t > f.bp))
                    };
                    (t, p)
                })
                .collect();
            series.push(Series {
                label: format!("logistic fit (BP {:.2}, WF {:.2})", f.bp, f.wf),
                points: pts,
                line: true,
                color: 1,
            });
            markers.push((f.bp, "BP".to_string()));
        }
        let chart = Chart {
            title: format!("{model}: bisection {}-{}", b.short, b.long),
            x_label: "probe duration (steps)".into(),
            y_label: "P(long)".into(),
            series,
            markers,
            y_range: Some((-0.05, 1.05)),
        };
        out.extend(write_chart(&dir.join("psychometric"), &chart)?);
    }
    let focs: Vec<(f64, f64)> = records
        .iter()
        .filter(|r| r.condition.kind == "fi")
        .filter_map(|r| {
            crate::foc::episode_foc(&r.episode).map(|f| (f64::from(r.condition.td), f64::from(f)))
        })
        .collect();
    if let Some(fi) = &metrics.fi {
        let diag: Vec<(f64, f64)> = fi
            .foc
            .iter()
            .map(|s| (f64::from(s.td), f64::from(s.td)))
            .collect();
        let chart = Chart {
            title: format!("{model}: first oven check"),
            x_label: "target duration (steps)".into(),
            y_label: "FOC (oven time, steps)".into(),
            series: vec![
                Series {
                    label: "episodes".into(),
                    points: focs,
                    line: false,
                    color: 0,
                },
                Series {
                    label: "mean".into(),
                    points: fi.foc.iter().map(|s| (f64::from(s.td), s.mean)).collect(),
                    line: true,
                    color: 1,
                },
                Series {
                    label: "FOC = TD".into(),
                    points: diag,
                    line: true,
                    color: 7,
                },
            ],
            ..Chart::default()
        };
        out.extend(write_chart(&dir.join("foc"), &chart)?);
    }
    if !metrics.pi.is_empty() {
        let mut series = Vec::new();
        for (k, c) in metrics.pi.iter().enumerate() {
            series.push(Series {
                label: format!("release at {}x TD", c.factor),
                points: c
                    .rate
                    .iter()
                    .enumerate()
                    .map(|(t, &v)| (t as f64, v))
                    .collect(),
                line: true,
                color: k,
            });
            if let Some(f) = &c.fit {
                let pts = (0..c.rate.len())
                    .map(|t| {
                        let z = (t as f64 - f.peak) / f.spread;
                        (t as f64, f.amplitude * (-0.5 * z * z).exp() + f.baseline)
                    })
                    .collect();
                series.push(Series {
                    label: format!("fit: peak {:.1}, CV {:.2}", f.peak, f.cv),
                    points: pts,
                    line: false,
                    color: k + 3,
                });
            }
        }
        let td = f64::from(metrics.pi[0].td);
        let chart = Chart {
            title: format!("{model}: peak-interval probes"),
            x_label: "oven time (steps)".into(),
            y_label: "oven checks per episode".into(),
            series,
            markers: vec![(td, "TD".into())],
            y_range: Some((-0.05, 1.05)),
        };
        out.extend(write_chart(&dir.join("pi"), &chart)?);
    }
    if let Some(mt) = metrics
        .multi_timer
        .as_ref()
        .filter(|m| !m.by_buffer.is_empty())
    {
        let mut tds: Vec<u32> = mt.by_buffer.iter().map(|b| b.0).collect();
        tds.dedup();
        let series = tds
            .iter()
            .enumerate()
            .map(|(k, &td)| Series {
                label: format!("TD {td}"),
                points: mt
                    .by_buffer
                    .iter()
                    .filter(|b| b.0 == td)
                    .map(|b| (100.0 * b.1, b.2))
                    .collect(),
                line: true,
                color: k,
            })
            .collect();
        out.extend(write_chart(
            &dir.join("reward_vs_buffer"),
            &Chart {
                title: format!("{model}: exact timer, reward vs buffer"),
                x_label: "buffer (% of TD)".into(),
                y_label: "mean reward".into(),
                series,
                y_range: Some((-0.02, 1.02)),
                ..Chart::default()
            },
        )?);
    }
    let mt: Vec<&crate::metrics::ConditionSummary> = metrics
        .conditions
        .iter()
        .filter(|c| c.kind == "multi_timer")
        .collect();
    if !mt.is_empty() {
        let chart = Chart {
            title: format!("{model}: multi-timer reward and oven-off time vs TD"),
            x_label: "TD (steps; untrained TDs are OOD)".into(),
            y_label: "mean reward / oven-off time ÷ TD".into(),
            series: vec![
                Series {
                    label: "mean reward".into(),
                    points: mt
                        .iter()
                        .map(|c| (f64::from(c.td), c.mean_reward))
                        .collect(),
                    line: true,
                    color: 0,
                },
                Series {
                    label: "oven-off time / TD".into(),
                    points: mt
                        .iter()
                        .map(|c| (f64::from(c.td), c.mean_oven_off / f64::from(c.td)))
                        .collect(),
                    line: true,
                    color: 1,
                },
            ],
            ..Chart::default()
        };
        out.extend(write_chart(&dir.join("multi_timer"), &chart)?);
    }
    Ok(out)
}

/// Population figures of one activity dataset population (`avg` = `[time, units]` trial
/// average, `cube` = the per-trial data): example ramps (the three units with the largest
/// |r| against time), the mean Welch spectrum, and decoder error vs time (ridge and Bayes).
pub fn population_figures(
    dir: &Path,
    title: &str,
    cube: &crate::neural::Cube,
) -> Result<Vec<PathBuf>, FigureError> {
    use crate::decode::{Decoder, decode_time};
    let u = cube.units;
    let avg = cube.average();
    let mut out = Vec::new();
    let mut ramps = crate::neural::classify_ramps(&avg, u, 0.9, 0.05);
    ramps.sort_by(|a, b| b.r.abs().total_cmp(&a.r.abs()));
    let series = ramps
        .iter()
        .take(3)
        .enumerate()
        .map(|(k, r)| Series {
            label: format!("unit {} (r = {:.2})", r.unit, r.r),
            points: (0..cube.time)
                .map(|t| (t as f64, avg[t * u + r.unit]))
                .collect(),
            line: true,
            color: k,
        })
        .collect();
    out.extend(write_chart(
        &dir.join("ramps"),
        &Chart {
            title: format!("{title}: most ramp-like units"),
            x_label: "time since oven on (steps)".into(),
            y_label: "trial-averaged activity".into(),
            series,
            ..Chart::default()
        },
    )?);
    if cube.time >= 8 {
        let mut mean_power: Vec<f64> = Vec::new();
        let mut freqs = Vec::new();
        for i in 0..u {
            let x: Vec<f64> = (0..cube.time)
                .map(|t| avg[t * u + i])
                .filter(|v| v.is_finite())
                .collect();
            if x.len() < 8 {
                continue;
            }
            let s = crate::oscillation::welch(&x, x.len().min(cube.time), 1.0);
            if mean_power.is_empty() {
                mean_power = vec![0.0; s.power.len()];
                freqs = s.freqs.clone();
            }
            for (m, p) in mean_power.iter_mut().zip(&s.power) {
                *m += p / u as f64;
            }
        }
        out.extend(write_chart(
            &dir.join("spectrum"),
            &Chart {
                title: format!("{title}: mean power spectrum"),
                x_label: "frequency (cycles per step)".into(),
                y_label: "power".into(),
                series: vec![Series {
                    label: String::new(),
                    points: freqs.into_iter().zip(mean_power).collect(),
                    line: true,
                    color: 0,
                }],
                ..Chart::default()
            },
        )?);
    }
    let series = [Decoder::Ridge, Decoder::Bayes]
        .iter()
        .enumerate()
        .map(|(k, &d)| {
            let r = decode_time(cube, d, 5, 1.0);
            Series {
                label: format!("{d:?} (mean {:.2} steps)", r.mean_abs_error),
                points: r
                    .error_by_time
                    .iter()
                    .enumerate()
                    .map(|(t, &e)| (t as f64, e))
                    .collect(),
                line: true,
                color: k,
            }
        })
        .collect();
    out.extend(write_chart(
        &dir.join("decoding"),
        &Chart {
            title: format!("{title}: elapsed-time decoding error"),
            x_label: "time since oven on (steps)".into(),
            y_label: "|decoded − true| (steps)".into(),
            series,
            ..Chart::default()
        },
    )?);
    Ok(out)
}

/// Learning curve of a run folder's `curves.csv` (PPO: training success and evaluation
/// success vs env steps; timing agents: the same vs env steps).
pub fn learning_curve(run_dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    let path = run_dir.join("curves.csv");
    let text = std::fs::read_to_string(&path).map_err(err(&path))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name);
    let x = col("env_steps");
    let train = col("success_rate").or_else(|| col("train_success"));
    let eval = col("eval_success");
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let pick = |c: Option<usize>| -> Vec<(f64, f64)> {
        match (x, c) {
            (Some(x), Some(c)) => rows
                .iter()
                .map(|r| {
                    (
                        r.get(x).copied().unwrap_or(f64::NAN),
                        r.get(c).copied().unwrap_or(f64::NAN),
                    )
                })
                .collect(),
            _ => Vec::new(),
        }
    };
    let mut series = vec![Series {
        label: "training success".into(),
        points: pick(train),
        line: true,
        color: 0,
    }];
    let ev: Vec<(f64, f64)> = pick(eval).into_iter().filter(|p| p.1.is_finite()).collect();
    if !ev.is_empty() {
        series.push(Series {
            label: "greedy evaluation".into(),
            points: ev,
            line: false,
            color: 3,
        });
    }
    write_chart(
        &run_dir.join("figures").join("learning_curve"),
        &Chart {
            title: format!("learning curve: {}", run_dir.display()),
            x_label: "env steps".into(),
            y_label: "success rate".into(),
            series,
            y_range: Some((-0.02, 1.02)),
            ..Chart::default()
        },
    )
}
