//! The fixed-interval statements.

use super::*;
use crate::fi::{fi_runs, run_focs};
use chronocooked_analysis::collect::CompactJob;

/// One FI run's statistics over its episodes with an oven check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FiRunStat {
    /// Share of the first oven checks at 0 (checking from the oven's start).
    pub zero_share: f64,
    /// Mean FOC / TD.
    pub ratio: f64,
    /// Mean |FOC / TD − 1| over the episodes: how far each first check is from the TD (a run
    /// whose checks straddle the TD, half at 0 and half at 2·TD, is 1 away, not 0).
    pub deviation: f64,
}

/// One FI run's statistics ([`FiRunStat`]; `None` for a run without an oven check).
pub fn fi_run_stat(job: &CompactJob, td: u32) -> Option<FiRunStat> {
    let f = run_focs(job, false);
    (!f.is_empty()).then(|| {
        let (n, td) = (f.len() as f64, f64::from(td));
        FiRunStat {
            zero_share: f.iter().filter(|x| **x == 0.0).count() as f64 / n,
            ratio: f.iter().sum::<f64>() / n / td,
            deviation: f.iter().map(|x| (x / td - 1.0).abs()).sum::<f64>() / n,
        }
    })
}

/// The fixed-interval statements (the paper's Results, "Fixed interval").
pub fn fi_claims(jobs: &[CompactJob]) -> Vec<ClaimRow> {
    let runs = fi_runs(jobs);
    if runs.is_empty() {
        return Vec::new();
    }
    // Per-run statistic `stat` of (model, TD) across its runs.
    let across = |m: &str, td: u32, stat: fn(FiRunStat) -> f64| {
        let js = runs.get(m).and_then(|t| t.get(&td));
        Spread::of(
            js.into_iter()
                .flatten()
                .filter_map(|j| fi_run_stat(j, td).map(stat)),
        )
    };
    let zero = |s: FiRunStat| s.zero_share;
    let ratio = |s: FiRunStat| s.ratio;
    let off = |s: FiRunStat| s.deviation;
    let mut tds: Vec<u32> = runs.values().flat_map(|t| t.keys().copied()).collect();
    tds.sort_unstable();
    tds.dedup();
    let task = "fixed interval";
    let mut rows = Vec::new();
    per_setting_statement(
        &mut rows,
        "fi_cnn_foc_zero",
        "in most cases the CNN's first oven check is at 0 (checking from the start)",
        (task, "TD"),
        "cnn-mlp share of FOCs at 0 per run, against 0.5: above, p < 0.05",
        &tds,
        |td| vec![across(CNN, td, zero)],
        |v| MeanTest::one_sample(&v[0], 0.5),
    );
    let reservoir = paper_ctrnn();
    for (other, name) in ctrnns() {
        per_setting_statement(
            &mut rows,
            "fi_lstm_closer",
            &format!("LSTM125's FOCs are closer to the TD than {name}'s"),
            (task, "TD"),
            &format!("mean |FOC/TD − 1| per run, {other} − lstm125: above 0, p < 0.05"),
            &tds,
            |td| vec![across(other, td, off), across(LSTM, td, off)],
            |v| MeanTest::two_sample(&v[0], &v[1]),
        );
        per_setting_statement(
            &mut rows,
            "fi_ctrnn_earlier",
            &format!("{name} checks the oven earlier than LSTM125"),
            (task, "TD"),
            &format!("FOC/TD per run, lstm125 − {other}: above 0, p < 0.05"),
            &tds,
            |td| vec![across(LSTM, td, ratio), across(other, td, ratio)],
            |v| MeanTest::two_sample(&v[0], &v[1]),
        );
    }
    // The paper's pair (its untrained reservoirs) and the lab's trained pair beside it.
    let big = lab_model("CTRNN256").unwrap_or("ctrnn-reservoir256");
    for (small, large, statement) in [
        (
            reservoir,
            big,
            "at a higher memory size CTRNN256's FOCs improve on CTRNN125's (lab: reservoirs)",
        ),
        (
            TRAINED_CTRNN,
            TRAINED_CTRNN_256,
            "at a higher memory size the lab's trained CTRNN256's FOCs improve on its trained CTRNN125's (not in the paper)",
        ),
    ] {
        per_setting_statement(
            &mut rows,
            "fi_ctrnn256_better",
            statement,
            (task, "TD"),
            &format!("mean |FOC/TD − 1| per run, {small} − {large}: above 0, p < 0.05"),
            &tds,
            |td| vec![across(small, td, off), across(large, td, off)],
            |v| MeanTest::two_sample(&v[0], &v[1]),
        );
    }
    rows
}
