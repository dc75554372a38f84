//! Run folders of the timing-model agents (`train --model ddm|sbf|timecells-*`).
//!
//! Files: `config.json` (resolved [`TimingRunConfig`]), `command.txt`, `curves.csv`
//! (episode, steps, train success/reward, eval success), `agent.json` (the trained agent:
//! learned drifts / stored times / TD weights; with its SHA-256 record in `SHA256SUMS`),
//! `summary.json`. Training is a few seconds,
//! deterministic from (config, seed), so an interrupted run is simply rerun: `--resume`
//! restarts it and reaches the identical result.

use crate::error::TrainError;
use crate::evaluate::eval_tds;
use crate::ppo::config::ENV_KEY;
use crate::settings::{
    self, timing::TIMING_SETTINGS, timing::TimerSettings, timing::TimingAgentSettings,
};
use chronocooked_env::fs::write_atomic;
use chronocooked_env::{ChronoEnv, ResponseKind, Task, TaskFamily, integrity, make_config};
use chronocooked_models::run_folder;
use chronocooked_models::timing::agent::TimingAgent;
use chronocooked_models::timing::zoo::{has_native_gate, make_timing_agent};
use chronocooked_models::{TimingCurvePoint, TimingTrainConfig, train_timing_agent};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Everything that defines a timing-agent run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "StoredTimingRunConfig")]
pub struct TimingRunConfig {
    /// Always `"timing"` (tells run folders apart from PPO ones).
    pub kind: String,
    /// The task and its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Zoo name of the timing model.
    pub model: String,
    /// Seed.
    pub seed: u64,
    /// Training schedule.
    pub train: TimingTrainConfig,
    /// Overrides of the agent's parameters, applied after construction (typed per model
    /// family; the keys and their ranges: [`TIMING_SETTINGS`]).
    pub agent: TimingAgentSettings,
}

/// `config.json` as stored: `agent` is the typed [`TimingAgentSettings`], or in folders
/// written before it the list of `key=value` overrides.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StoredTimingRunConfig {
    kind: String,
    #[serde(flatten)]
    task: Task,
    model: String,
    seed: u64,
    train: TimingTrainConfig,
    agent: serde_json::Value,
}

impl TryFrom<StoredTimingRunConfig> for TimingRunConfig {
    type Error = TrainError;

    fn try_from(s: StoredTimingRunConfig) -> Result<Self, TrainError> {
        let mut cfg = TimingRunConfig {
            agent: no_overrides(&s.model),
            kind: s.kind,
            task: s.task,
            model: s.model,
            seed: s.seed,
            train: s.train,
        };
        match s.agent {
            serde_json::Value::Array(list) => {
                for kv in list {
                    let kv = kv.as_str().unwrap_or_default();
                    let (key, value) = kv
                        .split_once('=')
                        .ok_or_else(|| TrainError::BadOverride(kv.into()))?;
                    match settings::find(TIMING_SETTINGS, key.trim()) {
                        Some(spec) if spec.path.first() == Some(&"agent") => {
                            settings::set_field(&mut cfg, spec, key.trim(), value)?
                        }
                        _ => return Err(TrainError::param("agent", kv, "agent settings")),
                    }
                }
            }
            typed => {
                cfg.agent = serde_json::from_value(typed)
                    .map_err(|e| TrainError::param("agent", "", &e.to_string()))?
            }
        }
        Ok(cfg)
    }
}

/// No override, for the family of timing model `model` (ddm when it is no timing model:
/// [`TimingRunConfig::validate`] refuses it).
fn no_overrides(model: &str) -> TimingAgentSettings {
    let fi = make_config("FixedInterval-v0", &[] as &[&str]).expect("FI is registered");
    let env = ChronoEnv::new(&fi).expect("FI builds");
    match make_timing_agent(model, &env, 0) {
        Ok(agent) => TimingAgentSettings::none(TimerSettings::family_of(&agent.timer)),
        Err(_) => TimingAgentSettings::none(TimerSettings::Ddm {
            noise: None,
            memory_noise: None,
            reproduction_rate: None,
        }),
    }
}

pub use crate::settings::timing::MAX_EPISODES;

/// Default training episodes on the uncertainty task: the never-ready ovens (20% of the
/// episodes) are where the time-out response is learned, so the task needs more episodes
/// than fixed interval (measured on never-ready ovens, seeds 0–3: 6,000 episodes leave the
/// microstimulus and Laplace agents at 0%; at 40,000 microstimulus, Laplace and CSC agents
/// reach 100% on every seed, 20,000 gave microstimuli 1 seed of 4).
pub const UNCERTAINTY_EPISODES: usize = 40_000;

