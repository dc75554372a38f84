//! Registry-driven `check_env`-style conformance over every registered task, plus the
//! vectorised env's equivalence with scalar stepping.

use chronocooked_env::{
    Action, Autoreset, ChronoEnv, INFO_KEYS, ResetOption, ResetOptions, TaskConfig, TaskFamily,
    VecEnv, all_tasks, derive_seed, make_config,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn random_episode_trace(env: &mut ChronoEnv, seed: u64, steps: usize) -> Vec<String> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut out = vec![];
    let info = env.reset(Some(seed), &ResetOptions::default()).unwrap();
    out.push(format!("{:?}{:?}", env.obs_codes(), info));
    for _ in 0..steps {
        let a = Action::ALL[rng.random_range(0..6)];
        let t = env.step(a).unwrap();
        out.push(format!("{:?}{:?}", env.obs_codes(), t));
        if t.done() {
            let info = env.reset(None, &ResetOptions::default()).unwrap();
            out.push(format!("reset{:?}{:?}", env.obs_codes(), info));
        }
    }
    out
}

#[test]
fn every_task_is_seed_and_step_deterministic() {
    for spec in all_tasks() {
        let cfg = spec.default_config();
        for seed in [0u64, 1, 7, 12345] {
            let a = random_episode_trace(&mut ChronoEnv::new(&cfg).unwrap(), seed, 800);
            let b = random_episode_trace(&mut ChronoEnv::new(&cfg).unwrap(), seed, 800);
            assert_eq!(a, b, "{} seed {seed}", spec.id);
        }
        // Different seeds give different start cells somewhere.
        let mut env = ChronoEnv::new(&cfg).unwrap();
        let starts: std::collections::HashSet<_> = (0..50)
            .map(|s| {
                env.reset(Some(s), &ResetOptions::default()).unwrap();
                env.state().agent
            })
            .collect();
        assert_eq!(
            starts.len(),
            env.layout().free_cells().len(),
            "{}: 50 seeds should visit every start cell",
            spec.id
        );
    }
}

/// Never-ready episodes are the families' own: a task has a share of them exactly when it
/// declares the `never_ready` reset option; the uncertainty task's default share is the
/// reference's 0.2, and a typed edit of the share reaches that task only.
#[test]
fn a_share_of_never_ready_episodes_belongs_to_the_tasks_that_declare_them() {
    for spec in all_tasks() {
        let mut config = spec.default_config();
        let declares = config.reset_options().contains(&ResetOption::NeverReady);
        assert_eq!(
            declares,
            spec.id == "Uncertainty-v0",
            "{}: only the uncertainty task declares never-ready episodes",
            spec.id
        );
        let default = if declares { 0.2 } else { 0.0 };
        assert_eq!(config.never_ready_prob(), default, "{}", spec.id);
        config.set_never_ready_prob(0.05);
        let expected = if declares { 0.05 } else { 0.0 };
        assert_eq!(config.never_ready_prob(), expected, "{}", spec.id);
        assert_eq!(config, {
            let mut c = spec.default_config();
            if declares {
                c.set("never_ready_prob", "0.05").unwrap();
            }
            c
        });
    }
}

