//! The paper's multi-timer statements (levels, timers stored, capacity) and the per-level
//! figure, tested on constructed runs whose verdicts are known by hand.

use crate::common;

use chronocooked_analysis::collect::{CompactJob, LevelEpisode};
use chronocooked_paper::claims::{capacity_claims, multitimer_claims, shift_claims};
use chronocooked_paper::multitimer::{LevelTd, analyse_multitimer, timers_stored};
use common::{find_claim as find, job, mt_ep};

/// An exact multi-timer run on the notebook's list that reached `level`, its final policy
/// earning `reward` at each of the five TDs.
fn mt_run(model: &str, seed: u64, level: usize, reward: f32) -> CompactJob {
    let mut j = job(
        "MultiTimer-v0",
        model,
        seed,
        &["tds=2,4,6,8,10", "mode=exact"],
        20.0,
    );
    j.level_steps = (0..=level as u64).map(|l| l * 1000).collect();
    CompactJob {
        job: j,
        episodes: [2, 4, 6, 8, 10]
            .into_iter()
            .map(|td| mt_ep(td, reward, td as i32))
            .collect(),
        curve: vec![],
        levels: vec![],
    }
}

#[test]
fn multitimer_statements_compare_levels_and_look_for_a_run_that_does_everything() {
    let mut jobs = Vec::new();
    // LSTM levels 2, 3, 2, 3; reservoir 1, 1, 1, 1; CNN 2, 3, 3, 2 (equal to the LSTM).
    for (s, l) in [(1, 2), (2, 3), (3, 2), (4, 3)] {
        jobs.push(mt_run("lstm125", s, l, 0.0));
    }
    for s in 1..=4 {
        jobs.push(mt_run("ctrnn-reservoir125", s, 1, 0.0));
    }
    for (s, l) in [(1, 2), (2, 3), (3, 3), (4, 2)] {
        jobs.push(mt_run("cnn-mlp", s, l, 0.0));
    }
    let mt = analyse_multitimer(&jobs);
    let rows = multitimer_claims(&mt);
    let setting = "multi-timer exact, TDs 2, 4, 6, 8, 10";
    // LSTM 2.5 ± 0.577 vs reservoir 1 ± 0: z = 1.5 / (0.57735/2) = 5.196, Welch df 3
    // (the reservoir has no variance), p 0.01385 (scipy).
    let r = find(
        &rows,
        "multitimer_lstm_further",
        setting,
        "ctrnn-reservoir125",
    );
    assert!((r.z - 1.5 / (0.57735 / 2.0)).abs() < 1e-3, "{r:?}");
    assert!((r.p - 0.0138468).abs() < 1e-6, "{r:?}");
    assert_eq!(r.verdict, "holds");
    assert_eq!(
        find(&rows, "multitimer_lstm_further", setting, "cnn-mlp").verdict,
        "not shown"
    );
    assert_eq!(
        find(&rows, "multitimer_lstm_further", setting, "− ctrnn125,").verdict,
        "n/a"
    );
    assert_eq!(
        find(&rows, "multitimer_none_all", setting, "").verdict,
        "holds"
    );

    // One reservoir run at five timers earning 0.95 at every TD: someone does it all.
    jobs.push(mt_run("ctrnn-reservoir125", 5, 5, 0.95));
    let rows = multitimer_claims(&analyse_multitimer(&jobs));
    let r = find(&rows, "multitimer_none_all", setting, "");
    assert_eq!(r.verdict, "contradicted", "{r:?}");
    // That run kept no level policies: the row says it was judged in the training setting.
    assert!(
        r.lab
            .contains("1 judged on the final policy in the training setting"),
        "{r:?}"
    );
    // At five timers earning 0.95 at four TDs and 0.5 at one: not every task.
    jobs.pop();
    let mut j = mt_run("ctrnn-reservoir125", 5, 5, 0.95);
    j.episodes[4].reward = 0.5;
    jobs.push(j);
    let rows = multitimer_claims(&analyse_multitimer(&jobs));
    assert_eq!(
        find(&rows, "multitimer_none_all", setting, "").verdict,
        "holds"
    );
    // At five timers but earning 0.5: reaching the level is not performing it.
    jobs.pop();
    jobs.push(mt_run("ctrnn-reservoir125", 5, 5, 0.5));
    let rows = multitimer_claims(&analyse_multitimer(&jobs));
    assert_eq!(
        find(&rows, "multitimer_none_all", setting, "").verdict,
        "holds"
    );
}