/// Default training episodes on the reproduction task: the time cells learn the production
/// as a value over (measurement at Set × time since Set) for every context, so they need
/// more episodes than one fixed interval (measured on the default task, seeds 1 and 3:
/// 6,000 episodes at a constant step size left microstimulus, Laplace and CSC agents at
/// 2–81% success, unstable from one evaluation to the next; 20,000 with the step size
/// annealed to [`REPRODUCTION_ALPHA_END`] gave 64–85% on all six runs). With the
/// exploration of later responses (`response_delay`), on the priors 10–16 and 15–21 that
/// no doc uses (2026-11-28, seeds 1–2): at 20,000 episodes microstimulus and Laplace agents
/// produced 0.79–0.80 × `ts` at the long end of a prior, at 60,000 0.83–0.87 — an ideal
/// observer with their clock noise (0.15) and this reward produces 0.89–0.90 there.
pub const REPRODUCTION_EPISODES: usize = 60_000;

/// Final SARSA(λ) step size on the reproduction task (annealed from the agent's own `α`,
/// [`TimingTrainConfig::alpha_end`]): a tenth of Ludvig et al.'s 0.05. A constant step size
/// left the values tracking the last few hundred episodes, and the greedy production
/// collapsed between evaluations (success 0.6 → 0 → 0.6 on one run).
pub const REPRODUCTION_ALPHA_END: f64 = 0.005;

/// Visit-count step floor on the reproduction task ([`TimingTrainConfig::visit_power`]):
/// ω = 0.85, inside Even-Dar & Mansour's (2003) range (1/2, 1) for polynomial learning
/// rates; the only value tried. The time cells' learner reads the conjunctive code
/// `m ⊗ p`, and with the delay line each (measurement, time since Set) pair is a feature of
/// its own. The greedy production moves across them as it learns, so the pairs just after
/// it are first tried late — by the exploration of later responses, at an annealed `α`
/// near 0.005 — and stayed near their initial value, below the greedy pair's: the learned
/// production stopped at the last well-learned pair, as little as 0.77–0.79 × `ts` at the
/// long end of the priors 10–16 and 15–21 (seeds 1–4), where an ideal observer with the
/// model's clock noise produces 0.90.
/// With the floor: RESULTS, "The 0.8–1.2 criterion". For the models whose responses are
/// learned (the time cells) only: drift-diffusion and SBF respond when their clock says so,
/// and with the floor their first values were raw early samples that slowed the start of
/// their runs (drift-diffusion seed 1 on the prior 9–15 after 20,000 episodes: 7% of the
/// trials at `ts` 9 unproduced; at least 95% produced at every `ts` without it).
pub const REPRODUCTION_VISIT_POWER: f64 = 0.85;

impl TimingRunConfig {
    /// Defaults for `model` on `task`.
    pub fn new(task: &Task, model: &str, seed: u64) -> Self {
        let mut train = TimingTrainConfig::default();
        let family = task.family();
        if family == TaskFamily::Uncertainty {
            train.episodes = UNCERTAINTY_EPISODES;
        }
        if task.unchecked_config().response_kind() == Some(ResponseKind::Reproduce) {
            train.episodes = REPRODUCTION_EPISODES;
            train.alpha_end = Some(REPRODUCTION_ALPHA_END);
            if has_native_gate(model) == Some(false) {
                train.visit_power = REPRODUCTION_VISIT_POWER;
            }
        }
        TimingRunConfig {
            kind: "timing".into(),
            task: task.clone(),
            model: model.into(),
            seed,
            train,
            agent: no_overrides(model),
        }
    }

    /// Applies one `key=value` override (the keys of [`TIMING_SETTINGS`] this model's family
    /// has, or `env.<task parameter>`), checked by the key's own rule; typed errors name the
    /// key and the allowed values. Rules across keys (a bisection's short anchor below its
    /// long one) are [`TimingRunConfig::validate`]'s, run once after every override, as the
    /// PPO path does: `--set env.short=20 --set env.long=40` passes through a state that is
    /// invalid only between the two keys.
    pub fn set(&mut self, kv: &str) -> Result<(), TrainError> {
        let (key, value) = kv
            .split_once('=')
            .ok_or_else(|| TrainError::BadOverride(kv.into()))?;
        let (key, value) = (key.trim(), value.trim());
        if let Some(name) = key.strip_prefix("env.") {
            self.task.set(name, value)?;
        } else {
            let Some(spec) = settings::find(TIMING_SETTINGS, key) else {
                return Err(settings::unknown(TIMING_SETTINGS, self, key, ENV_KEY));
            };
            settings::set_field(self, spec, key, value)?;
        }
        Ok(())
    }

