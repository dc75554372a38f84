//! A multi-timer curriculum run's per-level policies evaluated as the paper's notebooks do:
//! each level's policy on the TDs trained at that level, from every start cell, then (past
//! the warm-up) on every untrained TD from 1 to one past the level's longest.

use chronocooked_analysis::collect::{LEVELS_CSV, read_level_episodes};
use chronocooked_pipeline::stages::levels::evaluate_levels;
use chronocooked_training::{Check, Silent, resolve, run_training};
use std::collections::BTreeMap;

#[test]
fn every_kept_level_is_evaluated_on_its_own_tds_then_the_untrained_ones_from_every_start_cell() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-levels-eval-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cfg = resolve(
        "MultiTimer-v0",
        "lstm8".parse().unwrap(),
        "reference",
        5,
        &[
            "total_steps=10000",
            "n_steps=250",
            "n_epochs=1",
            "env.tds=2,4,6",
            "env.mode=exact",
            "env.under_buffer=3",
            "env.reduced_reward=0",
            "env.num_timers=3",
            "curriculum_thresholds=0,0,0",
            "curriculum_window=10",
        ],
    )
    .unwrap();
    let run = dir.join("run");
    run_training(Some(cfg.check().unwrap()), &run, "test", &mut Silent).unwrap();
    let out = dir.join("eval");
    assert_eq!(evaluate_levels(&run, &out, 7).unwrap(), Some(4));
    let rows = read_level_episodes(&out.join(LEVELS_CSV)).unwrap();
    let mut per: BTreeMap<(usize, u32), usize> = BTreeMap::new();
    for r in &rows {
        *per.entry((r.level, r.td)).or_default() += 1;
        // Categorical test setting: full reward only inside [TD − 2, TD]; else 0.1 for a
        // delivered soup (the warm-up: only at TD exactly, nothing earlier is takeable).
        let hit = r.oven_off_time >= 0
            && r.oven_off_time <= r.td as i32
            && r.oven_off_time >= r.td as i32 - if r.level == 0 { 0 } else { 2 };
        assert_eq!(r.success, hit && r.reward == 1.0, "{r:?}");
        assert!([0.0, 0.1, 1.0].contains(&r.reward), "{r:?}");
    }
    let expected: BTreeMap<(usize, u32), usize> = [
        ((0, 2), 12),
        ((1, 2), 12),
        ((2, 2), 12),
        ((2, 4), 12),
        ((3, 2), 12),
        ((3, 4), 12),
        ((3, 6), 12),
        // Untrained: level 1 (TD 2) on 1 and 3; level 2 (2, 4) on 1, 3, 5; level 3 (2, 4,
        // 6) on 1, 3, 5, 7.
        ((1, 1), 12),
        ((1, 3), 12),
        ((2, 1), 12),
        ((2, 3), 12),
        ((2, 5), 12),
        ((3, 1), 12),
        ((3, 3), 12),
        ((3, 5), 12),
        ((3, 7), 12),
    ]
    .into_iter()
    .collect();
    assert_eq!(per, expected);
    // Within a level the trained TDs come first (their episodes do not depend on the
    // untrained ones): every trained row precedes every untrained row.
    let trained = [2u32, 4, 6];
    for level in 1..=3 {
        let tds: Vec<u32> = rows
            .iter()
            .filter(|r| r.level == level)
            .map(|r| r.td)
            .collect();
        let first_ood = tds
            .iter()
            .position(|t| !trained[..level].contains(t))
            .unwrap();
        assert!(
            tds[first_ood..]
                .iter()
                .all(|t| !trained[..level].contains(t)),
            "{tds:?}"
        );
        assert_eq!(first_ood, 12 * level, "{tds:?}");
    }
    // The rerun is the same (greedy policies, seeded episodes).
    let again = dir.join("eval2");
    evaluate_levels(&run, &again, 7).unwrap();
    assert_eq!(read_level_episodes(&again.join(LEVELS_CSV)).unwrap(), rows);
    // A stray level file (one the learning curve never reached) is an error naming the
    // folder, not a silent extra row.
    let stray = run.join("levels").join("level-5.bpk");
    std::fs::copy(run.join("levels").join("level-0.bpk"), &stray).unwrap();
    let e = evaluate_levels(&run, &dir.join("eval-stray"), 7)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("levels") && e.contains("[0, 1, 2, 3, 5]"), "{e}");
    std::fs::remove_file(&stray).unwrap();
    // A run without per-level policies has nothing to evaluate.
    std::fs::remove_dir_all(run.join("levels")).unwrap();
    assert_eq!(evaluate_levels(&run, &dir.join("eval3"), 7).unwrap(), None);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The growing curricula of the extensions: each level's policy plays its own level's task
/// (multi-anchor: 2, 3, 4 counters of the anchors 3, 10, 20, 25; multi-oven: 1, 2 ovens)
/// with that task's reference protocol — every probe 1 … largest active anchor + 4 (multi-
/// anchor), or 1 … L + 4 on each oven and the one-oven baseline (multi-oven) — from every
/// start cell. Thresholds 0 move the run up a level as soon as the window has filled.
#[test]
fn each_growth_level_plays_its_own_task_with_its_protocol() {
    use chronocooked_analysis::ConditionKind;
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-growth-levels-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for (task, sets, levels, kind) in [
        (
            "MultiAnchor-v0",
            vec!["env.anchors=3,10,20,25", "curriculum_thresholds=0,0"],
            3,
            ConditionKind::MultiAnchor,
        ),
        (
            "MultiOven-v0",
            vec![
                "env.ovens=2",
                "env.short=3",
                "env.long=9",
                "curriculum_thresholds=0",
            ],
            2,
            ConditionKind::MultiOven,
        ),
    ] {
        let mut all = vec![
            "total_steps=6000",
            "n_steps=250",
            "n_epochs=1",
            "curriculum_window=10",
        ];
        all.extend(&sets);
        let cfg = resolve(task, "lstm8".parse().unwrap(), "reference", 3, &all).unwrap();
        let run = dir.join(task).join("run");
        run_training(Some(cfg.check().unwrap()), &run, "test", &mut Silent).unwrap();
        let out = dir.join(task).join("eval");
        assert_eq!(
            evaluate_levels(&run, &out, 7).unwrap(),
            Some(levels),
            "{task}"
        );
        let rows = read_level_episodes(&out.join(LEVELS_CSV)).unwrap();
        for level in 0..levels {
            let tds: std::collections::BTreeSet<u32> = rows
                .iter()
                .filter(|r| r.level == level)
                .map(|r| r.td)
                .collect();
            let longest = match task {
                "MultiAnchor-v0" => [10, 20, 25][level],
                _ => 9,
            };
            assert_eq!(tds, (1..=longest + 4).collect(), "{task} level {level}");
        }
        // Multi-oven: the one-oven level has no second oven to probe; the two-oven level
        // probes both ovens and the one-oven baseline, so it plays more episodes.
        let count = |level| rows.iter().filter(|r| r.level == level).count();
        if task == "MultiOven-v0" {
            assert!(count(1) > count(0), "{} vs {}", count(1), count(0));
        }
        assert!(rows.iter().all(|r| r.kind.is_some()));
        assert!(rows.iter().any(|r| r.kind == Some(kind)), "{task}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
