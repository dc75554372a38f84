//! `record`: the neural activity of any trained agent as an activity dataset (JSON), with
//! heat maps and the neural summary.

use anyhow::Result;
use chronocooked_env::{TaskConfig, make_config};
use chronocooked_models::agent::record_dataset;
use chronocooked_training::eval_tds;
use chronocooked_training::run_dir::write_atomic;
use chronocooked_training::timing_run::load_agent;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `record`.
#[derive(Args, Debug)]
pub struct RecordArgs {
    /// Run folder of a trained agent (PPO or timing model).
    #[arg(long)]
    pub run: PathBuf,
    /// Task to play (default: the run's own task).
    #[arg(long)]
    pub task: Option<String>,
    /// Task overrides `key=value` (with --task).
    #[arg(long = "env", value_name = "KEY=VALUE")]
    pub env: Vec<String>,
    /// Target durations to record (default: the task's evaluation TDs), e.g. `4,6,9,12`.
    #[arg(long, value_delimiter = ',')]
    pub tds: Vec<u32>,
    /// Repetitions of the every-start-cell protocol (different seeds for the model's noise).
    #[arg(long, default_value_t = 1)]
    pub repeats: u64,
    /// Seed of the recording.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output file (JSON activity dataset).
    #[arg(long, default_value = "activity.json")]
    pub out: PathBuf,
    /// Also write the neural summary of every population (fractions of ramping / time /
    /// oscillating units, sequentiality, decoding error) to `<out>.summary.json`.
    #[arg(long)]
    pub summary: bool,
    /// Also write heat maps (activity aligned to oven-on, units sorted by peak time) of every
    /// population with ≥ 2 units into this folder.
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Runs `record`.
pub fn record(args: RecordArgs) -> Result<()> {
    let (task, env) = match &args.task {
        Some(t) => (t.clone(), args.env.clone()),
        None => chronocooked_training::timing_run::run_task(&args.run)?,
    };
    let config: TaskConfig = make_config(&task, &env)?;
    let mut agent = load_agent(&args.run, Some(&config))?;
    let tds = if args.tds.is_empty() {
        eval_tds(&config)
    } else {
        args.tds.clone()
    };
    let dataset = record_dataset(
        agent.as_mut(),
        &config,
        &task,
        &env,
        &tds,
        args.repeats,
        args.seed,
    )?;
    write_atomic(&args.out, &serde_json::to_vec(&dataset)?)?;
    if let Some(dir) = &args.figures {
        chronocooked_analysis::report::figures::neural_figures(&dataset, dir)?;
    }
    if args.summary {
        let summaries: Vec<_> = dataset
            .meta
            .populations
            .iter()
            .filter_map(|p| {
                chronocooked_analysis::neural::summary::neural_summary(
                    &dataset,
                    Some(&p.name),
                    None,
                    args.seed,
                )
            })
            .collect();
        write_atomic(
            &args.out.with_extension("summary.json"),
            serde_json::to_string_pretty(&summaries)?.as_bytes(),
        )?;
    }
    println!(
        "{} trials × {} units of {} on {task} → {}",
        dataset.trials.len(),
        dataset.meta.n_units(),
        dataset.meta.model,
        args.out.display()
    );
    Ok(())
}
