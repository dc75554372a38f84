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
use chronocooked_env::fs::write_atomic;
use chronocooked_env::{ChronoEnv, TaskFamily, integrity, make_config};
use chronocooked_models::run_folder;
use chronocooked_models::timing::agent::TimingAgent;
use chronocooked_models::timing::judgment::DecisionRule;
use chronocooked_models::timing::zoo::make_timing_agent;
use chronocooked_models::{TimingCurvePoint, TimingTrainConfig, train_timing_agent};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Everything that defines a timing-agent run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimingRunConfig {
    /// Always `"timing"` (tells run folders apart from PPO ones).
    pub kind: String,
    /// Task id.
    pub task: String,
    /// Task overrides (`key=value`).
    pub env: Vec<String>,
    /// Zoo name of the timing model.
    pub model: String,
    /// Seed.
    pub seed: u64,
    /// Training schedule.
    pub train: TimingTrainConfig,
    /// Agent overrides applied after construction (`key=value`: `alpha`, `gamma`,
    /// `lambda`, `response_cost`, `probe`, `opportunity_cost`, `overdue_factor`,
    /// `wait_at_oven`, `q_init`,
    /// `noise`, `memory_noise`, `clock_noise`, `decision_rule`).
    pub agent: Vec<String>,
}

/// Default training episodes on the uncertainty task: the never-ready ovens (20% of the
/// episodes) are where the time-out response is learned, so the task needs more episodes
/// than fixed interval (measured on never-ready ovens, seeds 0–3: 6,000 episodes leave the
/// microstimulus and Laplace agents at 0%; at 40,000 microstimulus, Laplace and CSC agents
/// reach 100% on every seed, 20,000 gave microstimuli 1 seed of 4).
pub const UNCERTAINTY_EPISODES: usize = 40_000;

/// Most training episodes of a timing run (40,000 take seconds; 10^7 about hours): a
/// larger value is a typo or a corrupt `config.json`, not a run anyone waits for.
pub const MAX_EPISODES: usize = 10_000_000;

/// Every `--set` key of a timing run.
pub const TIMING_KEYS: &str = "episodes, epsilon_start, epsilon_end, anneal_fraction, eval_every, stop_at_success, alpha, gamma, lambda, response_cost, probe, opportunity_cost, overdue_factor, wait_at_oven (true, false), q_init, noise (ddm), memory_noise, clock_noise (sbf, timecells-*), decision_rule (ratio, difference, likelihood, learned), env.<task parameter>";

/// The allowed range of an agent override `key` when `v` lies outside it.
fn agent_value_range(key: &str, v: f64) -> Option<&'static str> {
    match key {
        "q_init" if !v.is_finite() => Some("a finite number (initial Q of unvisited pairs)"),
        "alpha" if !(v > 0.0 && v <= 1.0) => Some("a step size in (0, 1]"),
        "gamma" | "lambda" if !(0.0..=1.0).contains(&v) => Some("a number in [0, 1]"),
        "response_cost" if !(v >= 0.0 && v.is_finite()) => Some("a finite cost >= 0"),
        "probe" if !(0.0..1.0).contains(&v) => Some("a fraction in [0, 1)"),
        "opportunity_cost" if !(0.0..1.0).contains(&v) => Some("a step size in [0, 1) (0 = off)"),
        "overdue_factor" if !(v == 0.0 || (v >= 1.0 && v.is_finite())) => {
            Some("a number >= 1 (a multiple of the expected time), or 0 = off")
        }
        k if k.ends_with("noise") && !(v >= 0.0 && v.is_finite()) => {
            Some("a number >= 0 (0 = noise-free)")
        }
        _ => None,
    }
}

/// Parses an agent override's value and checks its range (typed error naming the key).
fn check_agent_value(key: &str, value: &str) -> Result<(), TrainError> {
    if key == "wait_at_oven" {
        return parse::<bool>(key, value, "true or false").map(|_| ());
    }
    if key == "decision_rule" {
        return DecisionRule::from_name(value)
            .map(|_| ())
            .map_err(|allowed| TrainError::InvalidParam {
                field: key.into(),
                value: value.into(),
                allowed,
            });
    }
    let v: f64 = parse(key, value, "a number")?;
    match agent_value_range(key, v) {
        Some(allowed) => Err(TrainError::InvalidParam {
            field: key.into(),
            value: value.into(),
            allowed: allowed.into(),
        }),
        None => Ok(()),
    }
}

fn parse<T: std::str::FromStr>(key: &str, value: &str, allowed: &str) -> Result<T, TrainError> {
    value.parse().map_err(|_| TrainError::InvalidParam {
        field: key.into(),
        value: value.into(),
        allowed: allowed.into(),
    })
}

