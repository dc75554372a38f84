//! The exact timer's statements.

use super::*;
use crate::multitimer::{buffer_rewards, exact_timer_groups};
use chronocooked_analysis::collect::CompactJob;
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
            &format!("lstm125 − {other}, mean reward over buffers: above 0, p < 0.05"),
            &tds,
            |td| vec![*get(LSTM, td), *get(other, td)],
            |v| MeanTest::two_sample(&v[0], &v[1]),
        );
    }

    {
        let td = PAPER_SHORTEST_TD;
        // At the shortest TD, LSTM125 and CTRNN125 perform equally well.
        for (other, name) in ctrnns() {
            let (a, b) = (get(LSTM, td), get(other, td));
            let t = MeanTest::two_sample(a, b);
            let (z, p) = z_p(t);
            rows.push(ClaimRow {
                claim: "exact_shortest_equal".into(),
                statement: format!("at the shortest TD, LSTM125 and {name} perform equally well"),
                setting: format!("exact timer, TD {td}"),
                test: format!(
                    "lstm125 − {other}, mean reward over buffers: 95% interval d ± t·se within ±{EQUIVALENCE_MARGIN} (wholly beyond it: contradicted)"
                ),
                lab: format!(
                    "{} vs {}; d = {}",
                    fmt_spread(a),
                    fmt_spread(b),
                    interval_text(t)
                ),
                z,
                p,
                verdict: equal(t, EQUIVALENCE_MARGIN).into(),
                summary: true,
            });
        }
        // At the shortest TD the CNN earns above the minimum 0.1.
        let a = get(CNN, td);
        let t = MeanTest::one_sample(a, REDUCED_REWARD);
        let (z, p) = z_p(t);
        let premise = directional(t);
        rows.push(ClaimRow {
            claim: "exact_cnn_above_min".into(),
            statement: "at the shortest TD the CNN earns above the minimum reward 0.1".into(),
            setting: format!("exact timer, TD {td}"),
            test: "cnn-mlp mean reward over buffers − 0.1: above 0, p < 0.05".into(),
            lab: fmt_spread(a),
            z,
            p,
            verdict: premise.into(),
            summary: true,
        });
        // … and that does not generalise to longer TDs: at each longer TD the CNN is at the
        // minimum (the equivalence test on its mean − 0.1). Without the capacity at the
        // shortest TD there is nothing to generalise: the statement is then n/a.
        let mut per_td = Vec::new();
        for &long in tds.iter().filter(|t| **t > td) {
            let b = get(CNN, long);
            let t = MeanTest::one_sample(b, REDUCED_REWARD);
            // One-sided: below the minimum (a CNN that does not deliver) is not above it
            // either.
            let verdict = at_most(t, EQUIVALENCE_MARGIN);
            let (z, p) = z_p(t);
            per_td.push(verdict);
            rows.push(ClaimRow {
                claim: "exact_cnn_short_only".into(),
                statement: "the CNN's timing does not generalise to longer TDs".into(),
                setting: format!("exact timer, TD {long}"),
                test: format!(
                    "cnn-mlp mean reward over buffers − 0.1: 95% interval's upper end ≤ +{EQUIVALENCE_MARGIN} (its lower end above: contradicted)"
                ),
                lab: format!("{}; d = {}", fmt_spread(b), interval_text(t)),
                z,
                p,
                verdict: verdict.into(),
                summary: false,
            });
        }
        let against = per_td.iter().filter(|v| **v == "contradicted").count();
        let tested = per_td.iter().filter(|v| **v != "n/a").count();
        let at_min = format!(
            "{} of {tested} longer TDs at the minimum, {against} above it",
            per_td.iter().filter(|v| **v == "holds").count()
        );
        let (lab, verdict) = if premise != "holds" {
            (
                format!(
                    "no capacity at TD {td} to generalise (the CNN there: {}); {at_min}",
                    fmt_spread(a)
                ),
                "n/a",
            )
        } else if per_td.contains(&"not shown") && against == 0 {
            (at_min, "not shown")
        } else {
            (at_min, unless_any(tested, against))
        };
        rows.push(ClaimRow {
            claim: "exact_cnn_short_only".into(),
            statement: "the CNN's timing does not generalise to longer TDs".into(),
            setting: "exact timer, every TD past the shortest".into(),
            test: format!(
                "the CNN above the minimum at TD {td} (the statement's premise) and at the minimum at every longer TD"
            ),
            lab,
            z: f64::NAN,
            p: f64::NAN,
            verdict: verdict.into(),
            summary: true,
        });
    }
    rows
}