    /// The guide's table of timing-model settings (docs/timing-models.md): every key, with the training defaults on
    /// fixed interval; the agent's parameters default per model (`zoo show MODEL`).
    pub fn settings_markdown() -> String {
        let mut rows: Vec<settings::Setting> = Vec::new();
        for model in ["ddm", "sbf", "timecells-ms"] {
            let cfg = TimingRunConfig::new(
                &chronocooked_env::Task::new("FixedInterval-v0").expect("FI is registered"),
                model,
                0,
            );
            for mut s in settings::listing(TIMING_SETTINGS, &cfg) {
                let spec = settings::find(TIMING_SETTINGS, &s.key).expect("listed keys have specs");
                if spec.path.first() == Some(&"agent") {
                    s.value = "per model".into();
                }
                if let Some(families) = spec.only_with {
                    s.doc = format!("{} ({families})", s.doc);
                }
                if !rows.iter().any(|r| r.key == s.key) {
                    rows.push(s);
                }
            }
        }
        settings::markdown_table(&rows)
    }

    /// Whether this model's settings have `key` (its family's timer keys included).
    pub fn has_setting(&self, key: &str) -> bool {
        settings::has(TIMING_SETTINGS, self, key)
    }

    /// Every setting of this run with its value (the model's default where not overridden),
    /// type, accepted values and meaning: what `zoo show` lists.
    pub fn listing(&self) -> Vec<settings::Setting> {
        let mut resolved = self.clone();
        if let Ok(agent) = self.build_agent() {
            resolved.agent = TimingAgentSettings::of(&agent);
        }
        settings::listing(TIMING_SETTINGS, &resolved)
    }

    /// Checks ranges and the task with its overrides (also applied to a loaded
    /// `config.json`).
    pub fn validate(&self) -> Result<(), TrainError> {
        if !chronocooked_models::timing::zoo::is_timing_model(&self.model) {
            return Err(TrainError::param(
                "model",
                &self.model,
                "a timing model (see `chronocooked zoo list`)",
            ));
        }
        if self.kind != "timing" {
            return Err(TrainError::param("kind", &self.kind, "timing"));
        }
        settings::check(TIMING_SETTINGS, self)?;
        self.task.config()?;
        Ok(())
    }

    /// Builds the untrained agent with the overrides applied.
    pub fn build_agent(&self) -> Result<TimingAgent, TrainError> {
        let env = ChronoEnv::new(&self.task.config()?)?;
        let mut agent = make_timing_agent(&self.model, &env, self.seed).map_err(|e| {
            TrainError::InvalidParam {
                field: "model".into(),
                value: self.model.clone(),
                allowed: e,
            }
        })?;
        self.agent.apply(&mut agent)?;
        Ok(agent)
    }
}

/// What a finished timing run reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimingRunSummary {
    /// Run folder.
    pub dir: PathBuf,
    /// Episodes trained.
    pub episodes: usize,
    /// Env steps trained.
    pub env_steps: u64,
    /// Wall seconds.
    pub wall_s: f64,
    /// Final deterministic evaluation success (every start cell; bisection anchors).
    pub eval_success: f64,
    /// First episode at which the evaluation reached 95%, if it did.
    pub solved_at_episode: Option<usize>,
}

fn json<T: Serialize>(v: &T) -> Vec<u8> {
    let mut s = serde_json::to_string_pretty(v).expect("serialisable");
    s.push('\n');
    s.into_bytes()
}

/// Trains a timing agent into `dir`; `progress` sees every curve point. Refuses a folder
/// that already holds a finished run (`summary.json`).
pub fn run_timing_training(
    cfg: &TimingRunConfig,
    dir: &Path,
    command: &str,
    progress: impl FnMut(&TimingCurvePoint),
) -> Result<TimingRunSummary, TrainError> {
    cfg.validate()?;
    let _lock = chronocooked_env::fs::FolderLock::acquire(dir)?;
    if dir.join(run_folder::SUMMARY).is_file() {
        return Err(TrainError::Resume {
            path: dir.display().to_string(),
            reason: "the folder already holds a finished run; use a new --out".into(),
        });
    }
    let start = std::time::Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| TrainError::io(dir, e))?;
    crate::run_config::write_config(dir, &json(cfg))?;
    // Every session of the folder is kept (`--resume` reruns an unfinished run).
    crate::run_config::append_line(&dir.join(run_folder::COMMAND), &format!("{command}\n"))?;
    let _ = chronocooked_env::fs::remove_temp_files(dir);
    let task = cfg.task.config()?;
    let mut agent = cfg.build_agent()?;
    let tds = eval_tds(&task);
    let curve = train_timing_agent(&mut agent, &task, &cfg.train, &tds, cfg.seed, progress)?;
    let mut csv = String::from("episode,env_steps,train_success,train_reward,eval_success\n");
    for p in &curve {
        csv += &format!(
            "{},{},{},{},{}\n",
            p.episode,
            p.steps,
            p.train_success,
            p.train_reward,
            p.eval_success.map_or(String::new(), |v| v.to_string())
        );
    }
    write_atomic(&dir.join(run_folder::CURVES), csv.as_bytes())?;
    integrity::write_recorded(&dir.join(run_folder::AGENT), &json(&agent))?;
    let last = curve.last();
    let summary = TimingRunSummary {
        dir: dir.to_path_buf(),
        episodes: last.map_or(0, |p| p.episode),
        env_steps: last.map_or(0, |p| p.steps),
        wall_s: start.elapsed().as_secs_f64(),
        eval_success: last.and_then(|p| p.eval_success).unwrap_or(0.0),
        solved_at_episode: curve
            .iter()
            .find(|p| p.eval_success.is_some_and(|s| s >= 0.95))
            .map(|p| p.episode),
    };
    write_atomic(&dir.join(run_folder::SUMMARY), &json(&summary))?;
    Ok(summary)
}

