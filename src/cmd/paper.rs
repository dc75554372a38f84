//! `chronocooked paper`: the paper's study from a sweep's output — compact results kept in
//! the repository, the paper's analyses beside the lab's, and the comparison table.

use anyhow::{Context, Result};
use chronocooked_analysis::collect;
use chronocooked_paper::heldout;
use clap::{Args, Subcommand};
use std::path::PathBuf;

/// `paper` subcommands.
#[derive(Subcommand, Debug)]
pub enum PaperCommand {
    /// Copy the compact results of every finished job of a sweep (summary, episode lines,
    /// thinned learning curve, metrics; no checkpoints) into a results folder.
    Collect(CollectArgs),
    /// Analyse a results folder as the paper does (and as the lab does), compare with the
    /// paper's numbers under the old rule and the z rule: writes analysis.json,
    /// comparison.csv, agreement.json (with the negative control), pi.csv (peak-interval
    /// uniformity), tables.md, report.html and figures/ there.
    Analyse(AnalyseArgs),
    /// Check jobs rerun with seeds the study never used against the study's reported spread:
    /// each FI and bisection statistic of each held-out job against the 95% range for one
    /// new run of its condition (the study's `ranges.csv`). Writes held-out.csv into the
    /// held-out results folder and prints the table.
    CheckHeldOut(CheckHeldOutArgs),
}

/// `paper collect`.
#[derive(Args, Debug)]
pub struct CollectArgs {
    /// Sweep output folder (e.g. lab-out/paper-core).
    pub sweep_out: PathBuf,
    /// Results folder (e.g. results/paper-core).
    #[arg(long)]
    pub out: PathBuf,
}

/// `paper analyse`.
#[derive(Args, Debug)]
pub struct AnalyseArgs {
    /// Results folder written by `paper collect`.
    pub results: PathBuf,
}

/// `paper check-held-out`.
#[derive(Args, Debug)]
pub struct CheckHeldOutArgs {
    /// Results folder of the held-out jobs (`paper collect` of a sweep with an unused seed,
    /// e.g. results/paper-core-heldout).
    pub held_out: PathBuf,
    /// The study's results folder (e.g. results/paper-core).
    #[arg(long)]
    pub study: PathBuf,
}

/// Runs a `paper` subcommand.
pub fn run(cmd: PaperCommand) -> Result<()> {
    match cmd {
        PaperCommand::Collect(a) => {
            let (written, pending) = collect::collect(&a.sweep_out, &a.out)?;
            println!(
                "{written} finished jobs collected into {} ({pending} unfinished skipped)",
                a.out.display()
            );
            Ok(())
        }
        PaperCommand::CheckHeldOut(a) => {
            let read = |p: &PathBuf| {
                collect::read_compact(p).with_context(|| format!("reading {}", p.display()))
            };
            let (study_jobs, held) = (read(&a.study)?, read(&a.held_out)?);
            let checks = heldout::check_held_out(&study_jobs, &held)
                .with_context(|| format!("checking {}", a.held_out.display()))?;
            let csv = a.held_out.join("held-out.csv");
            heldout::write_held_out_csv(&csv, &checks)?;
            print!("{}", heldout::held_out_markdown(&checks));
            println!("wrote {}", csv.display());
            Ok(())
        }
        PaperCommand::Analyse(a) => {
            let analysed = chronocooked_paper::analyse::analyse_folder(&a.results)
                .with_context(|| format!("analysing {}", a.results.display()))?;
            let (s, report, figures) = (&analysed.study, &analysed.report, &analysed.figures);
            // The main text's numbers; the appendix's sizes are counted on their own.
            let (appendix, main): (Vec<_>, Vec<_>) = s.comparison.iter().partition(|r| {
                r.table
                    .starts_with(chronocooked_paper::reference::APPENDIX_PREFIX)
            });
            let means: Vec<_> = appendix
                .iter()
                .filter(|r| matches!(r.table.as_str(), "appendix_wf" | "appendix_dl"))
                .collect();
            let agree = main.iter().filter(|r| r.agree == "yes").count();
            let agree_z = main.iter().filter(|r| r.agree_z == "yes").count();
            let printed: Vec<_> = main.iter().filter(|r| r.source == "paper").collect();
            println!(
                "{} jobs analysed; main text: {} of {} paper numbers within the lab's interval \
                 (old rule), {} with |z| <= 2; printed in the paper: {} (old) and {} (z) of {}; \
                 appendix sizes 8/256: {} of 48 WF/DL means run ({} with a finite lab value), \
                 {} of {} numbers agree (old), {} (z); \
                 wrote {}, {} and {} figure files (and agreement.json, pi.csv)",
                s.jobs,
                agree,
                main.len(),
                agree_z,
                printed.iter().filter(|r| r.agree == "yes").count(),
                printed.iter().filter(|r| r.agree_z == "yes").count(),
                printed.len(),
                means.len(),
                means.iter().filter(|r| r.lab_mean.is_finite()).count(),
                appendix.iter().filter(|r| r.agree == "yes").count(),
                appendix.len(),
                appendix.iter().filter(|r| r.agree_z == "yes").count(),
                a.results.join("tables.md").display(),
                report.display(),
                figures.len()
            );
            Ok(())
        }
    }
}
