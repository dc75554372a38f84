//! `paper analyse` as one library call: the whole analysis of a results folder written
//! beside it (tables, figures, report), for the CLI and the Python package alike.

use super::study::{PaperStudy, analyse, write_study};
use chronocooked_analysis::collect::{CollectError, err};
use std::path::{Path, PathBuf};

/// What [`analyse_folder`] wrote.
#[derive(Debug, Clone)]
pub struct Analysed {
    /// The study (also `study.json` in the folder).
    pub study: PaperStudy,
    /// `report.html`.
    pub report: PathBuf,
    /// The figure files under `figures/`.
    pub figures: Vec<PathBuf>,
}

/// Analyses the compact results under `results` (written by `paper collect`) as the paper
/// does and as the lab does, and writes into the same folder: the tables (`tables.md`,
/// `comparison.csv`, `agreement.json`, …), `figures/` and `report.html`. One writer at a
/// time: a folder another process writes is refused.
pub fn analyse_folder(results: &Path) -> Result<Analysed, CollectError> {
    // Checked before the lock, which would create the folder.
    if !results.is_dir() {
        return Err(err(
            results,
            "no such results folder (`paper collect SWEEP_OUT --out FOLDER` writes one)",
        ));
    }
    let _lock = chronocooked_env::fs::FolderLock::acquire(results).map_err(|e| err(results, e))?;
    let study = analyse(results)?;
    write_study(results, &study)?;
    let dir = results.join("figures");
    let figures = super::figures::write_figures(&dir, &study).map_err(|e| err(&dir, e))?;
    let report = super::report::write_paper_report(results, &study, &dir)?;
    Ok(Analysed {
        study,
        report,
        figures,
    })
}
