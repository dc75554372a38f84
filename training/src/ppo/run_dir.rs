//! PPO run folders: resolved config, command, learning curve CSV, atomic checkpoints, final model.
//!
//! ```text
//! RUN_DIR/config.json        resolved TrainConfig
//! RUN_DIR/policy.json        PolicyConfig (architecture, input shape)
//! RUN_DIR/command.txt        the command line(s) that produced the run
//! RUN_DIR/curves.csv         one row per PPO update
//! RUN_DIR/checkpoints/step-000000100000.json   full trainer state (resumable; the newest
//!                            `keep_checkpoints` are kept)
//! RUN_DIR/model.bpk          final policy (burnpack), RUN_DIR/summary.json
//! RUN_DIR/SHA256SUMS, RUN_DIR/checkpoints/SHA256SUMS   SHA-256 records of the learned state
//! ```
//!
//! Learned state (`policy.json`, `model.bpk`, checkpoints) is written with a SHA-256 record
//! ([`chronocooked_env::integrity`]) and verified whenever it is read.
//!
//! The file names are [`chronocooked_models::run_folder`]'s constants (shared with the
//! crates that read run folders); this module reads and writes the files with their types.

use crate::checked::{Check, Checked};
use crate::error::TrainError;
use crate::ppo::config::TrainConfig;
use crate::ppo::state::{TrainerState, UpdateLog};
use crate::run_config::{append_line, read_config_text, write_config};
use burn::module::Module;
use chronocooked_env::fs::write_atomic;
use chronocooked_env::integrity;
use chronocooked_models::run_folder;
use chronocooked_models::{ActorCritic, PolicyConfig};
use serde::{Deserialize, Serialize};
use std::fs;
use std::path::{Path, PathBuf};

/// Column names of `curves.csv`.
pub const CURVE_COLUMNS: [&str; 23] = [
    "update",
    "env_steps",
    "wall_s",
    "steps_per_s",
    "rollout_s",
    "optimize_s",
    "ep_return_mean",
    "ep_len_mean",
    "success_rate",
    "episodes",
    "policy_loss",
    "value_loss",
    "entropy",
    "approx_kl",
    "clip_fraction",
    "explained_variance",
    "grad_norm",
    "learning_rate",
    "num_timers",
    "never_ready_prob",
    "eval_success",
    "never_ready_success",
    "curriculum_level",
];

fn curve_line(r: &UpdateLog) -> String {
    let f = |x: f64| {
        if x.is_finite() {
            format!("{x}")
        } else {
            String::new()
        }
    };
    format!(
        "{},{},{:.3},{:.1},{:.4},{:.4},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
        r.update,
        r.env_steps,
        r.wall_s,
        r.steps_per_s,
        r.rollout_s,
        r.optimize_s,
        f(r.ep_return_mean),
        f(r.ep_len_mean),
        f(r.success_rate),
        r.episodes,
        f(r.policy_loss),
        f(r.value_loss),
        f(r.entropy),
        f(r.approx_kl),
        f(r.clip_fraction),
        f(r.explained_variance),
        f(r.grad_norm),
        r.learning_rate,
        r.num_timers,
        r.never_ready_prob,
        r.eval_success.map(f).unwrap_or_default(),
        f(r.never_ready_success),
        r.curriculum_level
    )
}

pub(crate) fn curve_header() -> String {
    format!("{}\n", CURVE_COLUMNS.join(","))
}

/// What a finished (or stopped) run reports.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunSummary {
    /// Run folder.
    pub dir: PathBuf,
    /// Env steps done.
    pub env_steps: u64,
    /// Updates done.
    pub updates: u64,
    /// Wall seconds of training (all sessions of a resumed run).
    pub wall_s: f64,
    /// Deterministic evaluation success from every start cell (anchors for bisection).
    pub eval_success: f64,
    /// Env steps at which the evaluation first reached `stop_at_success` (if it did).
    pub solved_at: Option<u64>,
    /// Final training success rate (stats window).
    pub train_success: f64,
}

/// A run folder on disk.
#[derive(Debug, Clone)]
pub struct RunDir {
    /// Root.
    pub path: PathBuf,
}

impl RunDir {
    /// Creates (or reuses) a run folder.
    pub fn create(path: &Path) -> Result<Self, TrainError> {
        fs::create_dir_all(path.join(run_folder::CHECKPOINTS))
            .map_err(|e| TrainError::io(path, e))?;
        Ok(RunDir {
            path: path.to_path_buf(),
        })
    }

    /// Opens an existing run folder (must hold `config.json`).
    pub fn open(path: &Path) -> Result<Self, TrainError> {
        if !path.join(run_folder::CONFIG).is_file() {
            return Err(crate::run_config::not_a_run(path));
        }
        Ok(RunDir {
            path: path.to_path_buf(),
        })
    }