/// A curve point: `td` where the soup is taken on `taken` of the cells at mean `off`.
fn point(td: u32, taken: f64, off: f64) -> LevelTd {
    LevelTd {
        td,
        trained: false,
        reward: 0.0,
        taken,
        off_time: off,
    }
}

#[test]
fn timers_stored_counts_distinct_oven_off_plateaus() {
    // A perfect timer over TDs 1 … 11: eleven plateaus.
    let perfect: Vec<LevelTd> = (1..=11).map(|t| point(t, 1.0, f64::from(t))).collect();
    assert_eq!(timers_stored(&perfect), 11);
    // The paper's CTRNN example: ≈ 2 at TD 2, ≈ 5 from TD 3 to 8, back to 2 at TD 9 → 2.
    let mut ctrnn = vec![point(1, 1.0, 2.0), point(2, 1.0, 2.1)];
    ctrnn.extend((3..=8).map(|t| point(t, 1.0, 4.8 + 0.1 * f64::from(t % 2))));
    ctrnn.push(point(9, 1.0, 1.9));
    assert_eq!(timers_stored(&ctrnn), 2);
    // Means within half a step are one timer; 0.6 apart are two.
    assert_eq!(timers_stored(&[point(1, 1.0, 4.8), point(2, 1.0, 5.2)]), 1);
    assert_eq!(timers_stored(&[point(1, 1.0, 4.8), point(2, 1.0, 5.4)]), 2);
    // A TD where the soup is taken on fewer than half the cells does not count.
    assert_eq!(timers_stored(&[point(1, 1.0, 2.0), point(2, 0.4, 7.0)]), 1);
    assert_eq!(timers_stored(&[point(1, 0.0, f64::NAN)]), 0);
    // A ramp in steps of 0.4 from 2.0 to 6.0 is not one plateau: groups span at most half a
    // step from their first value — [2.0, 2.4], [2.8, 3.2], [3.6, 4.0], [4.4, 4.8],
    // [5.2, 5.6], [6.0].
    let ramp: Vec<LevelTd> = (0..=10)
        .map(|k| point(k + 1, 1.0, 2.0 + 0.4 * f64::from(k)))
        .collect();
    assert_eq!(timers_stored(&ramp), 6);
}

fn level_episode(level: usize, td: u32, off: i32) -> LevelEpisode {
    LevelEpisode {
        level,
        td,
        row: 0,
        col: 0,
        steps: 20,
        reward: if off == td as i32 { 1.0 } else { 0.0 },
        success: off == td as i32,
        oven_off_time: off,
        kind: None,
    }
}

/// A run on the notebook's list whose level-1 … `top` policies take the soup at `off(level,
/// td)` at every TD 1 … longest + 1 (two start cells each).
fn shifting_run(model: &str, seed: u64, top: usize, off: impl Fn(usize, u32) -> i32) -> CompactJob {
    let tds = [2u32, 4, 6, 8, 10];
    let mut levels = vec![level_episode(0, 2, 2)];
    for level in 1..=top {
        let longest = tds[..level].iter().copied().max().unwrap();
        for td in 1..=longest + 1 {
            for _ in 0..2 {
                levels.push(level_episode(level, td, off(level, td)));
            }
        }
    }
    let mut j = job(
        "MultiTimer-v0",
        model,
        seed,
        &["tds=2,4,6,8,10", "mode=exact"],
        20.0,
    );
    j.level_steps = (0..=top as u64).map(|l| l * 1000).collect();
    CompactJob {
        job: j,
        episodes: vec![],
        curve: vec![],
        levels,
    }
}

