//! Timing agents on multi-oven bisection: one clock per oven, one shared memory of the two
//! anchors. Known answers: every soup goes to the counter of its own oven's duration (the
//! clocks are independent, so what the other ovens hold does not matter), on 2 ovens
//! asynchronous with S 5 / L 11 (a set-up no doc uses), for every mixed combination of
//! durations, from every start cell, on seeds 1–3 of three models.

use chronocooked_env::{ChronoEnv, PerOven, ResetOptions, make_config};
use chronocooked_models::agent::{Agent, run_episode};
use chronocooked_models::timing::train::{TimingTrainConfig, train_timing_agent};
use chronocooked_models::timing::zoo::make_timing_agent;

#[test]
fn each_soup_goes_to_the_counter_of_its_own_ovens_duration() {
    let sets: Vec<String> = ["ovens=2", "asynchronous=true", "short=5", "long=11"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let config = make_config("MultiOven-v0", &sets).unwrap();
    let train = TimingTrainConfig {
        eval_every: 0,
        ..Default::default()
    };
    let mut report = Vec::new();
    for model in ["ddm", "sbf", "timecells-csc"] {
        for seed in 1..=3u64 {
            let env = ChronoEnv::new(&config).unwrap();
            let mut agent = make_timing_agent(model, &env, seed).unwrap();
            train_timing_agent(&mut agent, &config, &train, &[5, 11], seed, |_| {}).unwrap();
            agent.set_training(false);
            let mut env = ChronoEnv::new(&config).unwrap();
            let starts: Vec<(usize, usize)> = env.layout().free_coords();
            let (mut right, mut total) = (0usize, 0usize);
            for (k, &start) in starts.iter().enumerate() {
                for (j, tds) in [[5, 11], [11, 5], [5, 5], [11, 11]].iter().enumerate() {
                    for on_time in [0u32, 3, 6] {
                        let options = ResetOptions {
                            start: Some(start),
                            oven_tds: Some(PerOven::new("oven_tds", tds).unwrap()),
                            on_times: Some(PerOven::new("on_times", &[on_time]).unwrap()),
                            ..Default::default()
                        };
                        let ep_seed = 1000 + (k * 100 + j * 10) as u64 + u64::from(on_time);
                        let rec =
                            run_episode(&mut env, &mut agent, ep_seed, &options, None).unwrap();
                        let ovens = *rec.ovens.last().unwrap();
                        for (i, &td) in tds.iter().enumerate() {
                            let want = if td == 5 { 1 } else { 2 };
                            right += usize::from(ovens.delivered[i] == want);
                            total += 1;
                        }
                    }
                }
            }
            let accuracy = right as f64 / total as f64;
            report.push(format!("{model} seed {seed}: {accuracy:.3}"));
            assert!(accuracy >= 0.9, "{report:#?}");
        }
    }
}
