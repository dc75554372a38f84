//! The reproduction task (Ready-Set-Go in the kitchen): the cue schedule and the reward
//! worked out by hand, the oracle on every interval of every prior and gain, the draws, and
//! the errors for bad values.

use chronocooked_env::{Action, ChronoEnv, EnvError, Events, Oracle, ResetOptions, make_config};

/// Reward by hand: `max(0, 1 − |tp − g·ts| / (tol·g·ts + c))`.
fn reward(tp: f64, ts: f64, g: f64, tol: f64, c: f64) -> f64 {
    (1.0 - (tp - g * ts).abs() / (tol * g * ts + c)).max(0.0)
}

/// Plays: wait at the oven (start next to it), take the soup `tp` steps after Set, deliver.
/// Returns (reward, steps of the Ready and Set cues seen in the observation).
fn produce(env: &mut ChronoEnv, ts: u32, tp: u32, seed: u64) -> (f32, Vec<u32>, Vec<u32>) {
    let options = ResetOptions {
        start: Some((2, 1)),
        td: Some(ts),
        ..ResetOptions::default()
    };
    let info = env.reset(Some(seed), &options).unwrap();
    assert_eq!(info.td, ts);
    let oven = env.layout().index(2, 0) * 6 + 4;
    let (mut cues, mut flashes) = (Vec::new(), Vec::new());
    let mut set_step = None;
    let mut total = 0.0;
    let mut step = 0u32;
    // Wait for Set.
    while set_step.is_none() {
        let t = env.step(Action::Wait).unwrap();
        step += 1;
        if t.info.events.has(Events::CUE) {
            cues.push(step);
        }
        if env.obs_codes()[oven] == 2 {
            flashes.push(step);
        }
        if cues.len() == 2 {
            set_step = Some(step);
        }
    }
    // Between the Set step and the response the oven shows "on".
    for _ in 1..tp {
        let t = env.step(Action::Wait).unwrap();
        assert_eq!(env.obs_codes()[oven], 1);
        if t.done() {
            return (0.0, cues, flashes);
        }
    }
    let t = env.step(Action::Interact).unwrap();
    assert!(
        t.info.events.has(Events::PICKUP),
        "the soup is taken after Set"
    );
    assert_eq!(
        t.info.oven_off_time, tp as i32,
        "tp = steps from Set to the response"
    );
    // Deliver from (2,1): up, up, right → (0,1), interact faces the counter at (0,2).
    for a in [Action::Up, Action::Up, Action::Interact] {
        let t = env.step(a).unwrap();
        total += t.reward;
        if a == Action::Interact {
            assert!(t.terminated);
        }
    }
    (total, cues, flashes)
}

#[test]
fn cues_follow_the_foreperiod_and_the_reward_is_the_linear_window() {
    let mut env = ChronoEnv::from_id(
        "Reproduction-v0",
        &[
            "priors=9-15",
            "foreperiod_min=3",
            "foreperiod_max=3",
            "tolerance=0.25",
            "tolerance_steps=2",
        ],
    )
    .unwrap();
    for ts in [9u32, 12, 15] {
        for tp in [ts - 3, ts - 1, ts, ts + 2, ts + 4] {
            let (r, cues, flashes) = produce(&mut env, ts, tp, 1);
            assert_eq!(
                cues,
                vec![3, 3 + ts],
                "Ready at the foreperiod, Set ts later"
            );
            assert_eq!(flashes, cues, "each cue flashes channel 4 = 2 for one step");
            let want = reward(f64::from(tp), f64::from(ts), 1.0, 0.25, 2.0);
            assert!(
                (f64::from(r) - want).abs() < 1e-6,
                "ts {ts} tp {tp}: {r} vs {want}"
            );
        }
    }
}

#[test]
fn a_response_before_set_does_nothing_and_a_late_one_is_delivered_unpaid() {
    let mut env = ChronoEnv::from_id(
        "Reproduction-v0",
        &["priors=10-12", "foreperiod_min=2", "foreperiod_max=2"],
    )
    .unwrap();
    let options = ResetOptions {
        start: Some((2, 1)),
        td: Some(10),
        ..ResetOptions::default()
    };
    env.reset(Some(3), &options).unwrap();
    for _ in 0..5 {
        let t = env.step(Action::Interact).unwrap();
        assert!(t.info.events.has(Events::NO_EFFECT) && !t.info.events.has(Events::PICKUP));
    }
    // Set at the end of step 12; window 0.2·10 + 1 = 3 steps, so tp = 13 pays nothing. The
    // episode waits for the response (no production is cut off): respond on step 33, tp = 21.
    for _ in 5..32 {
        let t = env.step(Action::Wait).unwrap();
        assert!(!t.done(), "a late production is not cut off");
    }
    let t = env.step(Action::Interact).unwrap();
    assert_eq!(
        t.info.oven_off_time,
        33 - 12,
        "tp = response step − Set step"
    );
    let mut reward = 0.0;
    for a in [Action::Up, Action::Up, Action::Interact] {
        let t = env.step(a).unwrap();
        reward += t.reward;
        if a == Action::Interact {
            assert!(t.terminated && !t.info.events.has(Events::IN_WINDOW));
        }
    }
    assert_eq!(reward, 0.0);
}

