//! `export`: activity datasets and evaluation records to NPZ (numpy), CSV and a JSON
//! metadata file describing every array.

use anyhow::{Context, Result, bail};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Activity dataset written by `record` (JSON).
    #[arg(long, conflicts_with = "run")]
    pub activity: Option<PathBuf>,
    /// A trained agent's run folder or a zoo agent (`zoo:<model>/<task>`): evaluated with
    /// its activity into `<out>/eval/` (the reference protocol of its own task, seed 0),
    /// then exported like `--activity <out>/eval/activity.json --eval <out>/eval`.
    #[arg(long, conflicts_with = "eval")]
    pub run: Option<PathBuf>,
    /// Evaluation folder written by `eval` (its records.jsonl).
    #[arg(long)]
    pub eval: Option<PathBuf>,
    /// Longest window (steps after oven-on) of the aligned activity array.
    #[arg(long, default_value_t = 200)]
    pub window: usize,
    /// Output folder.
    #[arg(long, default_value = "export")]
    pub out: PathBuf,
    /// `npz` (NPZ + CSV + JSON metadata) or `nwb`: also one NWB file `<out>/run.nwb` of the
    /// activity (from `eval --activity` or the Python `evaluate`) with the episodes of
    /// `--eval` — written by the Python package (`pip install './python[nwb]'`).
    #[arg(long, default_value = "npz", value_parser = ["npz", "nwb"])]
    pub format: String,
    /// Python interpreter with the `chronocooked` package (NWB export); default
    /// `$CHRONOCOOKED_PYTHON`, else `.venv/bin/python` when present, else `python3`.
    #[arg(long)]
    pub python: Option<PathBuf>,
}

/// The interpreter for the NWB export.
fn python(args: &ExportArgs) -> PathBuf {
    if let Some(p) = &args.python {
        return p.clone();
    }
    if let Some(p) = std::env::var_os("CHRONOCOOKED_PYTHON") {
        return PathBuf::from(p);
    }
    let venv = PathBuf::from(".venv/bin/python");
    if venv.is_file() {
        venv
    } else {
        PathBuf::from("python3")
    }
}

/// Writes `<out>/run.nwb` through the Python package (`python -m chronocooked.nwb`).
fn export_nwb(args: &ExportArgs) -> Result<PathBuf> {
    let (Some(_), Some(eval)) = (&args.activity, &args.eval) else {
        bail!(
            "--format nwb needs --activity FILE.json (from `eval --activity` or the Python `evaluate`) and --eval DIR of the same run"
        );
    };
    let py = python(args);
    let probe = std::process::Command::new(&py)
        .args(["-c", "import chronocooked.nwb, pynwb"])
        .output();
    match probe {
        Ok(o) if o.status.success() => {}
        Ok(o) => bail!(
            "the NWB export needs the Python package with pynwb, which {} cannot import ({}): \
             install it with `pip install './python[nwb]'` (or run `bash scripts/test.sh`, which \
             builds .venv), or name an interpreter with --python",
            py.display(),
            String::from_utf8_lossy(&o.stderr)
                .trim()
                .lines()
                .last()
                .unwrap_or("")
        ),
        Err(e) => bail!(
            "the NWB export needs a Python interpreter with the `chronocooked` package: {} ({e}); \
             install it with `pip install './python[nwb]'` or name one with --python",
            py.display()
        ),
    }
    let target = args.out.join("run.nwb");
    let status = std::process::Command::new(&py)
        .args(["-m", "chronocooked.nwb", "--overwrite"])
        .arg(args.out.join("activity.npz"))
        .arg(eval)
        .arg(&target)
        .stdout(std::process::Stdio::null())
        .status()
        .with_context(|| format!("running {}", py.display()))?;
    if !status.success() {
        bail!("the NWB export failed (see the message above)");
    }
    Ok(target)
}

/// Runs `export`.
pub fn run(mut args: ExportArgs) -> Result<()> {
    if let Some(run) = &args.run {
        use chronocooked_pipeline::stages::{EvalRequest, EvalSubject, evaluate};
        let out = args.out.join("eval");
        let outcome = evaluate(&EvalRequest {
            subject: EvalSubject::Run(crate::cmd::zoo_agents::resolve_run(run)?),
            task: None,
            mode: chronocooked_analysis::Mode::Reference,
            seed: 0,
            out: out.clone(),
            activity: true,
            unfinished: false,
        })?;
        args.activity = outcome.activity.map(|a| a.2);
        args.eval = Some(out);
    }
    let mut files = chronocooked_pipeline::stages::export(
        args.activity.as_deref(),
        args.eval.as_deref(),
        args.window,
        &args.out,
    )?;
    if args.format == "nwb" {
        files.push(export_nwb(&args)?);
    }
    for f in files {
        println!("{}", f.display());
    }
    Ok(())
}
