//! `export`: activity datasets and evaluation records to NPZ (numpy), CSV and a JSON
//! metadata file describing every array.

use anyhow::{Context, Result, bail};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// Activity dataset written by `record` (JSON).
    #[arg(long)]
    pub activity: Option<PathBuf>,
    /// Evaluation folder written by `eval` (its records.jsonl).
    #[arg(long)]
    pub eval: Option<PathBuf>,
    /// Longest window (steps after oven-on) of the aligned activity array.
    #[arg(long, default_value_t = 200)]
    pub window: usize,
    /// Output folder.
    #[arg(long, default_value = "export")]
    pub out: PathBuf,
}

/// Runs `export`.
pub fn run(args: ExportArgs) -> Result<()> {
    if args.activity.is_none() && args.eval.is_none() {
        bail!(
            "say what to export: --activity FILE.json (from `record`) and/or --eval DIR (from `eval`)"
        );
    }
    let mut files = Vec::new();
    if let Some(path) = &args.activity {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let ds: chronocooked_models::ActivityDataset =
            serde_json::from_str(&text).with_context(|| {
                format!(
                    "{} is not an activity dataset (from `record`)",
                    path.display()
                )
            })?;
        files.extend(
            chronocooked_analysis::export::export_activity(&ds, &args.out, args.window)
                .map_err(anyhow::Error::msg)?,
        );
    }
    if let Some(dir) = &args.eval {
        let records = chronocooked_analysis::protocol::read_records(dir)
            .map_err(|e| anyhow::anyhow!("{e} (not an eval folder)"))?;
        files.extend(
            chronocooked_analysis::export::export_eval(&records, &args.out)
                .map_err(anyhow::Error::msg)?,
        );
    }
    for f in files {
        println!("{}", f.display());
    }
    Ok(())
}
