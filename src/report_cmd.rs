//! `report`: the leaderboard (HTML with inline SVG figures, Markdown, CSV) from `eval`
//! output folders; folders of the same model are aggregated (mean ± SD).

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// `eval` output folders (any number; the same model's folders are aggregated).
    #[arg(long = "eval", value_name = "DIR", num_args = 1..)]
    pub evals: Vec<PathBuf>,
    /// Output folder (report.html, report.md, report.csv).
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
}

/// Runs `report`.
pub fn run(args: ReportArgs) -> Result<()> {
    if args.evals.is_empty() {
        bail!("give the evaluation folders to compare: --eval DIR [DIR ...] (from `eval`)");
    }
    let rows = chronocooked_analysis::report::load_rows(&args.evals).map_err(anyhow::Error::msg)?;
    for f in
        chronocooked_analysis::report::write_report(&rows, &args.out).map_err(anyhow::Error::msg)?
    {
        println!("{}", f.display());
    }
    Ok(())
}
