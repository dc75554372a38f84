//! The classic reproduction figure (Jazayeri & Shadlen 2010, Fig. 2): mean production `tp`
//! against the sample interval `ts`, one colour per context (prior × gain), the best
//! Bayesian observer's predicted mean where it was fitted, and the veridical line
//! `tp = g·ts`. Beside it, the speed figure (Remington et al. 2018, Fig. 4): KiNeT's
//! relative speed of the population's trajectory after Set against `ts`, one colour per
//! context, with the two known answers drawn as lines.

use super::draw::{Chart, Series};
use chronocooked_analysis::behaviour::reproduction::{ContextSummary, ReproductionMetrics};
use chronocooked_analysis::neural::production::ProductionSpeed;
use chronocooked_analysis::reproduction::{Observer, Prior, Rounding, predict};

/// The fitted observer's predicted mean `tp` at each of the context's sample intervals
/// (whole-step productions, as the fit assumes); empty without a fit.
fn observer_curve(c: &ContextSummary) -> Vec<(f64, f64)> {
    let Some(o) = &c.observer else {
        return Vec::new();
    };
    let Some(observer) = Observer::ALL.into_iter().find(|x| x.name() == o.best) else {
        return Vec::new();
    };
    let values: Vec<f64> = c.by_ts.iter().map(|b| f64::from(b.0)).collect();
    let Ok(prior) = Prior::new(&values) else {
        return Vec::new();
    };
    predict(observer, o.wm, o.wp, &prior, Rounding::WholeSteps)
        .map(|p| p.iter().map(|x| (x.ts, x.mean_tp)).collect())
        .unwrap_or_default()
}

/// Mean `tp` per `ts` for every context (dots), each context's best observer (line, same
/// colour) and the veridical line of each gain.
pub fn reproduction_chart(model: &str, m: &ReproductionMetrics) -> Chart {
    let mut series = Vec::new();
    for (k, c) in m.contexts.iter().enumerate() {
        series.push(Series {
            label: format!(
                "prior {}, gain {} (slope {})",
                c.prior,
                c.gain,
                c.slope.map_or("–".into(), |s| format!("{s:.2}"))
            ),
            points: c.by_ts.iter().map(|b| (f64::from(b.0), b.1)).collect(),
            line: false,
            color: k,
        });
        let fit = observer_curve(c);
        if let (false, Some(o)) = (fit.is_empty(), &c.observer) {
            series.push(Series {
                label: format!("{} (wm {:.2}, wp {:.2})", o.best, o.wm, o.wp),
                points: fit,
                line: true,
                color: k,
            });
        }
    }
    let ts: Vec<f64> = m
        .contexts
        .iter()
        .flat_map(|c| c.by_ts.iter().map(|b| f64::from(b.0)))
        .collect();
    let (lo, hi) = ts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
            (a.min(t), b.max(t))
        });
    let mut gains: Vec<f64> = m.contexts.iter().map(|c| c.gain).collect();
    gains.sort_by(f64::total_cmp);
    gains.dedup();
    if lo.is_finite() {
        for g in gains {
            series.push(Series {
                label: format!("tp = {g}·ts"),
                points: vec![(lo, g * lo), (hi, g * hi)],
                line: true,
                color: m.contexts.len() + 1,
            });
        }
    }
    Chart {
        title: format!("{model}: reproduction, mean tp against ts"),
        x_label: "sample interval ts (steps)".into(),
        y_label: "production tp (steps)".into(),
        series,
        markers: Vec::new(),
        y_range: None,
    }
}

