//! A multi-timer curriculum run's per-level policies evaluated as the paper's notebooks do:
//! each level's policy on the TDs trained at that level, from every start cell, then (past
//! the warm-up) on every untrained TD from 1 to one past the level's longest.

use chronocooked_analysis::paper::collect::{LEVELS_CSV, read_level_episodes};
use chronocooked_pipeline::stages::levels::evaluate_levels;
use chronocooked_training::{Silent, resolve, run_training};
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
    run_training(Some(cfg), &run, "test", &mut Silent).unwrap();
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
