//! The multi-anchor and multi-oven tasks beyond the golden traces: the oracle on anchor
//! sets and oven set-ups the traces do not use, the reference quirks (kept in
//! reference-compatible mode, fixed by default), curriculum layouts, aliases and the errors
//! for bad values.

use chronocooked_env::{
    Action, ChronoEnv, EnvError, Events, Oracle, PerOven, ResetOptions, make_config, optimal_return,
};

fn starts(env: &ChronoEnv) -> Vec<(usize, usize)> {
    env.layout().free_coords()
}

fn run_oracle(env: &mut ChronoEnv, options: &ResetOptions) -> f64 {
    let oracle = Oracle::new(env);
    env.reset(Some(3), options).unwrap();
    let mut total = 0.0;
    let mut last = Events::default();
    while !env.is_done() {
        let t = env.step(oracle.act(&env.state())).unwrap();
        total += t.reward as f64;
        last = t.info.events;
    }
    if env.ovens().is_some() {
        assert_eq!(
            last.has(Events::ALL_PAID),
            (total - 1.0).abs() < 1e-5,
            "the last delivery is flagged all_paid exactly when every soup paid ({total})"
        );
    }
    total
}

#[test]
fn multi_anchor_oracle_delivers_every_anchor_to_its_counter_from_every_start() {
    for anchors in ["2,5,9", "3,7,11,16", "6,9,13,20", "5,23"] {
        let n = anchors.split(',').count();
        for k in 2..=n {
            let mut env = ChronoEnv::from_id(
                "MultiAnchor-v0",
                &[format!("anchors={anchors}"), format!("num_anchors={k}")],
            )
            .unwrap();
            assert_eq!(env.layout().free_cells().len(), 10 - k, "{anchors} k={k}");
            for td in anchors
                .split(',')
                .take(k)
                .map(|a| a.parse::<u32>().unwrap())
            {
                for start in starts(&env) {
                    let options = ResetOptions {
                        start: Some(start),
                        td: Some(td),
                        ..ResetOptions::default()
                    };
                    let ret = run_oracle(&mut env, &options);
                    assert_eq!(ret, 1.0, "anchors {anchors} k={k} td={td} start {start:?}");
                }
            }
        }
    }
}

#[test]
fn multi_anchor_pays_only_the_counter_of_the_drawn_anchor() {
    // Every counter, every anchor: deliver by hand (walk from the oven to counter i).
    let mut env = ChronoEnv::from_id("MultiAnchor-v0", &["anchors=3,6,10,15"]).unwrap();
    // Cells next to counters 1..4: (1,0), (1,2), (2,0), (2,2); the oven from (2,1).
    let paths: [&[Action]; 4] = [
        &[Action::Up, Action::Left, Action::Interact],
        &[Action::Up, Action::Right, Action::Interact],
        &[Action::Left, Action::Interact],
        &[Action::Right, Action::Interact],
    ];
    for (i, &anchor) in [3u32, 6, 10, 15].iter().enumerate() {
        for (j, path) in paths.iter().enumerate() {
            let options = ResetOptions {
                start: Some((1, 1)),
                td: Some(anchor),
                ..ResetOptions::default()
            };
            env.reset(Some(1), &options).unwrap();
            // Onion (interact up at (1,1)), then down to (2,1), put, wait, take.
            for a in [Action::Interact, Action::Down, Action::Interact] {
                env.step(a).unwrap();
            }
            while env.state().timer < anchor as i32 || !env.state().ready {
                env.step(Action::Wait).unwrap();
            }
            env.step(Action::Interact).unwrap();
            let mut reward = 0.0;
            let mut last = None;
            for &a in path.iter() {
                let t = env.step(a).unwrap();
                reward += t.reward;
                last = Some(t);
            }
            let t = last.unwrap();
            assert!(t.terminated, "delivery ends the episode");
            assert_eq!(t.info.counter.map(|c| c.number()), Some(j as u8 + 1));
            assert_eq!(
                reward,
                f32::from(u8::from(i == j)),
                "anchor {i} counter {j}"
            );
        }
    }
}