/// Relative speed (KiNeT, reference = the context's middle `ts`) against `ts` for every
/// context with a speed, and per context the two known answers: time-stretched
/// trajectories (timing by speed, `speed = ts_ref / ts`) and a clock of fixed speed
/// (`speed = 1`). `None` when no context has a speed.
pub fn speed_chart(title: &str, contexts: &[ProductionSpeed]) -> Option<Chart> {
    let mut series = Vec::new();
    let mut ts_all = Vec::new();
    for (k, c) in contexts.iter().enumerate() {
        let points: Vec<(f64, f64)> = c
            .conditions
            .iter()
            .filter_map(|x| Some((f64::from(x.ts), x.relative_speed?)))
            .filter(|p| p.1.is_finite())
            .collect();
        if points.len() < 2 {
            continue;
        }
        ts_all.extend(points.iter().map(|p| p.0));
        let index = c.scaling_index.map_or("–".into(), |s| format!("{s:.2}"));
        series.push(Series {
            label: format!(
                "prior #{}, gain #{} (scaling index {index})",
                c.prior, c.gain
            ),
            points: points.clone(),
            line: false,
            color: k,
        });
        let reference = f64::from(c.reference_ts);
        series.push(Series {
            label: format!("time-stretched: ts_ref / ts (ts_ref {})", c.reference_ts),
            points: points.iter().map(|p| (p.0, reference / p.0)).collect(),
            line: true,
            color: k,
        });
    }
    if series.is_empty() {
        return None;
    }
    let (lo, hi) = ts_all
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
            (a.min(t), b.max(t))
        });
    series.push(Series {
        label: "fixed-speed clock: 1".into(),
        points: vec![(lo, 1.0), (hi, 1.0)],
        line: true,
        color: contexts.len() + 1,
    });
    Some(Chart {
        title: title.into(),
        x_label: "sample interval ts (steps)".into(),
        y_label: "relative speed after Set (KiNeT)".into(),
        series,
        markers: Vec::new(),
        y_range: None,
    })
}

/// One model's runs for the reproduction grid.
pub struct ReproductionRuns<'a> {
    /// Row label.
    pub model: &'a str,
    /// Every run's reproduction metrics.
    pub metrics: &'a [ReproductionMetrics],
    /// Every run's KiNeT speeds after Set (runs without a neural summary left out).
    pub speed: &'a [Vec<ProductionSpeed>],
}

/// The runs of one model pooled for its panel of the report's grid: per context (prior,
/// gain) of the first run, each `ts`'s mean `tp` averaged over the runs (SD the mean of
/// theirs, trials summed), the slope averaged, and the observer most runs chose with the
/// mean of their `wm` and `wp` — the fields [`reproduction_chart`] draws. `None` without
/// runs.
pub fn pool_reproduction(runs: &[&ReproductionMetrics]) -> Option<ReproductionMetrics> {
    let first = runs.first()?;
    let mean = |v: Vec<f64>| {
        let v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    };
    let contexts = first
        .contexts
        .iter()
        .map(|c0| {
            let same: Vec<&ContextSummary> = runs
                .iter()
                .filter_map(|r| {
                    r.contexts
                        .iter()
                        .find(|c| c.prior == c0.prior && c.gain == c0.gain)
                })
                .collect();
            let mut pooled = c0.clone();
            pooled.by_ts = c0
                .by_ts
                .iter()
                .map(|&(ts, _, _, _)| {
                    let at: Vec<&(u32, f64, f64, usize)> = same
                        .iter()
                        .filter_map(|c| c.by_ts.iter().find(|b| b.0 == ts))
                        .collect();
                    (
                        ts,
                        mean(at.iter().map(|b| b.1).collect()).unwrap_or(f64::NAN),
                        mean(at.iter().map(|b| b.2).collect()).unwrap_or(f64::NAN),
                        at.iter().map(|b| b.3).sum(),
                    )
                })
                .collect();
            pooled.slope = mean(same.iter().filter_map(|c| c.slope).collect());
            let choices: Vec<&chronocooked_analysis::behaviour::reproduction::ObserverChoice> =
                same.iter().filter_map(|c| c.observer.as_ref()).collect();
            let mut names: Vec<&str> = choices.iter().map(|o| o.best.as_str()).collect();
            names.sort_unstable();
            let best = names
                .iter()
                .max_by_key(|n| names.iter().filter(|m| m == n).count())
                .map(|n| n.to_string());
            pooled.observer = best.map(|best| {
                let of_best: Vec<_> = choices.iter().filter(|o| o.best == best).collect();
                chronocooked_analysis::behaviour::reproduction::ObserverChoice {
                    wm: mean(of_best.iter().map(|o| o.wm).collect()).unwrap_or(f64::NAN),
                    wp: mean(of_best.iter().map(|o| o.wp).collect()).unwrap_or(f64::NAN),
                    log_likelihoods: Vec::new(),
                    best,
                }
            });
            pooled
        })
        .collect();
    Some(ReproductionMetrics { contexts })
}

