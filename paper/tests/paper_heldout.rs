//! The held-out check on constructed runs with known answers: a held-out seed's FI run
//! against the study's 95% range for a new run (computed by hand), a run the paper's rule
//! excludes, a condition the study lacks, and a "held-out" seed the study already used.

use crate::common;

use chronocooked_analysis::collect::CompactJob;
use chronocooked_paper::heldout::{HeldOutError, HeldOutVerdict, check_held_out};
use common::{ep, job, lstm_fi_job};

/// An LSTM125 FI run at `td` whose two start cells both check first at `foc`.
fn fi_run(seed: u64, td: u32, foc: i32) -> CompactJob {
    lstm_fi_job(
        seed,
        td,
        vec![
            ep("fi", td, (0, 0), Some(foc), 0),
            ep("fi", td, (1, 1), Some(foc), 0),
        ],
    )
}

/// A bisection run (pair 4-12) that answers "long" above probe `bp`; `ep_len` is its last
/// training episodes' mean length (above 100 the notebook excludes the run).
fn bisection_run(seed: u64, ep_len: f64, bp: u32) -> CompactJob {
    let mut eps = Vec::new();
    for d in 1..=16u32 {
        for c in 0..8usize {
            eps.push(ep("bisection", d, (c, 0), None, if d > bp { 2 } else { 1 }));
        }
    }
    CompactJob {
        job: job(
            "Bisection-v0",
            "lstm125",
            seed,
            &["short=4", "long=12"],
            ep_len,
        ),
        episodes: eps,
        curve: vec![],
        levels: vec![],
    }
}

#[test]
fn a_held_out_run_is_judged_against_the_hand_computed_new_run_range() {
    // Study run means 4, 4, 5, 5 at TD 4: mean 4.5, SD 0.57735, range 2.44578 … 6.55422
    // (t(0.975, 3) = 3.18245 · SD · √1.25).
    let study: Vec<CompactJob> = [(1, 4), (2, 4), (3, 5), (4, 5)]
        .into_iter()
        .map(|(s, f)| fi_run(s, 4, f))
        .collect();
    let checks = check_held_out(&study, &[fi_run(9, 4, 6), fi_run(10, 4, 7)]).unwrap();
    let mean = |id: &str| {
        checks
            .iter()
            .find(|c| c.id.contains(id) && c.statistic == "foc_mean")
            .unwrap()
            .clone()
    };
    let (a, b) = (mean("seed9"), mean("seed10"));
    assert_eq!(
        (a.value, a.n, a.runs, a.verdict),
        (6.0, 4, 4, HeldOutVerdict::Inside)
    );
    assert!((a.lo - 2.44578).abs() < 1e-4 && (a.hi - 6.55422).abs() < 1e-4);
    // (6 − 4.5) / 0.57735 = 2.598 SDs: inside the range although beyond 2 SDs.
    assert!((a.sds_from_mean - 2.598076).abs() < 1e-5);
    assert_eq!((b.value, b.verdict), (7.0, HeldOutVerdict::Outside));
    // Each run's two FOCs are equal: CV 0 everywhere, SD 0, a zero-width range it lands on.
    let cv = checks
        .iter()
        .find(|c| c.id.contains("seed9") && c.statistic == "foc_cv")
        .unwrap();
    assert_eq!((cv.value, cv.verdict), (0.0, HeldOutVerdict::Inside));
}

#[test]
fn an_excluded_run_has_no_value_and_an_unstudied_condition_no_range() {
    let study: Vec<CompactJob> = [(1, 7), (2, 8), (3, 8), (4, 9)]
        .into_iter()
        .map(|(s, bp)| bisection_run(s, 30.0, bp))
        .chain((1..=4).map(|s| fi_run(s, 4, 4)))
        .collect();
    // Held out: a bisection run with 150-step training episodes (the notebook drops it) and
    // an FI run at a TD the study never ran.
    let checks = check_held_out(&study, &[bisection_run(9, 150.0, 8), fi_run(9, 12, 11)]).unwrap();
    let bis: Vec<_> = checks.iter().filter(|c| c.task == "Bisection-v0").collect();
    assert_eq!(bis.len(), 4, "anchor accuracy, wf, dl and bp");
    assert!(
        bis.iter()
            .all(|c| c.verdict == HeldOutVerdict::NoValue && c.n >= 2 && c.runs == 4)
    );
    let fi: Vec<_> = checks.iter().filter(|c| c.condition == "TD 12").collect();
    assert!(!fi.is_empty());
    assert!(
        fi.iter()
            .all(|c| c.verdict == HeldOutVerdict::NoRange && c.n == 0)
    );
    // The same bisection run with short episodes is kept and judged.
    let kept = check_held_out(&study, &[bisection_run(9, 30.0, 8)]).unwrap();
    let bp = kept.iter().find(|c| c.statistic == "bp").unwrap();
    assert!(matches!(
        bp.verdict,
        HeldOutVerdict::Inside | HeldOutVerdict::Outside
    ));
    assert!(bp.value.is_finite() && bp.value > 4.0 && bp.value < 12.0);
    // Its anchors are all delivered right, as in every study run: accuracy 1 with SD 0.
    let anchors = kept
        .iter()
        .find(|c| c.statistic == "anchor_accuracy")
        .unwrap();
    assert_eq!(
        (anchors.value, anchors.mean, anchors.verdict),
        (1.0, 1.0, HeldOutVerdict::Inside)
    );
}

#[test]
fn a_seed_the_study_used_is_refused_and_an_empty_check_is_an_error() {
    let study: Vec<CompactJob> = (1..=4).map(|s| fi_run(s, 4, 4)).collect();
    let err = check_held_out(&study, &[fi_run(3, 4, 4)]).unwrap_err();
    assert!(matches!(err, HeldOutError::SeedInStudy { seed: 3, .. }));
    assert!(err.to_string().contains("seed 3"));
    // The same seed at another condition is held out there.
    assert!(check_held_out(&study, &[fi_run(3, 6, 5)]).is_ok());
    assert_eq!(
        check_held_out(&study, &[]).unwrap_err(),
        HeldOutError::NothingToCheck
    );
}
