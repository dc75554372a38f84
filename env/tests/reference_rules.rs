//! One test per step rule of the original implementation (docs/tasks.md), and the typed errors of every invalid input.

use Action::*;
use chronocooked_env::{
    Action, ChronoEnv, Counter, EnvError, Events, Layout, ResetOptions, Transition, make_config,
};

fn env(id: &str, sets: &[&str], start: (usize, usize), td: u32) -> ChronoEnv {
    let mut e = ChronoEnv::from_id(id, sets).unwrap();
    let opts = ResetOptions {
        start: Some(start),
        td: Some(td),
        never_ready: None,
        ..ResetOptions::default()
    };
    e.reset(Some(0), &opts).unwrap();
    e
}

fn run(e: &mut ChronoEnv, actions: &[Action]) -> Vec<Transition> {
    actions.iter().map(|&a| e.step(a).unwrap()).collect()
}

/// FI layout: from (1,0): up to (0,0), take onion, down to (1,0), onion in (step 4).
const FI_PUT: [Action; 4] = [Up, Interact, Down, Interact];

#[test]
fn action_codes_move_as_documented_and_blocked_moves_stay() {
    let mut e = env("FixedInterval-v0", &[], (1, 1), 4);
    let pos = |e: &ChronoEnv| e.state().agent;
    e.step(Down).unwrap();
    assert_eq!(pos(&e), (2, 1));
    e.step(Right).unwrap();
    assert_eq!(pos(&e), (2, 2));
    e.step(Up).unwrap();
    assert_eq!(pos(&e), (1, 2));
    e.step(Up).unwrap(); // blocked by the delivery counter
    assert_eq!(pos(&e), (1, 2));
    e.step(Left).unwrap();
    e.step(Left).unwrap();
    assert_eq!(pos(&e), (1, 0));
    e.step(Left).unwrap(); // edge
    assert_eq!(pos(&e), (1, 0));
    e.step(Wait).unwrap();
    assert_eq!(pos(&e), (1, 0));
    assert_eq!(
        Action::from_code(6),
        Err(EnvError::InvalidAction { action: 6 })
    );
    assert!(e.step_code(-1).is_err());
}

#[test]
fn earliest_pickup_is_exactly_td_steps_after_the_put_step() {
    for td in [1u32, 2, 5, 12] {
        let mut e = env("FixedInterval-v0", &[&format!("td={td}")], (1, 0), td);
        let put = run(&mut e, &FI_PUT);
        assert!(put[3].info.events.has(Events::ONION_IN));
        assert_eq!(
            put[3].info.oven_timer, 1,
            "timer is incremented on the put step"
        );
        let put_step = put[3].info.timestep;
        // Interact on every step: pickup first succeeds at step put_step + td.
        loop {
            let t = e.step(Interact).unwrap();
            assert!(t.info.events.has(Events::OVEN_CHECK));
            if t.info.events.has(Events::PICKUP) {
                assert_eq!(t.info.timestep, put_step + td, "td={td}");
                assert_eq!(t.info.oven_off_time, td as i32);
                assert_eq!(t.info.timer_at_action, td as i32);
                break;
            }
            assert!(t.info.timestep < put_step + td, "no pickup by TD (td={td})");
        }
        // Deliver: (1,0) -> (1,1) -> (1,2), interact.
        let t = run(&mut e, &[Right, Right, Interact]);
        assert_eq!(t[2].reward, 1.0);
        assert!(t[2].terminated && !t[2].truncated);
        assert_eq!(t[2].info.counter, Some(Counter::Main));
    }
}

#[test]
fn fi_oven_shows_only_on_and_off() {
    let mut e = env("FixedInterval-v0", &["td=3"], (1, 0), 3);
    run(&mut e, &FI_PUT);
    let oven = |e: &ChronoEnv| e.obs_codes()[(2 * 3) * 6 + 4];
    assert_eq!(oven(&e), 1);
    run(&mut e, &[Wait, Wait, Wait, Wait]);
    assert_eq!(oven(&e), 1, "no ready cue in FI");
    e.step(Interact).unwrap();
    assert_eq!(oven(&e), 0);
}

