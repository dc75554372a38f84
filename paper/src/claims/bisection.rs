//! The bisection statements.

use super::*;
use crate::spreads::{ConditionStat, condition_stats};
use chronocooked_analysis::collect::CompactJob;

/// The bisection statements (the paper's Results, "Bisection task"): "LSTM125 performs
/// better than its biologically plausible recurrent counterpart CTRNN125" and "for a higher
/// memory size (256) the two models have comparable performance", on the psychometric
/// curves' anchor accuracy (each kept run's share of correct answers at the two anchors:
/// `spreads::condition_stats`), per anchor pair; "comparable" is the equivalence test
/// ([`equal`]) with the margin [`EQUIVALENCE_MARGIN`] = 0.1 of anchor accuracy: 1.6 of a
/// run's 16 anchor trials (8 start cells per anchor), i.e. the mean accuracies provably
/// differ by less than about two answers in sixteen.
pub fn bisection_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let stats: Vec<ConditionStat> = condition_stats(jobs)
        .into_iter()
        .filter(|c| c.task == "Bisection-v0" && c.statistic == "anchor_accuracy")
        .collect();
    if stats.is_empty() {
        return Vec::new();
    }
    let mut pairs: Vec<&str> = stats.iter().map(|c| c.condition.as_str()).collect();
    pairs.sort_by_key(|p| {
        let (a, b) = p.split_once('-').unwrap_or((p, ""));
        (a.parse::<u32>().unwrap_or(0), b.parse::<u32>().unwrap_or(0))
    });
    pairs.dedup();
    let acc = |m: &str, pair: &str| {
        stats
            .iter()
            .find(|c| c.model == m && c.condition == pair)
            .map_or(Spread::of([]), |c| c.spread)
    };
    let task = "bisection";
    let mut rows = Vec::new();
    for (other, name) in ctrnns() {
        per_setting_statement(
            &mut rows,
            "bisection_lstm_better",
            &format!("LSTM125 performs better than {name}"),
            (task, "pair"),
            &format!("anchor accuracy per kept run, lstm125 − {other}: above 0, p < 0.05"),
            &pairs,
            |p| vec![acc(LSTM, p), acc(other, p)],
            |v| MeanTest::two_sample(&v[0], &v[1]),
        );
    }
    let lstm256 = lab_model("LSTM256").unwrap_or("lstm256");
    let reservoir256 = lab_model("CTRNN256").unwrap_or("ctrnn-reservoir256");
    // The paper's pair (its CTRNN256 is untrained) and the lab's trained CTRNN256 beside it.
    for (ctrnn256, statement) in [
        (
            reservoir256,
            "at size 256, LSTM256 and CTRNN256 (lab: reservoir) perform comparably",
        ),
        (
            TRAINED_CTRNN_256,
            "at size 256, LSTM256 and the lab's trained CTRNN256 (not in the paper) perform comparably",
        ),
    ] {
        let mut verdicts = Vec::new();
        for &pair in &pairs {
            let (a, b) = (acc(lstm256, pair), acc(ctrnn256, pair));
            let t = MeanTest::two_sample(&a, &b);
            let verdict = equal(t, EQUIVALENCE_MARGIN);
            let (z, p) = z_p(t);
            verdicts.push(verdict);
            rows.push(ClaimRow {
                claim: "bisection_256_comparable".into(),
                statement: statement.into(),
                setting: format!("{task}, pair {pair}"),
                test: format!(
                    "anchor accuracy per kept run, {lstm256} − {ctrnn256}: 95% interval d ± t·se within ±{EQUIVALENCE_MARGIN}"
                ),
                lab: format!(
                    "{} vs {}; d = {}",
                    fmt_spread(&a),
                    fmt_spread(&b),
                    interval_text(t)
                ),
                z,
                p,
                verdict: verdict.into(),
                summary: false,
            });
        }
        rows.push(general_row(
            "bisection_256_comparable",
            statement,
            (task, "pair"),
            &verdicts,
        ));
    }
    rows
}
