//! Scalar env stepping as another crate calls it (the Python bindings, an agent's loop):
//! `N` steps of `FixedInterval-v0` with uniformly random actions and a reset at every
//! episode's end, the loop of `bench env`'s scalar codes row. Built against two commits, the
//! same source measures their env crates through the same caller (BENCHMARKS.md, "Scalar
//! stepping from another crate"); the episode count it prints must agree between them.
//!
//! `cargo run --release --example scalar_step -- 20000000`

use chronocooked_env::{Action, ChronoEnv, ResetOptions, make_config};
use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::hint::black_box;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: u64 = match std::env::args().nth(1) {
        Some(n) => n.parse()?,
        None => 20_000_000,
    };
    let config = make_config::<&str>("FixedInterval-v0", &[])?;
    let mut env = ChronoEnv::new(&config)?;
    env.reset(Some(1), &ResetOptions::default())?;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
    let start = std::time::Instant::now();
    let mut episodes = 0u64;
    for _ in 0..steps {
        // Multiply-shift maps a u32 to 0..6 (as `bench env`).
        let a = Action::ALL[((u64::from(rng.next_u32()) * 6) >> 32) as usize];
        let t = env.step(a)?;
        black_box(env.obs_codes());
        if t.done() {
            env.reset(None, &ResetOptions::default())?;
            episodes += 1;
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{steps} steps, {episodes} episodes: {:.1} M steps/s",
        steps as f64 / seconds / 1e6
    );
    Ok(())
}