/// Whether `dir` holds a timing-agent run (its `agent.json`, or a timing run's
/// `config.json`: an unfinished or damaged run is still a timing run, so a missing agent
/// is reported as such rather than as a PPO config error).
pub fn is_timing_run(dir: &Path) -> bool {
    std::fs::symlink_metadata(dir.join(run_folder::AGENT)).is_ok()
        || crate::run_config::says_timing(dir)
}

fn bad_file(dir: &Path, name: &str, e: serde_json::Error) -> TrainError {
    TrainError::Resume {
        path: dir.join(name).display().to_string(),
        reason: e.to_string(),
    }
}

/// Loads and checks the config of a timing run folder (finished or not): a folder without
/// `config.json` is "not a run folder"; a hand-edited config gets the same checks as
/// `--set`, and errors name the file and the field.
pub fn load_timing_config(dir: &Path) -> Result<TimingRunConfig, TrainError> {
    let p = dir.join(run_folder::CONFIG);
    let text = crate::run_config::read_config_text(dir)?;
    let cfg: TimingRunConfig =
        serde_json::from_str(&text).map_err(|e| bad_file(dir, run_folder::CONFIG, e))?;
    cfg.validate().map_err(|e| TrainError::ConfigFile {
        file: p.display().to_string(),
        message: e.to_string(),
    })?;
    Ok(cfg)
}

/// Loads the config and trained agent of a timing run folder: `agent.json` checked against
/// its SHA-256 record, then against the agent its config builds
/// ([`crate::timing_check::check_agent`]).
pub fn load_timing_agent(dir: &Path) -> Result<(TimingRunConfig, TimingAgent), TrainError> {
    let cfg = load_timing_config(dir)?;
    let p = dir.join(run_folder::AGENT);
    if std::fs::symlink_metadata(&p).is_err() {
        return Err(TrainError::Corrupt {
            path: p.display().to_string(),
            reason:
                "missing: the timing run has not finished (train it again with `train --resume`)"
                    .into(),
        });
    }
    let bytes = integrity::read_verified(&p)?;
    let agent: TimingAgent =
        serde_json::from_slice(&bytes).map_err(|e| bad_file(dir, run_folder::AGENT, e))?;
    crate::timing_check::check_agent(&agent, &cfg.build_agent()?).map_err(|reason| {
        TrainError::Corrupt {
            path: p.display().to_string(),
            reason,
        }
    })?;
    Ok((cfg, agent))
}

/// Loads the agent of any run folder — PPO (`policy.json`) or timing model (`agent.json`) —
/// to play `task` (the run's own task when `None`). Returns the agent and its model name.
pub fn load_agent(
    dir: &Path,
    task: Option<&chronocooked_env::TaskConfig>,
) -> Result<Box<dyn chronocooked_models::Agent>, TrainError> {
    if is_timing_run(dir) {
        let (cfg, agent) = load_timing_agent(dir)?;
        if let Some(t) = task {
            let own = cfg.task.config()?;
            let (a, b) = (ChronoEnv::new(&own)?, ChronoEnv::new(t)?);
            if a.layout() != b.layout() {
                return Err(TrainError::InvalidParam {
                    field: "task".into(),
                    value: format!("{:?}", t.family()),
                    allowed: format!(
                        "a task with the layout the agent was trained on ({})",
                        cfg.task
                    ),
                });
            }
        }
        return Ok(Box::new(agent));
    }
    Ok(Box::new(crate::ppo::agent::PpoAgent::load(dir, task)?))
}

impl crate::checked::Check for TimingRunConfig {
    type Error = TrainError;

    /// [`TimingRunConfig::validate`].
    fn validate(&self) -> Result<(), TrainError> {
        TimingRunConfig::validate(self)
    }
}