impl TimingRunConfig {
    /// Defaults for `model` on `task`.
    pub fn new(task: &str, model: &str, seed: u64) -> Self {
        let mut train = TimingTrainConfig::default();
        let family = make_config(task, &[] as &[&str]).map(|c| c.family());
        if family == Ok(TaskFamily::Uncertainty) {
            train.episodes = UNCERTAINTY_EPISODES;
        }
        TimingRunConfig {
            kind: "timing".into(),
            task: task.into(),
            env: Vec::new(),
            model: model.into(),
            seed,
            train,
            agent: Vec::new(),
        }
    }

    /// Applies one `key=value` override (typed errors name the field and allowed values).
    pub fn set(&mut self, kv: &str) -> Result<(), TrainError> {
        let (key, value) = kv
            .split_once('=')
            .ok_or_else(|| TrainError::BadOverride(kv.into()))?;
        let (key, value) = (key.trim(), value.trim());
        let t = &mut self.train;
        match key {
            "episodes" => t.episodes = parse(key, value, "a positive integer (at most 10^7)")?,
            "epsilon_start" => t.epsilon_start = parse(key, value, "a number in [0, 1]")?,
            "epsilon_end" => t.epsilon_end = parse(key, value, "a number in [0, 1]")?,
            "anneal_fraction" => t.anneal_fraction = parse(key, value, "a number in (0, 1]")?,
            "eval_every" => t.eval_every = parse(key, value, "episodes, 0 = only at the end")?,
            "stop_at_success" => {
                t.stop_at_success = match value {
                    "none" | "null" => None,
                    v => Some(parse(key, v, "a success rate in (0, 1], or none")?),
                }
            }
            "alpha" | "gamma" | "lambda" | "response_cost" | "probe" | "opportunity_cost"
            | "overdue_factor" | "q_init" | "noise" | "memory_noise" | "clock_noise"
            | "decision_rule" | "wait_at_oven" => {
                check_agent_value(key, value)?;
                self.agent.push(format!("{key}={value}"));
            }
            k if k.starts_with("env.") => {
                self.env.push(format!("{}={value}", &k[4..]));
                make_config(&self.task, &self.env)?;
            }
            _ => {
                return Err(TrainError::InvalidParam {
                    field: "--set".into(),
                    value: key.into(),
                    allowed: TIMING_KEYS.into(),
                });
            }
        }
        self.validate()
    }

    /// Checks ranges and the task with its overrides (also applied to a loaded
    /// `config.json`).
    pub fn validate(&self) -> Result<(), TrainError> {
        let t = &self.train;
        let bad = |field: &str, value: String, allowed: &str| {
            Err(TrainError::InvalidParam {
                field: field.into(),
                value,
                allowed: allowed.into(),
            })
        };
        if !chronocooked_models::timing::zoo::is_timing_model(&self.model) {
            return bad(
                "model",
                self.model.clone(),
                "a timing model (see `chronocooked zoo list`)",
            );
        }
        if self.kind != "timing" {
            return bad("kind", self.kind.clone(), "timing");
        }
        if t.episodes == 0 || t.episodes > MAX_EPISODES {
            return bad(
                "episodes",
                t.episodes.to_string(),
                &format!("1..={MAX_EPISODES}"),
            );
        }
        for (f, v) in [
            ("epsilon_start", t.epsilon_start),
            ("epsilon_end", t.epsilon_end),
        ] {
            if !(0.0..=1.0).contains(&v) {
                return bad(f, v.to_string(), "a number in [0, 1]");
            }
        }
        if let Some(v) = t.stop_at_success
            && !(v > 0.0 && v <= 1.0)
        {
            return bad(
                "stop_at_success",
                v.to_string(),
                "a success rate in (0, 1], or none",
            );
        }
        if !(t.anneal_fraction > 0.0 && t.anneal_fraction <= 1.0) {
            return bad(
                "anneal_fraction",
                t.anneal_fraction.to_string(),
                "a number in (0, 1]",
            );
        }
        for kv in &self.agent {
            let (key, value) = kv.split_once('=').unwrap_or((kv, ""));
            check_agent_value(key, value)?;
        }
        make_config(&self.task, &self.env)?;
        Ok(())
    }

