//! Figures of the paper's study in the paper's form (SVG + PNG): FOC distributions per TD,
//! mean FOC vs TD and SD vs mean with their regression lines, the psychometric grid (models ×
//! anchor pairs) with the paper's least-squares fit and the lab's maximum-likelihood fit,
//! WF against log2(L/S), the multi-timer reward per curriculum level, and the exact timer's
//! reward against the test buffer.

use super::bisection::BisectionModel;
use super::fi::FiModel;
use super::multitimer::LEVELS;
use super::study::PaperStudy;
use chronocooked_analysis::behaviour::foc::linear_fit;
use chronocooked_present::figures::{Chart, FigureError, Series, write_chart, write_panels};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn series(label: &str, points: Vec<(f64, f64)>, line: bool, color: usize) -> Series {
    Series {
        label: label.into(),
        points,
        line,
        color,
    }
}

/// Least-squares line through `pts` (three or more finite points), labelled with its R².
fn regression_line(label: &str, pts: &[(f64, f64)], color: usize) -> Option<Series> {
    let (x, y): (Vec<f64>, Vec<f64>) = pts.iter().copied().filter(|p| p.1.is_finite()).unzip();
    // A line through two points says nothing (R² 1 by construction).
    if x.len() < 3 {
        return None;
    }
    let (slope, icpt, r2) = linear_fit(&x, &y);
    if !slope.is_finite() {
        return None;
    }
    let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some(series(
        &format!("{label} (R² {r2:.2})"),
        vec![(lo, slope * lo + icpt), (hi, slope * hi + icpt)],
        true,
        color,
    ))
}

/// `pts` as dots with their regression line; one legend entry, `label`, on the line (on the
/// dots when there is no line).
fn dots_with_fit(label: &str, pts: Vec<(f64, f64)>, color: usize) -> Vec<Series> {
    let fit = regression_line(label, &pts, color);
    let dots_label = if fit.is_some() { "" } else { label };
    let mut out = vec![series(dots_label, pts, false, color)];
    out.extend(fit);
    out
}

/// One panel per model: every pooled FOC per TD (dots, spread slightly along x) with the
/// per-TD mean (line) and FOC = TD (grey).
pub fn foc_panels(fi: &[FiModel]) -> Vec<Option<Chart>> {
    fi.iter()
        .map(|m| {
            let mut dots = Vec::new();
            for c in &m.cells {
                let n = c.focs.len().max(1) as f64;
                for (i, f) in c.focs.iter().enumerate() {
                    let jitter = (i as f64 / n - 0.5) * 0.8;
                    dots.push((f64::from(c.td) + jitter, *f));
                }
            }
            let tds: Vec<f64> = m.cells.iter().map(|c| f64::from(c.td)).collect();
            let means = m
                .cells
                .iter()
                .map(|c| (f64::from(c.td), c.pooled.mean))
                .collect();
            let lo = tds.first().copied().unwrap_or(0.0);
            let hi = tds.last().copied().unwrap_or(1.0);
            Some(Chart {
                title: format!("{}: first oven check", m.model),
                x_label: "TD (steps)".into(),
                y_label: "FOC (steps)".into(),
                series: vec![
                    series("FOC = TD", vec![(lo, lo), (hi, hi)], true, 7),
                    series("episodes", dots, false, 0),
                    series("mean", means, true, 3),
                ],
                markers: vec![],
                y_range: None,
            })
        })
        .collect()
}

/// Mean FOC vs TD and SD vs mean FOC, every model with its regression line.
pub fn scalar_panels(fi: &[FiModel]) -> Vec<Option<Chart>> {
    let mut mean_vs_td = Vec::new();
    let mut sd_vs_mean = Vec::new();
    for (k, m) in fi.iter().enumerate() {
        let a: Vec<(f64, f64)> = m
            .cells
            .iter()
            .map(|c| (f64::from(c.td), c.pooled.mean))
            .collect();
        let b: Vec<(f64, f64)> = m
            .cells
            .iter()
            .map(|c| (c.pooled.mean, c.pooled.sd))
            .collect();
        mean_vs_td.extend(dots_with_fit(&m.model, a, k));
        sd_vs_mean.extend(dots_with_fit(&m.model, b, k));
    }
    vec![
        Some(Chart {
            title: "mean FOC vs TD".into(),
            x_label: "TD (steps)".into(),
            y_label: "mean FOC (steps)".into(),
            series: mean_vs_td,
            markers: vec![],
            y_range: None,
        }),
        Some(Chart {
            title: "SD vs mean FOC (scalar property)".into(),
            x_label: "mean FOC (steps)".into(),
            y_label: "SD of FOC (steps)".into(),
            series: sd_vs_mean,
            markers: vec![],
            y_range: None,
        }),
    ]
}