#[test]
fn every_obs_is_in_its_space_and_info_has_every_key() {
    for spec in all_tasks() {
        let mut env = ChronoEnv::new(&spec.default_config()).unwrap();
        let codes = env.codes_space();
        let onehot = env.onehot_space();
        assert_eq!(
            codes.shape,
            vec![env.layout().rows(), env.layout().cols(), 6]
        );
        assert_eq!(
            onehot.shape[1..],
            [env.layout().rows(), env.layout().cols()]
        );
        assert!(env.action_space().contains(5) && !env.action_space().contains(6));
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        env.reset(Some(3), &ResetOptions::default()).unwrap();
        let mut timestep = 0;
        let cols = env.layout().cols();
        for _ in 0..3000 {
            let t = env.step(Action::ALL[rng.random_range(0..6)]).unwrap();
            assert!(codes.contains(env.obs_codes()), "{}", spec.id);
            assert!(onehot.contains(&env.obs_onehot()), "{}", spec.id);
            // The serialised info has exactly the documented keys ...
            let json = serde_json::to_value(t.info).unwrap();
            let mut keys: Vec<&str> = json
                .as_object()
                .unwrap()
                .keys()
                .map(String::as_str)
                .collect();
            let mut documented = INFO_KEYS.to_vec();
            // Every oven's state is beside the info, only in the multi-oven task.
            assert_eq!(
                env.ovens().is_some(),
                spec.family == TaskFamily::MultiOven,
                "{}",
                spec.id
            );
            keys.sort_unstable();
            documented.sort_unstable();
            assert_eq!(keys, documented, "{}", spec.id);
            // ... and says what the observation shows: one more step, the agent's cell, what
            // it carries.
            timestep += 1;
            assert_eq!(t.info.timestep, timestep, "{}", spec.id);
            assert_eq!(json["timestep"], timestep, "{}", spec.id);
            let obs = env.obs_codes();
            let cell = obs.chunks_exact(6).position(|c| c[1] == 1).unwrap();
            assert_eq!(
                (cell / cols, cell % cols),
                (t.info.agent.0 as usize, t.info.agent.1 as usize),
                "{}",
                spec.id
            );
            assert_eq!(json["agent"], serde_json::json!([cell / cols, cell % cols]));
            let carry = match (obs[cell * 6 + 2], obs[cell * 6 + 3]) {
                (1, _) => "onion",
                // Multi-oven soup shows its oven's code (6, 9, 12).
                (_, c) if c != 0 => "soup",
                _ => "nothing",
            };
            assert_eq!(json["carrying"], carry, "{}", spec.id);
            // The one-hot view has exactly one agent.
            let plane = env.layout().n_cells();
            let ch = env.onehot_encoder().agent_channel();
            let agent: f32 = env.obs_onehot()[ch * plane..(ch + 1) * plane].iter().sum();
            assert_eq!(agent, 1.0);
            if t.done() {
                env.reset(None, &ResetOptions::default()).unwrap();
                timestep = 0;
            }
        }
    }
}

#[test]
fn the_observation_never_encodes_the_timer() {
    // Two states that differ only in the hidden timer have identical observations.
    let mut env = ChronoEnv::from_id("FixedInterval-v0", &["td=20"]).unwrap();
    let opts = ResetOptions {
        start: Some((1, 0)),
        td: None,
        never_ready: None,
        ..ResetOptions::default()
    };
    env.reset(Some(0), &opts).unwrap();
    env.step(Action::Up).unwrap(); // to (0,0), next to the onion
    env.step(Action::Interact).unwrap();
    env.step(Action::Down).unwrap(); // (1,0), next to the oven
    env.step(Action::Interact).unwrap(); // onion in
    let first = env.obs_codes().to_vec();
    env.step(Action::Wait).unwrap();
    assert_eq!(env.obs_codes(), &first[..]);
    assert!(env.state().timer >= 2);
}

#[test]
fn vec_env_matches_scalar_envs_with_derived_seeds() {
    for spec in all_tasks() {
        let cfg = spec.default_config();
        let n = 5;
        let mut venv = VecEnv::new(&cfg, n, Autoreset::SameStep).unwrap();
        venv.reset(99);
        let mut envs: Vec<ChronoEnv> = (0..n)
            .map(|i| {
                let mut e = ChronoEnv::new(&cfg).unwrap();
                e.reset(Some(derive_seed(99, i as u64)), &ResetOptions::default())
                    .unwrap();
                e
            })
            .collect();
        let len = venv.obs_len();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let mut ended = 0;
        for _ in 0..1500 {
            let actions: Vec<u8> = (0..n).map(|_| rng.random_range(0..6)).collect();
            venv.step(&actions).unwrap();
            for (i, e) in envs.iter_mut().enumerate() {
                let t = e
                    .step(Action::from_code(actions[i] as i64).unwrap())
                    .unwrap();
                assert_eq!(venv.rewards[i], t.reward);
                assert_eq!(venv.terminated[i], t.terminated);
                assert_eq!(venv.truncated[i], t.truncated);
                if t.done() {
                    ended += 1;
                    assert_eq!(&venv.final_obs[i * len..(i + 1) * len], e.obs_codes());
                    assert_eq!(venv.final_infos[i], t.info);
                    let info = e.reset(None, &ResetOptions::default()).unwrap();
                    assert_eq!(venv.infos[i], info);
                }
                assert_eq!(
                    &venv.obs[i * len..(i + 1) * len],
                    e.obs_codes(),
                    "{}",
                    spec.id
                );
            }
        }
        assert!(ended > 0, "{}: no episode ended", spec.id);
        // One-hot batch equals the per-env encoding.
        let per = venv.onehot_encoder().len();
        let mut batch = vec![0.0; n * per];
        venv.write_onehot(&mut batch);
        for (i, e) in envs.iter().enumerate() {
            assert_eq!(&batch[i * per..(i + 1) * per], &e.obs_onehot()[..]);
        }
    }
}

