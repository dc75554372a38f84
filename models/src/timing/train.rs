//! Training loop of the timing-model agents: episodes with ε-greedy SARSA(λ) and the
//! models' native rules, periodic deterministic evaluation from every start cell.

use crate::agent::{Agent, evaluate_agent, run_episode, success_rate};
use crate::timing::agent::TimingAgent;
use chronocooked_env::{ChronoEnv, EnvError, ResetOptions, TaskConfig, derive_seed};
use serde::{Deserialize, Serialize};

/// Settings of a timing-agent training run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimingTrainConfig {
    /// Training episodes (per level, for a task learned in levels: [`training_levels`]).
    pub episodes: usize,
    /// Exploration at the start …
    pub epsilon_start: f64,
    /// … annealed linearly to this value …
    pub epsilon_end: f64,
    /// … over this fraction of the episodes (the step size too, when `alpha_end` is set).
    pub anneal_fraction: f64,
    /// Final SARSA(λ) step size: `α` anneals linearly from the agent's own value to this
    /// one over the same episodes as ε (`None`: constant `α`). A constant step size leaves
    /// the values tracking the last ~`1/α` episodes' returns, and the greedy first check is
    /// where a noisy check-minus-wait advantage first crosses zero, which can come early,
    /// the more so the more steps an interval spends near the threshold (long TDs). Decreasing step sizes are the
    /// stochastic-approximation condition for the estimates to converge (Robbins & Monro
    /// 1951; Sutton & Barto 2018 §2.5). Off by default (Ludvig et al.'s constant α): the
    /// measured gain was partial and seed-dependent (RESULTS.md, "Step-size annealing").
    #[serde(default)]
    pub alpha_end: Option<f64>,
    /// Exponent ω of the visit-count step floor (0 = off): while training, each weight
    /// steps by at least `nᵢ^−ω` (normalised by `|φ|²`), `nᵢ` its feature's summed squared
    /// activity over its pair's visits ([`crate::timing::sarsa::SarsaLambda::set_visit_power`];
    /// Even-Dar & Mansour 2003). With `alpha_end` a pair first visited late in training
    /// would learn at the annealed step size from its initial value; with the floor it
    /// learns from its first samples. Off by default; 0.85 for the time cells on the
    /// reproduction task.
    #[serde(default)]
    pub visit_power: f64,
    /// Evaluate every this many episodes (0: only at the end).
    pub eval_every: usize,
    /// Stop once an evaluation reaches this success rate.
    pub stop_at_success: Option<f64>,
}

impl Default for TimingTrainConfig {
    fn default() -> Self {
        TimingTrainConfig {
            episodes: 6000,
            epsilon_start: 0.3,
            epsilon_end: 0.0,
            anneal_fraction: 0.8,
            alpha_end: None,
            visit_power: 0.0,
            eval_every: 500,
            stop_at_success: None,
        }
    }
}

/// One point of the learning curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimingCurvePoint {
    /// Episodes done.
    pub episode: usize,
    /// Env steps done.
    pub steps: u64,
    /// Success rate of the last (up to) 100 training episodes.
    pub train_success: f64,
    /// Mean reward of the last (up to) 100 training episodes.
    pub train_reward: f64,
    /// Deterministic evaluation success rate, when evaluated at this point.
    pub eval_success: Option<f64>,
}

/// Training episode number `ep` of a run seeded `seed` (default reset, no recording).
fn training_episode(
    env: &mut ChronoEnv,
    agent: &mut TimingAgent,
    seed: u64,
    ep: usize,
) -> Result<crate::agent::EpisodeRecord, EnvError> {
    run_episode(
        env,
        agent,
        derive_seed(seed, ep as u64),
        &ResetOptions::default(),
        None,
    )
}

/// The tasks a timing agent trains through on `config`, in order: the reference's
/// curricula, as it trains its agents.
///
/// * Multi-anchor categorization with more than two active anchors: 2, 3, … counters. A
///   model stores an anchor only when its counter pays (among more than two counters an
///   unpaid choice does not say which was right), so from scratch on all counters at once
///   it must find every counter by exploration before it can judge; measured on 3–4
///   anchors (6000 episodes, seeds 1–3), some runs stopped using the oven at all (success
///   0). Two counters first teach both anchors from every choice.
/// * Multi-oven bisection with more than one oven: 1, 2, … ovens. From scratch on 3
///   synchronous ovens drift-diffusion (seed 1) sent every soup of the first oven to the
///   short counter, a local optimum of the TD learner (the long counter is the longer
///   walk from that oven), while its clocks judged the other ovens right.
///
/// Other tasks: `config` itself.
pub fn training_levels(config: &TaskConfig) -> Result<Vec<TaskConfig>, EnvError> {
    config.growth_levels()
}