#[test]
fn the_oracle_takes_the_best_reward_for_every_interval_prior_gain_and_start() {
    let mut env = ChronoEnv::from_id(
        "Reproduction-v0",
        &["priors=short,intermediate,long", "gains=1,1.5"],
    )
    .unwrap();
    let oracle = Oracle::new(&env);
    let starts: Vec<(usize, usize)> = env.layout().free_coords();
    let priors = [(8u32, 14u32), (11, 17), (14, 20)];
    for (p, &(lo, hi)) in priors.iter().enumerate() {
        for (g, gain) in [1.0f64, 1.5].iter().enumerate() {
            for ts in lo..=hi {
                for (k, &start) in starts.iter().enumerate() {
                    let options = ResetOptions {
                        start: Some(start),
                        td: Some(ts),
                        prior: Some(p as u8),
                        gain: Some(g as u8),
                        ..ResetOptions::default()
                    };
                    env.reset(Some(k as u64), &options).unwrap();
                    let mut total = 0.0;
                    while !env.is_done() {
                        total += f64::from(env.step(oracle.act(&env.state())).unwrap().reward);
                    }
                    let target = gain * f64::from(ts);
                    let best = reward(target.round(), f64::from(ts), *gain, 0.2, 1.0);
                    assert!(
                        (total - best).abs() < 1e-5,
                        "prior {p} g {gain} ts {ts} start {start:?}: {total} vs {best}"
                    );
                }
            }
        }
    }
}

#[test]
fn draws_cover_the_prior_and_the_cue_names_the_context() {
    let mut env =
        ChronoEnv::from_id("Reproduction-v0", &["priors=short,long", "gains=1,1.5"]).unwrap();
    let counter = env.layout().index(0, 2) * 6 + 4;
    let mut seen = std::collections::BTreeMap::new();
    for seed in 0..400 {
        let info = env.reset(Some(seed), &ResetOptions::default()).unwrap();
        let s = env.state().reproduction.unwrap();
        let (lo, hi) = if s.prior == 0 { (8, 14) } else { (14, 20) };
        assert!((lo..=hi).contains(&info.td));
        assert!((2..=6).contains(&s.foreperiod));
        // Cue = 1 + prior·(gains) + gain.
        assert_eq!(env.obs_codes()[counter], 1 + 2 * s.prior + s.gain);
        *seen.entry((s.prior, s.gain, info.td)).or_insert(0) += 1;
    }
    // Every (prior, gain, ts) drawn: 2 × 2 × 7.
    assert_eq!(seen.len(), 28);
    // One-hot: a channel per cued context after the 13 base channels.
    assert_eq!(env.onehot_encoder().shape()[0], 13 + 4);
    let blocked =
        ChronoEnv::from_id("Reproduction-v0", &["priors=short", "prior_cue=false"]).unwrap();
    assert_eq!(blocked.onehot_encoder().shape()[0], 13, "nothing to cue");
}

#[test]
fn bad_values_name_the_key_and_the_allowed_values() {
    let err = |sets: &[&str]| match make_config("Reproduction-v0", sets).unwrap_err() {
        EnvError::InvalidParam { field, allowed, .. } => (field, allowed),
        other => panic!("{sets:?}: {other}"),
    };
    let (f, a) = err(&["priors=20-10"]);
    assert_eq!(f, "priors");
    assert!(a.contains("LO-HI"), "{a}");
    let (f, _) = err(&["priors=medium"]);
    assert_eq!(f, "priors");
    let (f, a) = err(&["priors=short,long,intermediate,8-9"]);
    assert_eq!(f, "priors");
    assert!(a.contains("1 to 3"), "{a}");
    let (f, a) = err(&["gains=4"]);
    assert_eq!(f, "gains");
    assert!(a.contains("[0.5, 3]"), "{a}");
    let (f, _) = err(&["gains=1,1"]);
    assert_eq!(f, "gains");
    let (f, _) = err(&["foreperiod_min=5", "foreperiod_max=3"]);
    assert_eq!(f, "foreperiod_max");
    let (f, a) = err(&["max_timesteps=30"]);
    assert_eq!(f, "max_timesteps");
    assert!(a.contains("at least"), "{a}");
    let mut env = ChronoEnv::from_id("Reproduction-v0", &[] as &[&str]).unwrap();
    for (options, field) in [
        (
            ResetOptions {
                prior: Some(2),
                ..ResetOptions::default()
            },
            "prior",
        ),
        (
            ResetOptions {
                gain: Some(1),
                ..ResetOptions::default()
            },
            "gain",
        ),
    ] {
        match env.reset(Some(0), &options).unwrap_err() {
            EnvError::InvalidResetOption { field: f, .. } => assert_eq!(f, field),
            other => panic!("{other}"),
        }
    }
    let mut fi = ChronoEnv::from_id("FixedInterval-v0", &[] as &[&str]).unwrap();
    let e = fi
        .reset(
            Some(0),
            &ResetOptions {
                prior: Some(0),
                ..ResetOptions::default()
            },
        )
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`prior` is an option of Reproduction-v0")
            && e.contains("FixedInterval-v0 (its options: start, td)"),
        "{e}"
    );
}