/// A checkpoint's env state (`VecEnv::snapshot`, through JSON as the trainer stores it)
/// restores into a fresh vec-env of every registered task, which then steps exactly as the
/// original: a task whose state some check refuses could never resume a training run.
#[test]
fn every_task_s_vec_env_resumes_from_its_snapshot() {
    for spec in all_tasks() {
        let cfg = spec.default_config();
        let mut venv = VecEnv::new(&cfg, 3, Autoreset::SameStep).unwrap();
        venv.reset(17);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        let act = |rng: &mut Xoshiro256PlusPlus| -> Vec<u8> {
            (0..3).map(|_| rng.random_range(0..6)).collect()
        };
        for _ in 0..137 {
            venv.step(&act(&mut rng)).unwrap();
        }
        let json = serde_json::to_string(&venv.snapshot()).unwrap();
        let snap = serde_json::from_str(&json).unwrap();
        let mut resumed = VecEnv::new(&cfg, 3, Autoreset::SameStep).unwrap();
        resumed
            .restore(&snap)
            .unwrap_or_else(|e| panic!("{}: {e}", spec.id));
        for _ in 0..300 {
            let a = act(&mut rng);
            venv.step(&a).unwrap();
            resumed.step(&a).unwrap();
            assert_eq!(venv.obs, resumed.obs, "{}", spec.id);
            assert_eq!(venv.rewards, resumed.rewards, "{}", spec.id);
        }
    }
}

#[test]
fn vec_env_next_step_and_disabled_modes() {
    let cfg = make_config("FixedInterval-v0", &["max_timesteps=2"]).unwrap();
    let mut v = VecEnv::new(&cfg, 2, Autoreset::NextStep).unwrap();
    v.reset(1);
    for _ in 0..3 {
        v.step(&[0, 0]).unwrap();
    }
    assert!(v.truncated.iter().all(|&t| t));
    let terminal = v.obs.clone();
    assert_eq!(v.final_obs.len(), terminal.len());
    v.step(&[0, 0]).unwrap(); // the reset step
    assert!(v.rewards.iter().all(|&r| r == 0.0));
    assert!(!v.truncated[0] && !v.terminated[0]);
    assert_eq!(
        v.infos[0].timestep, 0,
        "the reset step reports the new episode's reset info"
    );
    v.step(&[0, 0]).unwrap();
    assert_eq!(v.infos[0].timestep, 1);

    let mut d = VecEnv::new(&cfg, 1, Autoreset::Disabled).unwrap();
    d.reset(1);
    for _ in 0..3 {
        d.step(&[0]).unwrap();
    }
    assert!(d.step(&[0]).is_err());
    assert!(
        v.step(&[0, 9]).is_err(),
        "action out of range is a typed error"
    );
    assert!(v.step(&[0]).is_err(), "wrong number of actions is an error");
}

