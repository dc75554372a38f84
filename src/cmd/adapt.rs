//! `adapt`: the uncertainty-adaptation protocol — a trained agent keeps learning on a new
//! task (default `Uncertainty-v0`) and the episodes it needs to adapt are counted.

use anyhow::Result;
use chronocooked_pipeline::stages::AdaptRequest;
use chronocooked_training::adapt::{self, AdaptConfig};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `adapt`.
#[derive(Args, Debug)]
pub struct AdaptArgs {
    /// Run folder of the trained agent (PPO or timing model), or a zoo agent
    /// (`zoo:<model>/<task>`).
    #[arg(long)]
    pub run: PathBuf,
    /// Task to adapt to.
    #[arg(long, default_value = "Uncertainty-v0")]
    pub task: String,
    /// Task overrides `key=value` (default: the run's own task settings without
    /// `never_ready_prob` when it was trained on the task to adapt to, else its `td`).
    #[arg(long = "env", value_name = "KEY=VALUE")]
    pub task_params: Vec<String>,
    /// Episodes played by a timing agent (1–10,000,000, the bound of timing-model training
    /// episodes: each episode's outcome is kept).
    #[arg(long, default_value_t = adapt::DEFAULT_EPISODES as u64,
          value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub episodes: u64,
    /// Env steps of PPO fine-tuning.
    #[arg(long, default_value_t = adapt::DEFAULT_STEPS)]
    pub steps: u64,
    /// Window (episodes of every kind) of the success rates.
    #[arg(long, default_value_t = adapt::DEFAULT_WINDOW)]
    pub window: usize,
    /// Success on both the never-ready and the normal ovens of the window that counts as
    /// adapted.
    #[arg(long, default_value_t = adapt::DEFAULT_THRESHOLD)]
    pub threshold: f64,
    /// Exploration of a timing agent while adapting.
    #[arg(long, default_value_t = adapt::DEFAULT_EPSILON)]
    pub epsilon: f64,
    /// Seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output folder (adapt.json, adapt.csv; PPO: the fine-tuning run in run/).
    #[arg(long, default_value = "adapt")]
    pub out: PathBuf,
}

/// Runs `adapt`.
pub fn run(args: AdaptArgs) -> Result<()> {
    let config = AdaptConfig {
        task: chronocooked_env::Task::parse(&args.task, &args.task_params)?,
        episodes: args.episodes as usize,
        steps: args.steps,
        window: args.window,
        threshold: args.threshold,
        epsilon: args.epsilon,
        seed: args.seed,
    };
    let r = chronocooked_pipeline::stages::adapt(&AdaptRequest {
        run: crate::cmd::zoo_agents::resolve_run(&args.run)?,
        config,
        out: args.out.clone(),
    })?;
    println!(
        "{} ({} → {}): {} episodes; never-ready success {:.2} → {:.2} (normal ovens {:.2}); adapted {} → {}",
        r.model,
        r.from_task,
        r.task,
        r.episodes,
        r.initial_success,
        r.final_success,
        r.final_normal_success,
        r.episodes_to_adapt
            .map_or("never".to_string(), |n| format!("after {n} episodes")),
        args.out.join("adapt.json").display()
    );
    Ok(())
}