/// Trains `agent` on `config` for `train.episodes` episodes from `seed`; evaluates on
/// `eval_tds` from every start cell. Calls `progress` at every curve point.
///
/// Tasks learned in levels ([`training_levels`]) train `train.episodes` episodes per level,
/// each level with its own exploration schedule (ε from `epsilon_start` to `epsilon_end`
/// over `anneal_fraction` of the level's episodes); evaluation always plays `config`. (With
/// half the default budget per level — 3000 — 2 of 20 runs on anchors 4, 8, 16 never
/// found the third counter: microstimuli and Laplace seed 4, anchor accuracy 0.63; with
/// 6000 per level both reached 0.93.)
pub fn train_timing_agent(
    agent: &mut TimingAgent,
    config: &TaskConfig,
    train: &TimingTrainConfig,
    eval_tds: &[u32],
    seed: u64,
    mut progress: impl FnMut(&TimingCurvePoint),
) -> Result<Vec<TimingCurvePoint>, EnvError> {
    let levels = training_levels(config)?;
    let mut curve = Vec::new();
    let mut window: std::collections::VecDeque<(bool, f32)> = Default::default();
    let mut steps = 0u64;
    let alpha_start = agent.learner.config.alpha;
    agent.learner.set_visit_power(train.visit_power);
    let mut ep = 0;
    'levels: for (i, level) in levels.iter().enumerate() {
        let mut env = ChronoEnv::new(level)?;
        if levels.len() > 1 {
            agent.transfer_to(&env);
        }
        let end = train.episodes * (i + 1);
        let first = ep;
        let anneal = ((end - first) as f64 * train.anneal_fraction).max(1.0);
        while ep < end {
            let frac = ((ep - first) as f64 / anneal).min(1.0);
            agent.set_epsilon(
                train.epsilon_start + (train.epsilon_end - train.epsilon_start) * frac,
            );
            if let Some(end) = train.alpha_end {
                agent.learner.config.alpha = alpha_start + (end - alpha_start) * frac;
            }
            agent.set_training(true);
            let rec = training_episode(&mut env, agent, seed, ep)?;
            ep += 1;
            steps += rec.actions.len() as u64;
            window.push_back((rec.success, rec.reward));
            if window.len() > 100 {
                window.pop_front();
            }
            let done = ep;
            let eval_now = done == train.episodes * levels.len()
                || (train.eval_every > 0 && done % train.eval_every == 0);
            if eval_now {
                if levels.len() > 1 {
                    agent.transfer_to(&ChronoEnv::new(config)?);
                }
                let records =
                    evaluate_agent(agent, config, eval_tds, derive_seed(seed, 1 << 40), None)?;
                if levels.len() > 1 {
                    agent.transfer_to(&env);
                }
                // No evaluation episode (a task without evaluated TDs): no rate, no stop.
                let rate = success_rate(records.iter().map(|r| r.success));
                let n = window.len().max(1) as f64;
                let point = TimingCurvePoint {
                    episode: done,
                    steps,
                    train_success: window.iter().filter(|w| w.0).count() as f64 / n,
                    train_reward: window.iter().map(|w| f64::from(w.1)).sum::<f64>() / n,
                    eval_success: rate,
                };
                progress(&point);
                curve.push(point);
                if train.stop_at_success.zip(rate).is_some_and(|(s, r)| r >= s) {
                    break 'levels;
                }
            }
        }
    }
    if levels.len() > 1 {
        agent.transfer_to(&ChronoEnv::new(config)?);
    }
    agent.learner.config.alpha = alpha_start;
    agent.learner.set_visit_power(0.0);
    agent.set_training(false);
    Ok(curve)
}

/// Plays `episodes` training episodes of `config` with learning on and exploration
/// `epsilon`, and returns `(never_ready, success)` of each episode in order — the
/// adaptation record of an already trained agent moved to a new task.
pub fn adaptation_episodes(
    agent: &mut TimingAgent,
    config: &TaskConfig,
    episodes: usize,
    epsilon: f64,
    seed: u64,
) -> Result<Vec<(bool, bool)>, EnvError> {
    let mut env = ChronoEnv::new(config)?;
    agent.transfer_to(&env);
    agent.set_epsilon(epsilon);
    agent.set_training(true);
    let mut out = Vec::with_capacity(episodes);
    for ep in 0..episodes {
        let rec = training_episode(&mut env, agent, seed, ep)?;
        let never_ready = rec.infos.last().is_some_and(|i| i.never_ready);
        out.push((never_ready, rec.success));
    }
    agent.set_training(false);
    Ok(out)
}