fn random_config(family_index: usize, knobs: &[u32]) -> TaskConfig {
    let spec = &all_tasks()[family_index % all_tasks().len()];
    let k = |i: usize| knobs[i % knobs.len()];
    let mut sets = vec![format!("max_timesteps={}", k(0) % 300)];
    match spec.family {
        TaskFamily::FixedInterval | TaskFamily::Dual | TaskFamily::Uncertainty => {
            sets.push(format!("td={}", 1 + k(1) % 40));
        }
        TaskFamily::PeakInterval => {
            sets.push(format!("td={}", 1 + k(1) % 40));
            sets.push(format!("probe_factor={}", k(2) % 6));
        }
        TaskFamily::Bisection => {
            let s = 1 + k(1) % 20;
            sets.push(format!("short={s}"));
            sets.push(format!("long={}", s + 1 + k(2) % 20));
        }
        TaskFamily::MultiTimer => {
            let n = 1 + k(1) % 5;
            let tds: Vec<String> = (0..n)
                .map(|i| (1 + i * (1 + k(2) % 7)).to_string())
                .collect();
            sets.push(format!("tds={}", tds.join(",")));
            sets.push(format!("num_timers={}", 1 + k(3) % n));
            sets.push(format!(
                "mode={}",
                if k(4) % 2 == 0 {
                    "exact"
                } else {
                    "lower_bounded"
                }
            ));
            sets.push(format!(
                "cue={}",
                if k(5) % 2 == 0 {
                    "value"
                } else {
                    "categorical"
                }
            ));
            sets.push(format!("under_buffer={}", k(6) % 5));
            sets.push(format!("over_buffer={}", k(7) % 5));
        }
        TaskFamily::MultiAnchor => {
            let n = 2 + k(1) as usize % 3;
            let mut a = 1 + k(2) % 5;
            let anchors: Vec<String> = (0..n)
                .map(|i| {
                    a += 1 + k(3 + i) % 9;
                    a.to_string()
                })
                .collect();
            sets.push(format!("anchors={}", anchors.join(",")));
            sets.push(format!("num_anchors={}", 2 + k(7) as usize % (n - 1)));
        }
        TaskFamily::Reproduction => {
            let lo = 1 + k(1) % 10;
            let prior = format!("{lo}-{}", lo + 1 + k(2) % 8);
            let named = ["short", "intermediate", "long"][k(3) as usize % 3];
            sets.push(format!("priors={prior},{named}"));
            sets.push(format!("prior_cue={}", k(4) % 2 == 0));
            sets.push(
                if k(5) % 2 == 0 {
                    "gains=1"
                } else {
                    "gains=1,1.5"
                }
                .into(),
            );
            sets.push(format!("foreperiod_max={}", 2 + k(6) % 5));
            // Long enough for the latest paid production (validated).
            sets.push("max_timesteps=120".into());
        }
        TaskFamily::MultiOven => {
            let s = 1 + k(1) % 20;
            sets.push(format!("short={s}"));
            sets.push(format!("long={}", s + 1 + k(2) % 20));
            sets.push(format!("ovens={}", 1 + k(3) % 3));
            sets.push(format!("asynchronous={}", k(4) % 2 == 0));
        }
        // No external family is registered in this test binary.
        TaskFamily::External => {}
    }
    if spec.family == TaskFamily::Uncertainty {
        sets.push(format!("never_ready_prob={}", (k(3) % 11) as f32 / 10.0));
    }
    if k(8) % 3 == 0 {
        sets.push("reference_compat=true".into());
    }
    make_config(spec.id, &sets).expect("generated configs are valid")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_valid_configs_and_long_random_action_streams_never_panic(
        family in 0usize..6,
        knobs in proptest::collection::vec(0u32..1000, 9),
        actions in proptest::collection::vec(0i64..6, 2000..3000),
        seed in any::<u64>(),
    ) {
        let cfg = random_config(family, &knobs);
        let mut env = ChronoEnv::new(&cfg).unwrap();
        let space = env.codes_space();
        env.reset(Some(seed), &ResetOptions::default()).unwrap();
        for a in actions {
            let t = env.step_code(a).unwrap();
            prop_assert!(space.contains(env.obs_codes()));
            prop_assert!((-1e-6..=1.0001).contains(&t.reward));
            prop_assert!(t.info.timestep <= cfg.max_timesteps + 1);
            if t.done() {
                prop_assert!(t.terminated != t.truncated || t.terminated);
                prop_assert!(env.step(Action::Wait).is_err());
                env.reset(None, &ResetOptions::default()).unwrap();
            }
        }
    }
}