#[test]
fn untrained_tds_leave_the_level_reward_alone_and_give_the_timers_stored() {
    // Level 2 (TDs 2, 4) timed perfectly at its trained TDs, at 4 everywhere else (1, 3, 5):
    // its level reward is 1 (trained TDs only), its untrained reward 0, and its oven-off
    // curve 4, 2, 4, 4, 4 holds two timers.
    let j = shifting_run("lstm125", 1, 2, |_, td| if td == 2 { 2 } else { 4 });
    let mt = analyse_multitimer(&[j]);
    let r = &mt[0].runs[0];
    assert_eq!(r.level_eval[2], Some(1.0));
    assert_eq!(r.level_timers[2], Some(2));
    let trained: Vec<u32> = r.level_curves[2]
        .iter()
        .filter(|c| c.trained)
        .map(|c| c.td)
        .collect();
    assert_eq!(trained, [2, 4]);
    assert_eq!(mt[0].level_untrained_reward[2].mean, 0.0);
    // Level 1 (TD 2) on 1, 2, 3: 4, 2, 4 → reward 1 at its TD, two timers; level 0 (TD 2
    // only, taken at 2): one.
    assert_eq!((r.level_eval[1], r.level_timers[1]), (Some(1.0), Some(2)));
    assert_eq!(r.level_timers[0], Some(1));
    assert_eq!(r.level_timers[3], None);
}

#[test]
fn more_shifts_is_tested_level_by_level() {
    let mut jobs = Vec::new();
    // LSTM: one timer at every level (always 4). Reservoir: a perfect timer at every TD
    // (level L stores 2L + 1 timers: TDs 1 … 2L + 1).
    for s in 1..=4 {
        jobs.push(shifting_run("lstm125", s, 3, |_, _| 4));
        jobs.push(shifting_run("ctrnn-reservoir125", s, 3, |_, td| td as i32));
    }
    let rows = shift_claims(&analyse_multitimer(&jobs));
    let task = "multi-timer exact, TDs 2, 4, 6, 8, 10";
    // Equal counts on every run (SD 0) and a difference: z = +∞, the exact randomisation
    // test p = 2 / C(8, 4) = 2/70 → holds at levels 1–3; levels 4–5 were never reached →
    // n/a; over the levels: 3 of 3 → holds.
    let r = find(
        &rows,
        "multitimer_ctrnn_more_shifts",
        &format!("{task}, level 2"),
        "reservoir",
    );
    assert_eq!((r.z, r.verdict.as_str()), (f64::INFINITY, "holds"));
    assert!((r.p - 2.0 / 70.0).abs() < 1e-12, "{r:?}");
    assert!(
        r.lab.starts_with("5.00 ± 0.00 (4) vs 1.00 ± 0.00 (4)"),
        "{r:?}"
    );
    let r = find(
        &rows,
        "multitimer_ctrnn_more_shifts",
        &format!("{task}, level 5"),
        "reservoir",
    );
    assert_eq!(r.verdict, "n/a");
    let r = rows
        .iter()
        .find(|r| r.summary && r.statement.contains("reservoir"))
        .unwrap();
    assert_eq!(
        (r.setting.as_str(), r.verdict.as_str()),
        (format!("{task}, every level").as_str(), "holds")
    );
    // No trained-CTRNN runs.
    let r = rows
        .iter()
        .find(|r| r.summary && r.statement.contains("trained"))
        .unwrap();
    assert_eq!(r.verdict, "n/a");
}

#[test]
fn the_papers_level_figure_has_a_reward_and_an_off_time_panel_per_reached_level() {
    use chronocooked_paper::figures::level_panels;
    use chronocooked_paper::study::PaperStudy;
    let jobs: Vec<CompactJob> = (1..=2)
        .map(|s| shifting_run("lstm125", s, 2, |_, td| td as i32))
        .collect();
    let study = PaperStudy {
        jobs: jobs.len(),
        fi: vec![],
        bisection: vec![],
        multitimer: analyse_multitimer(&jobs),
        exact_timer: vec![],
        claims: vec![],
        comparison: vec![],
        agreement: Default::default(),
        pi: vec![],
        pi_verdicts: vec![],
        cost: vec![],
        spreads: vec![],
        ranges: vec![],
    };
    let (grid, panels) = level_panels(&study);
    // One curriculum × TD list: a reward row and an oven-off row, levels 1 … 5.
    assert_eq!(grid, (2, 5));
    assert_eq!(panels.len(), 10);
    let present: Vec<bool> = panels.iter().map(Option::is_some).collect();
    assert_eq!(
        present,
        [
            true, true, false, false, false, true, true, false, false, false
        ]
    );
    // Level 2's oven-off panel: the perfect timer's curve is the diagonal over TDs 1 … 5,
    // and its trained TDs 2 and 4 are marked.
    let c = panels[6].as_ref().unwrap();
    assert_eq!(c.series.len(), 1);
    let want: Vec<(f64, f64)> = (1..=5).map(|t| (f64::from(t), f64::from(t))).collect();
    assert_eq!(c.series[0].points, want);
    let marks: Vec<f64> = c.markers.iter().map(|m| m.0).collect();
    assert_eq!(marks, [2.0, 4.0]);
}

