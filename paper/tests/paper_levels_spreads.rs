//! The paper's analyses of the grid's later parts on constructed data with known answers:
//! per-level multi-timer evaluation and its comparison, the exact timer, spreads and new-run
//! ranges, and z verdicts where the old rule has none.

use crate::common;

use chronocooked_analysis::collect::{CompactJob, EpisodeRow};
use common::{curve_at, ep, job, mt_ep};

fn level_ep(level: usize, td: u32, reward: f32) -> chronocooked_analysis::collect::LevelEpisode {
    chronocooked_analysis::collect::LevelEpisode {
        level,
        td,
        row: 0,
        col: 0,
        steps: 20,
        reward,
        success: reward == 1.0,
        oven_off_time: if reward > 0.0 { td as i32 } else { -1 },
        kind: None,
    }
}

#[test]
fn each_levels_policy_is_scored_and_compared_on_its_own_td_list() {
    use chronocooked_paper::compare::compare;
    use chronocooked_paper::multitimer::analyse_multitimer;
    let cat = ["tds=2,4,6,8,10", "mode=exact", "under_buffer=3"];
    // Four categorical LSTM125 runs on the notebook's list, each with 20 level-2 episodes
    // (TDs 2 and 4) of which 10 + hits earn 1 and the rest 0.5 (means 0.825, 0.85, 0.875,
    // 0.9), and one run on the code's list 3 … 15 whose level-2 policy scores 0.
    let mut jobs = Vec::new();
    for (seed, hits) in [(1u64, 3usize), (2, 4), (3, 5), (4, 6)] {
        // Plus one level-0 episode earning 1.
        let mut levels = vec![level_ep(0, 2, 1.0)];
        for k in 0..20 {
            let td = if k % 2 == 0 { 2 } else { 4 };
            levels.push(level_ep(2, td, if k < 10 + hits { 1.0 } else { 0.5 }));
        }
        let mut j = job("MultiTimer-v0", "lstm125", seed, &cat, 20.0);
        j.level_steps = vec![0, 10, 20];
        jobs.push(CompactJob {
            job: j,
            episodes: vec![mt_ep(2, 1.0, 2)],
            curve: vec![curve_at(0, 0.5), curve_at(2, 0.9)],
            levels,
        });
    }
    let mut other = job(
        "MultiTimer-v0",
        "lstm125",
        9,
        &["mode=exact", "under_buffer=3"],
        20.0,
    );
    other.level_steps = vec![0, 10, 20];
    jobs.push(CompactJob {
        job: other,
        episodes: vec![mt_ep(3, 1.0, 3)],
        curve: vec![curve_at(2, 0.9)],
        levels: vec![level_ep(2, 3, 0.0)],
    });
    let mt = analyse_multitimer(&jobs);
    assert_eq!(mt.len(), 2, "the two TD lists are separate cells");
    let c = mt.iter().find(|c| c.tds == [2, 4, 6, 8, 10]).unwrap();
    // Level 2 per run: (10 + hits)·1 + (10 − hits)·0.5 over 20 = 0.75 + 0.025·hits.
    let want = [0.825, 0.85, 0.875, 0.9];
    for (r, w) in c.runs.iter().zip(want) {
        assert!(
            (r.level_eval[2].unwrap() - w).abs() < 1e-9,
            "{:?}",
            r.level_eval
        );
        assert_eq!(r.level_eval[1], None);
        assert_eq!(r.level_eval[0], Some(1.0));
    }
    assert!((c.level_eval[2].mean - 0.8625).abs() < 1e-9);
    // The comparison uses the 2–10 cell only: notebook level 2 = mean of 0.85, 0.79, 0.82,
    // 0.82 = 0.82 with SD 0.0245 (by hand), against the lab's 0.8625 ± 0.0323 (4 runs).
    let rows = compare(&[], &[], &mt);
    let r = rows
        .iter()
        .find(|r| r.table == "multitimer_2_10_level_reward" && r.column == "categorical level 2")
        .unwrap();
    assert_eq!(r.source, "notebook");
    assert!((r.paper - 0.82).abs() < 1e-9 && (r.paper_sd - 0.024495).abs() < 1e-5);
    assert_eq!((r.n, r.paper_n), (4, 4));
    let se = (0.032275_f64.powi(2) / 4.0 + 0.024495_f64.powi(2) / 4.0).sqrt();
    assert!((r.z - (0.8625 - 0.82) / se).abs() < 1e-3, "z {}", r.z);
    // No level-3 policy was kept: that notebook number has no lab value.
    assert!(!rows.iter().any(|r| r.column == "categorical level 3"));
}