#[test]
fn bisection_ready_flag_timing_including_td_one() {
    // Bisection layout: from (2,1) the oven (3,1) is below; onion (0,1) is reached from (1,1).
    for td in [1u32, 2, 4, 12] {
        let mut e = env("Bisection-v0", &["short=4", "long=12"], (1, 1), td);
        run(&mut e, &[Interact, Down]);
        let put = e.step(Interact).unwrap();
        assert!(put.info.events.has(Events::ONION_IN));
        let oven = |e: &ChronoEnv| e.obs_codes()[(3 * 3 + 1) * 6 + 4];
        // Ready appears at the end of the step on which timer == TD.
        let mut t = put;
        while !t.info.events.has(Events::OVEN_READY) {
            assert_eq!(oven(&e), 1);
            let check = e.step(Interact).unwrap();
            assert!(
                !check.info.events.has(Events::PICKUP),
                "pickup before ready"
            );
            t = check;
        }
        assert_eq!(t.info.oven_timer, td as i32);
        assert_eq!(oven(&e), 2);
        let pick = e.step(Interact).unwrap();
        assert!(pick.info.events.has(Events::PICKUP));
        assert_eq!(pick.info.timestep, put.info.timestep + td);
    }
}

#[test]
fn bisection_counters_are_coded_4_and_8_and_the_wrong_counter_pays_zero() {
    let e = env("Bisection-v0", &[], (1, 1), 4);
    assert_eq!(e.obs_codes()[0], 4, "short counter at (0,0)");
    assert_eq!(e.obs_codes()[2 * 6], 8, "long counter at (0,2)");
    assert_eq!(e.obs_codes()[6], 3, "onion at (0,1)");
    assert_eq!(e.obs_codes()[(3 * 3 + 1) * 6], 5, "oven at (3,1)");
    for (td, counter_moves, expected, counter) in [
        (4, [Up, Left], 1.0, Counter::Short),
        (4, [Up, Right], 0.0, Counter::Long),
        (12, [Up, Right], 1.0, Counter::Long),
        (12, [Up, Left], 0.0, Counter::Short),
        (8, [Up, Left], 0.0, Counter::Short),
        (8, [Up, Right], 0.0, Counter::Long),
    ] {
        let mut e = env("Bisection-v0", &["short=4", "long=12"], (1, 1), td);
        run(&mut e, &[Interact, Down, Interact]);
        while !e.step(Interact).unwrap().info.events.has(Events::PICKUP) {}
        // From (2,1): up to (1,1), then to (1,0) or (1,2), then up is blocked; interact.
        let t = run(&mut e, &[counter_moves[0], counter_moves[1], Interact]);
        assert_eq!(t[2].reward, expected, "td={td} {counter:?}");
        assert!(t[2].terminated, "any delivery ends the episode");
        assert_eq!(t[2].info.counter, Some(counter));
    }
}

/// Puts the onion in (FI layout, start (1,0)), waits so that the pickup happens at
/// timer `k`, delivers; returns the delivery reward.
fn multi_reward(sets: &[&str], td: u32, k: u32) -> Option<f32> {
    let mut e = env("MultiTimer-v0", sets, (1, 0), td);
    run(&mut e, &FI_PUT);
    for _ in 1..k {
        e.step(Wait).unwrap();
    }
    let t = e.step(Interact).unwrap();
    if !t.info.events.has(Events::PICKUP) {
        return None;
    }
    assert_eq!(t.info.oven_off_time, k as i32);
    let d = run(&mut e, &[Right, Right, Interact]);
    Some(d[2].reward)
}

#[test]
fn multi_timer_window_edges_in_both_modes() {
    let exact = ["tds=9", "mode=exact", "under_buffer=2", "over_buffer=3"];
    assert_eq!(multi_reward(&exact, 9, 6), Some(0.1));
    assert_eq!(multi_reward(&exact, 9, 7), Some(1.0));
    assert_eq!(multi_reward(&exact, 9, 9), Some(1.0));
    assert_eq!(multi_reward(&exact, 9, 12), Some(1.0));
    assert_eq!(multi_reward(&exact, 9, 13), Some(0.1));
    assert_eq!(
        multi_reward(&exact, 9, 1),
        Some(0.1),
        "undercooked soup can be taken"
    );
    let lower = [
        "tds=9",
        "mode=lower_bounded",
        "under_buffer=2",
        "over_buffer=3",
    ];
    assert_eq!(multi_reward(&lower, 9, 8), None, "no pickup before TD");
    assert_eq!(multi_reward(&lower, 9, 9), Some(1.0));
    assert_eq!(multi_reward(&lower, 9, 12), Some(1.0));
    assert_eq!(multi_reward(&lower, 9, 13), Some(0.1));
    let zero = ["tds=4", "mode=exact", "reduced_reward=0.3"];
    assert_eq!(multi_reward(&zero, 4, 3), Some(0.3));
    assert_eq!(multi_reward(&zero, 4, 4), Some(1.0));
    assert_eq!(multi_reward(&zero, 4, 5), Some(0.3));
}