#[test]
fn a_five_timer_policy_that_times_everything_goes_against_no_strong_capacity() {
    // Always at 4: level 5 earns 1 at TD 4 only and 0 at every other TD → it holds.
    let weak: Vec<CompactJob> = (1..=2)
        .map(|s| shifting_run("lstm125", s, 5, |_, _| 4))
        .collect();
    let rows = capacity_claims(&analyse_multitimer(&weak));
    assert_eq!(rows.len(), 1);
    assert_eq!(rows[0].verdict, "holds", "{:?}", rows[0]);
    // Worst trained TD (2, 6, 8 or 10) and worst untrained TD: 0.
    assert!(
        rows[0].lab.contains("lstm125 0.00 / 0.00 (2)"),
        "{:?}",
        rows[0]
    );
    // Timing only its trained (even) TDs: stores the intervals → against it.
    let mut even = weak.clone();
    even.extend((1..=2).map(|s| {
        shifting_run(
            "cnn-mlp",
            s,
            5,
            |_, td| if td % 2 == 0 { td as i32 } else { 99 },
        )
    }));
    let rows = capacity_claims(&analyse_multitimer(&even));
    assert_eq!(rows[0].verdict, "contradicted");
    assert!(
        rows[0].lab.contains("cnn-mlp 1.00 / 0.00 (2)"),
        "{:?}",
        rows[0]
    );
    // A perfect timer at every TD 1 … 11 → contradicted, naming the model.
    let mut jobs = weak;
    jobs.extend((1..=2).map(|s| shifting_run("ctrnn125", s, 5, |_, td| td as i32)));
    let rows = capacity_claims(&analyse_multitimer(&jobs));
    assert_eq!(rows[0].verdict, "contradicted");
    assert!(rows[0].lab.ends_with("against: ctrnn125"), "{:?}", rows[0]);
    // No run kept a five-timer policy: n/a.
    let short: Vec<CompactJob> = (1..=2)
        .map(|s| shifting_run("lstm125", s, 3, |_, td| td as i32))
        .collect();
    assert_eq!(
        capacity_claims(&analyse_multitimer(&short))[0].verdict,
        "n/a"
    );
}

#[test]
fn performing_every_timer_is_judged_in_the_notebooks_test_setting_where_the_run_kept_it() {
    // Final policy perfect in its training setting (1 at every trained TD), but its kept
    // five-timer policy in the test setting takes the soup at 4 everywhere (0 at TDs 2, 6, 8,
    // 10): it does not perform every task.
    let mut j = shifting_run("lstm125", 1, 5, |_, _| 4);
    j.episodes = [2, 4, 6, 8, 10]
        .into_iter()
        .map(|td| mt_ep(td, 1.0, td as i32))
        .collect();
    let rows = multitimer_claims(&analyse_multitimer(&[j.clone()]));
    let setting = "multi-timer exact, TDs 2, 4, 6, 8, 10";
    assert_eq!(
        find(&rows, "multitimer_none_all", setting, "").verdict,
        "holds"
    );
    // Without kept level policies the final policy decides: every TD at 1 → against it.
    j.levels.clear();
    let rows = multitimer_claims(&analyse_multitimer(&[j]));
    assert_eq!(
        find(&rows, "multitimer_none_all", setting, "").verdict,
        "contradicted"
    );
}
