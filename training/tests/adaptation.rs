//! The uncertainty-adaptation protocol: rolling success and episodes-to-adapt on hand-built
//! sequences, the shared success criterion on never-ready ovens, a timing agent trained on
//! FI adapting to the uncertainty task, and PPO fine-tuning from a run's weights.

use chronocooked_env::{ChronoEnv, ResetOptions, make_config};
use chronocooked_models::agent::{OracleAgent, run_episode};
use chronocooked_training::adapt::{
    AdaptConfig, episodes_to_adapt, rolling_success, run_adaptation,
};
use chronocooked_training::ppo::params::flat_params;
use chronocooked_training::{Check, TimingRunConfig, Trainer, load_policy, resolve, run_training};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("chronocooked-adapt-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn episodes_to_adapt_counts_episodes_until_the_window_reaches_the_threshold() {
    // 8 failures then successes: with a window of 4 and threshold 0.75, the window first
    // holds 3 successes after episode 11.
    let s: Vec<bool> = (0..20).map(|i| i >= 8).collect();
    assert_eq!(episodes_to_adapt(&s, 4, 0.75), Some(11));
    assert_eq!(episodes_to_adapt(&s, 4, 1.0), Some(12));
    // Never reaching it; a window longer than the data.
    assert_eq!(episodes_to_adapt(&[true, false, true, false], 2, 0.9), None);
    assert_eq!(episodes_to_adapt(&[true; 3], 5, 0.5), None);
    // Already adapted from the start: the first full window.
    assert_eq!(episodes_to_adapt(&[true; 10], 5, 0.9), Some(5));
    let r = rolling_success(&[true, false, true, true], 2);
    assert_eq!(r, vec![(1, 1.0), (2, 0.5), (3, 0.5), (4, 1.0)]);
}

#[test]
fn a_button_delivery_is_a_success_only_when_the_oven_never_readies() {
    let config = make_config("Uncertainty-v0", &[] as &[&str]).unwrap();
    let mut env = ChronoEnv::new(&config).unwrap();
    let mut oracle = OracleAgent::new(&env);
    for never_ready in [false, true] {
        let opts = ResetOptions {
            start: Some((1, 1)),
            td: None,
            never_ready: Some(never_ready),
            ..ResetOptions::default()
        };
        let rec = run_episode(&mut env, &mut oracle, 0, &opts, None).unwrap();
        let last = rec.infos.last().unwrap();
        assert_eq!(last.never_ready, never_ready);
        assert!(
            rec.success,
            "oracle, never_ready {never_ready}: reward {}",
            rec.reward
        );
        if never_ready {
            assert!(last.manual_stop_time >= 0, "the oracle used the button");
            assert!(rec.reward < 0.5, "reduced reward {}", rec.reward);
        }
    }
    // Pressing the button on a normal oven pays the reduced reward: not a success.
    let info = chronocooked_env::Info {
        never_ready: false,
        manual_stop_time: 3,
        events: chronocooked_env::Events(chronocooked_env::Events::DELIVERY),
        ..Default::default()
    };
    assert!(!chronocooked_models::agent::is_success(&info, 0.1));
    let info = chronocooked_env::Info {
        never_ready: true,
        ..info
    };
    assert!(chronocooked_models::agent::is_success(&info, 0.1));
}

