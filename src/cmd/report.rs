//! `report`: the leaderboard (HTML with inline SVG figures, Markdown, CSV) from `eval`
//! output folders, or from any run / sweep folders holding them; folders of the same model
//! are aggregated (mean ± SD), with the neural summaries recorded next to them; with
//! `--baselines`, the committed study results (default `results/paper-core`) as marked
//! baseline rows beside them.

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `report`.
#[derive(Args, Debug)]
pub struct ReportArgs {
    /// `eval` output folders (any number; the same model's folders are aggregated).
    #[arg(long = "eval", value_name = "DIR", num_args = 1..)]
    pub evals: Vec<PathBuf>,
    /// Run or sweep folders searched for `eval` folders (e.g. a sweep's output, or several
    /// sweeps' outputs to merge them into one report).
    #[arg(long = "runs", value_name = "DIR", num_args = 1..)]
    pub runs: Vec<PathBuf>,
    /// Committed baselines: compact study results folders (`results/<study>`, the
    /// `jobs/` layout of `paper collect`) shown as marked rows, one per model, size and
    /// variant; the flag alone adds the committed `results/paper-core` (found from the
    /// current folder or the program's location, or `$CHRONOCOOKED_BASELINES`).
    #[arg(long, value_name = "DIR", num_args = 0..)]
    pub baselines: Option<Vec<PathBuf>>,
    /// Take only baselines and evaluations that `chronocooked verify` verifies (metrics
    /// against their episodes; evaluations in sweep jobs played again from their runs):
    /// one difference refuses the report, naming it.
    #[arg(long)]
    pub verified: bool,
    /// Output folder (report.html, report.md, report.csv, psychometric_grid.svg/png).
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Also write the probability of improvement between every two rows on this column
    /// (`improvement.csv` / `.md`: P(row > column) over pairs of their runs), e.g.
    /// `fi_success`.
    #[arg(long, value_name = "METRIC")]
    pub improvement: Option<String>,
}

/// Runs `report`.
pub fn run(args: ReportArgs) -> Result<()> {
    use chronocooked_present::report::baselines::{load_baseline_rows, locate_default_baselines};
    use chronocooked_present::report::leaderboard::{find_eval_folders, load_rows};
    if args.evals.is_empty() && args.runs.is_empty() && args.baselines.is_none() {
        bail!(
            "say what to compare: --eval DIR [DIR ...] (from `eval`), --runs DIR [DIR ...] (run or sweep folders) and/or --baselines [DIR ...] (committed study results)"
        );
    }
    for d in &args.runs {
        if !d.is_dir() {
            bail!("--runs {}: no such folder", d.display());
        }
    }
    let mut folders = args.evals.clone();
    folders.extend(find_eval_folders(&args.runs));
    if folders.is_empty() && args.baselines.is_none() {
        bail!(
            "no evaluation folders (eval.json + records.jsonl) under {}; run `eval` or a sweep first",
            args.runs
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    if args.verified {
        for f in &folders {
            // An evaluation inside a sweep job is verified with its job (played again).
            let job = f.parent().filter(|p| p.join("job.json").is_file());
            require_verified(job.unwrap_or(f))?;
        }
    }
    let mut rows = load_rows(&folders).map_err(anyhow::Error::msg)?;
    if let Some(dirs) = &args.baselines {
        let dirs = if dirs.is_empty() {
            vec![locate_default_baselines()?]
        } else {
            dirs.clone()
        };
        for d in dirs {
            if args.verified {
                require_verified(&d)?;
            }
            let before = rows.len();
            rows.extend(load_baseline_rows(&d)?);
            let runs: usize = rows[before..].iter().map(|r| r.runs.len()).sum();
            eprintln!(
                "baselines: {} rows from {} ({runs} runs)",
                rows.len() - before,
                d.display()
            );
        }
    }
    let mut files =
        chronocooked_present::report::write_report(&rows, &args.out).map_err(anyhow::Error::msg)?;
    if let Some(metric) = &args.improvement {
        files.extend(
            chronocooked_present::report::write_improvement(&rows, metric, &args.out)
                .map_err(anyhow::Error::msg)?,
        );
    }
    for f in files {
        println!("{}", f.display());
    }
    Ok(())
}

/// Refuses `dir` unless `verify` finds no difference in it.
fn require_verified(dir: &std::path::Path) -> Result<()> {
    let v = crate::cmd::verify::verify_any(dir, None, false)?;
    if let Some(d) = v.differences.first() {
        bail!(
            "--verified: {} does not verify: {} difference(s), first {} field `{}`: recorded {}, \
             re-derived {} (see `chronocooked verify {}`)",
            dir.display(),
            v.differences.len(),
            d.file.display(),
            d.field,
            d.recorded,
            d.recomputed,
            dir.display()
        );
    }
    eprintln!("verified: {} ({} checks)", dir.display(), v.checked.len());
    Ok(())
}