fn logistic_points(bp: f64, k: f64, hi: u32) -> Vec<(f64, f64)> {
    (0..=(hi * 10))
        .map(|i| {
            let d = f64::from(i) / 10.0;
            let p = if k > 0.0 {
                1.0 / (1.0 + (-(d - bp) / k).exp())
            } else {
                f64::from(u8::from(d > bp))
            };
            (d, p)
        })
        .collect()
}

/// Models × anchor pairs: the run-averaged P(long), the paper's least-squares fit and the
/// lab's binomial maximum-likelihood fit; returns the grid shape and its panels.
pub fn psychometric_panels(bis: &[BisectionModel]) -> ((usize, usize), Vec<Option<Chart>>) {
    let mut pairs: Vec<(u32, u32)> = bis
        .iter()
        .flat_map(|m| m.cells.iter().map(|c| (c.short, c.long)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let mut panels = Vec::new();
    for m in bis {
        for &(s, l) in &pairs {
            let Some(c) = m.cells.iter().find(|c| (c.short, c.long) == (s, l)) else {
                panels.push(None);
                continue;
            };
            let avg: Vec<(f64, f64)> = c
                .curve
                .iter()
                .enumerate()
                .map(|(i, p)| (i as f64 + 1.0, *p))
                .collect();
            let mut ser = vec![series("run average", avg, false, 0)];
            if let Some(f) = c.fit {
                ser.push(series(
                    &format!("least squares (BP {:.1}, WF {:.2})", f.bp, f.wf),
                    logistic_points(f.bp, f.k, l + 4),
                    true,
                    3,
                ));
            }
            if let Some(f) = &c.mle {
                ser.push(series(
                    &format!("max. likelihood (BP {:.1})", f.bp),
                    logistic_points(f.bp, f.scale, l + 4),
                    true,
                    2,
                ));
            }
            let am = 0.5 * f64::from(s + l);
            let gm = f64::from(s * l).sqrt();
            panels.push(Some(Chart {
                title: format!("{} {s}-{l}", m.model),
                x_label: "probe duration (steps)".into(),
                y_label: "P(long)".into(),
                series: ser,
                markers: vec![(am, "AM".into()), (gm, "GM".into())],
                y_range: Some((-0.05, 1.05)),
            }));
        }
    }
    ((bis.len(), pairs.len()), panels)
}

/// WF (least-squares fit of the averaged curve) against log2(L/S), per model with its
/// regression line.
pub fn wf_chart(bis: &[BisectionModel]) -> Chart {
    let mut ser = Vec::new();
    for (k, m) in bis.iter().enumerate() {
        let pts: Vec<(f64, f64)> = m
            .cells
            .iter()
            .filter_map(|c| {
                let f = c.fit?;
                (f.wf.is_finite() && f.wf > 0.0)
                    .then(|| ((f64::from(c.long) / f64::from(c.short)).log2(), f.wf))
            })
            .collect();
        if pts.is_empty() {
            continue;
        }
        ser.extend(dots_with_fit(&m.model, pts, k));
    }
    Chart {
        title: "Weber fraction vs anchor ratio".into(),
        x_label: "log2(L/S)".into(),
        y_label: "WF".into(),
        series: ser,
        markers: vec![],
        y_range: None,
    }
}

/// Palette index of a curriculum (exact red, categorical blue).
fn curriculum_color(curriculum: &str) -> usize {
    if curriculum == "exact" { 3 } else { 0 }
}

/// The distinct `names` in the order first seen (a figure's models, in legend order).
fn first_seen<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

/// Multi-timer small multiples, one column per model: the training reward at each
/// curriculum level (run means as dots, their mean as a line), the final policy's reward at
/// every evaluated TD (trained TDs marked; the others are out of distribution, as in the
/// paper's figure) and its oven-off time against TD (−1: never taken); exact red,
/// categorical blue, the legend in the top row. Returns the grid
/// shape (3 rows × models) and its panels.
pub fn multitimer_panels(s: &PaperStudy) -> ((usize, usize), Vec<Option<Chart>>) {
    let models = first_seen(s.multitimer.iter().map(|c| c.model.as_str()));
    let mut levels = Vec::new();
    let mut rewards = Vec::new();
    let mut offs = Vec::new();
    for &model in &models {
        let mut lv = Vec::new();
        let mut rw = Vec::new();
        let mut of = Vec::new();
        let mut trained: Vec<u32> = Vec::new();
        let mut hi = 1.0_f64;
        for c in s.multitimer.iter().filter(|c| c.model == model) {
            let k = curriculum_color(&c.curriculum);
            // Several TD lists for one model (the full paper grid): each says which.
            let lists = s
                .multitimer
                .iter()
                .filter(|d| d.model == model && d.curriculum == c.curriculum)
                .count();
            let label = if lists > 1 {
                let tds: Vec<String> = c.tds.iter().map(u32::to_string).collect();
                format!(
                    "{}, TDs {} ({} runs)",
                    c.curriculum,
                    tds.join(","),
                    c.runs.len()
                )
            } else {
                format!("{} ({} runs)", c.curriculum, c.runs.len())
            };
            let dots: Vec<(f64, f64)> = c
                .runs
                .iter()
                .flat_map(|r| {
                    r.level_reward
                        .iter()
                        .enumerate()
                        .filter_map(|(l, x)| Some((l as f64, (*x)?)))
                })
                .collect();
            lv.push(series("", dots, false, k));
            lv.push(series(
                &label,
                c.level_reward
                    .iter()
                    .enumerate()
                    .map(|(l, x)| (l as f64, x.mean))
                    .collect(),
                true,
                k,
            ));
            if c.level_eval.iter().any(|x| x.n > 0) {
                lv.push(series(
                    &format!("{}: level's policy, test", c.curriculum),
                    c.level_eval
                        .iter()
                        .enumerate()
                        .filter(|(_, x)| x.n > 0)
                        .map(|(l, x)| (l as f64, x.mean))
                        .collect(),
                    true,
                    k + 1,
                ));
            }
            // One legend per column (top row): the curricula keep their colours below.
            rw.push(series(
                "",
                c.tested
                    .iter()
                    .map(|(td, r, _)| (f64::from(*td), r.mean))
                    .collect(),
                true,
                k,
            ));
            of.push(series(
                "",
                c.tested
                    .iter()
                    .map(|(td, _, o)| (f64::from(*td), o.mean))
                    .collect(),
                true,
                k,
            ));
            for (td, _, _) in &c.per_td {
                if !trained.contains(td) {
                    trained.push(*td);
                }
            }
            if let Some((td, _, _)) = c.tested.last() {
                hi = hi.max(f64::from(*td));
            }
        }
        of.insert(0, series("off = TD", vec![(1.0, 1.0), (hi, hi)], true, 7));
        let marks: Vec<(f64, String)> = trained
            .iter()
            .map(|td| (f64::from(*td), String::new()))
            .collect();
        levels.push(Some(Chart {
            title: format!("{model}: training reward per level"),
            x_label: "curriculum level (0 warm-up, then timers)".into(),
            y_label: "mean training reward".into(),
            series: lv,
            markers: vec![],
            y_range: Some((-0.05, 1.05)),
        }));
        rewards.push(Some(Chart {
            title: format!("{model}: final reward per TD"),
            x_label: "tested TD (steps; lines: trained TDs)".into(),
            y_label: "mean reward".into(),
            series: rw,
            markers: marks.clone(),
            y_range: Some((-0.05, 1.05)),
        }));
        offs.push(Some(Chart {
            title: format!("{model}: oven-off time"),
            x_label: "tested TD (steps; lines: trained TDs)".into(),
            y_label: "oven-off time (steps; −1 never)".into(),
            series: of,
            markers: marks,
            y_range: None,
        }));
    }
    let cols = models.len();
    let panels = levels.into_iter().chain(rewards).chain(offs).collect();
    ((3, cols), panels)
}

/// The exact timer in the paper's form: one panel per TD, mean reward against the test
/// buffer (% of TD) per model, ± SD over runs as dots, and the reduced reward 0.1 that any
/// delivery earns (the paper's red dotted line) in grey.
pub fn exact_timer_panels(s: &PaperStudy) -> Vec<Option<Chart>> {
    let mut tds: Vec<u32> = s.exact_timer.iter().map(|c| c.td).collect();
    tds.sort_unstable();
    tds.dedup();
    let models = first_seen(s.exact_timer.iter().map(|c| c.model.as_str()));
    tds.iter()
        .map(|&td| {
            let mut ser = vec![series(
                "reduced reward 0.1",
                vec![(0.0, 0.1), (75.0, 0.1)],
                true,
                7,
            )];
            for (k, &model) in models.iter().enumerate() {
                let Some(c) = s
                    .exact_timer
                    .iter()
                    .find(|c| c.td == td && c.model == model)
                else {
                    continue;
                };
                let pts = |sign: f64| -> Vec<(f64, f64)> {
                    c.buffers
                        .iter()
                        .filter(|(_, x)| x.n > 1)
                        .map(|(f, x)| (f * 100.0, x.mean + sign * x.sd))
                        .collect()
                };
                ser.push(series(
                    &format!("{model} ({} runs)", c.runs),
                    c.buffers.iter().map(|(f, x)| (f * 100.0, x.mean)).collect(),
                    true,
                    k,
                ));
                ser.push(series("", pts(1.0), false, k));
                ser.push(series("", pts(-1.0), false, k));
            }
            Some(Chart {
                title: format!("exact timer, TD {td}"),
                x_label: "test buffer (% of TD, either side)".into(),
                y_label: "mean reward".into(),
                series: ser,
                markers: vec![],
                y_range: Some((-0.05, 1.05)),
            })
        })
        .collect()
}

/// The paper's multi-timer figures ("Timers = 1 … 5": reward and average oven-off time
/// against the tested TD, untrained TDs included): per curriculum and TD list two rows —
/// each level's policy's mean reward, then its mean oven-off time over the cells where the
/// soup was taken — and one column per level 1 … 5, a line per model (mean over the runs
/// that kept that level), the level's trained TDs as markers. Returns the grid shape and
/// its panels (none without per-level curves).
pub fn level_panels(s: &PaperStudy) -> ((usize, usize), Vec<Option<Chart>>) {
    let mut keys: Vec<(&str, &[u32])> = s
        .multitimer
        .iter()
        .filter(|c| {
            c.runs
                .iter()
                .any(|r| r.level_curves.iter().skip(1).any(|v| !v.is_empty()))
        })
        .map(|c| (c.curriculum.as_str(), c.tds.as_slice()))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    let models = first_seen(s.multitimer.iter().map(|c| c.model.as_str()));
    let mut panels = Vec::new();
    for &(curriculum, tds) in &keys {
        for (row, y_label) in [(0, "mean reward"), (1, "mean oven-off time (taken)")] {
            for level in 1..LEVELS {
                let mut ser = Vec::new();
                for (k, &model) in models.iter().enumerate() {
                    let Some(c) = s
                        .multitimer
                        .iter()
                        .find(|c| c.model == model && c.curriculum == curriculum && c.tds == tds)
                    else {
                        continue;
                    };
                    let mut at: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
                    let mut runs = 0;
                    for r in &c.runs {
                        let Some(curve) = r.level_curves.get(level).filter(|v| !v.is_empty())
                        else {
                            continue;
                        };
                        runs += 1;
                        for p in curve {
                            let y = if row == 0 { p.reward } else { p.off_time };
                            if y.is_finite() {
                                at.entry(p.td).or_default().push(y);
                            }
                        }
                    }
                    if runs == 0 {
                        continue;
                    }
                    let pts = at
                        .into_iter()
                        .map(|(td, v)| (f64::from(td), v.iter().sum::<f64>() / v.len() as f64))
                        .collect();
                    ser.push(series(&format!("{model} ({runs} runs)"), pts, true, k));
                }
                let trained = &tds[..level.min(tds.len())];
                panels.push((!ser.is_empty()).then(|| {
                    Chart {
                        title: format!("{curriculum}, Timers = {level} ({})", {
                            let t: Vec<String> = trained.iter().map(u32::to_string).collect();
                            t.join(",")
                        }),
                        x_label: "tested TD (steps)".into(),
                        y_label: y_label.into(),
                        series: ser,
                        markers: trained
                            .iter()
                            .map(|&t| (f64::from(t), "trained".to_string()))
                            .collect(),
                        y_range: (row == 0).then_some((-0.05, 1.05)),
                    }
                }));
            }
        }
    }
    ((keys.len() * 2, LEVELS - 1), panels)
}

/// Writes every figure into `dir`; returns the files written.
pub fn write_figures(dir: &Path, s: &PaperStudy) -> Result<Vec<PathBuf>, FigureError> {
    let mut out = Vec::new();
    if !s.fi.is_empty() {
        let foc = foc_panels(&s.fi);
        let cols = foc.len().min(4);
        let rows = foc.len().div_ceil(cols);
        out.extend(write_panels(&dir.join("fi_foc"), (rows, cols), &foc)?);
        out.extend(write_panels(
            &dir.join("fi_scalar"),
            (1, 2),
            &scalar_panels(&s.fi),
        )?);
    }
    if !s.bisection.is_empty() {
        let (grid, panels) = psychometric_panels(&s.bisection);
        out.extend(write_panels(&dir.join("bisection_grid"), grid, &panels)?);
        out.extend(write_chart(
            &dir.join("wf_vs_ratio"),
            &wf_chart(&s.bisection),
        )?);
    }
    if !s.multitimer.is_empty() {
        let (grid, panels) = multitimer_panels(s);
        out.extend(write_panels(&dir.join("multitimer"), grid, &panels)?);
        let (grid, panels) = level_panels(s);
        if panels.iter().any(Option::is_some) {
            out.extend(write_panels(&dir.join("multitimer_levels"), grid, &panels)?);
        }
    }
    if !s.exact_timer.is_empty() {
        let panels = exact_timer_panels(s);
        let cols = panels.len().min(5);
        let rows = panels.len().div_ceil(cols);
        out.extend(write_panels(
            &dir.join("exact_timer"),
            (rows, cols),
            &panels,
        )?);
    }
    Ok(out)
}
