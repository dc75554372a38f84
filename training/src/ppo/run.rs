//! A PPO run folder trained to its budget: a new run (config, policy description, curve
//! header written first) or a stopped one continued from its newest checkpoint; periodic
//! evaluation, early stop at a success target, checkpoints (the newest `keep_checkpoints`
//! kept), the final model and summary. A resume never starts over silently: it continues
//! from the newest intact checkpoint (warning about each one skipped), fails naming the
//! files when none is usable, removes a killed writer's temporary files and cuts
//! `curves.csv` back to the checkpoint.

use crate::checked::Checked;
use crate::error::TrainError;
use crate::evaluate::eval_tds;
use crate::ppo::config::TrainConfig;
use crate::ppo::evaluate::{EvalEpisode, evaluate_policy};
use crate::ppo::run_dir::{RunDir, RunSummary, curve_header, expected_policy, read_policy_config};
use crate::ppo::state::UpdateLog;
use crate::ppo::trainer::Trainer;
use chronocooked_env::fs::write_atomic;
use chronocooked_env::integrity;
use chronocooked_models::run_folder;
use std::path::Path;

/// Callbacks of a training run (progress display).
pub trait Progress {
    /// Called after every update.
    fn update(&mut self, _row: &UpdateLog, _total_steps: u64) {}
}

/// No progress output.
pub struct Silent;
impl Progress for Silent {}

