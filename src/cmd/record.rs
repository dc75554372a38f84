//! `record`: the neural activity of any trained agent as an activity dataset (JSON), with
//! heat maps and the neural summary.

use anyhow::Result;
use chronocooked_pipeline::stages::RecordRequest;
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
    let r = chronocooked_pipeline::stages::record(&RecordRequest {
        run: args.run.clone(),
        task: args.task.clone(),
        env: args.env.clone(),
        tds: args.tds.clone(),
        repeats: args.repeats,
        seed: args.seed,
        out: args.out.clone(),
        summary: args.summary,
        figures: args.figures.clone(),
    })?;
    println!(
        "{} trials × {} units of {} on {} → {}",
        r.trials,
        r.units,
        r.model,
        r.task,
        args.out.display()
    );
    Ok(())
}
