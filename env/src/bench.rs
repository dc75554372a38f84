//! Throughput benchmark of env stepping (single thread): scalar and vectorised,
//! codes and one-hot encodings, uniformly random actions with autoreset.
//!
//! Run with `cargo run --release -- bench env` (see BENCHMARKS.md).

use crate::action::Action;
use crate::env::ChronoEnv;
use crate::error::EnvError;
use crate::kitchen::ResetOptions;
use crate::task::make_config;
use crate::vec_env::{Autoreset, VecEnv};
use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// One measured configuration.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRow {
    /// Task id.
    pub task: String,
    /// `scalar` or `vec<N>`.
    pub mode: String,
    /// `codes` or `onehot`.
    pub encoding: String,
    /// Env steps taken.
    pub steps: u64,
    /// Wall time (s).
    pub seconds: f64,
    /// Env steps per second.
    pub steps_per_sec: f64,
}

#[inline]
fn random_action(rng: &mut Xoshiro256PlusPlus) -> u8 {
    // Multiply-shift maps a u32 to 0..6 (bias < 2e-9).
    ((rng.next_u32() as u64 * Action::COUNT as u64) >> 32) as u8
}

fn timed(min_time: Duration, mut chunk: impl FnMut() -> u64) -> (u64, f64) {
    // Warm-up.
    chunk();
    let start = Instant::now();
    let mut steps = 0;
    while start.elapsed() < min_time {
        steps += chunk();
    }
    (steps, start.elapsed().as_secs_f64())
}

/// Measures every mode for `task_id` (with overrides) for about `seconds` each.
pub fn run(
    task_id: &str,
    overrides: &[String],
    n_envs: usize,
    seconds: f64,
) -> Result<Vec<BenchRow>, EnvError> {
    let config = make_config(task_id, overrides)?;
    let min_time = Duration::from_secs_f64(seconds.max(0.01));
    let mut rows = Vec::new();
    let mut row = |mode: String, encoding: &str, (steps, secs): (u64, f64)| {
        rows.push(BenchRow {
            task: config.id.clone(),
            mode,
            encoding: encoding.to_string(),
            steps,
            seconds: secs,
            steps_per_sec: steps as f64 / secs,
        })
    };

    for onehot in [false, true] {
        let mut env = ChronoEnv::new(&config)?;
        env.reset(Some(1), &ResetOptions::default())?;
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
        let mut buf = vec![0f32; env.onehot_encoder().len()];
        let result = timed(min_time, || {
            const CHUNK: u64 = 100_000;
            for _ in 0..CHUNK {
                let a = Action::ALL[random_action(&mut rng) as usize];
                let t = env.step(a).expect("episode is reset when done");
                if onehot {
                    env.obs_onehot_into(&mut buf);
                    black_box(&buf);
                } else {
                    black_box(env.obs_codes());
                }
                if t.done() {
                    env.reset(None, &ResetOptions::default())
                        .expect("default reset is valid");
                }
            }
            CHUNK
        });
        row(
            "scalar".into(),
            if onehot { "onehot" } else { "codes" },
            result,
        );
    }

    for onehot in [false, true] {
        let mut venv = VecEnv::new(&config, n_envs, Autoreset::SameStep)?;
        venv.reset(1);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
        let mut actions = vec![0u8; n_envs];
        let mut buf = vec![0f32; n_envs * venv.onehot_encoder().len()];
        let result = timed(min_time, || {
            let iters = (200_000 / n_envs).max(1);
            for _ in 0..iters {
                for a in actions.iter_mut() {
                    *a = random_action(&mut rng);
                }
                venv.step(&actions).expect("actions are valid");
                if onehot {
                    venv.write_onehot(&mut buf);
                    black_box(&buf);
                } else {
                    black_box(&venv.obs);
                }
            }
            (iters * n_envs) as u64
        });
        row(
            format!("vec{n_envs}"),
            if onehot { "onehot" } else { "codes" },
            result,
        );
    }
    Ok(rows)
}
