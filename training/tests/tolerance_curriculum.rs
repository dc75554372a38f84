//! The reproduction task's tolerance curriculum: the reward window narrows level by level
//! from the curriculum's first window to the task's own, gated on in-window deliveries,
//! steps back when they fall below the fallback, resumes at its level and is refused where
//! it cannot apply.

use chronocooked_env::{TaskConfig, TaskParams};
use chronocooked_training::{Check, Trainer, resolve};

fn cfg(sets: &[&str], steps: u64) -> chronocooked_training::TrainConfig {
    let mut all: Vec<String> = vec![
        format!("total_steps={steps}"),
        "n_steps=250".into(),
        "n_epochs=1".into(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    resolve(
        "Reproduction-v0",
        "lstm8".parse().unwrap(),
        "reference",
        7,
        &all,
    )
    .unwrap()
}

fn window(task: &TaskConfig) -> (f32, f32) {
    match &task.params {
        TaskParams::Reproduction {
            tolerance,
            tolerance_steps,
            ..
        } => (*tolerance, *tolerance_steps),
        other => panic!("not a reproduction task: {other:?}"),
    }
}

fn close(a: (f32, f32), b: (f32, f32)) -> bool {
    (a.0 - b.0).abs() < 1e-6 && (a.1 - b.1).abs() < 1e-6
}

/// Windows of levels 0..=3 from (0.6, 4) to (0.3, 1), worked out by hand: steps of
/// (0.1, 1) per level.
const HAND: [(f32, f32); 4] = [(0.6, 4.0), (0.5, 3.0), (0.4, 2.0), (0.3, 1.0)];

const NARROWING: [&str; 7] = [
    "curriculum=tolerance",
    "curriculum_tolerance_start=0.6",
    "curriculum_tolerance_steps_start=4",
    "curriculum_levels=4",
    "curriculum_window=3",
    "env.tolerance=0.3",
    "env.tolerance_steps=1",
];

#[test]
fn the_window_narrows_level_by_level_to_the_task_s_own_and_stays_there() {
    let mut sets = NARROWING.to_vec();
    sets.extend(["curriculum_thresholds=0", "curriculum_fallback=0"]);
    let mut t = Trainer::new(cfg(&sets, 6000).check().unwrap()).unwrap();
    assert!(close(window(t.task()), HAND[0]), "{:?}", window(t.task()));
    let mut seen = vec![0];
    while !t.finished() {
        let before = t.state().curriculum_level;
        t.update().unwrap();
        let level = t.state().curriculum_level;
        assert!(
            level == before || level == before + 1,
            "one level at a time"
        );
        assert!(
            t.take_left_level().is_none(),
            "no per-level policies: every level plays the same task"
        );
        assert!(
            close(window(t.task()), HAND[level.min(3)]),
            "level {level}: {:?}",
            window(t.task())
        );
        if seen.last() != Some(&level) {
            seen.push(level);
        }
    }
    assert_eq!(
        seen,
        [0, 1, 2, 3],
        "every level in order, none past the task's"
    );
}

#[test]
fn a_level_is_kept_until_its_share_of_in_window_deliveries_is_reached() {
    let mut sets = NARROWING.to_vec();
    // An untrained policy delivers inside the window on far fewer than all of 3 episodes
    // in a row at every check of a 4,000-step run.
    sets.push("curriculum_thresholds=1");
    let mut t = Trainer::new(cfg(&sets, 4000).check().unwrap()).unwrap();
    while !t.finished() {
        t.update().unwrap();
        let recent = &t.state().recent;
        if t.state().curriculum_level > 0 {
            let last: Vec<bool> = recent.iter().rev().map(|e| e.success).collect();
            panic!("left level 0 with a threshold of 1: recent successes {last:?}");
        }
    }
    assert!(close(window(t.task()), HAND[0]));
    assert!(
        t.state().episodes >= 3,
        "episodes ended: the gate was checked"
    );
}

/// Every check against the rule recomputed from the episodes it saw: with a window of 4
/// episodes, threshold 0.5 and fallback 0.5, a due check (4 episodes since the last change)
/// raises the level when at least 2 of the last 4 delivered inside the window and lowers it
/// when fewer did, except at the ends; a check not yet due keeps the level.
#[test]
fn each_check_follows_the_share_of_the_last_window_of_episodes() {
    let sets = [
        "curriculum=tolerance",
        "curriculum_tolerance_start=0.6",
        "curriculum_tolerance_steps_start=4",
        "curriculum_levels=4",
        "curriculum_window=4",
        "curriculum_thresholds=0.5",
        "curriculum_fallback=0.5",
        "env.tolerance=0.3",
        "env.tolerance_steps=1",
    ];
    let mut t = Trainer::new(cfg(&sets, 20000).check().unwrap()).unwrap();
    let (mut ups, mut downs, mut due) = (0, 0, 0);
    while !t.finished() {
        let level = t.state().curriculum_level;
        let (since, episodes) = (t.state().since_change, t.state().episodes);
        t.update().unwrap();
        let s = t.state();
        let seen = since + (s.episodes - episodes) as usize;
        let hits = s.recent.iter().rev().take(4).filter(|e| e.success).count();
        let expected = if seen < 4 {
            level
        } else if hits >= 2 && level < 3 {
            level + 1
        } else if hits < 2 && level > 0 {
            level - 1
        } else {
            level
        };
        due += usize::from(seen >= 4);
        assert_eq!(
            s.curriculum_level, expected,
            "level {level}, {seen} episodes since the last change, {hits} of the last 4 in the window"
        );
        ups += usize::from(expected > level);
        downs += usize::from(expected < level);
    }
    assert!(
        due > 10 && ups > 0 && downs > 0,
        "{due} checks, {ups} up, {downs} down"
    );
}

/// With every level passed at once (threshold 0) and a fallback no untrained policy meets
/// (every one of the last 3 episodes in the window), the last level steps back: the level
/// sequence climbs to 3, then alternates, and every step back follows a window of
/// episodes with a delivery outside the window.
#[test]
fn a_level_steps_back_when_its_share_falls_below_the_fallback() {
    let mut sets = NARROWING.to_vec();
    sets.extend(["curriculum_thresholds=0", "curriculum_fallback=1"]);
    let mut t = Trainer::new(cfg(&sets, 8000).check().unwrap()).unwrap();
    let (mut climbed, mut backs) = (false, 0);
    while !t.finished() {
        let before = t.state().curriculum_level;
        t.update().unwrap();
        let level = t.state().curriculum_level;
        assert!(close(window(t.task()), HAND[level]), "level {level}");
        climbed |= level == 3;
        if level + 1 == before {
            backs += 1;
            assert!(
                climbed && before == 3,
                "only the last level fails threshold 0"
            );
            let last3: Vec<bool> = t
                .state()
                .recent
                .iter()
                .rev()
                .take(3)
                .map(|e| e.success)
                .collect();
            assert!(last3.contains(&false), "stepped back after {last3:?}");
        } else {
            assert!(
                level == before || level == before + 1,
                "{before} -> {level}"
            );
        }
    }
    assert!(
        climbed && backs > 0,
        "climbed {climbed}, stepped back {backs} times"
    );
}

#[test]
fn a_resumed_run_plays_its_level_s_window() {
    let mut sets = NARROWING.to_vec();
    sets.extend(["curriculum_thresholds=0", "curriculum_fallback=0"]);
    let c = cfg(&sets, 3000);
    let mut t = Trainer::new(c.clone().check().unwrap()).unwrap();
    while t.state().curriculum_level < 2 {
        t.update().unwrap();
    }
    let state = t.state().clone();
    let level = state.curriculum_level;
    let resumed = Trainer::restore(c.clone().check().unwrap(), state.clone()).unwrap();
    assert!(close(window(resumed.task()), HAND[level]));
    let mut bad = state;
    bad.curriculum_level = 4;
    let err = Trainer::restore(c.check().unwrap(), bad)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("curriculum_level") && err.contains("0..=3"),
        "{err}"
    );
}

#[test]
fn the_curriculum_is_refused_on_other_tasks_and_with_a_narrower_first_window() {
    let refused = |task: &str, sets: &[&str]| {
        resolve(task, "lstm8".parse().unwrap(), "reference", 7, sets)
            .expect_err("refused")
            .to_string()
    };
    let err = refused("Bisection-v0", &["curriculum=tolerance"]);
    assert!(
        err.contains("curriculum") && err.contains("Bisection-v0"),
        "{err}"
    );
    let err = refused(
        "Reproduction-v0",
        &[
            "curriculum=tolerance",
            "curriculum_tolerance_start=0.1",
            "curriculum_tolerance_steps_start=3",
        ],
    );
    assert!(
        err.contains("curriculum_tolerance_start") && err.contains("tolerance >= 0.2,"),
        "{err}"
    );
    // A first window equal to the task's own is accepted (compared as the task stores it).
    resolve(
        "Reproduction-v0",
        "lstm8".parse().unwrap(),
        "reference",
        7,
        &[
            "curriculum=tolerance",
            "env.tolerance=0.3",
            "curriculum_tolerance_start=0.3",
        ],
    )
    .expect("a start window equal to the task's");
    // The first level's window is checked as a task: one wider than the time limit allows.
    let err = refused(
        "Reproduction-v0",
        &[
            "curriculum=tolerance",
            "curriculum_tolerance_steps_start=100",
            "env.max_timesteps=60",
        ],
    );
    assert!(err.contains("curriculum_tolerance_start"), "{err}");
    // The curriculum's window cannot exceed the episodes kept for its checks.
    let err = refused(
        "Reproduction-v0",
        &["curriculum=tolerance", "stats_window=50"],
    );
    assert!(
        err.contains("curriculum_window") && err.contains("stats_window (50)"),
        "{err}"
    );
}
