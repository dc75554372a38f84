//! `demo`: the README's main command — the built-in demo study (`sweeps/demo.toml`): oracle,
//! random agent, one timing model of each kind and short-budget LSTM / CTRNN agents on fixed
//! interval (three TDs) and bisection; trained, evaluated, recorded and exported in parallel,
//! then compared in one leaderboard. Rerunning skips what is finished.

use anyhow::Result;
use chronocooked_env::fs::write_atomic;
use chronocooked_pipeline::sweep::SweepFile;
use clap::Args;
use std::path::PathBuf;

/// The demo sweep file, built in.
pub const DEMO_SWEEP: &str = include_str!("../../sweeps/demo.toml");

/// Arguments of `demo`.
#[derive(Args, Debug)]
pub struct StudyArgs {
    /// Output folder (job folders and `report/`).
    #[arg(long, default_value = "lab-out/demo")]
    pub out: PathBuf,
    /// Worker processes at once (default: the number of cores).
    #[arg(long)]
    pub workers: Option<usize>,
    /// Override a demo setting, e.g. `--set steps=50000` or `--set episodes=500`
    /// (top-level keys of sweeps/demo.toml; values in TOML syntax).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// List the demo's jobs and whether each is finished, run nothing (as `sweep --dry-run`).
    #[arg(long)]
    pub dry_run: bool,
}

/// The demo sweep text with `key=value` overrides of top-level keys applied.
pub fn demo_sweep(sets: &[String]) -> Result<String> {
    let mut table: toml::Table = DEMO_SWEEP.parse()?;
    for kv in sets {
        let Some((k, v)) = kv.split_once('=') else {
            anyhow::bail!("--set `{kv}` is not key=value (e.g. --set steps=50000)");
        };
        let value: toml::Value = format!("x = {}", v.trim())
            .parse::<toml::Table>()
            .ok()
            .and_then(|t| t.get("x").cloned())
            .unwrap_or_else(|| toml::Value::String(v.trim().to_string()));
        table.insert(k.trim().to_string(), value);
    }
    let text = toml::to_string(&table)?;
    SweepFile::parse(&text, "demo settings")?;
    Ok(text)
}

/// Runs `demo`.
pub fn run(args: StudyArgs) -> Result<()> {
    let text = demo_sweep(&args.sets)?;
    let sweep = SweepFile::parse(&text, "demo")?;
    let workers = args
        .workers
        .unwrap_or_else(crate::cmd::sweep::default_workers);
    if args.dry_run {
        crate::cmd::sweep::print_dry_run(&sweep, &sweep.jobs()?, &args.out, workers);
        return Ok(());
    }
    std::fs::create_dir_all(&args.out)?;
    let file = args.out.join("sweep.toml");
    write_atomic(&file, text.as_bytes())?;
    let file = std::path::absolute(&file)?;
    let t0 = std::time::Instant::now();
    crate::cmd::sweep::run_sweep(&sweep, &file, &args.out, workers, true)?;
    eprintln!(
        "demo finished in {:.0} s; leaderboard: {}",
        t0.elapsed().as_secs_f64(),
        args.out.join("report").join("report.html").display()
    );
    Ok(())
}
