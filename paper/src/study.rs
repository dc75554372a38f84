//! The whole paper analysis of a compact results folder: FI, bisection, multi-timer, the
//! comparison with the paper (under both rules, with the negative control), the
//! peak-interval probes, and the cost of each job kind; written as `analysis.json`,
//! `comparison.csv`, `agreement.json`, `pi.csv` and `tables.md`.

use super::agreement::{Agreement, agreement};
use super::bisection::{BisectionModel, analyse_bisection};
use super::claims::{
    ClaimRow, bisection_claims, capacity_claims, claims_markdown, exact_timer_claims, fi_claims,
    multitimer_claims, shift_claims,
};
use super::compare::{ComparisonRow, compare};
use super::fi::{FiModel, analyse_fi};
use super::multitimer::{
    ExactTimerCell, LEVELS, MtCell, PLATEAU_GAP, analyse_exact_timer, analyse_multitimer,
};
use super::pi::{PiRow, PiVerdict, analyse_pi, pi_verdicts};
use super::reference::HUMAN_WF_VS_RATIO;
use super::spreads::{NewRunRange, SpreadChange, new_run_ranges, spread_changes};
use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_analysis::collect::{CollectError, CompactJob, err, read_compact, write_csv};
use chronocooked_env::markdown::{Align, Table};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Training cost of one job kind (task × model).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobCost {
    /// Task id.
    pub task: String,
    /// Zoo model name.
    pub model: String,
    /// Finished jobs.
    pub jobs: usize,
    /// Training wall-clock seconds per job (one core each).
    pub wall_s: Spread,
    /// Env steps per second.
    pub steps_per_s: Spread,
    /// Core-hours of all these jobs.
    pub core_hours: f64,
}

/// Everything the study reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PaperStudy {
    /// Finished jobs analysed.
    pub jobs: usize,
    /// Fixed interval per model.
    pub fi: Vec<FiModel>,
    /// Bisection per model.
    pub bisection: Vec<BisectionModel>,
    /// Multi-timer per model, curriculum and TD list.
    pub multitimer: Vec<MtCell>,
    /// The exact timer (runs trained on one TD): reward against the test buffer.
    #[serde(default)]
    pub exact_timer: Vec<ExactTimerCell>,
    /// Comparison with the paper.
    pub comparison: Vec<ComparisonRow>,
    /// Verdict counts under both rules and the negative control (`agreement.json`).
    pub agreement: Agreement,
    /// The paper's exact-timer and multi-timer statements, tested (`claims.csv`).
    #[serde(default)]
    pub claims: Vec<ClaimRow>,
    /// Peak-interval probe curves (`pi.csv`).
    pub pi: Vec<PiRow>,
    /// Uniform-checking verdict per model × probe factor.
    pub pi_verdicts: Vec<PiVerdict>,
    /// Cost per job kind.
    pub cost: Vec<JobCost>,
    /// Each condition's spread on the first four seeds and on every run (`spreads.csv`).
    #[serde(default)]
    pub spreads: Vec<SpreadChange>,
    /// Where one more run of each condition should land (`ranges.csv`).
    #[serde(default)]
    pub ranges: Vec<NewRunRange>,
}

/// Cost of each job kind.
pub fn job_costs(jobs: &[CompactJob]) -> Vec<JobCost> {
    let mut g: BTreeMap<(&str, &str), Vec<&CompactJob>> = BTreeMap::new();
    for j in jobs {
        g.entry((j.job.task.id(), j.job.label()))
            .or_default()
            .push(j);
    }
    g.into_iter()
        .map(|((task, model), js)| JobCost {
            task: task.into(),
            model: model.into(),
            jobs: js.len(),
            wall_s: Spread::of(js.iter().map(|j| j.job.wall_s)),
            steps_per_s: Spread::of(js.iter().map(|j| j.job.steps_done as f64 / j.job.wall_s)),
            core_hours: js.iter().map(|j| j.job.wall_s).sum::<f64>() / 3600.0,
        })
        .collect()
}

