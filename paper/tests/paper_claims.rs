//! The paper's statements in words (fixed interval, bisection, exact timer; the multi-timer's
//! in `paper_claims_multitimer.rs`),
//! tested on constructed runs whose verdicts are known by hand.

use crate::common;

use chronocooked_analysis::collect::{CompactJob, EpisodeRow};
use chronocooked_paper::claims::{
    ClaimRow, bisection_claims, exact_timer_claims, exact_timer_run_means, fi_claims, fi_run_stat,
    general,
};
use common::{ep, find_claim as find, job, mt_ep};

/// An exact-timer run of `model` at `td` whose buffer-0 episodes earn `r0` and buffer-50%
/// episodes earn `r50` (two start cells each): its mean over buffers is `(r0 + r50) / 2`.
fn exact_run(model: &str, seed: u64, td: u32, r0: f32, r50: f32) -> CompactJob {
    let mut episodes = Vec::new();
    for (f, r) in [(0.0, r0), (0.5, r50)] {
        for _ in 0..2 {
            episodes.push(EpisodeRow {
                kind: "buffer".parse().unwrap(),
                factor: Some(f),
                ..mt_ep(td, r, td as i32)
            });
        }
    }
    CompactJob {
        job: job(
            "MultiTimer-v0",
            model,
            seed,
            &[&format!("tds={td}"), "num_timers=1", "mode=exact"],
            20.0,
        ),
        episodes,
        curve: vec![],
        levels: vec![],
    }
}

/// Four runs of `model` at `td` with these means over buffers (each run: buffer 0 earns
/// `m − 0.05`, buffer 50% `m + 0.05`, so its mean is `m`).
fn runs(model: &str, td: u32, means: [f32; 4]) -> Vec<CompactJob> {
    means
        .iter()
        .enumerate()
        .map(|(i, &m)| exact_run(model, i as u64 + 1, td, m - 0.05, m + 0.05))
        .collect()
}

/// The verdict row of "the CNN's timing does not generalise to longer TDs".
fn short_only_overall(rows: &[ClaimRow]) -> &ClaimRow {
    find(
        rows,
        "exact_cnn_short_only",
        "exact timer, every TD past the shortest",
        "",
    )
}

/// The verdict row over every TD of the statement `claim` whose wording contains `about`.
fn overall<'a>(rows: &'a [ClaimRow], claim: &str, about: &str) -> &'a ClaimRow {
    rows.iter()
        .find(|r| {
            r.claim == claim && r.setting.ends_with("every TD") && r.statement.contains(about)
        })
        .unwrap_or_else(|| panic!("no {claim} over every TD about {about}"))
}

#[test]
fn a_runs_exact_timer_score_is_its_mean_over_the_test_buffers() {
    // Buffer 0: 0.1 twice; buffer 50%: 1 twice → (0.1 + 1) / 2 = 0.55. Second run: 0 and 1.
    let jobs = [
        exact_run("lstm125", 1, 4, 0.1, 1.0),
        exact_run("lstm125", 2, 4, 0.0, 1.0),
    ];
    let m = exact_timer_run_means(&jobs);
    let s = &m[&("lstm125".to_string(), 4)];
    assert_eq!(s.n, 2);
    assert!((s.mean - 0.525).abs() < 1e-6, "{s:?}");
    // SD of 0.55 and 0.5: 0.05/√2.
    assert!((s.sd - 0.05 / 2f64.sqrt()).abs() < 1e-6, "{s:?}");
}

