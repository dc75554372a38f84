//! The reproduction protocol plays each context's sample intervals in random order
//! (Jazayeri & Shadlen 2010), so a model with a memory from trial to trial shows the
//! regression it predicts. Known answer: drift-diffusion without noise and with a drift
//! learning rate `α` at Set keeps the running average `A_n = (1 − α) A_{n−1} + α z/ts_n`, so
//! its production `z/A_n` mixes the trial's interval with the earlier ones — the slope of the
//! mean `tp` on `ts` is about `α` when the trials mix, and 1 when one `ts` follows another
//! (the memory settles on it). With `α` 0.5 the slope must be below 0.75.

use chronocooked_analysis::{Mode, compute_metrics, reference_conditions, run_protocol};
use chronocooked_env::{ChronoEnv, make_config};
use chronocooked_models::agent::Agent;
use chronocooked_models::timing::timers::Timer;
use chronocooked_models::timing::train::{TimingTrainConfig, train_timing_agent};
use chronocooked_models::timing::zoo::make_timing_agent;

#[test]
fn interleaved_sample_intervals_reveal_a_memory_averaging_clocks_regression() {
    let sets = vec!["priors=9-15".to_string()];
    let config = make_config("Reproduction-v0", &sets).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    let mut agent = make_timing_agent("ddm", &env, 5).unwrap();
    let alpha = 0.5;
    if let Timer::Ddm(d) = &mut agent.timer {
        d.acc.noise = 0.0;
        d.memory_noise = 0.0;
        d.reproduction_rate = alpha;
    }
    let train = TimingTrainConfig {
        eval_every: 0,
        ..Default::default()
    };
    train_timing_agent(&mut agent, &config, &train, &[], 5, |_| {}).unwrap();
    agent.set_training(false);
    let conds =
        reference_conditions(&chronocooked_env::Task::parse("Reproduction-v0", &sets).unwrap())
            .unwrap();
    let recs = run_protocol(&mut agent, &conds, Mode::Reference, 9).unwrap();
    // The order mixes the intervals: not one run per ts.
    let played: Vec<u32> = recs.iter().map(|r| r.condition.td).collect();
    let runs = 1 + played.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(
        runs > played.len() / 2,
        "{runs} runs of {} trials",
        played.len()
    );
    let m = compute_metrics("ddm", &recs, 0).reproduction.unwrap();
    let c = &m.contexts[0];
    assert_eq!(c.failures, 0);
    let slope = c.slope.unwrap();
    assert!(
        slope > 0.25 && slope < 0.75,
        "slope {slope:.3} (about {alpha} expected)"
    );
}

#[test]
fn a_gain_contexts_bias_is_measured_against_its_target() {
    // The oracle takes the soup at the target g·ts rounded to a whole step: its BIAS
    // against the target is under half a step, and its slope per step of ts is g. (Against
    // ts itself a veridical gain of 1.5 reads as a BIAS of half the prior's mean.)
    use chronocooked_models::agent::OracleAgent;
    let sets = vec!["gains=1,1.5".to_string(), "priors=10-16".to_string()];
    let env = ChronoEnv::from_id("Reproduction-v0", &sets).unwrap();
    let mut oracle = OracleAgent::new(&env);
    let conds =
        reference_conditions(&chronocooked_env::Task::parse("Reproduction-v0", &sets).unwrap())
            .unwrap();
    let recs = run_protocol(&mut oracle, &conds, Mode::Reference, 4).unwrap();
    let all = compute_metrics("oracle", &recs, 0);
    // The leaderboard's columns: every production in its window, slope per unit of g·ts 1
    // at both gains.
    let h = chronocooked_analysis::columns::headline(&all);
    assert_eq!(h["rp_success"], 1.0);
    assert!((h["rp_slope"] - 1.0).abs() < 0.07, "{h:?}");
    assert!(h["rp_bias"] < 0.5, "{h:?}");
    let m = all.reproduction.unwrap();
    assert_eq!(m.contexts.len(), 2);
    for c in &m.contexts {
        let (bias, slope) = (c.bias.unwrap(), c.slope.unwrap());
        assert!(bias < 0.5, "gain {}: BIAS {bias:.3}", c.gain);
        assert!(
            (slope - c.gain).abs() < 0.1,
            "gain {}: slope {slope:.3}",
            c.gain
        );
    }
}