/// Analyses the compact results under `root`.
pub fn analyse(root: &Path) -> Result<PaperStudy, CollectError> {
    let jobs = read_compact(root)?;
    let fi = analyse_fi(&jobs);
    let bisection = analyse_bisection(&jobs);
    let multitimer = analyse_multitimer(&jobs);
    let exact_timer = analyse_exact_timer(&jobs);
    let comparison = compare(&fi, &bisection, &multitimer);
    let agreement = agreement(&comparison, &fi, &bisection, &multitimer);
    let pi = analyse_pi(root, &jobs)?;
    let pi_verdicts = pi_verdicts(&pi);
    let mut claims = fi_claims(&jobs);
    claims.extend(bisection_claims(&jobs));
    claims.extend(exact_timer_claims(&jobs));
    claims.extend(multitimer_claims(&multitimer));
    claims.extend(shift_claims(&multitimer));
    claims.extend(capacity_claims(&multitimer));
    Ok(PaperStudy {
        claims,
        jobs: jobs.len(),
        agreement,
        pi,
        pi_verdicts,
        cost: job_costs(&jobs),
        spreads: spread_changes(&jobs),
        ranges: new_run_ranges(&jobs),
        fi,
        bisection,
        multitimer,
        exact_timer,
        comparison,
    })
}

fn f(x: f64, digits: usize) -> String {
    if x.is_finite() {
        format!("{x:.digits$}")
    } else {
        "–".into()
    }
}

fn pm(s: &Spread, digits: usize) -> String {
    if s.n == 0 {
        "–".into()
    } else if s.n == 1 {
        f(s.mean, digits)
    } else {
        format!("{} ± {}", f(s.mean, digits), f(s.sd, digits))
    }
}

