//! The timing models learn the reproduction task (Ready-Set-Go) on a prior no doc uses
//! (9–15 steps, one prior, no cue), productions measured over episodes from every start
//! cell at every `ts` of the prior. Known answers from the mechanisms:
//! * drift-diffusion (one-shot drift learning at Set) and SBF (the pattern stored at Set)
//!   reproduce the trial's own measurement: mean `tp/ts` within 0.8–1.2 at every `ts` (the
//!   issue's criterion), nearly every episode produces, and the slope of the mean `tp` on
//!   `ts` is 1 within 0.15 — no regression to the mean. Their production is the clock's,
//!   not a learned value, so they train for 20,000 episodes (the way to the oven and the
//!   counter), a third of the run default, to keep the suite short;
//! * the time cells (delay line, microstimuli, Laplace) learn the production by TD with
//!   their run defaults, whose values average the rewards over every `ts` that gave a
//!   similar population at Set: a learned prior, so the slope is below 0.9 (an ideal
//!   observer with the model's clock noise, 0.15, and this reward has a slope near 0.5 and
//!   produces 1.11 … 0.90 × `ts` from the short to the long end), and still within 0.8–1.2
//!   at every `ts`. The delay line's conjunctive code has a feature per (measurement, time)
//!   pair, and the run default's visit-count step floor (`visit_power`) lets the pairs
//!   tried late learn from their first samples; without it the delay line produced 0.77–0.79
//!   × `ts` at the long end of the priors 10–16 and 15–21 (RESULTS, "The 0.8–1.2 criterion").

use chronocooked_env::{ChronoEnv, ResetOptions};
use chronocooked_models::agent::{Agent, run_episode};
use chronocooked_models::timing::train::train_timing_agent;
use chronocooked_training::TimingRunConfig;

/// Per `ts` of the prior: mean `tp/ts` and the share of episodes that produced.
struct Productions {
    ratios: Vec<(u32, f64, f64)>,
    slope: f64,
}

fn productions(model: &str, seed: u64, episodes: Option<usize>) -> Productions {
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("Reproduction-v0").unwrap(),
        model,
        seed,
    );
    cfg.set("env.priors=9-15").unwrap();
    if let Some(n) = episodes {
        cfg.train.episodes = n;
    }
    cfg.train.eval_every = 0;
    let config = cfg.task.config().unwrap();
    let mut agent = cfg.build_agent().unwrap();
    train_timing_agent(&mut agent, &config, &cfg.train, &[], seed, |_| {}).unwrap();
    agent.set_training(false);
    let mut env = ChronoEnv::new(&config).unwrap();
    let starts: Vec<(usize, usize)> = env.layout().free_coords();
    let mut ratios = Vec::new();
    for ts in 9..=15u32 {
        let (mut sum, mut produced, mut total) = (0.0, 0usize, 0usize);
        for (k, &start) in starts.iter().enumerate() {
            for draw in 0..8u64 {
                let options = ResetOptions {
                    start: Some(start),
                    td: Some(ts),
                    ..Default::default()
                };
                let ep_seed = 10_000 + u64::from(ts) * 1000 + k as u64 * 10 + draw;
                let rec = run_episode(&mut env, &mut agent, ep_seed, &options, None).unwrap();
                total += 1;
                let tp = rec.infos.last().map_or(-1, |i| i.oven_off_time);
                if tp > 0 {
                    produced += 1;
                    sum += f64::from(tp) / f64::from(ts);
                }
            }
        }
        ratios.push((
            ts,
            sum / produced.max(1) as f64,
            produced as f64 / total as f64,
        ));
    }
    // Least-squares slope of the mean tp on ts.
    let pts: Vec<(f64, f64)> = ratios
        .iter()
        .map(|&(ts, r, _)| (f64::from(ts), r * f64::from(ts)))
        .collect();
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    Productions {
        ratios,
        slope: sxy / sxx,
    }
}

fn describe(model: &str, seed: u64, p: &Productions) -> String {
    let rows: Vec<String> = p
        .ratios
        .iter()
        .map(|(ts, r, share)| format!("ts {ts}: tp/ts {r:.2}, produced {share:.2}"))
        .collect();
    format!("{model} seed {seed}: slope {:.2}, {rows:?}", p.slope)
}

#[test]
fn clocks_that_keep_the_trials_measurement_reproduce_it_without_regression() {
    let mut failures = Vec::new();
    for model in ["ddm", "sbf"] {
        for seed in 1..=2 {
            let p = productions(model, seed, Some(20_000));
            let ok = p
                .ratios
                .iter()
                .all(|&(_, r, share)| (0.8..=1.2).contains(&r) && share >= 0.95)
                && (p.slope - 1.0).abs() <= 0.15;
            if !ok {
                failures.push(describe(model, seed, &p));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Trains `model` (time cells) with its run defaults and checks the learned prior and the
/// issue's criterion.
fn time_cells_reproduce_with_a_prior(model: &str) {
    let mut failures = Vec::new();
    for seed in 1..=2 {
        let p = productions(model, seed, None);
        let ok = p
            .ratios
            .iter()
            .all(|&(_, r, share)| (0.8..=1.2).contains(&r) && share >= 0.95)
            && p.slope < 0.9;
        if !ok {
            failures.push(describe(model, seed, &p));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn delay_line_time_cells_learn_the_production_with_a_prior() {
    time_cells_reproduce_with_a_prior("timecells-csc");
}

#[test]
fn microstimulus_time_cells_learn_the_production_with_a_prior() {
    time_cells_reproduce_with_a_prior("timecells-ms");
}

#[test]
fn laplace_time_cells_learn_the_production_with_a_prior() {
    time_cells_reproduce_with_a_prior("timecells-laplace");
}