#[test]
fn the_exact_timer_scores_each_test_buffer_per_run() {
    use chronocooked_paper::multitimer::{analyse_exact_timer, analyse_multitimer};
    let buf = |td: u32, f: f64, reward: f32| EpisodeRow {
        factor: Some(f),
        reward,
        ..mt_ep(td, reward, td as i32)
    };
    let mk = |seed: u64, rewards: [[f32; 2]; 2]| {
        let mut kind_buffer = Vec::new();
        for (f, rs) in [0.0, 0.5].into_iter().zip(rewards) {
            for r in rs {
                let mut e = buf(4, f, r);
                e.kind = "buffer".parse().unwrap();
                kind_buffer.push(e);
            }
        }
        CompactJob {
            job: job(
                "MultiTimer-v0",
                "cnn-mlp",
                seed,
                &["tds=4", "num_timers=1"],
                20.0,
            ),
            episodes: kind_buffer,
            curve: vec![],
            levels: vec![],
        }
    };
    // Run 1: buffer 0 → 0.1, 0.1; buffer 50% → 1, 0.1. Run 2: 1, 0.1; 1, 1.
    let jobs = [
        mk(1, [[0.1, 0.1], [1.0, 0.1]]),
        mk(2, [[1.0, 0.1], [1.0, 1.0]]),
    ];
    assert!(
        analyse_multitimer(&jobs).is_empty(),
        "one TD is not a multi-timer cell"
    );
    let et = analyse_exact_timer(&jobs);
    assert_eq!(et.len(), 1);
    assert_eq!((et[0].td, et[0].runs), (4, 2));
    let (f0, s0) = &et[0].buffers[0];
    let (f1, s1) = &et[0].buffers[1];
    assert_eq!((*f0, *f1), (0.0, 0.5));
    // Per run means: 0.1 and 0.55 at buffer 0; 0.55 and 1.0 at 50%.
    assert!((s0.mean - 0.325).abs() < 1e-6 && (s1.mean - 0.775).abs() < 1e-6);
    assert!((s0.sd - 0.45 / 2f64.sqrt()).abs() < 1e-6);
}

#[test]
fn spreads_compare_the_first_four_seeds_with_every_run_by_hand() {
    use chronocooked_paper::spreads::spread_changes;
    let fi_run = |seed: u64, foc: i32| {
        common::lstm_fi_job(
            seed,
            4,
            vec![
                ep("fi", 4, (0, 0), Some(foc), 0),
                ep("fi", 4, (1, 1), Some(foc), 0),
            ],
        )
    };
    // Run means: seeds 1–4 → 4, 4, 5, 5; seeds 5, 6 → 2, 8.
    let mut jobs: Vec<CompactJob> = [(1, 4), (2, 4), (3, 5), (4, 5)]
        .into_iter()
        .map(|(s, f)| fi_run(s, f))
        .collect();
    // Only the first four seeds: nothing changed, no row.
    assert!(spread_changes(&jobs).is_empty());
    jobs.push(fi_run(5, 2));
    jobs.push(fi_run(6, 8));
    let rows = spread_changes(&jobs);
    let r = rows.iter().find(|r| r.statistic == "foc_mean").unwrap();
    assert_eq!((r.condition.as_str(), r.n_first, r.n_all), ("TD 4", 4, 6));
    assert!((r.mean_first - 4.5).abs() < 1e-9 && (r.sd_first - 0.577350).abs() < 1e-6);
    // Every run: mean 28/6, SD √(19.3333/5) = 1.96638.
    assert!((r.mean_all - 28.0 / 6.0).abs() < 1e-9 && (r.sd_all - 1.966384).abs() < 1e-6);
    // Each run's CV is 0 (its two FOCs are equal).
    let cv = rows.iter().find(|r| r.statistic == "foc_cv").unwrap();
    assert_eq!((cv.mean_first, cv.mean_all), (0.0, 0.0));
}

#[test]
fn a_new_runs_range_is_the_95_percent_prediction_interval() {
    use chronocooked_analysis::stats::Spread;
    use chronocooked_paper::spreads::prediction_interval;
    // Runs 4, 4, 5, 5: mean 4.5, SD 0.57735; t(0.975, 3) = 3.18245; half-width
    // 3.18245 · 0.57735 · √(1.25) = 2.05422.
    let (lo, hi) = prediction_interval(&Spread::of([4.0, 4.0, 5.0, 5.0]));
    assert!(
        (lo - 2.44578).abs() < 1e-4 && (hi - 6.55422).abs() < 1e-4,
        "{lo} {hi}"
    );
    assert!(prediction_interval(&Spread::of([4.0])).0.is_nan());
}

#[test]
fn a_row_the_old_rule_cannot_judge_has_no_z_verdict_either() {
    use chronocooked_paper::compare::compare;
    use chronocooked_paper::fi::analyse_fi;
    // LSTM125 at one TD only: its R² rows (mean vs TD, SD vs mean) need three TDs.
    let jobs: Vec<CompactJob> = (1..=4)
        .map(|seed| CompactJob {
            job: job("FixedInterval-v0", "lstm125", seed, &["td=4"], 20.0),
            episodes: vec![
                ep("fi", 4, (0, 0), Some(4), 0),
                ep("fi", 4, (1, 1), Some(3 + seed as i32 % 2), 0),
            ],
            curve: vec![],
            levels: vec![],
        })
        .collect();
    let rows = compare(&analyse_fi(&jobs), &[], &[]);
    let r2: Vec<_> = rows.iter().filter(|r| r.table.contains("r2")).collect();
    assert!(!r2.is_empty());
    for r in r2 {
        assert_eq!(
            (r.agree.as_str(), r.agree_z.as_str()),
            ("n/a", "n/a"),
            "{r:?}"
        );
    }
}