/// Every combination of short/long durations per oven, synchronous and asynchronous with
/// every pair of on-times in the reference's range: the oracle delivers every soup right.
#[test]
fn multi_oven_oracle_delivers_every_soup_right_in_every_set_up() {
    for (short, long) in [(3u32, 7u32), (5, 11)] {
        for ovens in 1..=3usize {
            for asynchronous in [false, true] {
                let mut env = ChronoEnv::from_id(
                    "MultiOven-v0",
                    &[
                        format!("short={short}"),
                        format!("long={long}"),
                        format!("ovens={ovens}"),
                        format!("asynchronous={asynchronous}"),
                    ],
                )
                .unwrap();
                let cells = starts(&env);
                for combo in 0..(1u32 << ovens) {
                    let tds: Vec<u32> = (0..ovens)
                        .map(|i| if combo >> i & 1 == 1 { long } else { short })
                        .collect();
                    let limit = 6 + tds[0] / 2;
                    let on_sets: Vec<Vec<u32>> = if asynchronous && ovens > 1 {
                        let mut sets = Vec::new();
                        for a in 0..=limit {
                            if ovens == 2 {
                                sets.push(vec![a]);
                            } else {
                                for b in (0..=limit).filter(|&b| b != a).step_by(3) {
                                    sets.push(vec![a, b]);
                                }
                            }
                        }
                        sets
                    } else {
                        vec![Vec::new()]
                    };
                    for (k, on) in on_sets.iter().enumerate() {
                        let start = cells[k % cells.len()];
                        let options = ResetOptions {
                            start: Some(start),
                            oven_tds: Some(PerOven::new("oven_tds", &tds).unwrap()),
                            on_times: (asynchronous && ovens > 1)
                                .then(|| PerOven::new("on_times", on).unwrap()),
                            ..ResetOptions::default()
                        };
                        let ret = run_oracle(&mut env, &options);
                        assert!(
                            (ret - 1.0).abs() < 1e-5,
                            "S{short} L{long} n={ovens} async={asynchronous} tds {tds:?} on {on:?} start {start:?}: {ret}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn oracles_equal_the_brute_force_optimum_on_small_horizons() {
    let cases: &[(&str, &[&str], ResetOptions)] = &[
        (
            "MultiAnchor-v0",
            &["anchors=2,3,5", "max_timesteps=16"],
            ResetOptions {
                start: Some((2, 2)),
                td: Some(3),
                ..ResetOptions::default()
            },
        ),
        (
            "MultiOven-v0",
            &["short=2", "long=3", "ovens=2", "max_timesteps=18"],
            ResetOptions {
                start: Some((1, 0)),
                oven_tds: Some(PerOven::new("oven_tds", &[3, 2]).unwrap()),
                ..ResetOptions::default()
            },
        ),
        (
            "MultiOven-v0",
            &[
                "short=2",
                "long=4",
                "ovens=2",
                "asynchronous=true",
                "max_timesteps=18",
            ],
            ResetOptions {
                start: Some((2, 2)),
                oven_tds: Some(PerOven::new("oven_tds", &[2, 4]).unwrap()),
                on_times: Some(PerOven::new("on_times", &[3]).unwrap()),
                ..ResetOptions::default()
            },
        ),
    ];
    for (task, sets, options) in cases {
        let mut env = ChronoEnv::from_id(task, sets).unwrap();
        env.reset(Some(1), options).unwrap();
        let best = optimal_return(&env);
        let ret = run_oracle(&mut env, options);
        assert!(
            best > 0.99,
            "{task} {sets:?}: the optimum {best} should pay in full"
        );
        assert!(
            (ret - best).abs() < 1e-5,
            "{task} {sets:?}: oracle {ret} vs optimum {best}"
        );
    }
}

#[test]
fn multi_oven_soup_carries_its_oven_code_and_pays_one_nth() {
    let mut env = ChronoEnv::from_id("MultiOven-v0", &["short=2", "long=5", "ovens=3"]).unwrap();
    let options = ResetOptions {
        start: Some((1, 1)),
        oven_tds: Some(PerOven::new("oven_tds", &[2, 5, 2]).unwrap()),
        ..ResetOptions::default()
    };
    env.reset(Some(1), &options).unwrap();
    // Onion from (1,1); oven 1 at (3,0) is reached from (2,0).
    for a in [
        Action::Interact,
        Action::Down,
        Action::Left,
        Action::Interact,
    ] {
        env.step(a).unwrap();
    }
    // Synchronous: the put started all three ovens.
    let s = *env.state().multi_oven.as_ref().unwrap();
    assert!(s.timer.iter().all(|&t| t == 1), "{:?}", s.timer);
    env.step(Action::Wait).unwrap(); // oven 1 and 3 ready (timer 2)
    let t = env.step(Action::Interact).unwrap();
    assert!(t.info.events.has(chronocooked_env::Events::PICKUP));
    let agent = env.layout().index(2, 0);
    assert_eq!(
        env.obs_codes()[agent * 6 + 3],
        6,
        "soup of oven 1 carries code 6"
    );
    // Deliver to the short counter from (1,0): +1/3, the episode goes on.
    for a in [Action::Up, Action::Interact] {
        let t = env.step(a).unwrap();
        if a == Action::Interact {
            assert!((t.reward - 1.0 / 3.0).abs() < 1e-6);
            assert!(!t.terminated, "two soups left");
        }
    }
    // Oven 3 at (3,2), reached from (2,2): its soup shows code 12.
    for a in [Action::Down, Action::Right, Action::Right, Action::Interact] {
        env.step(a).unwrap();
    }
    let agent = env.layout().index(2, 2);
    assert_eq!(env.obs_codes()[agent * 6 + 3], 12);
    // To the LONG counter (wrong for a short soup): 0, recorded as 2.
    for a in [Action::Up, Action::Interact] {
        let t = env.step(a).unwrap();
        if a == Action::Interact {
            assert_eq!(t.reward, 0.0);
            assert_eq!(env.ovens().unwrap().delivered, [1, 0, 2]);
            assert!(
                !t.info.events.has(Events::ALL_PAID),
                "oven 3's soup did not pay"
            );
        }
    }
}

#[test]
fn quirks_are_kept_in_reference_mode_and_fixed_by_default() {
    // On-time 0: never fires in reference mode, starts at reset by default.
    for (compat, fires) in [(true, false), (false, true)] {
        let mut env = ChronoEnv::from_id(
            "MultiOven-v0",
            &[
                format!("reference_compat={compat}"),
                "asynchronous=true".into(),
                "ovens=2".into(),
            ],
        )
        .unwrap();
        let options = ResetOptions {
            start: Some((1, 1)),
            oven_tds: Some(PerOven::new("oven_tds", &[4, 4]).unwrap()),
            on_times: Some(PerOven::new("on_times", &[0]).unwrap()),
            ..ResetOptions::default()
        };
        env.reset(Some(1), &options).unwrap();
        for _ in 0..4 {
            env.step(Action::Wait).unwrap();
        }
        let s = env.state().multi_oven.unwrap();
        assert_eq!(s.ready[1], fires, "compat={compat}: {s:?}");
    }
    // A second onion: deadlock in reference mode, handed back by default.
    for (compat, back) in [(true, false), (false, true)] {
        for task in ["MultiAnchor-v0", "MultiOven-v0"] {
            let mut env =
                ChronoEnv::from_id(task, &[format!("reference_compat={compat}")]).unwrap();
            let options = ResetOptions {
                start: Some((1, 1)),
                ..ResetOptions::default()
            };
            env.reset(Some(1), &options).unwrap();
            env.step(Action::Interact).unwrap();
            let t = env.step(Action::Interact).unwrap();
            assert_eq!(
                t.info.carrying == chronocooked_env::Carry::Nothing,
                back,
                "{task} compat={compat}"
            );
        }
    }
    // TD 0: a reference replay may ask for it (never ready); otherwise it is an error.
    let mut compat = ChronoEnv::from_id("MultiAnchor-v0", &["reference_compat=true"]).unwrap();
    let td0 = ResetOptions {
        td: Some(0),
        ..ResetOptions::default()
    };
    assert!(compat.reset(Some(1), &td0).is_ok());
    let mut default = ChronoEnv::from_id("MultiAnchor-v0", &[] as &[&str]).unwrap();
    let err = default.reset(Some(1), &td0).unwrap_err().to_string();
    assert!(err.contains("`td`") && err.contains("1..=10000"), "{err}");
}

#[test]
fn reference_names_are_aliases() {
    let a = make_config(
        "MultiAnchor-v0",
        &["anchors=3,10,20,25", "max_timesteps=150"],
    )
    .unwrap();
    assert_eq!(a.params.active_anchors(), Some(&[3, 10, 20, 25][..]));
    assert_eq!(a.max_timesteps, 150);
    let o = make_config(
        "MultiOven-v0",
        &[
            "n_ovens=3",
            "asynchronous=true",
            "short_duration=4",
            "long_duration=18",
        ],
    )
    .unwrap();
    let canonical = make_config(
        "MultiOven-v0",
        &["ovens=3", "asynchronous=true", "short=4", "long=18"],
    )
    .unwrap();
    assert_eq!(o, canonical);
}

fn field_error(task: &str, sets: &[&str]) -> (String, String, String) {
    match make_config(task, sets).unwrap_err() {
        EnvError::InvalidParam {
            field,
            value,
            allowed,
        } => (field, value, allowed),
        other => panic!("{task} {sets:?}: expected an invalid-parameter error, got {other}"),
    }
}

#[test]
fn bad_values_name_the_key_and_the_allowed_values() {
    let (f, _, allowed) = field_error("MultiAnchor-v0", &["anchors=2,4,6,8,10"]);
    assert_eq!(f, "anchors");
    assert!(allowed.contains("2 to 4"), "{allowed}");
    let (f, v, allowed) = field_error("MultiAnchor-v0", &["anchors=4,8,8"]);
    assert_eq!((f.as_str(), v.as_str()), ("anchors", "4,8,8"));
    assert!(allowed.contains("distinct"), "{allowed}");
    let (f, _, _) = field_error("MultiAnchor-v0", &["anchors=8,4"]);
    assert_eq!(f, "anchors");
    let (f, _, allowed) = field_error("MultiAnchor-v0", &["anchors=4,8", "num_anchors=3"]);
    assert_eq!(f, "num_anchors");
    assert!(allowed.contains("2..=2"), "{allowed}");
    let (f, v, allowed) = field_error("MultiOven-v0", &["n_ovens=4"]);
    assert_eq!((f.as_str(), v.as_str()), ("ovens", "4"));
    assert!(allowed.contains("1..=3"), "{allowed}");
    let (f, _, _) = field_error("MultiOven-v0", &["td=0"]);
    assert_eq!(f, "td");
    let (f, _, _) = field_error("MultiOven-v0", &["short=12", "long=12"]);
    assert_eq!(f, "long");
    let (f, _, allowed) = field_error("MultiOven-v0", &["asynchronous=maybe"]);
    assert_eq!(f, "asynchronous");
    assert!(allowed.contains("true or false"));

    // Reset options: on-times outside the episode, in synchronous mode, of the wrong
    // length; durations of the wrong length.
    let mut env = ChronoEnv::from_id(
        "MultiOven-v0",
        &["asynchronous=true", "ovens=3", "max_timesteps=50"],
    )
    .unwrap();
    let bad = |on: &[u32], tds: Option<&[u32]>| ResetOptions {
        on_times: Some(PerOven::new("on_times", on).unwrap()),
        oven_tds: tds.map(|t| PerOven::new("oven_tds", t).unwrap()),
        ..ResetOptions::default()
    };
    for (options, field, says) in [
        (bad(&[3, 51], None), "on_times", "0..=50"),
        (bad(&[3], None), "on_times", "2 on-times"),
        (bad(&[4, 4], None), "on_times", "distinct"),
        (bad(&[1, 2], Some(&[4, 12])), "oven_tds", "3 durations"),
    ] {
        match env.reset(Some(1), &options).unwrap_err() {
            EnvError::InvalidResetOption {
                field: f, allowed, ..
            } => {
                assert_eq!(f, field);
                assert!(allowed.contains(says), "{allowed}");
            }
            other => panic!("expected a reset-option error, got {other}"),
        }
    }
    let mut sync = ChronoEnv::from_id("MultiOven-v0", &[] as &[&str]).unwrap();
    let err = sync
        .reset(Some(1), &bad(&[2], None))
        .unwrap_err()
        .to_string();
    assert!(err.contains("asynchronous"), "{err}");
    assert!(
        PerOven::new("oven_tds", &[4, 4, 4, 4]).is_err(),
        "four ovens"
    );
}

#[test]
fn curriculum_levels_change_the_layout_as_the_reference_does() {
    for (k, free) in [(2, 8), (3, 7), (4, 6)] {
        let cfg = make_config(
            "MultiAnchor-v0",
            &["anchors=4,12,18,25".to_string(), format!("num_anchors={k}")],
        )
        .unwrap();
        let env = ChronoEnv::new(&cfg).unwrap();
        assert_eq!(env.layout().free_cells().len(), free, "k={k}");
    }
    for (n, free) in [(1, 8), (2, 7), (3, 6)] {
        let env = ChronoEnv::from_id("MultiOven-v0", &[format!("ovens={n}")]).unwrap();
        assert_eq!(env.layout().free_cells().len(), free, "n={n}");
        // One observation size for every level (networks keep their input).
        assert_eq!(env.onehot_encoder().shape(), [20, 4, 3]);
    }
}

#[test]
fn drawn_episodes_use_only_active_anchors_and_the_reference_on_time_range() {
    let mut env =
        ChronoEnv::from_id("MultiAnchor-v0", &["anchors=3,10,20,25", "num_anchors=3"]).unwrap();
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..200 {
        seen.insert(env.reset(Some(seed), &ResetOptions::default()).unwrap().td);
    }
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), vec![3, 10, 20]);
    let mut env = ChronoEnv::from_id("MultiOven-v0", &["ovens=3", "asynchronous=true"]).unwrap();
    let mut max_on = 0;
    for seed in 0..300 {
        env.reset(Some(seed), &ResetOptions::default()).unwrap();
        let o = env.ovens().expect("a multi-oven env has ovens");
        assert_eq!(o.on_time[0], -1);
        assert_ne!(o.on_time[1], o.on_time[2], "without replacement");
        let limit = 6 + o.td[0] as i32 / 2;
        for &t in &o.on_time[1..3] {
            assert!((0..=limit).contains(&t), "{o:?}");
            max_on = max_on.max(t);
        }
        assert!(o.td.iter().all(|&d| d == 4 || d == 12));
    }
    assert!(max_on >= 10, "the range 0..=6+d0/2 is used up to its top");
}

/// The guide's task-parameter table (docs/tasks.md) is the generated one (`chronocooked env list
/// --markdown`), so docs and parser cannot disagree.
#[test]
fn the_guide_task_parameter_table_is_generated_from_the_tables() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/tasks.md")).unwrap();
    let (open, close) = ("<!-- settings:task -->\n", "<!-- /settings:task -->");
    let start = readme
        .find(open)
        .expect("docs/tasks.md has the task table markers")
        + open.len();
    let end = readme[start..].find(close).unwrap() + start;
    let generated = chronocooked_env::registry::parameters_markdown();
    assert_eq!(
        readme[start..end],
        generated,
        "docs/tasks.md's task table is stale: regenerate with `chronocooked env list --markdown`"
    );
    for key in [
        "anchors",
        "num_anchors",
        "ovens",
        "asynchronous",
        "probe_factor",
    ] {
        assert!(generated.contains(&format!("`{key}`")), "{key}");
    }
}

/// Every parameter `env list` shows is accepted with a value its rule allows, and a value
/// outside the rule is refused naming the key — for every registered task.
#[test]
fn every_listed_parameter_is_accepted_and_bounded_as_documented() {
    use chronocooked_env::settings::Rule;
    for t in chronocooked_env::all_tasks() {
        let base = t.default_config();
        for row in chronocooked_env::task::params::rows(&base) {
            // The default is accepted as written.
            if row.key != "layout" {
                let set = format!("{}={}", row.key, row.default);
                make_config(t.id, &[set.as_str()])
                    .unwrap_or_else(|e| panic!("{}: default `{set}` refused: {e}", t.id));
            }
            let spec = chronocooked_env::task::params::table(t.family)
                .into_iter()
                .find(|s| s.key == row.key)
                .unwrap();
            let mut rule = spec.rule;
            while let Rule::Optional(inner) | Rule::Mapped { inner, .. } = rule {
                rule = *inner;
            }
            if let Rule::Int { hi, .. } = rule {
                let over = format!("{}={}", row.key, hi + 1);
                match make_config(t.id, &[over.as_str()]) {
                    Err(EnvError::InvalidParam { field, allowed, .. }) => {
                        assert_eq!(field, row.key, "{}", t.id);
                        assert!(allowed.contains(&hi.to_string()), "{}: {allowed}", t.id);
                    }
                    other => panic!("{}: `{over}` should be refused, got {other:?}", t.id),
                }
            }
        }
    }
}