    /// Reads the resolved config and checks it like any other ([`TrainConfig::validate`]:
    /// a hand-edited `config.json` gets the same range checks as `--set`).
    pub fn config(&self) -> Result<Checked<TrainConfig>, TrainError> {
        let p = self.path.join(run_folder::CONFIG);
        let text = read_config_text(&self.path)?;
        let bad = |message: String| TrainError::ConfigFile {
            file: p.display().to_string(),
            message,
        };
        let cfg: TrainConfig = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
        cfg.check().map_err(|e| bad(e.to_string()))
    }

    /// Checkpoint files (`checkpoints/step-*.json`), oldest first.
    pub fn checkpoints(&self) -> Vec<PathBuf> {
        let mut v: Vec<PathBuf> = fs::read_dir(self.path.join(run_folder::CHECKPOINTS))
            .map(|rd| {
                rd.filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|p| {
                        p.file_name()
                            .and_then(|n| n.to_str())
                            .is_some_and(|n| n.starts_with("step-") && n.ends_with(".json"))
                    })
                    .collect()
            })
            .unwrap_or_default();
        v.sort();
        v
    }

    /// Reads one checkpoint: its SHA-256 record checked, then parsed. Errors name the file.
    pub fn read_checkpoint(path: &Path) -> Result<TrainerState, TrainError> {
        let bytes = integrity::read_verified(path)?;
        serde_json::from_slice(&bytes).map_err(|e| TrainError::Corrupt {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }

    /// The newest intact checkpoint (SHA-256 record checked, parsed), if any.
    pub fn latest_state(&self) -> Result<Option<TrainerState>, TrainError> {
        Ok(self
            .checkpoints()
            .iter()
            .rev()
            .find_map(|p| Self::read_checkpoint(p).ok()))
    }

    /// Writes the checkpoint of `state` (with its SHA-256 record), then deletes the oldest
    /// checkpoints beyond the newest `keep`.
    pub(crate) fn write_checkpoint(
        &self,
        state: &TrainerState,
        keep: usize,
    ) -> Result<(), TrainError> {
        let p = self
            .path
            .join(run_folder::CHECKPOINTS)
            .join(format!("step-{:012}.json", state.steps));
        let json = serde_json::to_vec(state).map_err(|e| TrainError::Corrupt {
            path: p.display().to_string(),
            reason: format!("cannot serialise the trainer state: {e}"),
        })?;
        integrity::write_recorded(&p, &json)?;
        let all = self.checkpoints();
        for old in &all[..all.len().saturating_sub(keep.max(1))] {
            integrity::remove_recorded(old)?;
        }
        Ok(())
    }

    /// Raises the run's env-step budget to `total_steps` (what `train --resume DIR --steps N`
    /// does before continuing): `config.json` is rewritten with its new SHA-256 record, so a
    /// budget is changed this way, never by a hand edit (which a resume refuses).
    pub fn extend_budget(&self, total_steps: u64) -> Result<Checked<TrainConfig>, TrainError> {
        let mut cfg = self.config()?.into_inner();
        if total_steps < cfg.total_steps {
            return Err(TrainError::param(
                "steps",
                total_steps,
                &format!(
                    "at least the run's budget ({} env steps): --steps with --resume extends a run",
                    cfg.total_steps
                ),
            ));
        }
        cfg.total_steps = total_steps;
        let cfg = cfg.check()?;
        let json = serde_json::to_string_pretty(&cfg).unwrap_or_default();
        write_config(&self.path, json.as_bytes())?;
        Ok(cfg)
    }

    /// Checkpoints newer than every checkpoint on disk that `checkpoints/SHA256SUMS` records
    /// but that are missing — learned state that was lost or deleted, which a resume must
    /// not paper over by starting from an earlier point. Not counted: the record a killed
    /// checkpoint write leaves (the newest record, beyond the last learning-curve row: a
    /// checkpoint is recorded just before it is renamed into place, and its update's curve
    /// row is appended only after that), and older missing ones (a killed pruning), which do
    /// not change where a resume starts.
    pub fn lost_checkpoints(&self) -> Result<Vec<String>, TrainError> {
        let dir = self.path.join(run_folder::CHECKPOINTS);
        let records = integrity::read_manifest(&dir)?;
        let step_of = |name: &str| -> Option<u64> {
            name.strip_prefix("step-")?
                .strip_suffix(".json")?
                .parse()
                .ok()
        };
        let mut missing: Vec<(u64, String)> = records
            .keys()
            .filter_map(|n| step_of(n).map(|s| (s, n.clone())))
            .filter(|(_, n)| std::fs::symlink_metadata(dir.join(n)).is_err())
            .collect();
        missing.sort();
        let newest_present = self
            .checkpoints()
            .iter()
            .filter_map(|p| step_of(p.file_name()?.to_str()?))
            .max();
        missing.retain(|(step, _)| newest_present.is_none_or(|p| *step > p));
        let newest_recorded = records.keys().filter_map(|n| step_of(n)).max();
        let last_curve_step = self.last_curve_step();
        if let Some((step, _)) = missing.last()
            && Some(*step) == newest_recorded
            && last_curve_step.is_none_or(|c| c < *step)
        {
            missing.pop();
        }
        Ok(missing.into_iter().map(|(_, n)| n).collect())
    }

    /// The env step of the last complete row of `curves.csv` (`None` without rows).
    fn last_curve_step(&self) -> Option<u64> {
        let curves = run_folder::Curves::read(&self.path.join(run_folder::CURVES)).ok()?;
        // A row cut by a kill has fewer fields and is not read.
        curves
            .column("env_steps")?
            .into_iter()
            .rev()
            .find(|v| v.is_finite() && *v >= 0.0)
            .map(|v| v as u64)
    }

    /// Removes what a killed writer left in the run folder, `checkpoints/` and `figures/`
    /// (temporary files of atomic writes); returns them.
    pub fn remove_stale_temps(&self) -> Vec<PathBuf> {
        let mut removed = chronocooked_env::fs::remove_temp_files(&self.path);
        for sub in [
            run_folder::CHECKPOINTS,
            run_folder::FIGURES,
            run_folder::LEVELS,
        ] {
            removed.extend(chronocooked_env::fs::remove_temp_files(
                &self.path.join(sub),
            ));
        }
        removed
    }

    /// Rewrites `curves.csv` as the rows of `rows` (a checkpoint's learning curve: the file
    /// is cut back to the checkpoint it resumes from, the history before it kept).
    pub(crate) fn write_curves(&self, rows: &[UpdateLog]) -> Result<(), TrainError> {
        let mut s = curve_header();
        rows.iter().for_each(|r| s.push_str(&curve_line(r)));
        write_atomic(&self.path.join(run_folder::CURVES), s.as_bytes())?;
        Ok(())
    }

    pub(crate) fn append_curve(&self, row: &UpdateLog) -> Result<(), TrainError> {
        append_line(&self.path.join(run_folder::CURVES), &curve_line(row))
    }

    /// Appends a command line to `command.txt` (every session of a run is kept).
    pub fn append_command(&self, command: &str) -> Result<(), TrainError> {
        append_line(
            &self.path.join(run_folder::COMMAND),
            &format!("{command}\n"),
        )
    }

    /// Saves a policy atomically as burnpack, with its SHA-256 record.
    pub fn save_model(&self, model: ActorCritic, name: &str) -> Result<PathBuf, TrainError> {
        let p = self.path.join(name);
        let bytes = crate::ppo::params::with_stable_ids(model)
            .into_record()
            .into_bytes()
            .map_err(|e| TrainError::Corrupt {
                path: p.display().to_string(),
                reason: format!("saving the model failed: {e:?}"),
            })?;
        integrity::write_recorded(&p, &bytes)?;
        Ok(p)
    }

    /// Saves `model` as the policy that left curriculum level `level`
    /// (`levels/level-<level>.bpk`, with its SHA-256 record).
    pub fn save_level_model(
        &self,
        level: usize,
        model: ActorCritic,
    ) -> Result<PathBuf, TrainError> {
        let dir = self.path.join(run_folder::LEVELS);
        fs::create_dir_all(&dir).map_err(|e| TrainError::io(&dir, e))?;
        let name = format!("{}/{}", run_folder::LEVELS, run_folder::level_model(level));
        self.save_model(model, &name)
    }

    /// The curriculum levels whose policy the run kept (`levels/level-*.bpk`), ascending.
    pub fn saved_levels(&self) -> Vec<usize> {
        let mut v: Vec<usize> = fs::read_dir(self.path.join(run_folder::LEVELS))
            .map(|rd| {
                rd.filter_map(|e| {
                    let name = e.ok()?.file_name().into_string().ok()?;
                    name.strip_prefix("level-")?
                        .strip_suffix(".bpk")?
                        .parse()
                        .ok()
                })
                .collect()
            })
            .unwrap_or_default();
        v.sort_unstable();
        v
    }
}

/// The policy description a run of `cfg` trains (what its `policy.json` must hold).
pub fn expected_policy(cfg: &TrainConfig) -> Result<PolicyConfig, TrainError> {
    let task = cfg.task.config()?;
    let enc = crate::ppo::obs::ObsEncoder::for_config(cfg.obs, &task)?;
    let mut p = PolicyConfig::new(
        cfg.model,
        enc.cells(),
        enc.channels(),
        chronocooked_env::Action::COUNT,
    );
    p.core_init = cfg.core_init;
    Ok(p)
}

/// Reads a run's `policy.json` (SHA-256 record checked) and checks it: sizes in range
/// ([`PolicyConfig::validate`]) and the description its `config.json` implies.
pub fn read_policy_config(dir: &Path, cfg: &TrainConfig) -> Result<PolicyConfig, TrainError> {
    let pp = dir.join(run_folder::POLICY);
    let corrupt = |reason: String| TrainError::Corrupt {
        path: pp.display().to_string(),
        reason,
    };
    let bytes = integrity::read_verified(&pp)?;
    let pcfg: PolicyConfig = serde_json::from_slice(&bytes).map_err(|e| corrupt(e.to_string()))?;
    pcfg.validate().map_err(|e| corrupt(e.to_string()))?;
    let want = expected_policy(cfg)?;
    if pcfg != want {
        return Err(corrupt(format!(
            "does not describe the policy of config.json (expected {})",
            serde_json::to_string(&want).unwrap_or_default()
        )));
    }
    Ok(pcfg)
}

fn finite_params(path: &Path, theta: &[f32]) -> Result<(), TrainError> {
    match theta.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(TrainError::Corrupt {
            path: path.display().to_string(),
            reason: format!("parameter {i} is not a finite number"),
        }),
        None => Ok(()),
    }
}