#[test]
fn exact_timer_statements_get_the_verdicts_worked_out_by_hand() {
    let mut jobs = Vec::new();
    // TD 4: LSTM 0.9, 0.8, 1.0, 0.9 and the reservoir 0.85, 0.95, 0.9, 0.8 (equal);
    // the CNN 0.3, 0.4, 0.2, 0.3 (above 0.1).
    jobs.extend(runs("lstm125", 4, [0.9, 0.8, 1.0, 0.9]));
    jobs.extend(runs("ctrnn-reservoir125", 4, [0.85, 0.95, 0.9, 0.8]));
    jobs.extend(runs("cnn-mlp", 4, [0.3, 0.4, 0.2, 0.3]));
    // TD 10: LSTM 0.8, 0.7, 0.9, 0.8 against the reservoir 0.1, 0.1, 0.2, 0.1 (LSTM
    // better); the CNN at the minimum 0.1 on every run; the trained CTRNN better than the
    // LSTM (0.95, 1.0, 0.95, 1.0).
    jobs.extend(runs("lstm125", 10, [0.8, 0.7, 0.9, 0.8]));
    jobs.extend(runs("ctrnn-reservoir125", 10, [0.1, 0.1, 0.2, 0.1]));
    jobs.extend(runs("cnn-mlp", 10, [0.1, 0.1, 0.1, 0.1]));
    jobs.extend(runs("ctrnn125", 10, [0.95, 1.0, 0.95, 1.0]));
    let rows = exact_timer_claims(&jobs);

    // TD 4, LSTM vs reservoir: means 0.9 and 0.875, SDs √(0.02/3) and √(0.0125/3):
    // z = 0.025 / √((0.02 + 0.0125)/12) = 0.4804, Welch df 5.697, p 0.6488 (scipy
    // `ttest_ind(equal_var=False)`) — not a difference, but the 95% interval 0.025 ± 0.1290
    // reaches past the 0.1 margin: equality is not shown either.
    let r = find(
        &rows,
        "exact_shortest_equal",
        "exact timer, TD 4",
        "ctrnn-reservoir125",
    );
    assert!(
        (r.z - 0.025 / (0.0325f64 / 12.0).sqrt()).abs() < 1e-4,
        "{r:?}"
    );
    assert!((r.p - 0.648842).abs() < 1e-5, "{r:?}");
    assert!(r.lab.ends_with("d = 0.025 ± 0.129"), "{r:?}");
    assert_eq!(r.verdict, "not shown");
    assert_eq!(
        find(
            &rows,
            "exact_shortest_equal",
            "exact timer, TD 4",
            "− ctrnn125,"
        )
        .verdict,
        "n/a"
    );
    let r = find(
        &rows,
        "exact_lstm_best",
        "exact timer, TD 4",
        "ctrnn-reservoir125",
    );
    assert_eq!(r.verdict, "not shown");
    // TD 10: 0.8 vs 0.125 (SDs √(0.02/3), √(0.0075/3)): z = 0.675 / √(0.0275/12) ≈ 14.1,
    // df 4.97, p 3.36e-5.
    let r = find(
        &rows,
        "exact_lstm_best",
        "exact timer, TD 10",
        "ctrnn-reservoir125",
    );
    assert!(
        (r.z - 0.675 / (0.0275f64 / 12.0).sqrt()).abs() < 1e-3,
        "{r:?}"
    );
    assert!((r.p - 3.36016e-5).abs() < 1e-8, "{r:?}");
    assert_eq!(r.verdict, "holds");
    // Over both TDs: holds at one of two — two settings are not a generality (at least
    // three are needed) → not shown.
    let r = find(&rows, "exact_lstm_best", "exact timer, every TD", "").clone();
    assert!(r.statement.contains("CTRNN125 (lab: reservoir)"), "{r:?}");
    assert_eq!(r.verdict, "not shown");
    // The trained CTRNN beats the LSTM at TD 10 (0.975 vs 0.8): z −4.04, df 3.74, p 0.0178
    // → contradicted there; with no TD-4 runs that is the only testable TD → not shown
    // overall.
    let r = find(&rows, "exact_lstm_best", "exact timer, TD 10", "− ctrnn125");
    assert!((r.p - 0.0178256).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "contradicted");
    let overall: Vec<&ClaimRow> = rows
        .iter()
        .filter(|r| r.claim == "exact_lstm_best" && r.setting == "exact timer, every TD")
        .collect();
    assert_eq!(overall.len(), 3);
    assert_eq!(overall[2].verdict, "not shown", "{:?}", overall[2]);
    assert!(
        overall[2]
            .lab
            .contains("0 of 1 TDs hold, 1 contradicted (1 untested"),
        "{:?}",
        overall[2]
    );
    // CNN at TD 4: mean 0.3, SD √(0.02/3): z = 0.2 / (SD/2) = 4.899, t on 3 df: p 0.01628
    // → holds.
    let r = find(&rows, "exact_cnn_above_min", "exact timer, TD 4", "");
    assert!(
        (r.z - 0.2 / ((0.02f64 / 3.0).sqrt() / 2.0)).abs() < 1e-3,
        "{r:?}"
    );
    assert!((r.p - 0.0162766).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    // CNN at TD 10 exactly at the minimum on every run (SD 0, mean 0.1): z 0, p 1 and the
    // interval 0 ± 0 within the margin → holds; the premise holds → holds overall.
    let r = find(&rows, "exact_cnn_short_only", "exact timer, TD 10", "");
    assert_eq!((r.z, r.p, r.verdict.as_str()), (0.0, 1.0, "holds"));
    let r = short_only_overall(&rows);
    assert_eq!(r.verdict, "holds", "{r:?}");
}

#[test]
fn a_cnn_without_the_capacity_at_the_shortest_td_has_nothing_to_generalise() {
    // The CNN never delivers at TD 4 (0 on all four runs) and earns the minimum at TD 10.
    let mut jobs = runs("cnn-mlp", 4, [0.05, 0.05, 0.05, 0.05]);
    for j in &mut jobs {
        for e in &mut j.episodes {
            e.reward = 0.0;
        }
    }
    jobs.extend(runs("cnn-mlp", 10, [0.1, 0.1, 0.1, 0.1]));
    let rows = exact_timer_claims(&jobs);
    // Four runs all at 0 against 0.1: no variance, so the exact sign-flip test: all four
    // signs agree in 2 of 2⁴ patterns, p = 0.125 — four runs cannot show it at 5%.
    let r = find(&rows, "exact_cnn_above_min", "exact timer, TD 4", "");
    assert_eq!(
        (r.z, r.p, r.verdict.as_str()),
        (f64::NEG_INFINITY, 0.125, "not shown")
    );
    let r = short_only_overall(&rows);
    assert_eq!(r.verdict, "n/a", "{r:?}");
    assert!(r.lab.starts_with("no capacity at TD 4"), "{r:?}");
}

#[test]
fn equally_well_needs_the_whole_interval_inside_the_margin() {
    // Tight runs: LSTM 0.90, 0.91, 0.90, 0.91 and reservoir 0.90, 0.90, 0.91, 0.91 → d = 0,
    // 95% half-width t(6)·se = 0.00999 → holds. A reservoir at 0.5: d = 0.4, its whole
    // interval beyond the margin → contradicted.
    let mut jobs = runs("lstm125", 4, [0.9, 0.91, 0.9, 0.91]);
    jobs.extend(runs("ctrnn-reservoir125", 4, [0.9, 0.9, 0.91, 0.91]));
    let rows = exact_timer_claims(&jobs);
    let r = find(
        &rows,
        "exact_shortest_equal",
        "exact timer, TD 4",
        "ctrnn-reservoir125",
    );
    assert_eq!(r.verdict, "holds", "{r:?}");
    let mut jobs = runs("lstm125", 4, [0.9, 0.91, 0.9, 0.91]);
    jobs.extend(runs("ctrnn-reservoir125", 4, [0.5, 0.5, 0.51, 0.51]));
    let rows = exact_timer_claims(&jobs);
    let r = find(
        &rows,
        "exact_shortest_equal",
        "exact timer, TD 4",
        "ctrnn-reservoir125",
    );
    assert_eq!(r.verdict, "contradicted", "{r:?}");
    // A noisy CNN at a longer TD, 0.1, 0.1, 0.5, 0.1: d = 0.1 above the minimum with
    // half-width t(3)·0.1 = 0.318 — neither wholly above the margin nor within it.
    let mut jobs = runs("cnn-mlp", 4, [0.3, 0.4, 0.2, 0.3]);
    jobs.extend(runs("cnn-mlp", 10, [0.1, 0.1, 0.5, 0.1]));
    let rows = exact_timer_claims(&jobs);
    assert_eq!(
        find(&rows, "exact_cnn_short_only", "exact timer, TD 10", "").verdict,
        "not shown"
    );
    assert_eq!(short_only_overall(&rows).verdict, "not shown");
}

#[test]
fn a_cnn_that_times_long_durations_contradicts_the_short_only_statement() {
    let mut jobs = runs("cnn-mlp", 4, [0.3, 0.4, 0.2, 0.3]);
    jobs.extend(runs("cnn-mlp", 15, [0.6, 0.7, 0.5, 0.6]));
    let rows = exact_timer_claims(&jobs);
    assert_eq!(
        find(&rows, "exact_cnn_short_only", "exact timer, TD 15", "").verdict,
        "contradicted"
    );
    assert_eq!(short_only_overall(&rows).verdict, "contradicted");
    // No LSTM runs: the LSTM statements cannot be tested.
    assert!(
        rows.iter()
            .filter(|r| r.claim == "exact_lstm_best")
            .all(|r| r.verdict == "n/a")
    );
}

#[test]
fn general_statements_need_a_majority_of_at_least_three_settings_and_no_contradiction() {
    // Fewer than three tested settings are not a generality.
    assert_eq!(general(["holds", "holds"]), "not shown");
    assert_eq!(
        general(["contradicted", "contradicted", "n/a"]),
        "not shown"
    );
    assert_eq!(general(["n/a", "n/a"]), "n/a");
    // A strict majority: 2 of 3 holds, 2 of 4 does not.
    assert_eq!(general(["holds", "holds", "not shown"]), "holds");
    assert_eq!(
        general(["holds", "holds", "not shown", "not shown"]),
        "not shown"
    );
    assert_eq!(general(["holds", "not shown", "not shown"]), "not shown");
    // One contradiction blocks "holds"; a majority of them is "contradicted".
    assert_eq!(general(["holds", "holds", "contradicted"]), "not shown");
    assert_eq!(
        general(["contradicted", "contradicted", "not shown"]),
        "contradicted"
    );
    // Untested settings do not count.
    assert_eq!(general(["n/a", "holds", "holds", "holds"]), "holds");
}

#[test]
fn tests_on_runs_are_welch_t_or_exact_without_variance() {
    use chronocooked_analysis::behaviour::aggregate::Spread;
    use chronocooked_paper::claims::MeanTest;
    // Welch: the FI example below (ratios 1, 0.875, 1.125, 1 against 0.25, 0.375, 0.25,
    // 0.125): t 10.3923 on 6 df, p 4.649e-5, half-width 0.17659 (scipy).
    let a = Spread::of([1.0, 0.875, 1.125, 1.0]);
    let b = Spread::of([0.25, 0.375, 0.25, 0.125]);
    let t = MeanTest::two_sample(&a, &b).unwrap();
    assert!(
        (t.z - 10.392305).abs() < 1e-5 && (t.df - 6.0).abs() < 1e-9,
        "{t:?}"
    );
    assert!((t.p - 4.64893e-5).abs() < 1e-9, "{t:?}");
    assert!((t.half_width() - 0.176591).abs() < 1e-5, "{t:?}");
    // Unequal spreads: deviations 0.75, 0.625, 0.75, 0.875 against 0, 0.125, 0.125, 0:
    // Welch df 5.4, p 6.689e-5.
    let t = MeanTest::two_sample(
        &Spread::of([0.75, 0.625, 0.75, 0.875]),
        &Spread::of([0.0, 0.125, 0.125, 0.0]),
    )
    .unwrap();
    assert!(
        (t.df - 5.4).abs() < 1e-9 && (t.p - 6.68935e-5).abs() < 1e-9,
        "{t:?}"
    );
    // No variance on either side: the exact randomisation test, 2 / C(8, 4) = 2/70 with
    // four runs a side (significant), 2 / C(5, 2) = 0.2 with three against two (not).
    let t = MeanTest::two_sample(&Spread::of([1.0; 4]), &Spread::of([0.0; 4])).unwrap();
    assert_eq!((t.z, t.se), (f64::INFINITY, 0.0));
    assert!((t.p - 2.0 / 70.0).abs() < 1e-12 && t.significant());
    let t = MeanTest::two_sample(&Spread::of([1.0; 3]), &Spread::of([0.0; 2])).unwrap();
    assert!((t.p - 0.2).abs() < 1e-12 && !t.significant());
    // One sample without variance: the sign-flip test, 2 / 2ⁿ.
    let t = MeanTest::one_sample(&Spread::of([1.0; 6]), 0.5).unwrap();
    assert!((t.p - 2.0 / 64.0).abs() < 1e-12 && t.significant());
    // Runs equal up to rounding (a mean over cells can differ in the last bits: 1e-12) are
    // still runs without variance: exact p = 2 / C(6, 3) = 0.1, not a t on an SD of 1e-12.
    let tenth = f64::from(0.1f32);
    let rounded = Spread::of([tenth, tenth + 1e-12, tenth - 1e-12]);
    let t = MeanTest::two_sample(&rounded, &Spread::of([0.0; 3])).unwrap();
    assert_eq!(t.se, 0.0, "{t:?}");
    assert!((t.p - 0.1).abs() < 1e-12 && !t.significant(), "{t:?}");
    // The same value: no difference, p 1; below two runs: no test.
    let t = MeanTest::two_sample(&Spread::of([0.5; 3]), &Spread::of([0.5; 3])).unwrap();
    assert_eq!((t.d, t.z, t.p), (0.0, 0.0, 1.0));
    assert!(MeanTest::one_sample(&Spread::of([0.5]), 0.0).is_none());
}

/// A fixed-interval run of `model` at `td` with these first oven checks (one start cell
/// each; `None`: an episode without a check).
fn fi_run(model: &str, seed: u64, td: u32, focs: &[Option<i32>]) -> CompactJob {
    CompactJob {
        job: job(
            "FixedInterval-v0",
            model,
            seed,
            &[&format!("td={td}")],
            20.0,
        ),
        episodes: focs
            .iter()
            .enumerate()
            .map(|(i, f)| ep("fi", td, (i, 0), *f, 0))
            .collect(),
        curve: vec![],
        levels: vec![],
    }
}

#[test]
fn a_fi_runs_statistics_are_its_zero_share_and_mean_foc_over_td() {
    // FOCs 0, 0, 6 and one episode without a check: share 2/3 at 0, mean 2 → 2/6, each
    // check's distance from the TD 1, 1, 0 → 2/3.
    let j = fi_run("cnn-mlp", 1, 6, &[Some(0), Some(0), Some(6), None]);
    let s = fi_run_stat(&j, 6).unwrap();
    assert!((s.zero_share - 2.0 / 3.0).abs() < 1e-12 && (s.ratio - 1.0 / 3.0).abs() < 1e-12);
    assert!((s.deviation - 2.0 / 3.0).abs() < 1e-12, "{s:?}");
    // Checks straddling the TD (0 and 12 at TD 6): a mean FOC at the TD, but each check a
    // whole TD away.
    let s = fi_run_stat(&fi_run("lstm125", 1, 6, &[Some(0), Some(12)]), 6).unwrap();
    assert_eq!((s.ratio, s.deviation), (1.0, 1.0));
    assert_eq!(
        fi_run_stat(&fi_run("cnn-mlp", 2, 6, &[None, None]), 6),
        None
    );
}

#[test]
fn fixed_interval_statements_get_the_verdicts_worked_out_by_hand() {
    let mut jobs = Vec::new();
    // TD 8. The CNN: three runs checking from the start on all four cells, one on none of
    // them (FOC 8 everywhere): shares 1, 1, 1, 0 → 0.75 ± 0.5, z = 0.25/0.25 = 1 → not
    // shown. The LSTM: mean FOC 8, 7, 9, 8 (ratios 1, 0.875, 1.125, 1 → |ratio − 1| 0,
    // 0.125, 0.125, 0). The reservoir: mean FOC 2, 3, 2, 1 (ratios 0.25, 0.375, 0.25,
    // 0.125; deviations 0.75, 0.625, 0.75, 0.875).
    for (s, f) in [(1, 0), (2, 0), (3, 0), (4, 8)] {
        jobs.push(fi_run("cnn-mlp", s, 8, &[Some(f); 4]));
    }
    for (s, f) in [(1, 8), (2, 7), (3, 9), (4, 8)] {
        jobs.push(fi_run("lstm125", s, 8, &[Some(f); 4]));
    }
    for (s, f) in [(1, 2), (2, 3), (3, 2), (4, 1)] {
        jobs.push(fi_run("ctrnn-reservoir125", s, 8, &[Some(f); 4]));
    }
    let rows = fi_claims(&jobs);
    let r = find(&rows, "fi_cnn_foc_zero", "fixed interval, TD 8", "");
    assert!((r.z - 1.0).abs() < 1e-9, "{r:?}");
    assert_eq!(r.verdict, "not shown");
    // Earlier: LSTM ratio 1 ± 0.1021 vs reservoir 0.25 ± 0.1021: z = 0.75 / √(2·0.010417/4).
    let r = find(
        &rows,
        "fi_ctrnn_earlier",
        "fixed interval, TD 8",
        "ctrnn-reservoir125",
    );
    let se = (2.0 * (0.125f64.powi(2) * 2.0 / 3.0) / 4.0).sqrt();
    assert!((r.z - 0.75 / se).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    // Closer: deviations 0.75 ± 0.1021 (reservoir) vs 0.0625 ± 0.0722 (LSTM).
    let r = find(
        &rows,
        "fi_lstm_closer",
        "fixed interval, TD 8",
        "ctrnn-reservoir125",
    );
    let se = ((0.125f64.powi(2) * 2.0 / 3.0) / 4.0 + (0.125f64.powi(2) / 3.0) / 4.0).sqrt();
    assert!((r.z - 0.6875 / se).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    // No size-256 or trained-CTRNN runs: those statements cannot be tested.
    assert!(
        rows.iter()
            .filter(|r| r.claim == "fi_ctrnn256_better")
            .all(|r| r.verdict == "n/a")
    );
    assert_eq!(overall(&rows, "fi_ctrnn_earlier", "trained").verdict, "n/a");
    // The tables show the verdict rows, not the per-TD rows behind a "generally".
    assert!(overall(&rows, "fi_ctrnn_earlier", "reservoir").summary);
    assert!(
        !find(
            &rows,
            "fi_ctrnn_earlier",
            "fixed interval, TD 8",
            "reservoir"
        )
        .summary
    );

    // A CNN checking from the start on every run, at three TDs: no variance, so the exact
    // sign-flip test against 0.5 — with 4 runs p = 2/2⁴ = 0.125 (not shown at any TD), with
    // 6 runs 2/2⁶ = 0.031 (holds at each, so over the TDs). A reservoir later than the LSTM
    // at all three TDs contradicts "earlier".
    let cnn_runs = |n: u64| -> Vec<CompactJob> {
        [8, 12, 16]
            .iter()
            .flat_map(|&td| (1..=n).map(move |s| fi_run("cnn-mlp", s, td, &[Some(0); 3])))
            .collect()
    };
    let mut jobs = cnn_runs(4);
    for td in [8, 12, 16] {
        for (s, f) in [(1, td), (2, td - 1), (3, td + 1), (4, td)] {
            jobs.push(fi_run("lstm125", s, td, &[Some(f as i32); 2]));
            jobs.push(fi_run(
                "ctrnn-reservoir125",
                s,
                td,
                &[Some(f as i32 + 8); 2],
            ));
        }
    }
    let rows = fi_claims(&jobs);
    let r = find(&rows, "fi_cnn_foc_zero", "fixed interval, TD 8", "");
    assert_eq!((r.p, r.verdict.as_str()), (0.125, "not shown"));
    assert_eq!(
        find(&rows, "fi_cnn_foc_zero", "fixed interval, every TD", "").verdict,
        "not shown"
    );
    assert_eq!(
        overall(&rows, "fi_ctrnn_earlier", "reservoir").verdict,
        "contradicted"
    );
    let rows = fi_claims(&cnn_runs(6));
    let r = find(&rows, "fi_cnn_foc_zero", "fixed interval, TD 12", "");
    assert_eq!((r.p, r.verdict.as_str()), (2.0 / 64.0, "holds"));
    assert_eq!(
        find(&rows, "fi_cnn_foc_zero", "fixed interval, every TD", "").verdict,
        "holds"
    );
}

/// A bisection run of `model` on the anchor pair `short`-`long` answering `right` of its 4
/// short-anchor and 4 long-anchor episodes correctly (the wrong ones to the other counter).
fn bisection_run(model: &str, seed: u64, (short, long): (u32, u32), right: usize) -> CompactJob {
    let mut episodes = Vec::new();
    for (d, correct, wrong) in [(short, 1, 2), (long, 2, 1)] {
        for k in 0..4 {
            let counter = if k < right { correct } else { wrong };
            episodes.push(ep("bisection", d, (k, 0), None, counter));
        }
    }
    CompactJob {
        job: job(
            "Bisection-v0",
            model,
            seed,
            &[&format!("short={short}"), &format!("long={long}")],
            20.0,
        ),
        episodes,
        curve: vec![],
        levels: vec![],
    }
}

#[test]
fn bisection_statements_compare_anchor_accuracy_per_pair() {
    const PAIRS: [(u32, u32); 3] = [(4, 8), (6, 12), (6, 18)];
    // On every pair: LSTM125 accuracy 1, 1, 0.75, 1 (4 of 4, 3 of 4 per anchor); reservoir
    // 0.5 on every run: LSTM better (z = 0.4375 / (0.125/2) = 7 on 3 df, p 0.005986).
    // LSTM256 1, 1, 1, 1 and the reservoir256 answering `res256` of 4 right per anchor.
    let jobs = |res256: usize| -> Vec<CompactJob> {
        let mut jobs = Vec::new();
        for pair in PAIRS {
            for (s, r) in [(1, 4), (2, 4), (3, 3), (4, 4)] {
                jobs.push(bisection_run("lstm125", s, pair, r));
                jobs.push(bisection_run("ctrnn-reservoir125", s, pair, 2));
                jobs.push(bisection_run("lstm256", s, pair, 4));
                jobs.push(bisection_run("ctrnn-reservoir256", s, pair, res256));
            }
        }
        jobs
    };
    // Both 256s at 1 on every run: d = 0 ± 0 → comparable.
    let rows = bisection_claims(&jobs(4));
    let r = find(
        &rows,
        "bisection_lstm_better",
        "bisection, pair 4-8",
        "reservoir",
    );
    assert!((r.z - 0.4375 / (0.125 / 2.0)).abs() < 1e-9, "{r:?}");
    assert!((r.p - 0.0059863).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    assert_eq!(
        overall_pair(&rows, "bisection_lstm_better", "reservoir").verdict,
        "holds"
    );
    assert_eq!(
        overall_pair(&rows, "bisection_lstm_better", "trained").verdict,
        "n/a"
    );
    assert_eq!(
        overall_pair(&rows, "bisection_256_comparable", "256").verdict,
        "holds"
    );
    // A reservoir256 at 0.5: d = 0.5 beyond the margin on runs without variance, exact
    // p = 2/70 → contradicted on every pair.
    let rows = bisection_claims(&jobs(2));
    let r = find(
        &rows,
        "bisection_256_comparable",
        "bisection, pair 6-18",
        "",
    );
    assert!((r.p - 2.0 / 70.0).abs() < 1e-12, "{r:?}");
    assert_eq!(
        overall_pair(&rows, "bisection_256_comparable", "256").verdict,
        "contradicted"
    );
}

/// The verdict row over every anchor pair of `claim` whose wording contains `about`.
fn overall_pair<'a>(rows: &'a [ClaimRow], claim: &str, about: &str) -> &'a ClaimRow {
    rows.iter()
        .find(|r| {
            r.claim == claim && r.setting == "bisection, every pair" && r.statement.contains(about)
        })
        .unwrap_or_else(|| panic!("no {claim} over every pair about {about}: {rows:#?}"))
}

#[test]
fn the_lab_s_trained_ctrnn256_gets_its_own_rows_beside_the_paper_s_reservoirs() {
    // FI at TD 8. Trained CTRNN125: mean FOC 4, 5, 4, 3 (|FOC/TD − 1| 0.5, 0.375, 0.5,
    // 0.625 → 0.5 ± 0.1021); trained CTRNN256: 8, 7, 9, 8 (0, 0.125, 0.125, 0 → 0.0625 ±
    // 0.0722): closer by d = 0.4375. No reservoir256 runs: the paper's row is untested.
    let mut jobs = Vec::new();
    for (s, (f125, f256)) in [(4, 8), (5, 7), (4, 9), (3, 8)].into_iter().enumerate() {
        let s = s as u64 + 1;
        jobs.push(fi_run("ctrnn125", s, 8, &[Some(f125); 4]));
        jobs.push(fi_run("ctrnn256", s, 8, &[Some(f256); 4]));
        jobs.push(fi_run("ctrnn-reservoir125", s, 8, &[Some(2); 4]));
    }
    let rows = fi_claims(&jobs);
    let r = find(
        &rows,
        "fi_ctrnn256_better",
        "fixed interval, TD 8",
        "ctrnn125 − ctrnn256",
    );
    assert!(r.statement.contains("not in the paper"), "{r:?}");
    let se = ((0.125f64.powi(2) * 2.0 / 3.0) / 4.0 + (0.125f64.powi(2) / 3.0) / 4.0).sqrt();
    assert!((r.z - 0.4375 / se).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    let paper = find(
        &rows,
        "fi_ctrnn256_better",
        "fixed interval, TD 8",
        "ctrnn-reservoir125 − ctrnn-reservoir256",
    );
    assert_eq!(paper.verdict, "n/a");
    // One TD tested: too few settings for "generally".
    assert_eq!(
        overall(&rows, "fi_ctrnn256_better", "trained CTRNN256").verdict,
        "not shown"
    );

    // Bisection: LSTM256 right on every anchor trial, the trained CTRNN256 on half of them
    // (no variance on either side: exact p = 2/C(8, 4) = 2/70, d = 0.5 beyond the margin) →
    // contradicted on every pair; no reservoir256 → the paper's row is n/a.
    let mut jobs = Vec::new();
    for pair in [(4, 8), (6, 12), (6, 18)] {
        for s in 1..=4 {
            jobs.push(bisection_run("lstm256", s, pair, 4));
            jobs.push(bisection_run("ctrnn256", s, pair, 2));
        }
    }
    let rows = bisection_claims(&jobs);
    let r = find(
        &rows,
        "bisection_256_comparable",
        "bisection, pair 6-12",
        "lstm256 − ctrnn256",
    );
    assert!((r.p - 2.0 / 70.0).abs() < 1e-12, "{r:?}");
    assert_eq!(r.verdict, "contradicted");
    assert_eq!(
        overall_pair(&rows, "bisection_256_comparable", "trained CTRNN256").verdict,
        "contradicted"
    );
    assert_eq!(
        overall_pair(&rows, "bisection_256_comparable", "(lab: reservoir)").verdict,
        "n/a"
    );
}