/// Per task and statistic: how the SD over runs moved from the first four seeds to every
/// run (`spreads.csv` has each condition).
fn spreads_markdown(m: &mut String, rows: &[SpreadChange]) {
    if rows.is_empty() {
        return;
    }
    let _ = writeln!(
        m,
        "\n## Spread over runs: first four seeds vs every run\n\nSD ratio = SD over every run ÷ SD over seeds 1–4, per condition (both with ≥ 2 runs); each condition in `spreads.csv`. Shift = |mean over every run − mean over seeds 1–4| in units of the seeds-1–4 SD.\n"
    );
    let mut table = Table::new([
        "task",
        "model",
        "statistic",
        "conditions",
        "runs (first → all)",
        "median SD ratio",
        "SD ratio range",
        "ratio > 1.5",
        "median shift",
        "shift > 1",
    ])
    .right([3, 5, 7, 8, 9]);
    let mut keys: Vec<(&str, &str, &str)> = Vec::new();
    for r in rows {
        let k = (r.task.as_str(), r.model.as_str(), r.statistic.as_str());
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    for (task, model, stat) in keys {
        let sel: Vec<&SpreadChange> = rows
            .iter()
            .filter(|r| r.task == task && r.model == model && r.statistic == stat)
            .collect();
        let mut ratios: Vec<f64> = sel
            .iter()
            .map(|r| r.sd_all / r.sd_first)
            .filter(|x| x.is_finite())
            .collect();
        let mut shifts: Vec<f64> = sel
            .iter()
            .map(|r| (r.mean_all - r.mean_first).abs() / r.sd_first)
            .filter(|x| x.is_finite())
            .collect();
        ratios.sort_by(f64::total_cmp);
        shifts.sort_by(f64::total_cmp);
        let median = |v: &[f64]| match v.len() {
            0 => f64::NAN,
            n if n % 2 == 1 => v[n / 2],
            n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
        };
        let n_first = Spread::of(sel.iter().map(|r| r.n_first as f64));
        let n_all = Spread::of(sel.iter().map(|r| r.n_all as f64));
        table.row([
            task.to_string(),
            model.to_string(),
            stat.to_string(),
            sel.len().to_string(),
            format!("{} → {}", f(n_first.mean, 1), f(n_all.mean, 1)),
            f(median(&ratios), 2),
            format!(
                "{}–{}",
                f(ratios.first().copied().unwrap_or(f64::NAN), 2),
                f(ratios.last().copied().unwrap_or(f64::NAN), 2)
            ),
            ratios.iter().filter(|x| **x > 1.5).count().to_string(),
            f(median(&shifts), 2),
            shifts.iter().filter(|x| **x > 1.0).count().to_string(),
        ]);
    }
    m.push_str(&table.render());
}

/// A Markdown table of the `fixed` columns (left-aligned) then the numeric `cols`.
fn numeric_table<S: ToString>(fixed: &[&str], cols: &[S]) -> Table {
    let columns = fixed
        .iter()
        .map(|c| (c.to_string(), Align::Left))
        .chain(cols.iter().map(|c| (c.to_string(), Align::Right)));
    Table::aligned(columns)
}

/// The multi-timer table of the columns `cols` after model, curriculum and TD list.
fn mt_table(cols: &[&str]) -> Table {
    numeric_table(&["model", "curriculum", "TDs"], cols)
}

/// One multi-timer cell's table row: model, curriculum, TD list, then `cells`.
fn mt_row(table: &mut Table, c: &MtCell, cells: &[String]) {
    table.row(
        [c.model.clone(), c.curriculum.clone(), tds_label(&c.tds)]
            .into_iter()
            .chain(cells.iter().cloned()),
    );
}

fn tds_label(tds: &[u32]) -> String {
    tds.iter()
        .map(u32::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The per-level policies at the untrained TDs 1 … max + 1 of their level and the timers
/// they store (levels 1 … 5; runs whose levels were tested there only).
fn level_ood_markdown(m: &mut String, cells: &[MtCell]) {
    let with: Vec<&MtCell> = cells
        .iter()
        .filter(|c| c.level_timers.iter().skip(1).any(|x| x.n > 0))
        .collect();
    if with.is_empty() {
        return;
    }
    let _ = writeln!(
        m,
        "\nEach level's policy (levels 1 … 5) also on the TDs it was not trained on, 1 … its longest + 1 (the paper's figures' out-of-distribution TDs): mean reward there, and the timers it stores — the paper's \"number of distinct shifts\" in the oven-off curve over every tested TD (mean oven-off times where the soup is taken on ≥ half the cells, grouped when within {PLATEAU_GAP} step) — as reward at untrained TDs / timers, mean over runs (runs):\n"
    );
    let mut table = mt_table(&["1", "2", "3", "4", "5"]);
    for c in with {
        let r: Vec<String> = (1..LEVELS)
            .map(
                |l| match (c.level_untrained_reward.get(l), c.level_timers.get(l)) {
                    (Some(u), Some(t)) if t.n > 0 => {
                        format!("{} / {} ({})", f(u.mean, 2), f(t.mean, 1), t.n)
                    }
                    _ => "–".into(),
                },
            )
            .collect();
        mt_row(&mut table, c, &r);
    }
    m.push_str(&table.render());
}

/// Markdown tables of the study (what `RESULTS.md` quotes), titled with the study's name
/// (its results folder, e.g. `paper-core`).
pub fn tables_markdown(s: &PaperStudy, study: &str) -> String {
    let mut m = String::new();
    let _ = writeln!(m, "# {study}: tables ({} finished jobs)\n", s.jobs);
    let _ = writeln!(
        m,
        "## Fixed interval: first oven check (paper convention)\n\nPooled over runs × start \
         cells (the paper's statistic; a run's remaining cells are skipped after an episode \
         without a check, as in the notebook), and per run (mean ± SD over runs). \
         \"Lab convention\": the same pool with an interact run from the onion put counted as \
         a check at step 1 (the paper's code reports 0).\n"
    );
    let mut table = numeric_table(
        &["model"],
        &[
            "TD",
            "runs",
            "n",
            "FOC mean",
            "SD",
            "CV",
            "FOC mean, lab convention",
            "per-run mean FOC",
            "per-run CV",
            "FOC/TD per run",
        ],
    );
    for model in &s.fi {
        for c in &model.cells {
            table.row([
                model.model.clone(),
                c.td.to_string(),
                c.runs.to_string(),
                c.pooled.n.to_string(),
                f(c.pooled.mean, 2),
                f(c.pooled.sd, 2),
                f(c.pooled.cv, 2),
                c.pooled_checks
                    .as_ref()
                    .map_or("–".into(), |x| f(x.mean, 2)),
                pm(&c.run_mean, 2),
                pm(&c.run_cv, 2),
                pm(&c.run_ratio, 2),
            ]);
        }
    }
    m.push_str(&table.render());
    let mut table = numeric_table(
        &["model"],
        &[
            "R² mean vs TD (pooled)",
            "R² SD vs mean (pooled)",
            "slope mean vs TD",
            "R² mean vs TD per run",
            "R² SD vs mean per run",
        ],
    );
    for model in &s.fi {
        table.row([
            model.model.clone(),
            f(model.scalar.r2_mean_vs_td, 2),
            f(model.scalar.r2_sd_vs_mean, 2),
            f(model.scalar.mean_slope, 2),
            pm(&model.run_r2_mean_vs_td, 2),
            pm(&model.run_r2_sd_vs_mean, 2),
        ]);
    }
    let _ = write!(m, "\n{table}");
    let _ = writeln!(
        m,
        "\n## Bisection\n\nRuns excluded when their last 100 training episodes averaged more \
         than 100 steps (the notebook's rule). BP/DL/WF: least squares on the run-averaged \
         curve (paper figure) and per run (mean ± SD: the paper's tables); MLE: binomial \
         maximum likelihood on the pooled counts (the lab's).\n"
    );
    let mut table = numeric_table(
        &["model", "anchors"],
        &[
            "runs (excluded)",
            "anchor acc.",
            "BP (avg curve)",
            "WF (avg curve)",
            "WF per run",
            "DL per run",
            "BP per run",
            "BP (MLE)",
            "WF (MLE)",
        ],
    );
    for model in &s.bisection {
        for c in &model.cells {
            let excl = c.runs.iter().filter(|r| r.excluded).count();
            table.row([
                model.model.clone(),
                format!("{}-{}", c.short, c.long),
                format!("{} ({excl})", c.runs.len()),
                pm(&c.anchor_accuracy, 2),
                c.fit.map_or("failed".into(), |x| f(x.bp, 2)),
                c.fit.map_or("failed".into(), |x| f(x.wf, 3)),
                pm(&c.wf, 3),
                pm(&c.dl, 2),
                pm(&c.bp, 2),
                c.mle.as_ref().map_or("–".into(), |x| f(x.bp, 2)),
                c.mle.as_ref().map_or("–".into(), |x| f(x.wf, 3)),
            ]);
        }
    }
    m.push_str(&table.render());
    let _ = writeln!(
        m,
        "\nWF vs log2(L/S) (human reference: r = {}, p = {}):\n",
        HUMAN_WF_VS_RATIO.0, HUMAN_WF_VS_RATIO.1
    );
    let mut table = numeric_table(
        &["model"],
        &["r (avg curves)", "p", "n", "r (per run)", "p", "n"],
    );
    for model in &s.bisection {
        let r = |x: &Option<super::bisection::WfRegression>| {
            x.map_or(["–".to_string(), "–".into(), "–".into()], |w| {
                [f(w.r, 3), f(w.p, 3), w.n.to_string()]
            })
        };
        table.row(
            std::iter::once(model.model.clone())
                .chain(r(&model.wf_vs_ratio))
                .chain(r(&model.wf_vs_ratio_runs)),
        );
    }
    m.push_str(&table.render());
    let _ = writeln!(m, "\n## Multi-timer\n");
    let _ = writeln!(
        m,
        "Curriculum: level 0 warm-up, then 1 … 5 timers (the TDs of the list in order). Steps per level: env steps spent in a level by the runs that left it.\n"
    );
    let mut table = mt_table(&[
        "runs",
        "level reached",
        "runs at level 5",
        "steps in level 0",
        "1",
        "2",
        "3",
        "4",
    ]);
    for c in &s.multitimer {
        let cells: Vec<String> = [
            c.runs.len().to_string(),
            pm(&c.level, 1),
            c.reached_last.to_string(),
        ]
        .into_iter()
        .chain(c.steps_in_level.iter().map(|s| pm(s, 0)))
        .collect();
        mt_row(&mut table, c, &cells);
    }
    m.push_str(&table.render());
    let _ = writeln!(
        m,
        "\nTraining reward per curriculum level (mean of the learning curve's samples at that level, then mean ± SD over the runs with samples there):\n"
    );
    let mut table = mt_table(&["level 0", "1", "2", "3", "4", "5"]);
    for c in &s.multitimer {
        let r: Vec<String> = c.level_reward.iter().map(|s| pm(s, 2)).collect();
        mt_row(&mut table, c, &r);
    }
    m.push_str(&table.render());
    if s.multitimer
        .iter()
        .any(|c| c.level_eval.iter().any(|x| x.n > 0))
    {
        let _ = writeln!(
            m,
            "\nEach level's own policy in that level's test setting (the notebooks' evaluation: level 0 one timer, soup only at TD, reduced reward 0.1; level L ≥ 1 the first L TDs, undercooking possible; exact: reduced reward 0; categorical: reduced reward 0.1, 2 steps early allowed), mean reward over its TDs and 12 start cells, then mean ± SD (runs) over the runs that reached the level:\n"
        );
        let mut table = mt_table(&["level 0", "1", "2", "3", "4", "5"]);
        for c in s
            .multitimer
            .iter()
            .filter(|c| c.level_eval.iter().any(|x| x.n > 0))
        {
            let r: Vec<String> = c
                .level_eval
                .iter()
                .map(|x| {
                    if x.n == 0 {
                        "–".into()
                    } else {
                        format!("{} ({})", pm(x, 2), x.n)
                    }
                })
                .collect();
            mt_row(&mut table, c, &r);
        }
        m.push_str(&table.render());
    }
    level_ood_markdown(&mut m, &s.multitimer);
    let _ = writeln!(
        m,
        "\nFinal policy per trained TD, mean over runs of the 12-start-cell means: reward / oven-off time (steps since the onion went in; a soup never taken counts −1, as in the notebook):\n"
    );
    let mut tds: Vec<u32> = s
        .multitimer
        .iter()
        .flat_map(|c| c.per_td.iter().map(|x| x.0))
        .collect();
    tds.sort_unstable();
    tds.dedup();
    let head: Vec<String> = tds.iter().map(|td| format!("TD {td}")).collect();
    let mut table = numeric_table(&["model", "curriculum", "TDs"], &head);
    for c in &s.multitimer {
        let cells: Vec<String> = tds
            .iter()
            .map(|td| {
                c.per_td
                    .iter()
                    .find(|x| x.0 == *td)
                    .map_or("–".into(), |(_, r, o)| {
                        format!("{} / {}", f(r.mean, 2), f(o.mean, 1))
                    })
            })
            .collect();
        mt_row(&mut table, c, &cells);
    }
    m.push_str(&table.render());
    if !s.exact_timer.is_empty() {
        let mut fracs: Vec<f64> = s
            .exact_timer
            .iter()
            .flat_map(|c| c.buffers.iter().map(|b| b.0))
            .collect();
        fracs.sort_by(f64::total_cmp);
        fracs.dedup();
        let _ = writeln!(
            m,
            "\n## Exact timer\n\nOne timer per run, trained to take the soup at exactly TD; tested with a buffer of a fraction of TD on either side (rounded to whole steps): mean reward over the 12 start cells (1 inside TD ± buffer, the reduced reward 0.1 outside, 0 never delivered), then mean ± SD over runs.\n"
        );
        let head: Vec<String> = fracs
            .iter()
            .map(|f| format!("buffer {:.0}%", f * 100.0))
            .collect();
        let mut table = numeric_table(&["model", "TD", "runs"], &head);
        for c in &s.exact_timer {
            let cells: Vec<String> = fracs
                .iter()
                .map(|f| {
                    c.buffers
                        .iter()
                        .find(|b| b.0 == *f)
                        .map_or("–".into(), |b| pm(&b.1, 2))
                })
                .collect();
            table.row(
                [c.model.clone(), c.td.to_string(), c.runs.to_string()]
                    .into_iter()
                    .chain(cells),
            );
        }
        m.push_str(&table.render());
    }
    claims_markdown(&mut m, &s.claims);
    spreads_markdown(&mut m, &s.spreads);
    super::agreement::agreement_markdown(&mut m, &s.agreement);
    super::pi::pi_markdown(&mut m, &s.pi_verdicts);
    let _ = writeln!(m, "\n## Cost per job kind (one core per job)\n");
    let mut table = numeric_table(
        &["task", "model"],
        &["jobs", "wall-clock s per job", "env-steps/s", "core-hours"],
    );
    for c in &s.cost {
        table.row([
            c.task.clone(),
            c.model.clone(),
            c.jobs.to_string(),
            pm(&c.wall_s, 0),
            pm(&c.steps_per_s, 0),
            f(c.core_hours, 2),
        ]);
    }
    m.push_str(&table.render());
    m
}

/// Writes `rows` as CSV at `path`, or removes a stale `path` when there are none.
fn write_if_any<T: Serialize>(path: &Path, rows: &[T]) -> Result<(), CollectError> {
    if !rows.is_empty() {
        write_csv(path, rows)
    } else if path.is_file() {
        std::fs::remove_file(path).map_err(|x| err(path, x))
    } else {
        Ok(())
    }
}

/// Writes `analysis.json`, `comparison.csv`, `agreement.json`, `pi.csv`, `ranges.csv` (the
/// 95% prediction interval of one new run per condition), `spreads.csv`
/// (once a condition has more than the first four seeds' runs), `claims.csv` (with
/// exact-timer or multi-timer runs) and `tables.md` into `root`.
pub fn write_study(root: &Path, s: &PaperStudy) -> Result<(), CollectError> {
    let write = |name: &str, bytes: &[u8]| {
        let p = root.join(name);
        chronocooked_env::fs::write_atomic(&p, bytes).map_err(|x| err(&p, x.error))
    };
    let json = serde_json::to_string_pretty(s).map_err(|x| err(root, x))?;
    write("analysis.json", json.as_bytes())?;
    write_csv(&root.join("comparison.csv"), &s.comparison)?;
    let json = serde_json::to_string_pretty(&s.agreement).map_err(|x| err(root, x))?;
    write("agreement.json", json.as_bytes())?;
    write_csv(&root.join("pi.csv"), &s.pi)?;
    write_csv(&root.join("ranges.csv"), &s.ranges)?;
    // `spreads.csv` only once a condition has more runs than the first seeds, `claims.csv`
    // only with exact-timer or multi-timer runs: no stale file from an earlier analysis.
    write_if_any(&root.join("spreads.csv"), &s.spreads)?;
    write_if_any(&root.join("claims.csv"), &s.claims)?;
    let study = root
        .canonicalize()
        .ok()
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "study".into());
    write("tables.md", tables_markdown(s, &study).as_bytes())
}
