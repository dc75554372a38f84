//! Figures (plotters; every figure written as SVG and PNG with the bundled DejaVu Sans font,
//! so no system fonts are needed): the standard figures of an evaluation, of a recorded
//! population and of a run, and the leaderboard's psychometric grid ([`grid`]). Drawing
//! primitives (charts, heat maps) live in [`draw`], the HTML page kit of the reports and
//! cards in [`markup`]. The drawing kit of every report (leaderboard, paper study,
//! mechanism and fingerprint cards): it names metrics, never a report.

mod draw;
pub mod extensions;
pub mod grid;
pub mod markup;
mod matrix;
pub mod reproduction;

use chronocooked_analysis::records::ConditionKind;
use chronocooked_models::run_folder;
use draw::err;
pub use draw::{
    Chart, FigureError, Series, write_chart, write_chart_sized, write_heatmap, write_heatmap_sized,
};
pub use grid::{psychometric_grid, write_panels};
pub use matrix::{LabelledMatrix, write_matrix};
use std::path::{Path, PathBuf};

/// The standard figures of one evaluation into `dir` (SVG + PNG each): psychometric curve
/// (bisection), FOC strip per TD (FI), PI response curves with their Gaussian fits,
/// reward and oven-off time vs TD (multi-timer), the share of choices of each counter
/// (multi-anchor), each oven's P(long) beside the one-oven curve (multi-oven) and mean tp
/// against ts with the fitted observer (reproduction). Returns the files written.
pub fn eval_figures(
    dir: &Path,
    metrics: &chronocooked_analysis::behaviour::metrics::Metrics,
    records: &[chronocooked_analysis::records::EvalRecord],
) -> Result<Vec<PathBuf>, FigureError> {
    let mut out = Vec::new();
    let model = &metrics.model;
    if let Some(b) = &metrics.bisection {
        let mut series = vec![Series {
            label: "P(long)".into(),
            points: b.points(),
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
        .filter(|r| r.condition.kind == ConditionKind::Fi)
        .filter_map(|r| {
            chronocooked_analysis::behaviour::foc::episode_foc(&r.episode)
                .map(|f| (f64::from(r.condition.td), f64::from(f)))
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
    let mt: Vec<&chronocooked_analysis::behaviour::metrics::ConditionSummary> = metrics
        .conditions
        .iter()
        .filter(|c| c.kind == ConditionKind::MultiTimer)
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
    if let Some(m) = &metrics.multi_anchor {
        let chart = extensions::multi_anchor_chart(model, m);
        out.extend(write_chart(&dir.join("categorization"), &chart)?);
    }
    if let Some(m) = &metrics.multi_oven {
        let chart = extensions::multi_oven_chart(model, m);
        out.extend(write_chart(&dir.join("ovens"), &chart)?);
    }
    if let Some(m) = metrics
        .reproduction
        .as_ref()
        .filter(|m| !m.contexts.is_empty())
    {
        let chart = reproduction::reproduction_chart(model, m);
        out.extend(write_chart(&dir.join("reproduction"), &chart)?);
    }
    Ok(out)
}

/// Population figures of one activity dataset population (`avg` = `[time, units]` trial
/// average, `cube` = the per-trial data): example ramps (the three units with the largest
/// |r| against time), the mean Welch spectrum, and decoder error vs time (ridge and Bayes).
pub fn population_figures(
    dir: &Path,
    title: &str,
    cube: &chronocooked_analysis::neural::Cube,
) -> Result<Vec<PathBuf>, FigureError> {
    use chronocooked_analysis::neural::decode::{Decoder, decode_time};
    let u = cube.units();
    let avg = cube.average();
    let mut out = Vec::new();
    let mut ramps = chronocooked_analysis::neural::classify_ramps(&avg, u, 0.9, 0.05);
    ramps.sort_by(|a, b| b.r.abs().total_cmp(&a.r.abs()));
    let series = ramps
        .iter()
        .take(3)
        .enumerate()
        .map(|(k, r)| Series {
            label: format!("unit {} (r = {:.2})", r.unit, r.r),
            points: (0..cube.time())
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
    if cube.time() >= 8 {
        let mut mean_power: Vec<f64> = Vec::new();
        let mut freqs = Vec::new();
        for i in 0..u {
            let x: Vec<f64> = (0..cube.time())
                .map(|t| avg[t * u + i])
                .filter(|v| v.is_finite())
                .collect();
            if x.len() < 8 {
                continue;
            }
            let s = chronocooked_analysis::neural::oscillation::welch(
                &x,
                x.len().min(cube.time()),
                1.0,
            );
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

/// Scalars every learner records (value estimate, reward-prediction error): not a timing
/// mechanism's signature.
const LEARNER_SIGNALS: [&str; 2] = ["value", "rpe"];

/// Heat maps and population figures of every population (≥ 2 units) of `dataset`, and —
/// for a model with only one-unit populations — their per-TD traces, aligned to oven-on;
/// for a reproduction dataset, each population's speed after Set ([`speed_figures`]).
pub fn neural_figures(
    dataset: &chronocooked_models::ActivityDataset,
    dir: &Path,
) -> Result<(), FigureError> {
    use chronocooked_analysis::neural::Cube;
    use chronocooked_models::Marker;
    speed_figures(dataset, dir)?;
    let window = dataset
        .trials
        .iter()
        .filter_map(|t| {
            t.first(Marker::OvenOn)
                .map(|on| t.steps.saturating_sub(on as usize + 1))
        })
        .max()
        .unwrap_or(0)
        .clamp(1, 60);
    let (aligned, used) = dataset.aligned(Marker::OvenOn, window - 1);
    let n = dataset.meta.n_units();
    if used.is_empty() {
        return Ok(());
    }
    let cube = Cube::from_f32(&aligned, used.len(), window, n);
    let avg = cube.average();
    // A model without a multi-unit population (drift-diffusion) is shown by the per-TD
    // traces of its own one-unit populations (not the learner's `value` / `rpe`).
    let only_scalars = dataset.meta.populations.iter().all(|p| p.size < 2);
    for p in &dataset.meta.populations {
        let r = dataset.meta.range(&p.name).expect("population exists");
        if p.size < 2 {
            if !only_scalars || LEARNER_SIGNALS.contains(&p.name.as_str()) {
                continue;
            }
            // One unit (an accumulator): its trace per TD is the signature.
            let title = format!(
                "{}: {} per TD (trial average, aligned to oven on)",
                dataset.meta.model, p.name
            );
            unit_by_td(&dir.join(&p.name), &title, dataset, r.start, window)?;
            continue;
        }
        let sub: Vec<f64> = avg
            .chunks_exact(n)
            .flat_map(|row| row[r.clone()].to_vec())
            .collect();
        let title = format!(
            "{}: {} (trial average, aligned to oven on)",
            dataset.meta.model, p.name
        );
        write_heatmap(&dir.join(&p.name), &title, &sub, p.size)?;
        let pop = cube.select(window, &r.clone().collect::<Vec<_>>());
        let title = format!("{} {}", dataset.meta.model, p.name);
        population_figures(&dir.join(&p.name), &title, &pop)?;
    }
    Ok(())
}

/// Reproduction datasets: each population's KiNeT speed after Set against `ts`
/// (`<population>/speed.svg`; one-unit clocks such as drift-diffusion's accumulator too,
/// not the learner's `value` / `rpe`). Nothing for other datasets.
fn speed_figures(
    dataset: &chronocooked_models::ActivityDataset,
    dir: &Path,
) -> Result<(), FigureError> {
    for p in &dataset.meta.populations {
        if LEARNER_SIGNALS.contains(&p.name.as_str()) {
            continue;
        }
        let speeds =
            chronocooked_analysis::neural::production::production_speed(dataset, Some(&p.name));
        let title = format!(
            "{} {}: speed after Set (KiNeT, Remington et al. 2018)",
            dataset.meta.model, p.name
        );
        if let Some(chart) = reproduction::speed_chart(&title, &speeds) {
            write_chart(&dir.join(&p.name).join("speed"), &chart)?;
        }
    }
    Ok(())
}

/// Single-unit signature: the trial-averaged activity of unit `unit` of `dataset` for each
/// recorded TD, aligned to oven on (`window` steps: oven time 0 … window − 1), with a
/// marker at every TD — a drift-diffusion accumulator ramps to its threshold at each TD,
/// so its slope scales as 1/TD. Steps past a trial's end are left out of the averages.
pub fn unit_by_td(
    dir: &Path,
    title: &str,
    dataset: &chronocooked_models::ActivityDataset,
    unit: usize,
    window: usize,
) -> Result<Vec<PathBuf>, FigureError> {
    let (aligned, used) = dataset.aligned(chronocooked_models::Marker::OvenOn, window - 1);
    let n = dataset.meta.n_units();
    let mut tds: Vec<u32> = used.iter().map(|&i| dataset.trials[i].td).collect();
    tds.sort_unstable();
    tds.dedup();
    let series = tds
        .iter()
        .enumerate()
        .map(|(k, &td)| {
            let mut sum = vec![0.0f64; window];
            let mut count = vec![0usize; window];
            for (j, &i) in used.iter().enumerate() {
                if dataset.trials[i].td != td {
                    continue;
                }
                for t in 0..window {
                    let v = aligned[(j * window + t) * n + unit];
                    if v.is_finite() {
                        sum[t] += f64::from(v);
                        count[t] += 1;
                    }
                }
            }
            Series {
                label: format!("TD {td}"),
                points: (0..window)
                    .filter(|&t| count[t] > 0)
                    .map(|t| (t as f64, sum[t] / count[t] as f64))
                    .collect(),
                line: true,
                color: k,
            }
        })
        .collect();
    write_chart(
        &dir.join("by_td"),
        &Chart {
            title: title.to_string(),
            x_label: "time since oven on (steps)".into(),
            y_label: "trial-averaged activity".into(),
            series,
            markers: tds
                .iter()
                .map(|&td| (f64::from(td), format!("TD {td}")))
                .collect(),
            ..Chart::default()
        },
    )
}

/// Learning curve of a run folder's `curves.csv` (PPO: training success and evaluation
/// success vs env steps; timing agents: the same vs env steps).
pub fn learning_curve(run_dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    let path = run_dir.join(run_folder::CURVES);
    let curves = run_folder::Curves::read(&path).map_err(err(&path))?;
    let x = curves.index("env_steps");
    let train = curves
        .index("success_rate")
        .or_else(|| curves.index("train_success"));
    let eval = curves.index("eval_success");
    let pick = |c: Option<usize>| -> Vec<(f64, f64)> {
        match (x, c) {
            (Some(x), Some(c)) => curves.rows.iter().map(|r| (r[x], r[c])).collect(),
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
        &run_dir
            .join(chronocooked_models::run_folder::FIGURES)
            .join("learning_curve"),
        &Chart {
            title: format!("learning curve: {}", run_label(run_dir)),
            x_label: "env steps".into(),
            y_label: "success rate".into(),
            series,
            y_range: Some((-0.02, 1.02)),
            ..Chart::default()
        },
    )
}

/// Longest [`run_label`] in characters: a title that fits the chart's width at any size.
const RUN_LABEL_CHARS: usize = 48;

/// A run folder's name for a chart title: its last three path components (a sweep job's
/// `<task>/<model~variant>/seed<N>` when the folder is the job's `run/`), at most
/// [`RUN_LABEL_CHARS`] characters: a sweep variant (after `~`) is cut short with `…` first,
/// so the task, the model and the seed stay; anything still too long is cut from the left.
/// The full path made titles wider than the chart and clipped them in the report.
pub fn run_label(run_dir: &Path) -> String {
    let mut parts: Vec<String> = run_dir
        .components()
        .filter_map(|c| match c {
            std::path::Component::Normal(s) => Some(s.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect();
    if parts.len() > 1
        && parts
            .last()
            .is_some_and(|p| p == chronocooked_analysis::job_folder::RUN)
    {
        parts.pop();
    }
    let mut parts = parts.split_off(parts.len().saturating_sub(3));
    let width = |parts: &[String]| parts.join("/").chars().count();
    for k in 0..parts.len() {
        let excess = width(&parts).saturating_sub(RUN_LABEL_CHARS);
        if excess == 0 {
            break;
        }
        if let Some((model, variant)) = parts[k].split_once('~') {
            let keep = variant.chars().count().saturating_sub(excess + 1);
            let short: String = variant.chars().take(keep).collect();
            parts[k] = format!("{model}~{short}…");
        }
    }
    let chars: Vec<char> = parts.join("/").chars().collect();
    if chars.len() <= RUN_LABEL_CHARS {
        chars.into_iter().collect()
    } else {
        let tail: String = chars[chars.len() - (RUN_LABEL_CHARS - 1)..]
            .iter()
            .collect();
        format!("…{tail}")
    }
}

#[cfg(test)]
mod tests {
    use super::run_label;
    use std::path::Path;

    #[test]
    fn run_labels_keep_the_jobs_name_and_fit_a_title() {
        assert_eq!(
            run_label(Path::new(
                "lab-out/ext/MultiAnchor-v0/lstm125~env.anchors-3_10/seed1/run"
            )),
            "MultiAnchor-v0/lstm125~env.anchors-3_10/seed1"
        );
        assert_eq!(run_label(Path::new("runs/demo")), "runs/demo");
        assert_eq!(run_label(Path::new("run")), "run");
        let long = run_label(Path::new(
            "x/MultiOven-v0/ctrnn-reservoir125~env.ovens-3_env.short-4_env.long-12_env.asynchronous-true/seed4",
        ));
        assert_eq!(long.chars().count(), 48, "{long}");
        assert!(
            long.starts_with("MultiOven-v0/ctrnn-reservoir125~env.") && long.ends_with("…/seed4"),
            "{long}"
        );
        // No variant to shorten: cut from the left.
        let plain = run_label(Path::new(
            "a/some-very-long-folder-name-without-a-variant-at-all/and-another-long-one/seed1",
        ));
        assert_eq!(plain.chars().count(), 48, "{plain}");
        assert!(
            plain.starts_with('…') && plain.ends_with("/seed1"),
            "{plain}"
        );
    }
}