    /// Builds the untrained agent with the overrides applied.
    pub fn build_agent(&self) -> Result<TimingAgent, TrainError> {
        let env = ChronoEnv::new(&make_config(&self.task, &self.env)?)?;
        let mut agent = make_timing_agent(&self.model, &env, self.seed).map_err(|e| {
            TrainError::InvalidParam {
                field: "model".into(),
                value: self.model.clone(),
                allowed: e,
            }
        })?;
        for kv in &self.agent {
            let (k, v) = kv.split_once('=').unwrap_or((kv, "0"));
            if k == "decision_rule" {
                check_agent_value(k, v)?;
                agent.timer.decision_mut().rule =
                    DecisionRule::from_name(v).map_err(|allowed| TrainError::InvalidParam {
                        field: k.into(),
                        value: v.into(),
                        allowed,
                    })?;
                continue;
            }
            if k == "wait_at_oven" {
                agent.config.wait_at_oven = parse(k, v, "true or false")?;
                continue;
            }
            let v: f64 = parse(k, v, "a number")?;
            match k {
                "alpha" => agent.learner.config.alpha = v,
                "gamma" => agent.learner.config.gamma = v,
                "lambda" => agent.learner.config.lambda = v,
                "response_cost" => agent.config.response_cost = v,
                "probe" => agent.config.probe = v,
                "opportunity_cost" => agent.config.opportunity_cost = v,
                "overdue_factor" => agent.config.overdue_factor = v,
                "q_init" => agent.learner.q_init = v,
                "noise" => match &mut agent.timer {
                    chronocooked_models::timing::timers::Timer::Ddm(d) => d.acc.noise = v,
                    _ => return Err(TrainError::UnknownKey("noise (ddm only)".into())),
                },
                "memory_noise" => match &mut agent.timer {
                    chronocooked_models::timing::timers::Timer::Sbf(s) => s.model.memory_noise = v,
                    chronocooked_models::timing::timers::Timer::Ddm(d) => d.memory_noise = v,
                    chronocooked_models::timing::timers::Timer::TimeCells(tc) => {
                        tc.memory_noise = v
                    }
                },
                "clock_noise" => match &mut agent.timer {
                    chronocooked_models::timing::timers::Timer::TimeCells(tc) => {
                        tc.cells.speed_noise = v
                    }
                    chronocooked_models::timing::timers::Timer::Sbf(s) => s.clock_noise = v,
                    _ => {
                        return Err(TrainError::UnknownKey(
                            "clock_noise (sbf, timecells-* only)".into(),
                        ));
                    }
                },
                _ => return Err(TrainError::UnknownKey(k.into())),
            }
        }
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
    if dir.join(run_folder::SUMMARY).is_file() {
        return Err(TrainError::Resume {
            path: dir.display().to_string(),
            reason: "the folder already holds a finished run; use a new --out".into(),
        });
    }
    let start = std::time::Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| TrainError::io(dir, e))?;
    write_atomic(&dir.join(run_folder::CONFIG), &json(cfg))?;
    // Every session of the folder is kept (`--resume` reruns an unfinished run).
    crate::run_dir::append_line(&dir.join(run_folder::COMMAND), &format!("{command}\n"))?;
    let _ = chronocooked_env::fs::remove_temp_files(dir);
    let task = make_config(&cfg.task, &cfg.env)?;
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
    integrity::write_recorded(&dir.join("agent.json"), &json(&agent))?;
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

/// Task id and task overrides of any run folder (PPO or timing agent), from its
/// `config.json`.
pub fn run_task(dir: &Path) -> Result<(String, Vec<String>), TrainError> {
    let p = dir.join(run_folder::CONFIG);
    let text = std::fs::read_to_string(&p).map_err(|_| TrainError::NotARun {
        path: dir.display().to_string(),
    })?;
    let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| TrainError::Resume {
        path: p.display().to_string(),
        reason: e.to_string(),
    })?;
    let task = v["task"].as_str().unwrap_or("FixedInterval-v0").to_string();
    let env = v["env"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|s| s.as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    Ok((task, env))
}

/// Whether `dir`'s `config.json` describes a timing-agent run (finished or not).
pub fn is_timing_run_config(dir: &Path) -> bool {
    std::fs::read_to_string(dir.join(run_folder::CONFIG))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .is_some_and(|v| v["kind"] == "timing")
}

/// Whether `dir` holds a timing-agent run (its `agent.json`, or a timing run's
/// `config.json`: an unfinished or damaged run is still a timing run, so a missing agent
/// is reported as such rather than as a PPO config error).
pub fn is_timing_run(dir: &Path) -> bool {
    std::fs::symlink_metadata(dir.join("agent.json")).is_ok() || is_timing_run_config(dir)
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
    let text = std::fs::read_to_string(&p).map_err(|_| TrainError::NotARun {
        path: dir.display().to_string(),
    })?;
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
    let p = dir.join("agent.json");
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
        serde_json::from_slice(&bytes).map_err(|e| bad_file(dir, "agent.json", e))?;
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
            let own = make_config(&cfg.task, &cfg.env)?;
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