/// Trains `cfg` into a new run folder `dir`, or continues it when `resume` is set.
pub fn run_training(
    cfg: Option<Checked<TrainConfig>>,
    dir: &Path,
    command: &str,
    progress: &mut dyn Progress,
) -> Result<RunSummary, TrainError> {
    if cfg.is_none() {
        // A resume needs a run folder: said before any lock file is made there.
        RunDir::open(dir)?;
    }
    // One writer per run folder; taken before anything is read or written.
    let _lock = chronocooked_env::fs::FolderLock::acquire(dir)?;
    // SIGINT / SIGTERM stop the loop at the next update with a checkpoint.
    let _listening = chronocooked_env::interrupt::listen();
    let (run, mut trainer) = match cfg {
        Some(cfg) => {
            let run = RunDir::create(dir)?;
            if run.path.join(run_folder::CONFIG).exists() && !run.checkpoints().is_empty() {
                return Err(TrainError::Resume {
                    path: dir.display().to_string(),
                    reason: "the folder already holds a run; use `train --resume` or a new --out"
                        .into(),
                });
            }
            let trainer = Trainer::new(cfg.clone())?;
            let json = serde_json::to_string_pretty(&cfg).unwrap_or_default();
            crate::run_config::write_config(&run.path, json.as_bytes())?;
            let pj = serde_json::to_string_pretty(trainer.policy_config()).unwrap_or_default();
            integrity::write_recorded(&run.path.join(run_folder::POLICY), pj.as_bytes())?;
            write_atomic(
                &run.path.join(run_folder::CURVES),
                curve_header().as_bytes(),
            )?;
            (run, trainer)
        }
        None => {
            let run = RunDir::open(dir)?;
            let cfg = run.config()?;
            for p in run.remove_stale_temps() {
                eprintln!(
                    "note: removed {} (left by an interrupted write)",
                    p.display()
                );
            }
            let lost = run.lost_checkpoints()?;
            if !lost.is_empty() {
                return Err(TrainError::Resume {
                    path: dir.display().to_string(),
                    reason: format!(
                        "{}/{} records {} that {} missing: learned state was deleted or lost, \
                         and resuming would silently start from an earlier point. Restore the \
                         file, or start over on purpose: remove the run folder and train again",
                        run_folder::CHECKPOINTS,
                        integrity::MANIFEST,
                        lost.join(", "),
                        if lost.len() == 1 { "is" } else { "are" }
                    ),
                });
            }
            if run.checkpoints().is_empty() {
                // A finished run without any checkpoint: they were deleted (their folder with
                // its SHA256SUMS), and resuming would silently start again. (Curve rows alone
                // say nothing: updates before the first checkpoint write them too.)
                let mut learned: Vec<&str> = [run_folder::SUMMARY, run_folder::MODEL]
                    .into_iter()
                    .filter(|f| run.path.join(f).exists())
                    .collect();
                // A curve row at or past the first checkpoint's update: that checkpoint was
                // written before the row, so it was lost.
                if curve_passed_a_checkpoint(&run.path, &cfg) {
                    learned.push(run_folder::CURVES);
                }
                if !learned.is_empty() {
                    return Err(TrainError::Resume {
                        path: dir.display().to_string(),
                        reason: format!(
                            "no checkpoint in {}/, but the run got past one ({}): its \
                             checkpoints were deleted or lost, and resuming would silently \
                             start from step 0. Restore them, or start over on purpose: remove \
                             the run folder and train again",
                            run_folder::CHECKPOINTS,
                            learned.join(", ")
                        ),
                    });
                }
                // Nothing learned yet (killed before the first checkpoint, perhaps while the
                // folder was being set up): the policy description follows from the config.
                let pj = serde_json::to_string_pretty(&expected_policy(&cfg)?).unwrap_or_default();
                integrity::write_recorded(&run.path.join(run_folder::POLICY), pj.as_bytes())?;
            } else {
                read_policy_config(&run.path, &cfg)?;
            }
            let trainer = match resume_trainer(&run, &cfg)? {
                Some(t) => t,
                None => {
                    eprintln!(
                        "note: {} holds no checkpoint yet: training starts from step 0",
                        dir.display()
                    );
                    Trainer::new(cfg)?
                }
            };
            // The learning curve is cut back to the checkpoint (its rows are the
            // checkpoint's history); rows of the lost updates are written again as they rerun.
            run.write_curves(&trainer.state().curve)?;
            (run, trainer)
        }
    };
    run.append_command(command)?;
    let cfg = trainer.config().clone();
    let task = cfg.task.config()?;
    let batch = (cfg.ppo.n_envs * cfg.ppo.n_steps) as u64;
    let every = |k: u64, steps: u64| interval(k, batch).is_some_and(|n| steps.is_multiple_of(n));
    let mut solved_at = None;
    while !trainer.finished() {
        let row = trainer.update()?;
        let steps = row.env_steps;
        if let Some((level, policy)) = trainer.take_left_level() {
            run.save_level_model(level, policy)?;
        }
        if every(cfg.eval_every, steps) || (cfg.stop_at_success.is_some() && cfg.eval_every == 0) {
            let eps = evaluate_policy(&trainer.policy(), &task, cfg.obs, &eval_tds(&task))?;
            let s = eval_success(&eps);
            trainer.set_last_eval(s);
            if let Some(target) = cfg.stop_at_success
                && s >= target
            {
                solved_at = Some(steps);
            }
        }
        let row = trainer.state().curve.last().cloned().unwrap_or(row);
        let stop = chronocooked_env::interrupt::requested();
        let last = trainer.finished() || solved_at.is_some() || stop.is_some();
        // A checkpoint is written before its update's curve row is appended, so a record of
        // a missing checkpoint beyond the curve's last row can only be a killed checkpoint
        // write (`RunDir::lost_checkpoints`).
        if every(cfg.checkpoint_every, steps) || last {
            run.write_checkpoint(trainer.state(), cfg.keep_checkpoints)?;
        }
        run.append_curve(&row)?;
        progress.update(&row, cfg.total_steps);
        if let Some(signal) = stop {
            return Err(TrainError::Interrupted {
                dir: dir.display().to_string(),
                signal,
                signal_name: chronocooked_env::interrupt::signal_name(signal),
                steps,
            });
        }
        if solved_at.is_some() {
            break;
        }
    }
    if run.checkpoints().is_empty() {
        // A run resumed after its last update has its final checkpoint already.
        run.write_checkpoint(trainer.state(), cfg.keep_checkpoints)?;
    }
    run.save_model(trainer.policy(), run_folder::MODEL)?;
    if cfg.curriculum.has_levels() {
        // The last level reached keeps the final policy (the paper's newest checkpoint).
        run.save_level_model(trainer.state().curriculum_level, trainer.policy())?;
    }
    let eps = evaluate_policy(&trainer.policy(), &task, cfg.obs, &eval_tds(&task))?;
    let st = trainer.state();
    let summary = RunSummary {
        dir: run.path.clone(),
        env_steps: st.steps,
        updates: st.updates,
        wall_s: st.wall_s,
        eval_success: eval_success(&eps),
        solved_at,
        train_success: st.curve.last().map(|r| r.success_rate).unwrap_or(f64::NAN),
    };
    let json = serde_json::to_string_pretty(&summary).unwrap_or_default();
    write_atomic(&run.path.join(run_folder::SUMMARY), json.as_bytes())?;
    Ok(summary)
}

