//! `record`: the neural activity of any trained agent as an activity dataset (JSON), with
//! heat maps and the neural summary.
//!
//! The neural summary is meant for peak-interval probe trials: `record --probe --summary
//! --run RUN_TD6 --run RUN_TD12` plays each fixed-interval run on probe trials (soup
//! withheld) at its own TD and summarises windows of 2 x TD steps after oven-on.

use anyhow::Result;
use chronocooked_pipeline::stages::RecordRequest;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `record`.
#[derive(Args, Debug)]
pub struct RecordArgs {
    /// Run folder of a trained agent (PPO or timing model) or a zoo agent
    /// (`zoo:<model>/<task>`). Repeat it (`--run A --run B`) to
    /// record runs of the same model trained at different TDs into one dataset (each at its
    /// own TD unless --tds): the summary then measures temporal scaling between TDs.
    #[arg(long, required = true, num_args = 1..)]
    pub run: Vec<PathBuf>,
    /// Play peak-interval probe trials (PeakInterval-v0 with the run's settings and
    /// probe_factor=0: the soup is never released), so every trial lasts at least 2 x TD
    /// steps after oven-on (runs trained on FixedInterval-v0 / PeakInterval-v0). The
    /// documented way to get a neural summary.
    #[arg(long)]
    pub probe: bool,
    /// Task to play (default: the run's own task).
    #[arg(long)]
    pub task: Option<String>,
    /// Task parameters `key=value` of --task.
    #[arg(long = "env", value_name = "KEY=VALUE", requires = "task")]
    pub task_params: Vec<String>,
    /// Target durations to record (default: the task's evaluation TDs; with --probe each
    /// run's own TD), e.g. `4,6,9,12`. An agent trained on one fixed interval cannot tell
    /// probe trials of different TDs apart: record one run per TD instead.
    #[arg(long, value_delimiter = ',')]
    pub tds: Vec<u32>,
    /// Repetitions of the every-start-cell protocol (different seeds for the model's noise),
    /// 1–100: a repeat of an SBF agent (1,000 oscillators) holds ≈ 2.5 MB of activity per TD
    /// in memory; 100 repeats (≈ 1,000 trials per TD) are well beyond what the summaries need.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=chronocooked_pipeline::stages::record::MAX_REPEATS))]
    pub repeats: u64,
    /// Seed of the recording.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output file (JSON activity dataset).
    #[arg(long, default_value = "activity.json")]
    pub out: PathBuf,
    /// Also write the neural summary of every population to `<out>.summary.json`: per TD a
    /// window of 2 x TD steps after oven-on with the units' categories (ramp, time_field,
    /// oscillating, mixed, untuned, beyond_window: counts, Wilson 95% intervals, fractions
    /// from 10 units), trajectory speed, sequentiality and decoding error; with two or more TDs the median
    /// per-unit scaling factor and speed ratio between the shortest and the longest.
    #[arg(long)]
    pub summary: bool,
    /// Also write heat maps (activity aligned to oven-on, units sorted by peak time) of every
    /// population with ≥ 2 units into this folder.
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Runs `record`.
pub fn record(args: RecordArgs) -> Result<()> {
    let runs = args
        .run
        .iter()
        .map(|r| crate::cmd::zoo_agents::resolve_run(r))
        .collect::<Result<Vec<_>>>()?;
    let r = chronocooked_pipeline::stages::record(&RecordRequest {
        run: runs[0].clone(),
        more_runs: runs[1..].to_vec(),
        probe: args.probe,
        task: args
            .task
            .as_deref()
            .map(|t| chronocooked_env::Task::parse(t, &args.task_params))
            .transpose()?,
        tds: args.tds.clone(),
        repeats: args.repeats,
        seed: args.seed,
        out: args.out.clone(),
        summary: args.summary,
        figures: args.figures.clone(),
    })?;
    let populations: Vec<String> = r
        .populations
        .iter()
        .map(|(name, size)| format!("{name} {size}"))
        .collect();
    println!(
        "{} trials × {} units ({}) of {} on {} → {}",
        r.trials,
        r.units,
        populations.join(" + "),
        r.model,
        r.task,
        args.out.display()
    );
    Ok(())
}
