//! `chronocooked` — the Chronocooked Lab command line (a thin layer over the crates).

mod adapt_cmd;
mod demo;
mod env_cmd;
mod eval_cmd;
mod export_cmd;
mod paper_cmd;
mod play;
mod report_cmd;
mod study;
mod sweep_cmd;
mod timing_cmd;
mod train_cmd;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Chronocooked Lab: interval timing in RL agents and biological timing models.
#[derive(Parser)]
#[command(name = "chronocooked", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Tasks: list, replay action lists, render episodes, play in the terminal.
    Env {
        #[command(subcommand)]
        command: env_cmd::EnvCommand,
    },
    /// The built-in demo study: oracle, random, timing models and short LSTM/CTRNN agents on
    /// FI and bisection — trained, evaluated, recorded, exported — and the leaderboard.
    Demo(study::StudyArgs),
    /// Train a PPO agent or a timing model (run folder with config, curves, model).
    Train(train_cmd::TrainArgs),
    /// Evaluate an agent with its task's protocol: per-episode records + metrics JSON.
    Eval(eval_cmd::EvalArgs),
    /// Uncertainty adaptation: keep training a trained agent on a new task and count the
    /// episodes it needs to adapt.
    Adapt(adapt_cmd::AdaptArgs),
    /// Export activity / evaluation records to NPZ (numpy), CSV and JSON metadata.
    Export(export_cmd::ExportArgs),
    /// Leaderboard (HTML with inline figures, Markdown, CSV) from `eval` folders.
    Report(report_cmd::ReportArgs),
    /// Run a sweep file's jobs in parallel (train → eval → record → export, finished jobs
    /// skipped), then the leaderboard; or `--emit slurm` for a cluster job array.
    Sweep(sweep_cmd::SweepArgs),
    /// One job of a sweep, in this process (what sweep workers and Slurm tasks run).
    #[command(name = "sweep-job", hide = true)]
    SweepJob(sweep_cmd::SweepJobArgs),
    /// Record the neural activity of a trained agent (JSON activity dataset).
    Record(timing_cmd::RecordArgs),
    /// The model zoo: architectures, tasks and presets.
    Zoo {
        #[command(subcommand)]
        command: train_cmd::ZooCommand,
    },
    /// The paper's study: collect a sweep's compact results, analyse them as the paper does
    /// and compare with the paper's numbers.
    Paper {
        #[command(subcommand)]
        command: paper_cmd::PaperCommand,
    },
    /// Benchmarks (`bench env`: env steps/s).
    Bench {
        #[command(subcommand)]
        command: env_cmd::BenchCommand,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Env { command } => env_cmd::run(command),
        Command::Demo(args) => study::run(args),
        Command::Bench { command } => env_cmd::run_bench(command),
        Command::Train(args) => train_cmd::run(args),
        Command::Record(args) => timing_cmd::record(args),
        Command::Eval(args) => eval_cmd::run(args),
        Command::Export(args) => export_cmd::run(args),
        Command::Adapt(args) => adapt_cmd::run(args),
        Command::Report(args) => report_cmd::run(args),
        Command::Sweep(args) => sweep_cmd::run(args),
        Command::SweepJob(args) => sweep_cmd::run_job_cmd(args),
        Command::Zoo { command } => train_cmd::run_zoo(command),
        Command::Paper { command } => paper_cmd::run(command),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
