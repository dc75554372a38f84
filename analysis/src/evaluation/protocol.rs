//! Evaluation protocols (docs/metrics.md): the conditions each task is tested under and the runner
//! that plays them with any [`Agent`].
//!
//! Reference protocol: greedy policy, one episode per free start cell per condition (for
//! agents with internal noise, [`Agent::noise_draws`] episodes per start cell, each with its
//! own seed: a timing model's clock and memory noise is sampled, not frozen).
//! Stochastic variant: `N` episodes per condition from uniformly drawn start cells, actions
//! sampled from the policy, seeded. Conditions per trained task:
//! * FI: the trained TD, plus peak-interval probes with the soup released at 2× and 5× TD;
//! * bisection: probe durations 1 … L+4;
//! * multi-timer: every TD 1 … max(trained)+3 (OOD included), and for every trained TD the
//!   exact-timer buffers 0, 25, 50, 75% of TD;
//! * dual: the trained TD; uncertainty: normal and never-ready episodes.

use chronocooked_env::{ChronoEnv, EnvError, ResetOptions, Task, TaskConfig, derive_seed};
use chronocooked_models::activity::TrialRecorder;
use chronocooked_models::{Agent, run_episode};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

pub use crate::records::{Condition, ConditionKind, EvalRecord, Mode, RECORDS, read_records};

/// The reference conditions for an agent trained on `task`, as its family declares them
/// (`chronocooked_env::task::family`; the list per family is in this module's docs).
pub fn reference_conditions(task: &Task) -> Result<Vec<Condition>, EnvError> {
    task.config()?.conditions(task)
}

/// Plays every condition with `agent`; `seed` makes the run reproducible.
pub fn run_protocol(
    agent: &mut dyn Agent,
    conditions: &[Condition],
    mode: Mode,
    seed: u64,
) -> Result<Vec<EvalRecord>, EnvError> {
    run_protocol_recorded(agent, conditions, mode, seed, None)
}

/// Reproduction conditions are played as Jazayeri & Shadlen (2010) ran them: within each
/// context (prior × gain: a block of consecutive conditions) the sample intervals in a
/// seeded random order, not one `ts` after another. A model that carries a memory from
/// trial to trial (drift-diffusion's drift at a learning rate below 1) regresses towards
/// the prior's mean only when the trials mix; played in runs of one `ts` its memory
/// settles on that `ts` (measured: slope 1.00 with `reproduction_rate` 0.5). Episode seeds
/// stay those of each episode's condition and index, so only the order changes.
fn interleave_sample_intervals(
    jobs: &mut [(usize, usize, (usize, usize))],
    conditions: &[Condition],
    seed: u64,
) {
    let block_of = |ci: usize| {
        let c = &conditions[ci];
        (c.kind == ConditionKind::Reproduction).then_some(c.context)
    };
    let mut i = 0;
    while i < jobs.len() {
        let Some(block) = block_of(jobs[i].0) else {
            i += 1;
            continue;
        };
        let end = i + jobs[i..]
            .iter()
            .take_while(|j| block_of(j.0) == Some(block))
            .count();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(derive_seed(seed, (1 << 40) | i as u64));
        // Fisher–Yates.
        for a in (i + 1..end).rev() {
            let b = rng.random_range(i..=a);
            jobs.swap(a, b);
        }
        i = end;
    }
}

/// Most episodes per condition of the stochastic protocol (the paper's plays 100).
pub const MAX_STOCHASTIC_EPISODES: usize = 10_000;

/// Most steps an evaluation keeps in memory (all its episodes together; a step's record is
/// ≈ 100 bytes, so ≈ 2 GB): the reference protocol keeps thousands, 10,000 stochastic
/// episodes per condition (`--stochastic`'s maximum) of a solved task a few million; only
/// agents that never end their episodes under a large `max_timesteps` reach it.
pub const MAX_PROTOCOL_STEPS: usize = 20_000_000;

/// [`run_protocol`] that also records the agent's activity (one trial per episode, in
/// record order) into `recorder` when given. Fails (`InvalidParam`) once its episodes keep
/// more than [`MAX_PROTOCOL_STEPS`] steps.
pub fn run_protocol_recorded(
    agent: &mut dyn Agent,
    conditions: &[Condition],
    mode: Mode,
    seed: u64,
    recorder: Option<&mut TrialRecorder>,
) -> Result<Vec<EvalRecord>, EnvError> {
    run_protocol_within(agent, conditions, mode, seed, recorder, MAX_PROTOCOL_STEPS)
}

