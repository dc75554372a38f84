//! The classic reproduction figure (Jazayeri & Shadlen 2010, Fig. 2): mean production `tp`
//! against the sample interval `ts`, one colour per context (prior × gain), the best
//! Bayesian observer's predicted mean where it was fitted, and the veridical line
//! `tp = g·ts`.

use super::draw::{Chart, Series};
use crate::behaviour::reproduction::{ContextSummary, ReproductionMetrics};
use crate::reproduction::{Observer, Prior, Rounding, predict};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::behaviour::reproduction::ObserverChoice;

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
}