/// The newest checkpoint that is intact and fits the run, as a trainer ready to go on;
/// `Ok(None)` when there is no checkpoint at all. A corrupt or unusable checkpoint is
/// skipped with a warning on stderr naming it; when checkpoints exist but none is
/// usable, the error names each one and how to start over.
pub fn resume_trainer(
    run: &RunDir,
    cfg: &Checked<TrainConfig>,
) -> Result<Option<Trainer>, TrainError> {
    let all = run.checkpoints();
    let mut skipped = Vec::new();
    for p in all.iter().rev() {
        let restored = RunDir::read_checkpoint(p).and_then(|s| {
            Trainer::restore(cfg.clone(), s).map_err(|e| TrainError::Corrupt {
                path: p.display().to_string(),
                reason: e.to_string(),
            })
        });
        match restored {
            Ok(t) => return Ok(Some(t)),
            Err(e) => {
                eprintln!("warning: skipping checkpoint {e}; trying an older one");
                skipped.push(e.to_string());
            }
        }
    }
    if all.is_empty() {
        return Ok(None);
    }
    Err(TrainError::NoValidCheckpoint {
        dir: run.path.display().to_string(),
        skipped: skipped.join("; "),
    })
}

/// The greedy evaluation's success rate (NaN without an episode: every task evaluates at
/// least one TD from every start cell, so only an empty layout gives none).
fn eval_success(eps: &[EvalEpisode]) -> f64 {
    chronocooked_models::agent::success_rate(eps.iter().map(|e| e.success)).unwrap_or(f64::NAN)
}

/// Whether the learning curve of the run in `dir` has a row at or past the env step of the
/// run's first checkpoint (every `checkpoint_every` steps rounded up to whole updates, and
/// at the end of the budget): checkpoints are written before their update's row, so such a
/// row means a checkpoint existed.
fn curve_passed_a_checkpoint(dir: &Path, cfg: &TrainConfig) -> bool {
    let Ok(curves) = run_folder::Curves::read(&dir.join(run_folder::CURVES)) else {
        return false;
    };
    let Some(steps) = curves.column("env_steps") else {
        return false;
    };
    let last = steps.iter().copied().fold(0.0, f64::max) as u64;
    let batch = (cfg.ppo.n_envs * cfg.ppo.n_steps).max(1) as u64;
    let first = interval(cfg.checkpoint_every, batch).unwrap_or(u64::MAX);
    last >= first.min(cfg.total_steps)
}

/// The env steps between two events set every `k` steps (checkpoints, evaluations), `k`
/// rounded up to whole updates of `batch` steps; `None` when `k` is 0 (only at the end).
fn interval(k: u64, batch: u64) -> Option<u64> {
    (k > 0).then(|| k.div_ceil(batch).max(1).saturating_mul(batch))
}
