//! The probability of improvement between the leaderboard's rows on one metric
//! (`report --improvement METRIC`; rliable, Agarwal et al. 2021).

use crate::report::leaderboard::Row;
use chronocooked_env::markdown::Table;
use std::path::{Path, PathBuf};

/// Writes the probability of improvement on `metric` between every two rows with values
/// for it (`improvement.csv`, `improvement.md` into `out`): `P(row > column)`, the share of
/// (run of the row, run of the column) pairs in which the row's value is larger, ties
/// counting one half (rliable's probability of improvement for one task). For a metric
/// where lower is better (a CV, an error), read `1 − P`. Returns the files.
pub fn write_improvement(rows: &[Row], metric: &str, out: &Path) -> Result<Vec<PathBuf>, String> {
    use chronocooked_analysis::stats::robust::probability_of_improvement;
    let with: Vec<(&str, Vec<f64>)> = rows
        .iter()
        .filter_map(|r| {
            let v: Vec<f64> = r
                .robust
                .get(metric)?
                .values
                .iter()
                .copied()
                .filter(|x| x.is_finite())
                .collect();
            (!v.is_empty()).then_some((r.model.as_str(), v))
        })
        .collect();
    if with.len() < 2 {
        let known: Vec<&str> = {
            let mut k: Vec<&str> = rows
                .iter()
                .flat_map(|r| r.robust.keys().map(String::as_str))
                .collect();
            k.sort();
            k.dedup();
            k
        };
        return Err(format!(
            "probability of improvement on `{metric}`: {} row(s) have it, two are needed (columns with per-run values: {})",
            with.len(),
            known.join(", ")
        ));
    }
    let mut header = vec!["row".to_string()];
    header.extend(with.iter().map(|(m, _)| m.to_string()));
    let table: Vec<Vec<String>> = with
        .iter()
        .map(|(a, x)| {
            let mut line = vec![a.to_string()];
            line.extend(
                with.iter()
                    .map(|(_, y)| probability_of_improvement(x, y).to_string()),
            );
            line
        })
        .collect();
    let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
    let csv = crate::export::csv_text(&header_refs, &table)?;
    let mut md = format!(
        "# Probability of improvement on `{metric}`\n\nP(row > column): the share of (run of the row, run of the column) pairs in which the row's value is larger, ties counting one half (rliable). Runs: {}.\n\n",
        with.iter()
            .map(|(m, v)| format!("{m} {}", v.len()))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut shown = Table::new(std::iter::once("row").chain(with.iter().map(|(m, _)| *m)));
    for line in &table {
        shown.row(
            std::iter::once(line[0].clone()).chain(line[1..].iter().map(|v| {
                let v: f64 = v.parse().unwrap_or(f64::NAN);
                format!("{v:.2}")
            })),
        );
    }
    md += &shown.render();
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut files = Vec::new();
    for (name, text) in [("improvement.csv", csv), ("improvement.md", md)] {
        let path = out.join(name);
        chronocooked_env::fs::write_atomic(&path, text.as_bytes())
            .map_err(|e| format!("{}: {}", path.display(), e.error))?;
        files.push(path);
    }
    Ok(files)
}
