//! The multi-timer's statements.

use super::*;
use crate::multitimer::{LEVELS, MtCell};
use std::collections::BTreeMap;

/// The five-timer curricula among `cells` (exact and categorical: the paper's figures do not
/// say which they show, so each statement is tested on both), as (curriculum, TD list).
fn five_timer_lists(cells: &[MtCell]) -> Vec<(&str, &[u32])> {
    let mut keys: Vec<(&str, &[u32])> = cells
        .iter()
        .filter(|c| c.tds.len() == LEVELS - 1)
        .map(|c| (c.curriculum.as_str(), c.tds.as_slice()))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// The cell of `model` under `curriculum` on `tds`.
fn cell_of<'a>(
    cells: &'a [MtCell],
    curriculum: &str,
    tds: &[u32],
    model: &str,
) -> Option<&'a MtCell> {
    cells
        .iter()
        .find(|c| c.curriculum == curriculum && c.tds == tds && c.model == model)
}

/// The multi-timer's statements ("While LSTM125 generally performs better than other models,
/// none of the models perform all the tasks successfully"), per five-timer curriculum: the
/// reward of each level's policy at its trained TDs (the figure's "Timers = L" panels) per
/// level, the curriculum level reached (`multitimer_lstm_further`, a coarser proxy), and
/// whether any run performs every timer — reached five timers with its five-timer policy
/// earning ≥ [`PERFORMS`] at each of the five trained TDs (in the notebooks' test setting
/// where the run kept its level policies, else the final policy in its training setting).
pub fn multitimer_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let mut rows = Vec::new();
    let levels: Vec<u32> = (1..LEVELS as u32).collect();
    for (curriculum, tds) in five_timer_lists(cells) {
        let cell = |m: &str| cell_of(cells, curriculum, tds, m);
        let task = format!("multi-timer {curriculum}, TDs {}", tds_label(tds));
        for (other, name) in others() {
            let reward = |m: &str, l: u32| {
                cell(m)
                    .and_then(|c| c.level_eval.get(l as usize).copied())
                    .unwrap_or(Spread::of([]))
            };
            per_setting_statement(
                &mut rows,
                "multitimer_lstm_best",
                &format!("LSTM125 generally performs better than {name}"),
                (&task, "level"),
                &format!(
                    "reward of each level's policy at its trained TDs, lstm125 − {other}: above 0, p < 0.05"
                ),
                &levels,
                |l| vec![reward(LSTM, l), reward(other, l)],
                |v| MeanTest::two_sample(&v[0], &v[1]),
            );
            let level = |m: &str| cell(m).map_or(Spread::of([]), |c| c.level);
            let (a, b) = (level(LSTM), level(other));
            let t = MeanTest::two_sample(&a, &b);
            let (z, p) = z_p(t);
            rows.push(ClaimRow {
                claim: "multitimer_lstm_further".into(),
                statement: format!("LSTM125 gets further in the curriculum than {name} (a proxy of \"performs better\")"),
                setting: task.clone(),
                test: format!("lstm125 − {other}, curriculum level reached: above 0, p < 0.05"),
                lab: format!("{} vs {}", fmt_spread(&a), fmt_spread(&b)),
                z,
                p,
                verdict: if a.n == 0 || b.n == 0 { "n/a" } else { directional(t) }.into(),
                summary: true,
            });
        }
        let same: Vec<&MtCell> = cells
            .iter()
            .filter(|c| c.curriculum == curriculum && c.tds == tds)
            .collect();
        let total: usize = same.iter().map(|c| c.runs.len()).sum();
        // Per run at five timers: (model, its worst reward over the five trained TDs, whether
        // from its kept five-timer policy in the notebooks' test setting); `None` for a run
        // not evaluated at every trained TD.
        let at_top: Vec<(&str, Option<(f64, bool)>)> = same
            .iter()
            .flat_map(|c| {
                c.runs.iter().filter(|r| r.level == LEVELS - 1).map(|r| {
                    let kept: Vec<f64> = r
                        .level_curves
                        .get(LEVELS - 1)
                        .map(|v| v.iter().filter(|p| p.trained).map(|p| p.reward).collect())
                        .unwrap_or_default();
                    let (rewards, test_setting) = if kept.is_empty() {
                        (r.per_td.iter().map(|x| x.1).collect(), false)
                    } else {
                        (kept, true)
                    };
                    let worst = (rewards.len() == tds.len())
                        .then(|| rewards.into_iter().fold(f64::INFINITY, f64::min));
                    (c.model.as_str(), worst.map(|w| (w, test_setting)))
                })
            })
            .collect();
        let performing: Vec<&str> = at_top
            .iter()
            .filter(|r| r.1.is_some_and(|(w, _)| w >= PERFORMS))
            .map(|r| r.0)
            .collect();
        let judged = at_top.iter().filter(|r| r.1.is_some()).count();
        let in_training = at_top.iter().filter(|r| r.1.is_some_and(|x| !x.1)).count();
        let mut notes = Vec::new();
        if in_training > 0 {
            notes.push(format!(
                "{in_training} judged on the final policy in the training setting (no kept level policies)"
            ));
        }
        if judged < at_top.len() {
            notes.push(format!(
                "{} not evaluated at every trained TD",
                at_top.len() - judged
            ));
        }
        if !performing.is_empty() {
            notes.push(performing.join(", "));
        }
        rows.push(ClaimRow {
            claim: "multitimer_none_all".into(),
            statement: "none of the models perform all the tasks successfully".into(),
            setting: task,
            test: format!(
                "no run at five timers whose five-timer policy earns ≥ {PERFORMS} at each of the five TDs (the notebooks' test setting where the run kept its level policies, else its final policy in the training setting)"
            ),
            lab: format!(
                "{} of {total} runs reach five timers, {} of them earn ≥ {PERFORMS} at every TD{}",
                at_top.len(),
                performing.len(),
                if notes.is_empty() { String::new() } else { format!(" ({})", notes.join("; ")) }
            ),
            z: f64::NAN,
            p: f64::NAN,
            verdict: unless_any(total, performing.len()).into(),
            summary: true,
        });
    }
    rows
}

