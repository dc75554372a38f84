//! `bench`: env steps/s, PPO training env-steps/s and timing-model trials/s.

use anyhow::{Result, bail};
use chronocooked_env::{bench, find_task, make_config};
use chronocooked_models::agent::record_dataset;
use chronocooked_models::timing::zoo::{TIMING_MODELS, make_timing_agent};
use chronocooked_models::{Architecture, evaluate_agent};
use chronocooked_training::resolve;
use clap::Subcommand;

/// `bench` subcommands.
#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Env steps/s on one thread: scalar and vectorised, codes and one-hot, random actions.
    Env {
        /// Task id.
        #[arg(long, default_value = "FixedInterval-v0")]
        task: String,
        /// Parameter overrides `key=value`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Envs in the vectorised runs.
        #[arg(long, default_value_t = 256)]
        n_envs: usize,
        /// Seconds per measurement.
        #[arg(long, default_value_t = 3.0)]
        seconds: f64,
        /// Print JSON lines instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// PPO training env-steps/s (rollout + optimisation) per model on one task.
    Train {
        /// Task id.
        #[arg(long, default_value = "FixedInterval-v0")]
        task: String,
        /// Models to measure (comma-separated).
        #[arg(long, default_value = "cnn-mlp,lstm125,ctrnn125")]
        models: String,
        /// Preset.
        #[arg(long, default_value = "reference")]
        preset: String,
        /// Updates measured per model (after one warm-up update).
        #[arg(long, default_value_t = 5)]
        updates: u64,
        /// Extra settings `key=value`.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Timing-model trials/s on a 12-step FI trial (after brief training), recording off/on.
    Timing {
        /// Trials measured per model and setting.
        #[arg(long, default_value_t = 20000)]
        trials: usize,
    },
}

/// Runs a `bench` subcommand.
pub fn run_bench(cmd: BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Train {
            task,
            models,
            preset,
            updates,
            set,
        } => bench_train(&task, &models, &preset, updates, &set),
        BenchCommand::Timing { trials } => bench_timing(trials),
        BenchCommand::Env {
            task,
            set,
            n_envs,
            seconds,
            json,
        } => {
            find_task(&task)?;
            make_config(&task, &set)?;
            if n_envs == 0 {
                bail!("--n-envs must be >= 1");
            }
            let rows = bench::run(&task, &set, n_envs, seconds)?;
            for r in rows {
                if json {
                    println!("{}", serde_json::to_string(&r)?);
                } else {
                    println!(
                        "{:<18} {:<8} {:<7} {:>14.0} steps/s  ({} steps in {:.2} s)",
                        r.task, r.mode, r.encoding, r.steps_per_sec, r.steps, r.seconds
                    );
                }
            }
            Ok(())
        }
    }
}

/// `bench train`: mean env-steps/s over `updates` PPO updates (after one warm-up) per model.
pub fn bench_train(
    task: &str,
    models: &str,
    preset: &str,
    updates: u64,
    sets: &[String],
) -> Result<()> {
    for name in models.split(',').map(str::trim).filter(|m| !m.is_empty()) {
        let arch: Architecture = name.parse().map_err(anyhow::Error::msg)?;
        let mut cfg = resolve(task, arch, preset, 0, sets)?;
        // The budget the bench plays: a warm-up update and `updates` measured ones (a
        // budget beyond them would be refused by the settings' bounds, not used).
        let batch_steps = (cfg.ppo.n_envs * cfg.ppo.n_steps) as u64;
        cfg.total_steps = batch_steps.saturating_mul(updates.max(1) + 1);
        let batch = batch_steps as f64;
        let engine = format!("{:?}", cfg.ppo.engine).to_ascii_lowercase();
        let mut trainer =
            chronocooked_training::Trainer::new(chronocooked_training::Check::check(cfg)?)?;
        trainer.update()?;
        let (mut secs, mut roll, mut opt) = (0.0, 0.0, 0.0);
        for _ in 0..updates.max(1) {
            let r = trainer.update()?;
            secs += batch / r.steps_per_s;
            roll += r.rollout_s;
            opt += r.optimize_s;
        }
        let n = updates.max(1) as f64;
        println!(
            "{task:<18} {:<10} {preset:<9} {engine:<6} {:>8.0} env-steps/s  ({:.3} s/update: rollout {:.3} s, optimise {:.3} s; {} updates)",
            arch.name(),
            batch * n / secs,
            secs / n,
            roll / n,
            opt / n,
            updates.max(1)
        );
    }
    Ok(())
}

/// `bench timing`: trials/s of every timing model on a 12-step FI trial, recording off/on.
pub fn bench_timing(trials: usize) -> Result<()> {
    if trials == 0 {
        bail!("--trials must be positive");
    }
    let task = chronocooked_env::Task::parse("FixedInterval-v0", &["td=12"])?;
    let config = task.config()?;
    let env = chronocooked_env::ChronoEnv::new(&config)?;
    for m in TIMING_MODELS {
        let mut agent = make_timing_agent(m.name, &env, 0).map_err(anyhow::Error::msg)?;
        // Train briefly so that trials are the real, timed behaviour.
        let train = chronocooked_models::TimingTrainConfig {
            episodes: 1500,
            eval_every: 0,
            ..Default::default()
        };
        chronocooked_models::train_timing_agent(&mut agent, &config, &train, &[12], 0, |_| {})?;
        let free = env.layout().free_cells().len();
        let reps = trials.div_ceil(free).max(1);
        let mut rates = Vec::new();
        for recording in [false, true] {
            let t0 = std::time::Instant::now();
            let mut n = 0;
            for r in 0..reps {
                if recording {
                    let ds = record_dataset(&mut agent, &config, &task, &[12], 1, r as u64)?;
                    n += ds.trials.len();
                } else {
                    n += evaluate_agent(&mut agent, &config, &[12], r as u64, None)?.len();
                }
            }
            rates.push(n as f64 / t0.elapsed().as_secs_f64());
        }
        println!(
            "{:<20} {:>10.0} trials/s  recording on: {:>10.0} trials/s",
            m.name, rates[0], rates[1]
        );
    }
    Ok(())
}