/// [`run_protocol_recorded`] with a step budget of `max_steps` (tests use a small one).
fn run_protocol_within(
    agent: &mut dyn Agent,
    conditions: &[Condition],
    mode: Mode,
    seed: u64,
    mut recorder: Option<&mut TrialRecorder>,
    max_steps: usize,
) -> Result<Vec<EvalRecord>, EnvError> {
    agent.set_training(false);
    agent.set_sampling(matches!(mode, Mode::Stochastic { .. }));
    let mut envs = Vec::with_capacity(conditions.len());
    // Every episode as (condition, index within it, start cell), in condition order.
    let mut jobs: Vec<(usize, usize, (usize, usize))> = Vec::new();
    for (ci, c) in conditions.iter().enumerate() {
        let config: TaskConfig = c.task.config()?;
        let env = ChronoEnv::new(&config)?;
        let cells = env.layout().free_coords();
        envs.push(env);
        let starts: Vec<(usize, usize)> = match mode {
            // Agents with internal noise: each start cell `noise_draws` times, own seeds.
            Mode::Reference => (0..agent.noise_draws().max(1))
                .flat_map(|_| cells.iter().copied())
                .collect(),
            Mode::Stochastic { episodes } => {
                let mut rng = Xoshiro256PlusPlus::seed_from_u64(derive_seed(seed, ci as u64));
                (0..episodes)
                    .map(|_| cells[rng.random_range(0..cells.len())])
                    .collect()
            }
        };
        jobs.extend(starts.into_iter().enumerate().map(|(k, st)| (ci, k, st)));
    }
    interleave_sample_intervals(&mut jobs, conditions, seed);
    let episodes = jobs.len();
    let mut out = Vec::with_capacity(episodes);
    let mut kept_steps = 0usize;
    for (ci, k, start) in jobs {
        let c = &conditions[ci];
        let options = ResetOptions {
            start: Some(start),
            td: Some(c.td),
            never_ready: c.never_ready,
            prior: c.context.map(|x| x[0]),
            gain: c.context.map(|x| x[1]),
            ..ResetOptions::default()
        };
        let s = derive_seed(seed, (ci as u64) << 20 | k as u64);
        let episode = run_episode(&mut envs[ci], agent, s, &options, recorder.as_deref_mut())?;
        kept_steps += episode.infos.len();
        if kept_steps > max_steps {
            return Err(EnvError::InvalidParam {
                field: "evaluation size (episodes × steps per episode)".into(),
                value: format!(
                    "more than {max_steps} steps kept after {} of {episodes} episodes \
                     (episodes of {} last up to max_timesteps = {})",
                    out.len() + 1,
                    c.task,
                    envs[ci].config().max_timesteps
                ),
                allowed: format!(
                    "at most {max_steps} steps in all (every step is kept in memory \
                     for the metrics): fewer episodes (--stochastic) or a smaller max_timesteps"
                ),
            });
        }
        out.push(EvalRecord {
            condition: c.clone(),
            episode,
        });
    }
    agent.set_sampling(false);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use chronocooked_env::Action;

    /// Never ends an episode: waits at every step.
    struct Waiter;
    impl Agent for Waiter {
        fn name(&self) -> String {
            "waiter".into()
        }
        fn begin_episode(&mut self, _obs: &[u8], _seed: u64) {}
        fn act(&mut self, _obs: &[u8]) -> Action {
            Action::Wait
        }
    }

    #[test]
    fn an_evaluation_past_its_step_budget_stops_with_an_error_naming_the_settings() {
        let env = vec!["max_timesteps=50".to_string()];
        let conditions =
            reference_conditions(&Task::parse("FixedInterval-v0", &env).unwrap()).unwrap();
        let mode = Mode::Stochastic { episodes: 10 };
        // A waiting agent's episodes last until each task's time limit (the protocol's
        // peak-interval probes keep their own).
        let all = run_protocol_within(&mut Waiter, &conditions, mode, 1, None, usize::MAX).unwrap();
        let total: usize = all.iter().map(|r| r.episode.infos.len()).sum();
        let budget = total - 1;
        let err = run_protocol_within(&mut Waiter, &conditions, mode, 1, None, budget)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(&format!("more than {budget} steps"))
                && err.contains("max_timesteps = ")
                && err.contains("--stochastic"),
            "{err}"
        );
        // At the budget exactly, the protocol runs.
        run_protocol_within(&mut Waiter, &conditions, mode, 1, None, total).unwrap();
    }
}
