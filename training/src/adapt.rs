//! Adaptation protocol (the paper's uncertainty experiment): an agent trained without
//! uncertainty (e.g. on FI) keeps learning on a new task (by default `Uncertainty-v0`, where
//! the oven never readies itself with probability 0.2 and the manual button must be used),
//! and we count the episodes it needs to adapt.
//!
//! Success per episode is the shared criterion ([`chronocooked_models::agent::is_success`]):
//! a delivery paying the full reward available — 1, or the button's reduced reward when the
//! oven never readies. Success is read separately on never-ready and normal ovens within the
//! last `window` episodes (≈ 20 never-ready ones of 100 at probability 0.2): an agent that
//! ignores the button scores exactly 0 on the never-ready ones (so chance fluctuations cannot
//! fake adaptation), and one that presses the button at once scores 0 on the normal ones
//! (the button pays the reduced reward there). The agent has adapted once both rates reach
//! `threshold` (0.8). The pre-trained agent should come from the same task without
//! uncertainty (`Uncertainty-v0` with `never_ready_prob=0`: same layout and cues); an FI agent
//! also sees the ready cue for the first time.
//!
//! Timing agents keep learning with their own rules (SARSA(λ) with exploration ε); PPO agents
//! are fine-tuned from their final weights (`init_from`) with the run's hyperparameters, and
//! their rolling success over the last `window` episodes is read from the training curve.

use crate::checked::Check;
use crate::error::TrainError;
use crate::ppo::config::Curriculum;
use crate::ppo::run::{Silent, run_training};
use crate::ppo::run_dir::RunDir;
use crate::timing_run::{is_timing_run, load_timing_agent};
use chronocooked_env::Task;
use chronocooked_env::fs::write_atomic;
use chronocooked_models::run_folder;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Settings of an adaptation run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AdaptConfig {
    /// Task adapted to, with its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Episodes played by timing agents.
    pub episodes: usize,
    /// Env steps of PPO fine-tuning.
    pub steps: u64,
    /// Rolling window (episodes, all kinds) of the success rates.
    pub window: usize,
    /// Success rate on both never-ready and normal ovens in the window that counts as
    /// adapted.
    pub threshold: f64,
    /// Exploration of timing agents while adapting.
    pub epsilon: f64,
    /// Seed.
    pub seed: u64,
}

/// Default episodes of a timing agent's adaptation.
pub const DEFAULT_EPISODES: usize = 3000;
/// Default env steps of PPO fine-tuning.
pub const DEFAULT_STEPS: u64 = 100_000;
/// Default rolling window (episodes) of the success rates.
pub const DEFAULT_WINDOW: usize = 100;
/// Default success rate (never-ready and normal ovens) that counts as adapted.
pub const DEFAULT_THRESHOLD: f64 = 0.8;
/// Default exploration of timing agents while adapting.
pub const DEFAULT_EPSILON: f64 = 0.05;

impl Default for AdaptConfig {
    fn default() -> Self {
        AdaptConfig {
            task: Task::new("Uncertainty-v0").expect("the uncertainty task is registered"),
            episodes: DEFAULT_EPISODES,
            steps: DEFAULT_STEPS,
            window: DEFAULT_WINDOW,
            threshold: DEFAULT_THRESHOLD,
            epsilon: DEFAULT_EPSILON,
            seed: 0,
        }
    }
}

/// What an adaptation run measured (`adapt.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AdaptResult {
    /// Model name.
    pub model: String,
    /// Task the agent was trained on.
    pub from_task: String,
    /// Task adapted to, with its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Episodes played.
    pub episodes: usize,
    /// Episodes played when the never-ready and the normal success of the window first both
    /// reached the threshold (`None`: never).
    pub episodes_to_adapt: Option<usize>,
    /// Never-ready success in the first full window.
    pub initial_success: f64,
    /// Never-ready success in the last window.
    pub final_success: f64,
    /// Success on normal ovens in the last window.
    pub final_normal_success: f64,
    /// Window (episodes).
    pub window: usize,
    /// Threshold.
    pub threshold: f64,
    /// `(episodes so far, never-ready success, normal success)` over the window ending
    /// there, along the run.
    pub curve: Vec<(usize, f64, f64)>,
}