#[test]
fn a_timing_agent_trained_without_uncertainty_adapts_to_it() {
    let dir = temp_dir("timing");
    // Pre-training on the same task without uncertainty (the oven always readies).
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("Uncertainty-v0").unwrap(),
        "sbf",
        0,
    );
    cfg.set("episodes=3000").unwrap();
    cfg.set("env.never_ready_prob=0").unwrap();
    let run = dir.join("run");
    chronocooked_training::run_timing_training(&cfg, &run, "test", |_| {}).unwrap();
    let adapt = AdaptConfig {
        episodes: 4000,
        ..AdaptConfig::default()
    };
    let r = run_adaptation(&run, &adapt, &dir.join("adapt")).unwrap();
    assert_eq!(r.episodes, 4000);
    assert_eq!(r.from_task, "Uncertainty-v0");
    assert!(
        r.task.is_default(),
        "the task's own never-ready probability: {}",
        r.task
    );
    // At first never-ready ovens mostly fail (measured 0.32: the button is pressed only
    // by exploration); the agent adapts without giving up the normal ovens.
    assert!(r.initial_success < 0.5, "{}", r.initial_success);
    let n = r.episodes_to_adapt.expect("adapts within 4000 episodes");
    assert!((100..4000).contains(&n), "{n}");
    let at = r.curve[n - 1];
    assert!(at.1 >= 0.8 && at.2 >= 0.8, "{at:?}");
    assert!(r.final_normal_success > 0.8, "{}", r.final_normal_success);
    // Same seed, same result; the files are written.
    let again = run_adaptation(&run, &adapt, &dir.join("adapt2")).unwrap();
    assert_eq!(again.episodes_to_adapt, r.episodes_to_adapt);
    assert_eq!(
        again
            .curve
            .iter()
            .map(|c| c.1.to_bits())
            .collect::<Vec<_>>(),
        r.curve.iter().map(|c| c.1.to_bits()).collect::<Vec<_>>()
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("adapt/adapt.json")).unwrap())
            .unwrap();
    assert_eq!(json["episodes_to_adapt"].as_u64(), Some(n as u64));
    let csv = std::fs::read_to_string(dir.join("adapt/adapt.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4001);
}

#[test]
fn adaptation_curve_splits_never_ready_and_normal_episodes() {
    // (never_ready, success): the never-ready episodes fail, then succeed.
    let o = [
        (false, true),
        (true, false),
        (false, true),
        (true, false),
        (false, false),
        (true, true),
        (true, true),
    ];
    let c = chronocooked_training::adapt::adaptation_curve(&o, 4);
    assert!(c[0].1.is_nan() && c[0].2 == 1.0);
    assert_eq!((c[3].1, c[3].2), (0.0, 1.0));
    assert_eq!((c[4].0, c[4].1, c[4].2), (5, 0.0, 0.5));
    assert_eq!((c[6].1, c[6].2), (2.0 / 3.0, 0.0));
}

#[test]
fn ppo_fine_tuning_starts_from_the_source_run_weights() {
    let dir = temp_dir("ppo");
    let arch = "lstm8".parse().unwrap();
    let cfg = resolve(
        "FixedInterval-v0",
        arch,
        "fast",
        0,
        &["total_steps=2000", "env.td=6"],
    )
    .unwrap();
    let run = dir.join("run");
    run_training(
        Some(cfg.check().unwrap()),
        &run,
        "test",
        &mut chronocooked_training::Silent,
    )
    .unwrap();
    let (source, ..) = load_policy(&run).unwrap();
    let mut tuned = resolve("Uncertainty-v0", arch, "fast", 1, &["env.td=6"]).unwrap();
    tuned.init_from = Some(run.display().to_string());
    let trainer = Trainer::new(tuned.clone().check().unwrap()).unwrap();
    assert_eq!(flat_params(&trainer.policy()), flat_params(&source));
    // A different architecture is refused with a message naming the field.
    let mut wrong = resolve(
        "Uncertainty-v0",
        "lstm125".parse().unwrap(),
        "fast",
        1,
        &[] as &[&str],
    )
    .unwrap();
    wrong.init_from = tuned.init_from.clone();
    let err = wrong
        .check()
        .and_then(Trainer::new)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("init_from"), "{err}");
    // The protocol end to end: fine-tuning run, curve, result.
    let r = run_adaptation(
        &run,
        &AdaptConfig {
            task: chronocooked_env::Task::parse("Uncertainty-v0", &["td=6"]).unwrap(),
            steps: 3000,
            ..AdaptConfig::default()
        },
        &dir.join("adapt"),
    )
    .unwrap();
    assert_eq!(r.model, "lstm8");
    assert!(r.episodes > 0 && !r.curve.is_empty());
    let tuned_cfg: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("adapt/run/config.json")).unwrap())
            .unwrap();
    assert_eq!(tuned_cfg["task"], "Uncertainty-v0");
    assert!(tuned_cfg["init_from"].as_str().unwrap().ends_with("run"));
    let agent =
        chronocooked_training::timing_run::load_agent(&dir.join("adapt/run"), None).unwrap();
    assert_eq!(agent.name(), "lstm8");
}

#[test]
fn episodes_to_adapt_has_known_answers() {
    use chronocooked_training::adapt::episodes_to_adapt;
    // 10 failures then successes: a window of 4 at 75% is reached at episode 13.
    let mut v = vec![false; 10];
    v.extend(vec![true; 10]);
    assert_eq!(episodes_to_adapt(&v, 4, 0.75), Some(13));
    assert_eq!(episodes_to_adapt(&[false; 30], 5, 0.5), None);
}
