//! Run folders: resolved config, command, learning curve CSV, atomic checkpoints, final model.
//!
//! ```text
//! RUN_DIR/config.json        resolved TrainConfig
//! RUN_DIR/policy.json        PolicyConfig (architecture, input shape)
//! RUN_DIR/command.txt        the command line(s) that produced the run
//! RUN_DIR/curves.csv         one row per PPO update
//! RUN_DIR/checkpoints/step-000000100000.json   full trainer state (resumable)
//! RUN_DIR/model.bpk          final policy (burnpack), RUN_DIR/summary.json
//! ```

use crate::error::TrainError;
use crate::ppo::config::TrainConfig;
use crate::ppo::state::{TrainerState, UpdateLog};
use burn::module::Module;
use chronocooked_models::{ActorCritic, PolicyConfig};
use serde::{Deserialize, Serialize};
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` atomically (temporary file in the same folder, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), TrainError> {
    chronocooked_env::fs::write_atomic(path, bytes).map_err(|e| TrainError::io(path, e))
}

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
        fs::create_dir_all(path.join("checkpoints")).map_err(|e| TrainError::io(path, e))?;
        Ok(RunDir {
            path: path.to_path_buf(),
        })
    }

    /// Opens an existing run folder (must hold `config.json`).
    pub fn open(path: &Path) -> Result<Self, TrainError> {
        if !path.join("config.json").is_file() {
            return Err(TrainError::NotARun {
                path: path.display().to_string(),
            });
        }
        Ok(RunDir {
            path: path.to_path_buf(),
        })
    }

    /// Reads the resolved config and checks it like any other ([`TrainConfig::validate`]:
    /// a hand-edited `config.json` gets the same range checks as `--set`).
    pub fn config(&self) -> Result<TrainConfig, TrainError> {
        let p = self.path.join("config.json");
        let text = fs::read_to_string(&p).map_err(|e| TrainError::io(&p, e))?;
        let bad = |message: String| TrainError::ConfigFile {
            file: p.display().to_string(),
            message,
        };
        let cfg: TrainConfig = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
        cfg.validate().map_err(|e| bad(e.to_string()))?;
        Ok(cfg)
    }

    /// Checkpoint files, oldest first.
    pub fn checkpoints(&self) -> Vec<PathBuf> {
        let mut v: Vec<PathBuf> = fs::read_dir(self.path.join("checkpoints"))
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

    /// The newest checkpoint that parses.
    pub fn latest_state(&self) -> Result<Option<TrainerState>, TrainError> {
        for p in self.checkpoints().iter().rev() {
            if let Ok(text) = fs::read_to_string(p)
                && let Ok(s) = serde_json::from_str::<TrainerState>(&text)
            {
                return Ok(Some(s));
            }
        }
        Ok(None)
    }

    pub(crate) fn write_checkpoint(&self, state: &TrainerState) -> Result<(), TrainError> {
        let p = self
            .path
            .join("checkpoints")
            .join(format!("step-{:012}.json", state.steps));
        let json = serde_json::to_vec(state).map_err(|e| TrainError::Resume {
            path: p.display().to_string(),
            reason: e.to_string(),
        })?;
        write_atomic(&p, &json)
    }

    pub(crate) fn write_curves(&self, rows: &[UpdateLog]) -> Result<(), TrainError> {
        let mut s = curve_header();
        rows.iter().for_each(|r| s.push_str(&curve_line(r)));
        write_atomic(&self.path.join("curves.csv"), s.as_bytes())
    }

    pub(crate) fn append_curve(&self, row: &UpdateLog) -> Result<(), TrainError> {
        let p = self.path.join("curves.csv");
        let mut f = fs::OpenOptions::new()
            .append(true)
            .create(true)
            .open(&p)
            .map_err(|e| TrainError::io(&p, e))?;
        f.write_all(curve_line(row).as_bytes())
            .map_err(|e| TrainError::io(&p, e))
    }

    pub(crate) fn append_command(&self, command: &str) -> Result<(), TrainError> {
        let p = self.path.join("command.txt");
        let mut f = fs::OpenOptions::new()
            .append(true)
            .create(true)
            .open(&p)
            .map_err(|e| TrainError::io(&p, e))?;
        writeln!(f, "{command}").map_err(|e| TrainError::io(&p, e))
    }

    /// Saves a policy atomically as burnpack.
    pub fn save_model(&self, model: ActorCritic, name: &str) -> Result<PathBuf, TrainError> {
        let p = self.path.join(name);
        let tmp = self.path.join(format!("{name}.tmp{}", std::process::id()));
        model.save_file(&tmp).map_err(|e| TrainError::Resume {
            path: p.display().to_string(),
            reason: format!("saving the model failed: {e:?}"),
        })?;
        fs::rename(&tmp, &p).map_err(|e| TrainError::io(&p, e))?;
        Ok(p)
    }
}

/// Loads a run's policy: `model.bpk` if present, else the newest checkpoint's parameters.
pub fn load_policy(dir: &Path) -> Result<(ActorCritic, PolicyConfig, TrainConfig), TrainError> {
    let run = RunDir::open(dir)?;
    let cfg = run.config()?;
    let pp = dir.join("policy.json");
    let pcfg: PolicyConfig =
        serde_json::from_str(&fs::read_to_string(&pp).map_err(|e| TrainError::io(&pp, e))?)
            .map_err(|e| TrainError::Resume {
                path: pp.display().to_string(),
                reason: e.to_string(),
            })?;
    let device = chronocooked_models::cpu();
    let model = pcfg.init(cfg.seed, &device);
    let file = dir.join("model.bpk");
    if file.is_file() {
        let m = model.try_load_file(&file).map_err(|e| TrainError::Resume {
            path: file.display().to_string(),
            reason: format!("{e:?}"),
        })?;
        return Ok((m, pcfg, cfg));
    }
    match run.latest_state()? {
        Some(s) => Ok((crate::ppo::params::write_params(model, &s.theta), pcfg, cfg)),
        None => Err(TrainError::Resume {
            path: dir.display().to_string(),
            reason: "neither model.bpk nor a checkpoint".into(),
        }),
    }
}