/// Episodes an agent needs to adapt: the number of episodes played when the success rate
/// over the last `window` episodes first reaches `threshold` (`None` if it never does).
/// `successes` in episode order from the switch on.
pub fn episodes_to_adapt(successes: &[bool], window: usize, threshold: f64) -> Option<usize> {
    rolling_success(successes, window)
        .into_iter()
        .find(|&(n, r)| n >= window.max(1) && r >= threshold)
        .map(|(n, _)| n)
}

/// `(episodes so far, success rate over the last min(window, episodes) episodes)` after
/// every episode.
pub fn rolling_success(successes: &[bool], window: usize) -> Vec<(usize, f64)> {
    let w = window.max(1);
    let mut hits = 0usize;
    successes
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            hits += usize::from(s);
            if i >= w {
                hits -= usize::from(successes[i - w]);
            }
            (i + 1, hits as f64 / (i + 1).min(w) as f64)
        })
        .collect()
}

/// Adaptation curve of `(never_ready, success)` episodes: after every episode,
/// `(episodes so far, success among the never-ready episodes, success among the normal
/// episodes)` of the last `window` episodes (NaN for a kind absent from the window).
pub fn adaptation_curve(outcomes: &[(bool, bool)], window: usize) -> Vec<(usize, f64, f64)> {
    let w = window.max(1);
    let rate = |kind: bool, slice: &[(bool, bool)]| {
        let (n, k) = slice
            .iter()
            .filter(|o| o.0 == kind)
            .fold((0usize, 0usize), |(n, k), o| (n + 1, k + usize::from(o.1)));
        if n == 0 {
            f64::NAN
        } else {
            k as f64 / n as f64
        }
    };
    (0..outcomes.len())
        .map(|i| {
            let s = &outcomes[(i + 1).saturating_sub(w)..=i];
            (i + 1, rate(true, s), rate(false, s))
        })
        .collect()
}

/// `(episodes, never-ready success, success of every episode)` of every row of a PPO run's
/// `curves.csv`; the normal-oven success is recovered from the overall rate and the
/// never-ready probability `p`: `(overall − p·never_ready) / (1 − p)`.
fn curve_success(path: &Path, p: f64) -> Result<Vec<(usize, f64, f64)>, TrainError> {
    let curves = run_folder::Curves::read(path).map_err(|reason| TrainError::Resume {
        path: path.display().to_string(),
        reason,
    })?;
    let col = |name: &str| {
        curves.index(name).ok_or_else(|| TrainError::Resume {
            path: path.display().to_string(),
            reason: format!("no `{name}` column"),
        })
    };
    let (e, s, nr) = (
        col("episodes")?,
        col("success_rate")?,
        col("never_ready_success")?,
    );
    Ok(curves
        .rows
        .iter()
        .filter(|r| r[s].is_finite() && r[e].is_finite())
        .map(|r| {
            let (all, never) = (r[s], r[nr]);
            let normal = if never.is_finite() && p < 1.0 {
                ((all - p * never) / (1.0 - p)).clamp(0.0, 1.0)
            } else {
                all
            };
            (r[e] as usize, never, normal)
        })
        .collect())
}