#[test]
fn multi_timer_oven_channel_holds_the_cue() {
    for (cue, td, expected) in [
        ("value", 9u32, 9u8),
        ("value", 40, 40),
        ("categorical", 9, 3),
    ] {
        let mut e = env(
            "MultiTimer-v0",
            &["tds=3,6,9", "num_timers=3", &format!("cue={cue}")],
            (1, 0),
            td,
        );
        run(&mut e, &FI_PUT);
        assert_eq!(e.obs_codes()[(2 * 3) * 6 + 4], expected, "{cue} td={td}");
    }
    // Draws come from the first num_timers TDs only.
    let mut e = ChronoEnv::from_id("MultiTimer-v0", &["tds=3,6,9", "num_timers=2"]).unwrap();
    let mut seen = std::collections::BTreeSet::new();
    for s in 0..200 {
        seen.insert(e.reset(Some(s), &ResetOptions::default()).unwrap().td);
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![3, 6]);
    e.set_num_timers(3).unwrap();
    assert!(e.set_num_timers(4).is_err());
    let all: std::collections::BTreeSet<u32> = (0..200)
        .map(|s| e.reset(Some(s), &ResetOptions::default()).unwrap().td)
        .collect();
    assert_eq!(all.len(), 3, "the TD set grows during training");
}

#[test]
fn reference_time_limit_stops_at_step_max_plus_one() {
    for reference in [false, true] {
        let mut sets = vec!["max_timesteps=5"];
        if reference {
            sets.push("reference_compat=true");
        }
        let mut e = env("FixedInterval-v0", &sets, (4, 2), 4);
        let t = run(&mut e, &[Wait; 6]);
        assert!(t[..5].iter().all(|t| !t.done()));
        assert_eq!(t[5].info.timestep, 6);
        assert_eq!((t[5].terminated, t[5].truncated), (reference, !reference));
        assert!(
            e.step(Wait).is_err(),
            "stepping a finished episode is an error"
        );
    }
    // A delivery on step max+1 still pays and terminates.
    let mut e = env("FixedInterval-v0", &["td=1", "max_timesteps=6"], (1, 0), 1);
    let t = run(
        &mut e,
        &[Up, Interact, Down, Interact, Interact, Right, Right],
    );
    assert_eq!(t[6].info.timestep, 7);
    assert_eq!(t[6].reward, 0.0);
    let mut e = env("FixedInterval-v0", &["td=1", "max_timesteps=6"], (1, 0), 1);
    let t = run(
        &mut e,
        &[Up, Interact, Down, Interact, Interact, Right, Right],
    );
    assert!(t[6].truncated && !t[6].terminated);
    let mut e = env("FixedInterval-v0", &["td=1", "max_timesteps=7"], (1, 0), 1);
    let t = run(
        &mut e,
        &[
            Up, Interact, Down, Interact, Interact, Right, Right, Interact,
        ],
    );
    assert_eq!(t[7].reward, 1.0);
    assert!(t[7].terminated && !t[7].truncated);
}

#[test]
fn a_second_onion_while_the_soup_cooks_deadlocks_until_the_limit() {
    let mut e = env("FixedInterval-v0", &["td=2", "max_timesteps=30"], (1, 0), 2);
    run(&mut e, &FI_PUT);
    run(&mut e, &[Up, Interact, Down]); // carry a second onion back to the oven
    let mut last = None;
    while !e.is_done() {
        let t = e.step(Interact).unwrap();
        assert!(!t.info.events.has(Events::PICKUP));
        assert_eq!(t.reward, 0.0);
        last = Some(t);
    }
    assert!(last.unwrap().truncated);
}

#[test]
fn peak_interval_withholds_the_soup_until_k_times_td() {
    for (k, first_pickup) in [(2u32, Some(8i32)), (0, None)] {
        let mut e = env(
            "PeakInterval-v0",
            &["td=4", &format!("probe_factor={k}"), "max_timesteps=40"],
            (1, 0),
            4,
        );
        run(&mut e, &FI_PUT);
        let mut got = None;
        while !e.is_done() && got.is_none() {
            let t = e.step(Interact).unwrap();
            if t.info.events.has(Events::PICKUP) {
                got = Some(t.info.oven_off_time);
            }
        }
        assert_eq!(got, first_pickup, "k={k}");
    }
}

