//! The curricula that edit the task the envs play, read back from the envs: the
//! uncertainty task's never-ready ramp and the multi-timer warm-up level. Both edit the typed
//! task (`VecEnv::set_config`); the values are worked out by hand from the presets' rules.

use chronocooked_env::{RewardMode, TaskConfig, TaskParams};
use chronocooked_training::{Check, Trainer, resolve};

/// A reference-preset run of `model` on `task` with 4 envs × 250 steps = 1,000 env steps per
/// update, `total_steps` in all, and `sets`.
fn trainer(task: &str, model: &str, total_steps: u64, sets: &[&str]) -> Trainer {
    let mut all: Vec<String> = vec![
        format!("total_steps={total_steps}"),
        "n_envs=4".into(),
        "n_steps=250".into(),
        "n_epochs=1".into(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    let cfg = resolve(task, model.parse().unwrap(), "reference", 5, &all).unwrap();
    Trainer::new(cfg.check().unwrap()).unwrap()
}

fn never_ready_prob(task: &TaskConfig) -> f32 {
    match &task.params {
        TaskParams::Uncertainty {
            never_ready_prob, ..
        } => *never_ready_prob,
        other => panic!("not an uncertainty task: {other:?}"),
    }
}

/// The multi-timer reward rules: (mode, reduced reward, under buffer, over buffer).
fn timer_rules(task: &TaskConfig) -> (RewardMode, f32, u32, u32) {
    match &task.params {
        TaskParams::MultiTimer {
            mode,
            reduced_reward,
            under_buffer,
            over_buffer,
            ..
        } => (*mode, *reduced_reward, *under_buffer, *over_buffer),
        other => panic!("not a multi-timer task: {other:?}"),
    }
}

/// The reference ramp (0 → 0.2 over the first half of the budget, quantised to 0.005) over
/// 8,000 steps reaches 0.2 at step 4,000. Update `k` (from 0) applies the ramp at step
/// `1,000 k` before its rollout: 0, 0.05, 0.1, 0.15, then 0.2 to the end.
#[test]
fn the_never_ready_ramp_edits_the_task_the_envs_play() {
    let mut t = trainer("Uncertainty-v0", "lstm8", 8000, &[]);
    let hand = [0.0, 0.05, 0.1, 0.15, 0.2, 0.2, 0.2, 0.2];
    let mut k = 0;
    while !t.finished() {
        assert_eq!(t.state().steps, 1000 * k as u64, "1,000 steps per update");
        t.update().unwrap();
        let p = never_ready_prob(t.task());
        assert!(
            (p - hand[k]).abs() < 1e-7,
            "update {k}: {p}, by hand {}",
            hand[k]
        );
        assert_eq!(
            p,
            t.state().never_ready_prob as f32,
            "the state records the same value"
        );
        k += 1;
    }
    assert_eq!(k, hand.len(), "every update of the budget checked");
}

/// The paper's warm-up level plays the lower-bounded rules with reduced reward 0.1 and no
/// buffers; leaving it restores the configured rules exactly (here other than the defaults,
/// so a restore of the defaults would fail). Thresholds of 0 over one episode let the level
/// be left at the first check with an episode since the change (multi-timer returns are not
/// negative).
#[test]
fn the_multi_timer_warm_up_switches_the_rules_and_restores_the_configured_ones() {
    let configured = (RewardMode::Exact, 0.3, 1, 2);
    let mut t = trainer(
        "MultiTimer-v0",
        "lstm8",
        20_000,
        &[
            "env.mode=exact",
            "env.reduced_reward=0.3",
            "env.under_buffer=1",
            "env.over_buffer=2",
            "curriculum_thresholds=0",
            "curriculum_window=1",
        ],
    );
    assert_eq!(t.state().curriculum_level, 0);
    assert_eq!(
        timer_rules(t.task()),
        (RewardMode::LowerBounded, 0.1, 0, 0),
        "the warm-up rules at the start"
    );
    while !t.finished() && t.state().curriculum_level == 0 {
        t.update().unwrap();
        if t.state().curriculum_level == 0 {
            assert_eq!(timer_rules(t.task()), (RewardMode::LowerBounded, 0.1, 0, 0));
        }
    }
    assert!(
        t.state().curriculum_level >= 1,
        "the warm-up level was left"
    );
    assert_eq!(
        timer_rules(t.task()),
        configured,
        "the configured rules restored"
    );
}

/// The never-ready ramp and the multi-timer levels are refused on a task they cannot edit,
/// naming the curriculum and the task (they would otherwise train without their curriculum).
#[test]
fn the_ramp_and_the_timer_levels_are_refused_on_other_tasks() {
    let refused = |task: &str, curriculum: &str| {
        resolve(
            task,
            "lstm8".parse().unwrap(),
            "reference",
            5,
            &[format!("curriculum={curriculum}")],
        )
        .expect_err("refused")
        .to_string()
    };
    for (task, curriculum, missing) in [
        ("FixedInterval-v0", "uncertainty", "no never-ready episodes"),
        ("MultiTimer-v0", "uncertainty", "no never-ready episodes"),
        ("FixedInterval-v0", "multi_timer", "no timers to add"),
        ("Uncertainty-v0", "multi_timer", "no timers to add"),
    ] {
        let err = refused(task, curriculum);
        assert!(
            err.contains("curriculum") && err.contains(task) && err.contains(missing),
            "{task} with curriculum={curriculum}: {err}"
        );
    }
    for (task, curriculum) in [
        ("Uncertainty-v0", "uncertainty"),
        ("MultiTimer-v0", "multi_timer"),
    ] {
        let cfg = resolve(
            task,
            "lstm8".parse().unwrap(),
            "reference",
            5,
            &[format!("curriculum={curriculum}")],
        );
        assert!(cfg.is_ok(), "{task} with curriculum={curriculum}: {cfg:?}");
    }
}