/// The runs' KiNeT speeds pooled for one model's speed panel: per context of the first
/// run, each `ts`'s relative speed averaged over the runs that have it, and the scaling
/// index averaged. Empty without runs.
pub fn pool_speed(runs: &[&[ProductionSpeed]]) -> Vec<ProductionSpeed> {
    let Some(first) = runs.first() else {
        return Vec::new();
    };
    first
        .iter()
        .map(|c0| {
            let same: Vec<&ProductionSpeed> = runs
                .iter()
                .filter_map(|r| r.iter().find(|c| c.prior == c0.prior && c.gain == c0.gain))
                .collect();
            let mean = |v: Vec<f64>| {
                let v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
                (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
            };
            let mut pooled = c0.clone();
            for x in &mut pooled.conditions {
                x.relative_speed = mean(
                    same.iter()
                        .filter_map(|c| c.conditions.iter().find(|y| y.ts == x.ts))
                        .filter_map(|y| y.relative_speed)
                        .collect(),
                );
            }
            pooled.scaling_index = mean(same.iter().filter_map(|c| c.scaling_index).collect());
            pooled
        })
        .collect()
}

/// The report's reproduction grid, one row per model: its runs' pooled reproduction panel
/// ([`pool_reproduction`], [`reproduction_chart`]) and, when any model has one, its pooled
/// speed panel ([`pool_speed`], [`speed_chart`]). Rows without reproduction runs are left
/// out; returns the files written (`<stem>.svg` / `.png`), none without any.
pub fn reproduction_grid(
    stem: &std::path::Path,
    rows: &[ReproductionRuns<'_>],
) -> Result<Vec<std::path::PathBuf>, super::FigureError> {
    let rows: Vec<_> = rows.iter().filter(|r| !r.metrics.is_empty()).collect();
    if rows.is_empty() {
        return Ok(Vec::new());
    }
    let with_speed = rows.iter().any(|r| !r.speed.is_empty());
    let mut charts = Vec::new();
    for ReproductionRuns {
        model,
        metrics,
        speed: speeds,
    } in &rows
    {
        let runs: Vec<&ReproductionMetrics> = metrics.iter().collect();
        // Short titles: a panel is 420 pixels wide.
        charts.push(pool_reproduction(&runs).map(|m| Chart {
            title: format!("{model}: tp vs ts"),
            ..reproduction_chart(model, &m)
        }));
        if with_speed {
            let runs: Vec<&[ProductionSpeed]> = speeds.iter().map(Vec::as_slice).collect();
            charts.push(speed_chart(&format!("{model}: speed"), &pool_speed(&runs)));
        }
    }
    let shape = if with_speed {
        (rows.len(), 2)
    } else {
        super::grid::grid_shape(rows.len(), 1)
    };
    super::write_panels(stem, shape, &charts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use chronocooked_analysis::behaviour::reproduction::ObserverChoice;

    fn context(prior: u8, gain: f64, observer: Option<ObserverChoice>) -> ContextSummary {
        ContextSummary {
            prior,
            gain,
            episodes: 12,
            failures: 0,
            by_ts: vec![(8, 9.0, 1.0, 4), (10, 10.0, 1.0, 4), (12, 11.0, 1.0, 4)],
            ratio: vec![],
            slope: Some(0.5),
            bias: None,
            sqrt_var: None,
            rmse: None,
            weber: None,
            observer,
        }
    }

    /// Two runs pooled: each ts's mean production is the mean of the runs' means, trials
    /// add up, the slope is averaged, and the observer is the one both chose with the mean
    /// of their noises; a context only the second run has is not drawn.
    #[test]
    fn pooled_runs_average_their_means_slopes_and_observers() {
        let choice = |best: &str, wm: f64| ObserverChoice {
            best: best.into(),
            wm,
            wp: 0.04,
            log_likelihoods: vec![],
        };
        let a = ReproductionMetrics {
            contexts: vec![context(0, 1.0, Some(choice("BLS", 0.1)))],
        };
        let mut b_context = context(0, 1.0, Some(choice("BLS", 0.2)));
        b_context.by_ts = vec![(8, 11.0, 3.0, 6), (10, 12.0, 1.0, 6), (12, 13.0, 1.0, 6)];
        b_context.slope = Some(0.7);
        let b = ReproductionMetrics {
            contexts: vec![b_context, context(1, 1.0, None)],
        };
        let pooled = pool_reproduction(&[&a, &b]).unwrap();
        assert_eq!(pooled.contexts.len(), 1);
        let c = &pooled.contexts[0];
        assert_eq!(
            c.by_ts,
            vec![(8, 10.0, 2.0, 10), (10, 11.0, 1.0, 10), (12, 12.0, 1.0, 10)]
        );
        assert!((c.slope.unwrap() - 0.6).abs() < 1e-12);
        let o = c.observer.as_ref().unwrap();
        assert_eq!(o.best, "BLS");
        assert!((o.wm - 0.15).abs() < 1e-12 && (o.wp - 0.04).abs() < 1e-12);
        assert!(pool_reproduction(&[]).is_none());
    }

    /// Dots at the mean productions, the observer's line from the analytic prediction (a
    /// BLS observer regresses: its line is flatter than the veridical one and passes near
    /// the prior's mean at its middle), one veridical line per gain.
    #[test]
    fn the_figure_has_the_means_the_observer_and_the_veridical_lines() {
        let bls = ObserverChoice {
            best: "BLS".into(),
            wm: 0.15,
            wp: 0.05,
            log_likelihoods: vec![],
        };
        let m = ReproductionMetrics {
            contexts: vec![context(0, 1.0, Some(bls)), context(0, 1.5, None)],
        };
        let c = reproduction_chart("agent", &m);
        // Context 1: dots + BLS line; context 2: dots; two gains: two veridical lines.
        assert_eq!(c.series.len(), 5);
        assert_eq!(
            c.series[0].points,
            vec![(8.0, 9.0), (10.0, 10.0), (12.0, 11.0)]
        );
        let line = &c.series[1].points;
        assert_eq!(line.len(), 3);
        assert!(line[0].1 > 8.0 && line[2].1 < 12.0, "{line:?}");
        assert!((line[1].1 - 10.0).abs() < 0.3, "{line:?}");
        assert_eq!(c.series[3].points, vec![(8.0, 8.0), (12.0, 12.0)]);
        assert_eq!(c.series[4].points, vec![(8.0, 12.0), (12.0, 18.0)]);
    }

    fn condition(
        ts: u32,
        speed: Option<f64>,
    ) -> chronocooked_analysis::neural::production::ProductionCondition {
        chronocooked_analysis::neural::production::ProductionCondition {
            ts,
            trials: 4,
            steps: ts as usize,
            relative_speed: speed,
            mean_signed_distance: None,
        }
    }

    /// Speeds as dots, the time-stretched answer `ts_ref / ts` worked out by hand (10/8,
    /// 10/10, 10/16), the fixed clock at 1 across the range; a context with fewer than
    /// two speeds is left out, and nothing to draw gives no figure.
    #[test]
    fn the_speed_figure_has_the_speeds_and_both_known_answers() {
        let ctx = |prior, conditions| ProductionSpeed {
            prior,
            gain: 0,
            units: 8,
            reference_ts: 10,
            conditions,
            scaling_index: Some(0.9),
            initial_order: None,
            distance_order: None,
        };
        let a = ctx(
            0,
            vec![
                condition(8, Some(1.2)),
                condition(10, Some(1.0)),
                condition(12, None),
                condition(16, Some(0.7)),
            ],
        );
        let b = ctx(1, vec![condition(14, Some(1.0))]);
        let c = speed_chart("t", &[a, b.clone()]).expect("a figure");
        assert_eq!(c.series.len(), 3);
        assert_eq!(
            c.series[0].points,
            vec![(8.0, 1.2), (10.0, 1.0), (16.0, 0.7)]
        );
        assert_eq!(
            c.series[1].points,
            vec![(8.0, 1.25), (10.0, 1.0), (16.0, 0.625)]
        );
        assert_eq!(c.series[2].points, vec![(8.0, 1.0), (16.0, 1.0)]);
        assert!(c.series[0].label.contains("0.90"), "{}", c.series[0].label);
        assert!(speed_chart("t", &[b]).is_none());
    }
}