/// Loads a run's policy: `model.bpk` if present (anything at that path must be an intact
/// model: a corrupt one is an error, never a silent fall-back), else the newest intact
/// checkpoint's parameters.
pub fn load_policy(dir: &Path) -> Result<(ActorCritic, PolicyConfig, TrainConfig), TrainError> {
    load_policy_from(dir, &dir.join(run_folder::MODEL))
}

/// The policy saved as the burnpack `file` (e.g. a curriculum level's policy in
/// `levels/`) with the run folder `dir`'s architecture and config; like [`load_policy`],
/// but without the fallback to checkpoints when `file` is missing.
pub fn load_level_policy(
    dir: &Path,
    level: usize,
) -> Result<(ActorCritic, PolicyConfig, TrainConfig), TrainError> {
    let file = dir
        .join(run_folder::LEVELS)
        .join(run_folder::level_model(level));
    if fs::symlink_metadata(&file).is_err() {
        return Err(TrainError::Resume {
            path: file.display().to_string(),
            reason: format!("the run kept no policy for curriculum level {level}"),
        });
    }
    load_policy_from(dir, &file)
}

fn load_policy_from(
    dir: &Path,
    file: &Path,
) -> Result<(ActorCritic, PolicyConfig, TrainConfig), TrainError> {
    let run = RunDir::open(dir)?;
    let cfg = run.config()?;
    let pcfg = read_policy_config(dir, &cfg)?;
    let n_params: usize = chronocooked_models::deep::spec::param_spec(&pcfg)
        .iter()
        .map(|p| p.shape.iter().product::<usize>())
        .sum();
    let device = chronocooked_models::cpu();
    let model = pcfg.init(cfg.seed, &device);
    if fs::symlink_metadata(file).is_ok() {
        let bytes = integrity::read_verified(file)?;
        let corrupt = |reason: String| TrainError::Corrupt {
            path: file.display().to_string(),
            reason,
        };
        let record =
            burn::store::ModuleRecord::from_bytes(burn::tensor::Bytes::from_bytes_vec(bytes))
                .map_err(|e| corrupt(format!("not a burnpack model: {e:?}")))?;
        let m = model
            .try_load_record(record)
            .map_err(|e| corrupt(format!("does not fit policy.json: {e:?}")))?;
        finite_params(file, &crate::ppo::params::flat_params(&m))?;
        return Ok((m, pcfg, cfg.into_inner()));
    }
    let all = run.checkpoints();
    let mut skipped = Vec::new();
    for p in all.iter().rev() {
        let state = match RunDir::read_checkpoint(p) {
            Ok(s) if s.theta.len() == n_params => s,
            Ok(s) => {
                skipped.push(format!(
                    "{}: field `theta`: {} values, the policy has {n_params}",
                    p.display(),
                    s.theta.len()
                ));
                continue;
            }
            Err(e) => {
                skipped.push(e.to_string());
                continue;
            }
        };
        finite_params(p, &state.theta)?;
        for s in &skipped {
            eprintln!("warning: skipped checkpoint {s}");
        }
        let m = crate::ppo::params::write_params(model, &state.theta);
        return Ok((m, pcfg, cfg.into_inner()));
    }
    Err(TrainError::Resume {
        path: dir.display().to_string(),
        reason: if all.is_empty() {
            "neither model.bpk nor a checkpoint (the run has not saved any parameters yet)".into()
        } else {
            format!(
                "no model.bpk, and every checkpoint is corrupt or does not fit: {}",
                skipped.join("; ")
            )
        },
    })
}
