//! Figures of the public code's two extensions: the multi-category psychometric figure of
//! multi-anchor categorization (share of choices of each counter at every probe, one curve
//! per counter, anchors and boundaries marked) and the per-oven P(long) curves of
//! multi-oven bisection (one curve per oven beside the same agent's one-oven curve).

use super::draw::{Chart, Series};
use chronocooked_analysis::behaviour::categorization::MultiAnchorMetrics;
use chronocooked_analysis::behaviour::concurrent::MultiOvenMetrics;

/// Multi-anchor: per counter (anchor) the share of the episodes at each probe duration
/// that delivered to it (failed episodes count in the denominator), the anchors as
/// markers, each adjacent pair's fitted boundary (BP) as a marker.
pub fn multi_anchor_chart(model: &str, m: &MultiAnchorMetrics) -> Chart {
    let series = m
        .anchors
        .iter()
        .enumerate()
        .map(|(i, a)| Series {
            label: format!("counter of anchor {a}"),
            points: m
                .probes
                .iter()
                .map(|p| {
                    (
                        f64::from(p.t),
                        p.proportions().get(i).copied().unwrap_or(f64::NAN),
                    )
                })
                .collect(),
            line: true,
            color: i,
        })
        .collect();
    let mut markers: Vec<(f64, String)> = m
        .anchors
        .iter()
        .map(|a| (f64::from(*a), format!("{a}")))
        .collect();
    for b in &m.boundaries {
        if let Some(f) = &b.fit {
            markers.push((f.bp, format!("BP {}|{}", b.lower, b.upper)));
        }
    }
    let anchors: Vec<String> = m.anchors.iter().map(u32::to_string).collect();
    Chart {
        title: format!(
            "{model}: categorization, anchors {} (accuracy at the anchors {:.2})",
            anchors.join(", "),
            m.anchor_accuracy
        ),
        x_label: "probe duration (steps)".into(),
        y_label: "share of episodes choosing the counter".into(),
        series,
        markers,
        y_range: Some((-0.05, 1.05)),
    }
}

/// Multi-oven: each oven's P(long) per probe duration (NaN probes, where more than half the
/// episodes failed, are gaps), one colour per oven, then the same agent's one-oven curve,
/// with S, L and their geometric mean marked.
pub fn multi_oven_chart(model: &str, m: &MultiOvenMetrics) -> Chart {
    let curve = |c: &chronocooked_analysis::behaviour::concurrent::OvenCurve| -> Vec<(f64, f64)> {
        c.probes
            .iter()
            .zip(&c.p_long)
            .map(|(p, &v)| (p.t, v))
            .collect()
    };
    let mut series: Vec<Series> = m
        .per_oven
        .iter()
        .map(|c| Series {
            label: format!("oven {} (accuracy {:.2})", c.oven + 1, c.accuracy),
            points: curve(c),
            line: true,
            color: c.oven,
        })
        .collect();
    if let Some(single) = &m.single {
        series.push(Series {
            label: format!("one oven alone (accuracy {:.2})", single.accuracy),
            points: curve(single),
            line: true,
            color: m.per_oven.len(),
        });
    }
    let gm = (f64::from(m.short) * f64::from(m.long)).sqrt();
    Chart {
        title: format!(
            "{model}: {} ovens, {}, bisection {}-{}",
            m.ovens,
            if m.asynchronous {
                "asynchronous"
            } else {
                "synchronous"
            },
            m.short,
            m.long
        ),
        x_label: "probe duration of the oven (steps)".into(),
        y_label: "P(long)".into(),
        series,
        markers: vec![
            (f64::from(m.short), "S".into()),
            (f64::from(m.long), "L".into()),
            (gm, "GM".into()),
        ],
        y_range: Some((-0.05, 1.05)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use chronocooked_analysis::behaviour::categorization::CategoryCounts;
    use chronocooked_analysis::behaviour::concurrent::OvenCurve;
    use chronocooked_analysis::behaviour::psychometric::ProbeCounts;

    /// Anchors 4, 8, 12; at t = 4 three of four episodes chose counter 1 and one failed; at
    /// t = 8 all chose counter 2: the curves are those shares, the anchors are marked.
    #[test]
    fn each_counter_gets_its_share_of_the_episodes_at_every_probe() {
        let m = MultiAnchorMetrics {
            anchors: vec![4, 8, 12],
            probes: vec![
                CategoryCounts {
                    t: 4,
                    counters: vec![3, 0, 0],
                    failed: 1,
                },
                CategoryCounts {
                    t: 8,
                    counters: vec![0, 4, 0],
                    failed: 0,
                },
            ],
            anchor_accuracy: 1.0,
            category_errors: vec![],
            boundaries: vec![],
            wf_constancy: None,
        };
        let c = multi_anchor_chart("oracle", &m);
        assert_eq!(c.series.len(), 3);
        assert_eq!(c.series[0].points, vec![(4.0, 0.75), (8.0, 0.0)]);
        assert_eq!(c.series[1].points, vec![(4.0, 0.0), (8.0, 1.0)]);
        assert_eq!(c.series[2].label, "counter of anchor 12");
        let marked: Vec<f64> = c.markers.iter().map(|m| m.0).collect();
        assert_eq!(marked, vec![4.0, 8.0, 12.0]);
    }

    fn curve(oven: usize, p_long: &[f64]) -> OvenCurve {
        OvenCurve {
            oven,
            probes: (0..p_long.len())
                .map(|i| ProbeCounts {
                    t: 4.0 + 4.0 * i as f64,
                    valid: 4,
                    long: 0,
                    failed: 0,
                })
                .collect(),
            p_long: p_long.to_vec(),
            accuracy: 1.0,
            fit: None,
            fit_error: None,
            bp_over_gm: None,
        }
    }

    /// Two ovens and the one-oven curve: one series each, the one-oven curve last, P(long)
    /// as given per probe, S, L and GM = √48 marked.
    #[test]
    fn every_oven_and_the_one_oven_curve_are_drawn() {
        let m = MultiOvenMetrics {
            short: 4,
            long: 12,
            ovens: 2,
            asynchronous: true,
            per_oven: vec![curve(0, &[0.0, 0.5, 1.0]), curve(1, &[0.0, 0.25, 1.0])],
            single: Some(curve(0, &[0.0, 0.75, 1.0])),
            interference: vec![],
            by_offset: vec![],
            orders: vec![],
        };
        let c = multi_oven_chart("oracle", &m);
        assert_eq!(c.series.len(), 3);
        assert_eq!(
            c.series[1].points,
            vec![(4.0, 0.0), (8.0, 0.25), (12.0, 1.0)]
        );
        assert!(c.series[2].label.starts_with("one oven alone"));
        assert!((c.markers[2].0 - 48f64.sqrt()).abs() < 1e-12);
        assert!(c.title.contains("asynchronous"));
    }
}
