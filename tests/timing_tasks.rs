//! Timing-model agents learning what particular tasks ask beyond timing: the uncertainty
//! task's time-out category, the opportunity cost of time, and the dual task's one-step
//! window (split from `timing_agents.rs`).

use crate::timing_agents::trained_agent;
use chronocooked_analysis::{Mode, reference_conditions, run_protocol};
use chronocooked_training::{TimingRunConfig, run_timing_training};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-timing-tasks-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// (normal, never-ready) success of a trained uncertainty agent in the reference evaluation.
fn uncertainty_success(agent: &mut dyn chronocooked_models::Agent) -> (f64, f64) {
    let conditions =
        reference_conditions(&chronocooked_env::Task::new("Uncertainty-v0").unwrap()).unwrap();
    let records = run_protocol(agent, &conditions, Mode::Reference, 0).unwrap();
    let rate = |never: bool| {
        let kind: Vec<_> = records
            .iter()
            .filter(|r| r.condition.never_ready == Some(never))
            .collect();
        assert!(!kind.is_empty());
        kind.iter().filter(|r| r.episode.success).count() as f64 / kind.len() as f64
    };
    (rate(false), rate(true))
}

#[test]
fn the_time_out_category_lets_ramping_and_oscillator_clocks_learn_the_time_out() {
    // Past 1.5 × its expected time without the ready cue the model is "overdue", and the
    // TD learner sees that category instead of the ramp (whose linear readout would carry
    // the rising value of waiting past the expected time). Measured, seeds 0–15: drift-
    // diffusion 1.00 / 1.00 (normal / never-ready) on all 16; without it (the agent before
    // the category: `overdue_factor=0` also keeps the frozen clock after the cue) it waits
    // at the never-ready oven on seeds 7 and 14 (0.00; 5 of 16 seeds reach 0.9).
    // The measurement was made with the near-deterministic clock of that version
    // (`noise=0.06`, exact anchor memories); the defaults are noisier (next assertion).
    // Since the drift learns at rate 0.1 (was 0.2) seed 14 also reaches 0.91 without the
    // category, so the claim checked is the population one: with the category both seeds
    // learn the time-out, without it not both do.
    let mut without = Vec::new();
    for seed in [7, 14] {
        let mut cfg = TimingRunConfig::new(
            &chronocooked_env::Task::new("Uncertainty-v0").unwrap(),
            "ddm",
            seed,
        );
        cfg.set("noise=0.06").unwrap();
        cfg.set("memory_noise=0").unwrap();
        let (normal, never) =
            uncertainty_success(trained_agent(&cfg, &format!("unc-{seed}")).as_mut());
        assert!(
            normal >= 0.9 && never >= 0.9,
            "seed {seed}: {normal} / {never}"
        );
        let mut off = cfg.clone();
        // A factor below 1 would call the interval overdue before its expected time.
        let err = off.set("overdue_factor=0.5").unwrap_err().to_string();
        assert!(
            err.contains("overdue_factor") && err.contains(">= 1"),
            "{err}"
        );
        off.set("overdue_factor=0").unwrap();
        let (_, never_off) =
            uncertainty_success(trained_agent(&off, &format!("unc-off-{seed}")).as_mut());
        without.push(never_off);
    }
    assert!(
        without.iter().any(|&v| v < 0.9),
        "without the category every seed learned the time-out: {without:?}"
    );
    // SBF (its remembered time) learns it too, at its default noise. (Drift-diffusion at
    // its default noise: RESULTS.md's task matrix.)
    let cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("Uncertainty-v0").unwrap(),
        "sbf",
        0,
    );
    let (normal, never) = uncertainty_success(trained_agent(&cfg, "unc-sbf-0").as_mut());
    assert!(normal >= 0.9 && never >= 0.9, "sbf: {normal} / {never}");
}

#[test]
fn the_opportunity_cost_of_time_learns_the_reward_rate() {
    // The rate is learned only when asked for, and it is the reward per step.
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        "ddm",
        0,
    );
    cfg.set("episodes=1500").unwrap();
    cfg.set("opportunity_cost=0.001").unwrap();
    let dir = temp_dir("fi-oc");
    run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
    let saved: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("agent.json")).unwrap()).unwrap();
    let rho = saved["reward_rate"].as_f64().unwrap();
    // FI TD 12: one soup (reward 1) per episode of ≥ 12 + walking steps.
    assert!(rho > 0.01 && rho < 1.0 / 12.0, "reward rate {rho}");
    let _ = std::fs::remove_dir_all(&dir);
    let mut plain = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        "ddm",
        0,
    );
    plain.set("episodes=300").unwrap();
    let dir = temp_dir("fi-no-oc");
    run_timing_training(&plain, &dir, "test", |_| {}).unwrap();
    let saved: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("agent.json")).unwrap()).unwrap();
    assert_eq!(saved["reward_rate"].as_f64(), Some(0.0));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_complete_serial_compound_learns_the_one_step_window_of_the_dual_task() {
    // One unit per step and optimistic initial values (`CSC_Q_INIT`): the agent takes the
    // soup exactly at TD 12 instead of the early reduced reward. Without optimism ε-greedy
    // SARSA never finds the window (measured: 0% on four seeds). The delay line is exact
    // here (`clock_noise=0`): with the default scalar clock noise no model can confine a
    // response to one step (`task_limit`).
    // As measured then: exact clock, internal check cost 0.01 (the time cells' default is
    // now 0.05, at which plain SARSA found the window on seed 0 too).
    for seed in [0, 1] {
        let mut cfg = TimingRunConfig::new(
            &chronocooked_env::Task::new("DualTask-v0").unwrap(),
            "timecells-csc",
            seed,
        );
        cfg.set("clock_noise=0").unwrap();
        cfg.set("response_cost=0.01").unwrap();
        let mut agent = trained_agent(&cfg, &format!("dual-csc-{seed}"));
        let conditions =
            reference_conditions(&chronocooked_env::Task::new("DualTask-v0").unwrap()).unwrap();
        let records = run_protocol(agent.as_mut(), &conditions, Mode::Reference, 0).unwrap();
        let rate =
            records.iter().filter(|r| r.episode.success).count() as f64 / records.len() as f64;
        assert!(rate >= 0.9, "seed {seed}: dual success {rate}");
        let mut plain = cfg.clone();
        plain.set("q_init=0").unwrap();
        let mut agent = trained_agent(&plain, &format!("dual-csc-plain-{seed}"));
        let records = run_protocol(agent.as_mut(), &conditions, Mode::Reference, 0).unwrap();
        assert!(
            records.iter().all(|r| !r.episode.success),
            "seed {seed}: plain SARSA found the window"
        );
    }
}

