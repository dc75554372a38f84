//! `chronocooked` — the Chronocooked Lab command line (a thin layer over the crates), as a
//! library: the binary is [`run`]; a program that registers its own task family
//! (`chronocooked_env::task::family::register`) runs the same command line with its task
//! known (the `interval_production` example).

mod cmd;

use cmd::{
    adapt, bench, demo, env, eval, export, fingerprint, mechanisms, paper, record, report, sweep,
    train, verify, zoo,
};

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
        command: env::EnvCommand,
    },
    /// The built-in demo study: oracle, random, timing models and short LSTM/CTRNN agents on
    /// FI and bisection — trained, evaluated, recorded, exported — and the leaderboard.
    Demo(demo::StudyArgs),
    /// Train a PPO agent or a timing model (run folder with config, curves, model).
    Train(train::TrainArgs),
    /// Evaluate an agent with its task's protocol: per-episode records + metrics JSON.
    Eval(eval::EvalArgs),
    /// Uncertainty adaptation: keep training a trained agent on a new task and count the
    /// episodes it needs to adapt.
    Adapt(adapt::AdaptArgs),
    /// Export activity / evaluation records to NPZ (numpy), CSV and JSON metadata.
    Export(export::ExportArgs),
    /// Leaderboard (HTML with inline figures, Markdown, CSV) from `eval` folders.
    Report(report::ReportArgs),
    /// Run a sweep file's jobs in parallel (train → eval → record → export, finished jobs
    /// skipped), then the leaderboard; or `--emit slurm` for a cluster job array.
    Sweep(sweep::SweepArgs),
    /// One job of a sweep, in this process (what sweep workers and Slurm tasks run).
    #[command(name = "sweep-job", hide = true)]
    SweepJob(sweep::SweepJobArgs),
    /// Record the neural activity of a trained agent (JSON activity dataset).
    Record(record::RecordArgs),
    /// The model zoo: architectures, tasks and presets.
    Zoo {
        #[command(subcommand)]
        command: zoo::ZooCommand,
    },
    /// Mechanism fingerprints of a study's compact results: each model's behavioural and
    /// neural signatures and, per trained agent, the distance to every timing mechanism and
    /// the nearest one (bootstrap over seeds).
    Mechanisms(mechanisms::MechanismsArgs),
    /// Which timing mechanism does one agent resemble? Its runs (fixed interval TD 6 and
    /// TD 12, bisection 4-12) play the mechanisms protocol; its signature is placed among
    /// the committed timing mechanisms, each distance beside that mechanism's own seeds'.
    Fingerprint(fingerprint::FingerprintArgs),
    /// Re-derives what a run, an evaluation, a sweep's results or a zoo agent claims from
    /// what determines it (configuration, seed, learned state, records) and names every
    /// difference: file, field, recorded value, re-derived value.
    Verify(verify::VerifyArgs),
    /// Print the command-line reference (Markdown, `docs/cli.md`) generated from this parser.
    #[command(name = "cli-reference")]
    CliReference,
    /// The paper's study: collect a sweep's compact results, analyse them as the paper does
    /// and compare with the paper's numbers.
    Paper {
        #[command(subcommand)]
        command: paper::PaperCommand,
    },
    /// Benchmarks (`bench env`: env steps/s).
    Bench {
        #[command(subcommand)]
        command: bench::BenchCommand,
    },
}

/// Ends the process quietly when a reader of its output goes away (`chronocooked zoo show |
/// head`), as command-line tools do, instead of panicking in `println!` on a broken pipe:
/// the default action of SIGPIPE, which Rust's runtime sets to "ignore".
fn restore_default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread is spawned; `signal` with
    // `SIG_DFL` only resets the disposition of SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// A full disk (or a closed file) under stdout or stderr makes `println!` / `eprintln!`
/// panic; such a process ends with the error status 2 and without the panic's message and
/// backtrace, which it could not write either (a sweep worker's log on a full disk). Every
/// other panic keeps the default report.
fn quiet_exit_when_output_fails() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or_default();
        if message.starts_with("failed printing to std") {
            std::process::exit(2);
        }
        default(info);
    }));
}

/// SIGINT / SIGTERM: recorded for a loop that can stop cleanly (training saves a checkpoint,
/// a sweep stops its workers), the default action (the process ends) otherwise, and on a
/// second signal (see `chronocooked_env::interrupt`).
#[cfg(unix)]
extern "C" fn on_stop_signal(signal: libc::c_int) {
    if !chronocooked_env::interrupt::deliver(signal) {
        // SAFETY: `signal` and `raise` are async-signal-safe; the default action ends us.
        unsafe {
            libc::signal(signal, libc::SIG_DFL);
            libc::raise(signal);
        }
    }
}

fn install_stop_handlers() {
    #[cfg(unix)]
    // SAFETY: called once at start-up, before any thread is spawned; the handler only
    // touches atomics and async-signal-safe calls.
    unsafe {
        let handler = on_stop_signal as extern "C" fn(libc::c_int) as libc::sighandler_t;
        for signal in [libc::SIGINT, libc::SIGTERM] {
            // A signal the parent ignores (`nohup`, a background job's SIGINT) stays ignored.
            if libc::signal(signal, handler) == libc::SIG_IGN {
                libc::signal(signal, libc::SIG_IGN);
            }
        }
    }
}

/// Parses the process arguments and runs the command: the `chronocooked` binary. Returns
/// the exit status (0, or 2 with the error on stderr; a signal's conventional status after
/// a clean stop).
pub fn run() -> ExitCode {
    restore_default_sigpipe();
    quiet_exit_when_output_fails();
    install_stop_handlers();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Env { command } => env::run(command),
        Command::Demo(args) => demo::run(args),
        Command::Bench { command } => bench::run_bench(command),
        Command::Train(args) => train::run(args),
        Command::Record(args) => record::record(args),
        Command::Eval(args) => eval::run(args),
        Command::Export(args) => export::run(args),
        Command::Adapt(args) => adapt::run(args),
        Command::Report(args) => report::run(args),
        Command::Sweep(args) => sweep::run(args),
        Command::SweepJob(args) => sweep::run_job_cmd(args),
        Command::Zoo { command } => zoo::run_zoo(command),
        Command::Paper { command } => paper::run(command),
        Command::Mechanisms(args) => mechanisms::run(args),
        Command::Fingerprint(args) => fingerprint::run(args),
        Command::Verify(args) => verify::run(args),
        Command::CliReference => {
            use clap::CommandFactory;
            print!("{}", cmd::cli_reference::markdown(&Cli::command()));
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            // A clean stop on a signal exits with the signal's conventional status.
            match chronocooked_env::interrupt::requested() {
                Some(signal) => ExitCode::from(chronocooked_env::interrupt::exit_status(signal)),
                None => ExitCode::from(2),
            }
        }
    }
}
