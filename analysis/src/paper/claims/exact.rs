//! The exact timer's statements.

use super::*;
use crate::paper::collect::CompactJob;
use crate::paper::multitimer::{buffer_rewards, exact_timer_groups};
use std::collections::BTreeMap;

/// Per exact-timer (model, TD): each run's reward averaged over its test buffers.
pub fn exact_timer_run_means(jobs: &[CompactJob]) -> BTreeMap<(String, u32), Spread> {
    exact_timer_groups(jobs)
        .into_iter()
        .map(|((model, td), js)| {
            let runs = js.iter().filter_map(|j| {
                let b = buffer_rewards(j, td);
                (!b.is_empty()).then(|| b.iter().map(|x| x.1).sum::<f64>() / b.len() as f64)
            });
            ((model.to_string(), td), Spread::of(runs))
        })
        .collect()
}

/// The exact timer's statements (the paper's Results, "For the exact timing case …").
pub fn exact_timer_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let means = exact_timer_run_means(jobs);
    if means.is_empty() {
        return Vec::new();
    }
    let empty = Spread::of([]);
    let get = |m: &str, td: u32| means.get(&(m.to_string(), td)).unwrap_or(&empty);
    let mut tds: Vec<u32> = means.keys().map(|k| k.1).collect();
    tds.sort_unstable();
    tds.dedup();
    let mut rows = Vec::new();

    // LSTM125 generally outperforms the other two models.
    for (other, name) in others() {
        per_setting_statement(
            &mut rows,
            "exact_lstm_best",
            &format!("LSTM125 generally outperforms {name}"),
            ("exact timer", "TD"),
            &format!("lstm125 − {other}, mean reward over buffers: z > 2"),
            &tds,
            |td| vec![*get(LSTM, td), *get(other, td)],
            |v| two_sample(&v[0], &v[1]),
        );
    }

    {
        let td = PAPER_SHORTEST_TD;
        // At the shortest TD, LSTM125 and CTRNN125 perform equally well.
        for (other, name) in ctrnns() {
            let (a, b) = (get(LSTM, td), get(other, td));
            let z = two_sample(a, b);
            let (d, se) = difference(a, b);
            rows.push(ClaimRow {
                claim: "exact_shortest_equal".into(),
                statement: format!("at the shortest TD, LSTM125 and {name} perform equally well"),
                setting: format!("exact timer, TD {td}"),
                test: format!(
                    "lstm125 − {other}, mean reward over buffers: d ± 2·se within ±{EQUIVALENCE_MARGIN} (|z| > 2: contradicted)"
                ),
                lab: format!(
                    "{} vs {}; d = {}",
                    fmt_spread(a),
                    fmt_spread(b),
                    if d.is_nan() { "–".into() } else { format!("{d:.3} ± {:.3}", Z_AGREE * se) }
                ),
                z,
                verdict: equal(d, se).into(),
                summary: true,
            });
        }
        // At the shortest TD the CNN earns above the minimum 0.1.
        let a = get(CNN, td);
        let z = against_value(a, REDUCED_REWARD);
        rows.push(ClaimRow {
            claim: "exact_cnn_above_min".into(),
            statement: "at the shortest TD the CNN earns above the minimum reward 0.1".into(),
            setting: format!("exact timer, TD {td}"),
            test: "cnn-mlp mean reward over buffers − 0.1: z > 2".into(),
            lab: fmt_spread(a),
            z,
            verdict: directional(z).into(),
            summary: true,
        });
        // … and that does not generalise to longer TDs.
        let mut per_td = Vec::new();
        for &long in tds.iter().filter(|t| **t > td) {
            let b = get(CNN, long);
            // At the longer TD the CNN is at the minimum: significantly above 0.1 goes
            // against it; its whole interval mean + 2·se within the equivalence margin of
            // 0.1 shows it; anything between does not tell.
            let z = against_value(b, REDUCED_REWARD);
            let upper = b.mean + Z_AGREE * b.sd / (b.n as f64).sqrt();
            let verdict = if z.is_nan() || b.n < 2 {
                "n/a"
            } else if z > Z_AGREE {
                "contradicted"
            } else if upper <= REDUCED_REWARD + EQUIVALENCE_MARGIN + 1e-12 {
                "holds"
            } else {
                "not shown"
            };
            per_td.push(verdict);
            rows.push(ClaimRow {
                claim: "exact_cnn_short_only".into(),
                statement: "the CNN's timing does not generalise to longer TDs".into(),
                setting: format!("exact timer, TD {long}"),
                test: format!(
                    "cnn-mlp mean reward over buffers: mean + 2·se ≤ 0.1 + {EQUIVALENCE_MARGIN} (z > 2 above 0.1: contradicted)"
                ),
                lab: fmt_spread(b),
                z,
                verdict: verdict.into(),
                summary: false,
            });
        }
        let against = per_td.iter().filter(|v| **v == "contradicted").count();
        let tested = per_td.iter().filter(|v| **v != "n/a").count();
        rows.push(ClaimRow {
            claim: "exact_cnn_short_only".into(),
            statement: "the CNN's timing does not generalise to longer TDs".into(),
            setting: "exact timer, every TD past the shortest".into(),
            test: "holds at every longer TD".into(),
            lab: format!(
                "{} of {tested} longer TDs at the minimum, {against} above it",
                per_td.iter().filter(|v| **v == "holds").count()
            ),
            z: f64::NAN,
            verdict: if per_td.contains(&"not shown") && against == 0 {
                "not shown"
            } else {
                unless_any(tested, against)
            }
            .into(),
            summary: true,
        });
    }
    rows
}