fn check(cfg: &AdaptConfig) -> Result<(), TrainError> {
    let bad = |field: &str, value: String, allowed: &str| {
        Err(TrainError::InvalidParam {
            field: field.into(),
            value,
            allowed: allowed.into(),
        })
    };
    if cfg.window == 0 {
        return bad("window", "0".into(), "a positive number of episodes");
    }
    if !(cfg.threshold > 0.0 && cfg.threshold <= 1.0) {
        return bad("threshold", cfg.threshold.to_string(), "a rate in (0, 1]");
    }
    if !(0.0..=1.0).contains(&cfg.epsilon) {
        return bad("epsilon", cfg.epsilon.to_string(), "a rate in [0, 1]");
    }
    if cfg.episodes == 0 || cfg.steps == 0 {
        return bad("episodes/steps", "0".into(), "a positive budget");
    }
    cfg.task.config()?;
    Ok(())
}

/// Runs the adaptation protocol for the trained agent in `run` and writes `adapt.json` and
/// `adapt.csv` (plus, for PPO, the fine-tuning run folder `run/`) into `out`.
pub fn run_adaptation(
    run: &Path,
    cfg: &AdaptConfig,
    out: &Path,
) -> Result<AdaptResult, TrainError> {
    check(cfg)?;
    std::fs::create_dir_all(out).map_err(|e| TrainError::io(out, e))?;
    let task = cfg.task.config()?;
    let (model, from_task, curve, episodes) = if is_timing_run(run) {
        let (rc, mut agent) = load_timing_agent(run)?;
        let outcomes = chronocooked_models::adaptation_episodes(
            &mut agent,
            &task,
            cfg.episodes,
            cfg.epsilon,
            cfg.seed,
        )?;
        chronocooked_env::integrity::write_recorded(
            &out.join(run_folder::AGENT),
            serde_json::to_string(&agent).unwrap_or_default().as_bytes(),
        )?;
        let curve = adaptation_curve(&outcomes, cfg.window);
        (rc.model, rc.task.id().to_string(), curve, outcomes.len())
    } else {
        let source = RunDir::open(run)?.config()?;
        let mut tc = source.clone().into_inner();
        tc.task = cfg.task.clone();
        tc.seed = cfg.seed;
        tc.total_steps = cfg.steps;
        tc.eval_every = 0;
        tc.stop_at_success = None;
        tc.stats_window = cfg.window;
        tc.curriculum = Curriculum::None;
        tc.init_from = Some(
            std::path::absolute(run)
                .map_err(|e| TrainError::io(run, e))?
                .display()
                .to_string(),
        );
        let dir = out.join("run");
        let summary = if dir.join(run_folder::CONFIG).is_file() {
            run_training(None, &dir, "adapt (resumed)", &mut Silent)?
        } else {
            run_training(Some(tc.check()?), &dir, "adapt", &mut Silent)?
        };
        let p = f64::from(task.never_ready_prob());
        let curve = curve_success(&summary.dir.join(run_folder::CURVES), p)?;
        let episodes = curve.last().map_or(0, |c| c.0);
        (
            source.model.name(),
            source.task.id().to_string(),
            curve,
            episodes,
        )
    };
    let full: Vec<&(usize, f64, f64)> = curve.iter().filter(|c| c.0 >= cfg.window).collect();
    let result = AdaptResult {
        model,
        from_task,
        task: cfg.task.clone(),
        episodes,
        episodes_to_adapt: full
            .iter()
            .find(|c| c.1 >= cfg.threshold && c.2 >= cfg.threshold)
            .map(|c| c.0),
        initial_success: full.first().map_or(f64::NAN, |c| c.1),
        final_success: curve.last().map_or(f64::NAN, |c| c.1),
        final_normal_success: curve.last().map_or(f64::NAN, |c| c.2),
        window: cfg.window,
        threshold: cfg.threshold,
        curve,
    };
    let mut csv = String::from("episodes,never_ready_success,normal_success\n");
    for (n, a, b) in &result.curve {
        csv += &format!("{n},{a},{b}\n");
    }
    write_atomic(&out.join("adapt.csv"), csv.as_bytes())?;
    let json = serde_json::to_string_pretty(&result).unwrap_or_default();
    write_atomic(&out.join("adapt.json"), json.as_bytes())?;
    Ok(result)
}