/// "CTRNN125 generally shows more shifts than LSTM125" (the multi-timer's oven-off curves,
/// each level's policy on every TD 1 … its longest + 1): per curriculum and five-TD list, the
/// timers each level's policy stores ([`timers_stored`](crate::multitimer::timers_stored)),
/// CTRNN − LSTM per level 1 … 5 with the runs that kept that level, then over the levels.
/// The paper's figures do not say which curriculum they show, so both are tested.
pub fn shift_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let mut rows = Vec::new();
    let levels: Vec<u32> = (1..LEVELS as u32).collect();
    for (curriculum, tds) in five_timer_lists(cells) {
        let timers = |m: &str, level: u32| {
            cell_of(cells, curriculum, tds, m)
                .and_then(|c| c.level_timers.get(level as usize).copied())
                .unwrap_or(Spread::of([]))
        };
        let task = format!("multi-timer {curriculum}, TDs {}", tds_label(tds));
        for (ctrnn, name) in ctrnns() {
            per_setting_statement(
                &mut rows,
                "multitimer_ctrnn_more_shifts",
                &format!("{name} generally shows more shifts (timers stored) than LSTM125"),
                (&task, "level"),
                &format!("timers stored per run, {ctrnn} − lstm125: above 0, p < 0.05"),
                &levels,
                |l| vec![timers(ctrnn, l), timers(LSTM, l)],
                |v| MeanTest::two_sample(&v[0], &v[1]),
            );
        }
    }
    rows
}

/// "None of the models demonstrate a strong capacity to store multiple intervals or
/// generalize reliably to OOD durations": per five-timer curriculum, a model goes against it
/// when its five-timer policies (the runs that kept level 5), averaged over those runs, earn
/// at least [`PERFORMS`] at every one of the five trained TDs (stores the intervals) or at
/// every untrained TD 1 … 11 (generalises).
pub fn capacity_claims(cells: &[MtCell]) -> Vec<ClaimRow> {
    let top = LEVELS - 1;
    five_timer_lists(cells)
        .into_iter()
        .map(|(curriculum, tds)| {
            // Per model with five-timer policies: (model, runs, worst trained-TD mean,
            // worst untrained-TD mean).
            let at_top: Vec<(&str, usize, f64, f64)> = cells
                .iter()
                .filter(|c| c.curriculum == curriculum && c.tds == tds)
                .filter_map(|c| {
                    let curves: Vec<_> = c
                        .runs
                        .iter()
                        .filter_map(|r| r.level_curves.get(top).filter(|v| !v.is_empty()))
                        .collect();
                    if curves.is_empty() {
                        return None;
                    }
                    let mut at: BTreeMap<(bool, u32), Vec<f64>> = BTreeMap::new();
                    for p in curves.iter().flat_map(|v| v.iter()) {
                        at.entry((p.trained, p.td)).or_default().push(p.reward);
                    }
                    let worst = |trained: bool| {
                        at.iter()
                            .filter(|((t, _), _)| *t == trained)
                            .map(|(_, v)| v.iter().sum::<f64>() / v.len() as f64)
                            .fold(f64::NAN, f64::min)
                    };
                    Some((c.model.as_str(), curves.len(), worst(true), worst(false)))
                })
                .collect();
            let strong: Vec<&str> = at_top
                .iter()
                .filter(|x| x.2 >= PERFORMS || x.3 >= PERFORMS)
                .map(|x| x.0)
                .collect();
            let lab = at_top
                .iter()
                .map(|(m, n, t, u)| format!("{m} {t:.2} / {u:.2} ({n})"))
                .collect::<Vec<_>>()
                .join("; ");
            ClaimRow {
                claim: "multitimer_no_strong_capacity".into(),
                statement: "none of the models store multiple intervals strongly or generalise reliably to OOD durations".into(),
                setting: format!("multi-timer {curriculum}, TDs {}", tds_label(tds)),
                test: format!(
                    "no model's five-timer policies earn ≥ {PERFORMS} at every trained TD, or at every untrained TD (lab: worst trained / worst untrained TD)"
                ),
                lab: if lab.is_empty() {
                    "no run kept a five-timer policy".into()
                } else if strong.is_empty() {
                    lab
                } else {
                    format!("{lab}; against: {}", strong.join(", "))
                },
                z: f64::NAN,
                p: f64::NAN,
                verdict: unless_any(at_top.len(), strong.len()).into(),
                summary: true,
            }
        })
        .collect()
}