/// Actions between the onion going in and the soup coming out, per fixed-interval episode
/// of the reference evaluation of the timing run `cfg`.
fn interval_actions(cfg: &TimingRunConfig, label: &str) -> Vec<Vec<u8>> {
    use chronocooked_env::Events;
    let mut agent = trained_agent(cfg, label);
    let conditions = reference_conditions(&cfg.task).unwrap();
    let records = run_protocol(agent.as_mut(), &conditions, Mode::Reference, 0).unwrap();
    records
        .iter()
        .filter(|r| r.condition.kind == chronocooked_analysis::ConditionKind::Fi)
        .filter_map(|r| {
            let e = &r.episode;
            let on = e
                .infos
                .iter()
                .position(|i| i.events.has(Events::ONION_IN))?;
            let out = e.infos.iter().position(|i| i.events.has(Events::PICKUP))?;
            Some(e.actions[on + 1..=out].to_vec())
        })
        .collect()
}

#[test]
fn timing_agents_wait_at_the_oven_while_timing_unless_told_otherwise() {
    // With the default `wait_at_oven`, an empty-handed agent at the running oven may only
    // wait (0) or check (5): its first check comes from its clock, not from a walking
    // route. Drift-diffusion seed 3 at TD 5 is the case measured walking a fixed route
    // (checks at exactly TD, CV 0.00) before the setting.
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        "ddm",
        3,
    );
    cfg.set("env.td=5").unwrap();
    let eps = interval_actions(&cfg, "wait-on");
    assert!(eps.len() >= 40, "{} episodes with a pickup", eps.len());
    for a in &eps {
        assert!(a.iter().all(|&x| x == 0 || x == 5), "{a:?}");
    }
    // The first checks vary with the clock's noise (scalar timing, not a fixed route).
    let first: Vec<f64> = eps
        .iter()
        .filter_map(|a| a.iter().position(|&x| x == 5).map(|k| k as f64 + 1.0))
        .collect();
    let mean = first.iter().sum::<f64>() / first.len() as f64;
    let sd = (first.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / first.len() as f64).sqrt();
    assert!(sd / mean > 0.05, "first checks {first:?}");
    // Off, the agent may walk while timing (the setting exists and is applied).
    cfg.set("wait_at_oven=false").unwrap();
    let walked = interval_actions(&cfg, "wait-off")
        .iter()
        .any(|a| a.iter().any(|&x| (1..=4).contains(&x)));
    assert!(
        walked,
        "with wait_at_oven=false no episode walks while timing"
    );
    let err = cfg.set("wait_at_oven=maybe").unwrap_err().to_string();
    assert!(err.contains("true or false"), "{err}");
}

#[test]
fn timing_agents_respond_in_one_unbroken_run_from_the_first_check_to_the_pickup() {
    // Break-and-run (the default): once a check of the running oven has failed, the agent
    // keeps checking until the soup comes out — so the paper's first oven check (the start
    // of the unbroken run of interacts that ends in the pickup) is the agent's first check.
    // The delay line, seed 1 at TD 20, is the case measured alternating checks and waits
    // (in 92% of trials) before the setting.
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        "timecells-csc",
        1,
    );
    cfg.set("env.td=20").unwrap();
    let eps = interval_actions(&cfg, "run-on");
    assert!(eps.len() >= 40, "{} episodes with a pickup", eps.len());
    let gappy = |a: &Vec<u8>| {
        let first = a
            .iter()
            .position(|&x| x == 5)
            .expect("a pickup is an interact");
        a[first..].iter().any(|&x| x != 5)
    };
    for a in &eps {
        assert!(!gappy(a), "a wait inside the run: {a:?}");
    }
    // Off, the same seed's greedy choices alternate within the run (the setting is applied).
    cfg.set("break_and_run=false").unwrap();
    let off = interval_actions(&cfg, "run-off");
    let broken = off.iter().filter(|a| gappy(a)).count();
    assert!(
        broken * 4 >= off.len(),
        "with break_and_run=false only {broken} of {} runs are broken",
        off.len()
    );
    let err = cfg.set("break_and_run=maybe").unwrap_err().to_string();
    assert!(err.contains("true or false"), "{err}");
}