#[test]
fn uncertainty_button_readies_the_oven_at_a_reduced_reward() {
    let opts = |never| ResetOptions {
        start: Some((1, 0)),
        td: Some(5),
        never_ready: Some(never),
        ..ResetOptions::default()
    };
    // Never-ready episode: the oven stays dark; the button at (4,1) readies it.
    let mut e = ChronoEnv::from_id("Uncertainty-v0", &["td=5"]).unwrap();
    e.reset(Some(0), &opts(true)).unwrap();
    run(&mut e, &FI_PUT);
    run(&mut e, &[Wait; 10]);
    assert!(!e.state().ready);
    let t = run(&mut e, &[Right, Down, Down, Interact]); // (3,1): button below
    assert!(t[3].info.events.has(Events::BUTTON));
    assert_eq!(t[3].info.manual_stop_time, 14);
    assert_eq!(e.obs_codes()[(2 * 3) * 6 + 4], 2);
    let t = run(&mut e, &[Left, Interact]); // (3,0): oven above
    assert!(t[1].info.events.has(Events::PICKUP));
    let d = run(&mut e, &[Right, Up, Up, Right, Interact]);
    assert!((d[4].reward - 0.1).abs() < 1e-6);
    // Normal episode, soup taken late: overcooked reward.
    e.reset(Some(0), &opts(false)).unwrap();
    run(&mut e, &FI_PUT);
    run(&mut e, &[Wait; 6]);
    let t = e.step(Interact).unwrap();
    assert!(t.info.events.has(Events::PICKUP));
    let d = run(&mut e, &[Right, Right, Interact]);
    assert!((d[2].reward - 0.5).abs() < 1e-6);
    // The never-ready draw follows never_ready_prob.
    let mut e = ChronoEnv::from_id("Uncertainty-v0", &["never_ready_prob=0.2"]).unwrap();
    let never = (0..2000)
        .filter(|&s| {
            e.reset(Some(s), &ResetOptions::default())
                .unwrap()
                .never_ready
        })
        .count();
    assert!((330..470).contains(&never), "{never} of 2000");
}

#[test]
fn dual_sink_pays_only_while_the_oven_is_on() {
    let mut e = env("DualTask-v0", &["td=12"], (3, 2), 12);
    let t = e.step(Down).unwrap(); // blocked? (4,2) is the sink, so the agent stays
    assert_eq!(t.info.agent, (3, 2));
    let t = e.step(Interact).unwrap();
    assert_eq!(t.reward, 0.0, "oven off: the sink pays nothing");
    let mut e = env("DualTask-v0", &["td=12"], (1, 0), 12);
    run(&mut e, &FI_PUT);
    let t = run(&mut e, &[Right, Down, Down, Right, Interact, Interact]);
    assert!((t[4].reward - 0.01).abs() < 1e-6);
    assert_eq!(t[5].info.sink_count, 2);
    assert_eq!(t[5].info.last_sink_timer, 6);
}

#[test]
fn every_invalid_config_is_a_typed_error_naming_the_field() {
    let field = |r: Result<_, EnvError>| match r {
        Err(EnvError::InvalidParam { field, .. }) => field,
        Err(EnvError::InvalidResetOption { field, .. }) => field,
        Err(EnvError::UnknownParam { key, .. }) => format!("unknown:{key}"),
        Err(EnvError::UnknownTask { id, .. }) => format!("task:{id}"),
        Err(EnvError::InvalidLayout { .. }) => "layout".into(),
        Err(EnvError::BadOverride { text, .. }) => format!("override:{text}"),
        Err(e) => format!("{e:?}"),
        Ok(_) => "ok".into(),
    };
    let cfg = |id: &str, sets: &[&str]| field(make_config(id, sets).map(|_| ()));
    assert_eq!(cfg("FixedInterval-v0", &["td=0"]), "td");
    assert_eq!(cfg("FixedInterval-v0", &["td=-3"]), "td");
    assert_eq!(cfg("FixedInterval-v0", &["oven_duration=abc"]), "td");
    assert_eq!(cfg("Bisection-v0", &["short=12", "long=12"]), "long");
    assert_eq!(cfg("Bisection-v0", &["short=13", "long=12"]), "long");
    assert_eq!(cfg("MultiTimer-v0", &["over_buffer=-1"]), "over_buffer");
    assert_eq!(cfg("MultiTimer-v0", &["under_buffer=-2"]), "under_buffer");
    assert_eq!(cfg("MultiTimer-v0", &["tds=3,3"]), "tds");
    assert_eq!(cfg("MultiTimer-v0", &["tds=0,3"]), "tds");
    assert_eq!(cfg("MultiTimer-v0", &["tds=3,300"]), "tds");
    assert_eq!(cfg("MultiTimer-v0", &["num_timers=6"]), "num_timers");
    assert_eq!(cfg("MultiTimer-v0", &["mode=sometimes"]), "mode");
    assert_eq!(cfg("MultiTimer-v0", &["cue=colour"]), "cue");
    assert_eq!(
        cfg("MultiTimer-v0", &["reduced_reward=2"]),
        "reduced_reward"
    );
    assert_eq!(
        cfg("Uncertainty-v0", &["never_ready_prob=1.5"]),
        "never_ready_prob"
    );
    assert_eq!(cfg("DualTask-v0", &["sink_reward=nan"]), "sink_reward");
    assert_eq!(
        cfg("FixedInterval-v0", &["reference_compat=maybe"]),
        "reference_compat"
    );
    assert_eq!(
        cfg("FixedInterval-v0", &["max_timesteps=2000000"]),
        "max_timesteps"
    );
    assert_eq!(cfg("FixedInterval-v0", &["colour=red"]), "unknown:colour");
    assert_eq!(cfg("FixedInterval-v0", &["td"]), "override:td");
    assert_eq!(cfg("Cooking-v9", &[]), "task:Cooking-v9");
    assert_eq!(cfg("FixedInterval-v0", &["layout=O.D/.../V.."]), "layout");
    assert_eq!(
        cfg("FixedInterval-v0", &["layout=.OD/.../.../..."]),
        "layout",
        "missing oven"
    );
    assert_eq!(
        cfg("FixedInterval-v0", &["layout=.OD/.../V../.../..K"]),
        "layout",
        "stray sink"
    );
    assert!(matches!(
        Layout::parse("O.V"),
        Err(EnvError::InvalidLayout { .. })
    ));

    let mut e = ChronoEnv::from_id("MultiTimer-v0", &["cue=categorical", "tds=3,6"]).unwrap();
    let reset = |e: &mut ChronoEnv, start, td, never| {
        field(
            e.reset(
                None,
                &ResetOptions {
                    start,
                    td,
                    never_ready: never,
                    ..ResetOptions::default()
                },
            )
            .map(|_| ()),
        )
    };
    assert_eq!(
        reset(&mut e, None, Some(4), None),
        "td",
        "categorical cue has no code for TD 4"
    );
    assert_eq!(
        reset(&mut e, Some((0, 1)), None, None),
        "start",
        "(0,1) holds the onion"
    );
    assert_eq!(reset(&mut e, Some((9, 9)), None, None), "start");
    assert_eq!(reset(&mut e, None, None, Some(true)), "never_ready");
    let mut v = ChronoEnv::from_id::<&str>("MultiTimer-v0", &[]).unwrap();
    assert_eq!(
        reset(&mut v, None, Some(256), None),
        "td",
        "value cue is a u8"
    );
    assert_eq!(reset(&mut v, None, Some(0), None), "td");
    // Messages name the allowed values.
    let msg = make_config("Bisection-v0", &["short=8", "long=4"])
        .unwrap_err()
        .to_string();
    assert!(msg.contains("long") && msg.contains("> short"), "{msg}");
}

#[test]
fn reference_reset_duration_can_be_fixed_by_config_for_bisection_and_multi_timer() {
    let mut e = ChronoEnv::from_id(
        "MultiTimer-v0",
        &["oven_duration_list=3,6", "oven_duration=20"],
    )
    .unwrap();
    for s in 0..20 {
        assert_eq!(e.reset(Some(s), &ResetOptions::default()).unwrap().td, 20);
    }
    let mut e = ChronoEnv::from_id(
        "Bisection-v0",
        &["short_duration=4", "long_duration=12", "td=7"],
    )
    .unwrap();
    assert_eq!(e.reset(Some(1), &ResetOptions::default()).unwrap().td, 7);
    // A reset option still wins over the configured TD.
    let opts = ResetOptions {
        start: None,
        td: Some(12),
        never_ready: None,
        ..ResetOptions::default()
    };
    assert_eq!(e.reset(Some(1), &opts).unwrap().td, 12);
    assert!(make_config("MultiTimer-v0", &["cue=categorical", "tds=3,6", "td=4"]).is_err());
    assert!(make_config("MultiTimer-v0", &["td=300"]).is_err());
}
