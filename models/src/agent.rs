//! The one agent interface every model plays the tasks through, and the episode runner.
//!
//! An agent sees what a player sees: the "codes" observation `[R, C, 6]` and the reward.
//! It never sees the hidden oven timer or `info`. The runner owns the env, attaches the
//! event markers to recorded activity and keeps the per-step `info` for the metrics.

use crate::activity::{Marker, StepRecorder, TrialRecorder};
use chronocooked_env::{
    Action, CODE_CHANNELS, ChronoEnv, EnvError, Events, Info, Layout, ObjectKind, OvenSet,
    ResetOptions, Task, TaskConfig, derive_seed,
};
use serde::{Deserialize, Serialize};

/// A model that plays Chronocooked tasks.
pub trait Agent {
    /// Zoo name of the model (`ddm`, `lstm125`, …).
    fn name(&self) -> String;

    /// A new episode starts with observation `obs`; `seed` seeds the agent's own noise
    /// for this episode (the same seed gives the same behaviour).
    fn begin_episode(&mut self, obs: &[u8], seed: u64);

    /// Chooses the action for observation `obs`.
    fn act(&mut self, obs: &[u8]) -> Action;

    /// Outcome of the last action (learning agents learn here).
    fn observe(&mut self, _reward: f32, _next_obs: &[u8], _terminated: bool, _truncated: bool) {}

    /// Writes the populations behind the last action (called only while recording).
    fn record(&self, _rec: &mut StepRecorder) {}

    /// Switches learning and exploration on (training) or off (evaluation: greedy).
    fn set_training(&mut self, _on: bool) {}

    /// Stochastic evaluation: sample actions from the policy instead of taking the most
    /// probable one, without learning (models whose behaviour is noisy anyway ignore it).
    fn set_sampling(&mut self, _on: bool) {}

    /// Episodes the reference protocol plays per start cell and condition: 1 for agents
    /// that act the same way every time from the same start (greedy policies), more for
    /// agents with internal noise (a timing model's clock or memory), whose behaviour is a
    /// distribution to be sampled — each draw with its own seed.
    fn noise_draws(&self) -> usize {
        1
    }

    /// Hidden state before each action — only for reference policies (the oracle);
    /// agents that model timing must not override this.
    fn observe_state(&mut self, _state: &chronocooked_env::KitchenState) {}
}

/// The optimal scripted policy of the env crate as an agent (reads the hidden state; a
/// reference for the metrics, not a model).
#[derive(Debug, Clone)]
pub struct OracleAgent {
    oracle: chronocooked_env::Oracle,
    state: Option<chronocooked_env::KitchenState>,
}

impl OracleAgent {
    /// The oracle of `env`'s task.
    pub fn new(env: &ChronoEnv) -> Self {
        OracleAgent {
            oracle: chronocooked_env::Oracle::new(env),
            state: None,
        }
    }
}

impl Agent for OracleAgent {
    fn name(&self) -> String {
        "oracle".into()
    }
    fn begin_episode(&mut self, _obs: &[u8], _seed: u64) {}
    fn act(&mut self, _obs: &[u8]) -> Action {
        self.state
            .as_ref()
            .map_or(Action::Wait, |s| self.oracle.act(s))
    }
    fn observe_state(&mut self, state: &chronocooked_env::KitchenState) {
        self.state = Some(*state);
    }
}

/// Uniformly random actions (seeded per episode): the chance baseline.
#[derive(Debug, Clone)]
pub struct RandomAgent {
    rng: rand_xoshiro::Xoshiro256PlusPlus,
}

impl Default for RandomAgent {
    fn default() -> Self {
        RandomAgent {
            rng: rand::SeedableRng::seed_from_u64(0),
        }
    }
}

impl Agent for RandomAgent {
    fn name(&self) -> String {
        "random".into()
    }
    fn begin_episode(&mut self, _obs: &[u8], seed: u64) {
        self.rng = rand::SeedableRng::seed_from_u64(seed);
    }
    fn act(&mut self, _obs: &[u8]) -> Action {
        use rand::Rng;
        Action::ALL[self.rng.random_range(0..Action::COUNT)]
    }
}

/// What the agent can read off a codes observation: position, hands, visible oven.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub struct Percept {
    /// Agent cell index (`row · cols + col`).
    pub cell: usize,
    /// 0 empty hands, 1 onion, 2 soup.
    pub carry: u8,
    /// Visible oven channel value (0 off, 1 on, 2 ready; multi-timer: the cue).
    pub oven: u8,
}

/// Parses codes observations of one layout into [`Percept`]s.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PerceptParser {
    /// Grid cells `R · C`.
    pub cells: usize,
    /// Oven cell index.
    pub oven_cell: usize,
    /// Cells next to the oven.
    pub oven_neighbours: Vec<usize>,
}

impl PerceptParser {
    /// Parser for `layout`.
    pub fn new(layout: &Layout) -> Self {
        let oven_cell = layout
            .cells_of(ObjectKind::Oven)
            .first()
            .copied()
            .unwrap_or(0);
        let oven_neighbours = layout
            .free_cells()
            .iter()
            .map(|&c| c as usize)
            .filter(|&c| matches!(layout.adjacent_object(c), Some((ObjectKind::Oven, _))))
            .collect();
        PerceptParser {
            cells: layout.n_cells(),
            oven_cell,
            oven_neighbours,
        }
    }

    /// Reads `obs` (codes, `[R, C, 6]` row-major).
    pub fn parse(&self, obs: &[u8]) -> Percept {
        let mut p = Percept::default();
        for cell in 0..self.cells {
            let o = &obs[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            if o[1] == 1 {
                p.cell = cell;
                p.carry = if o[3] != 0 {
                    2
                } else if o[2] != 0 {
                    1
                } else {
                    0
                };
            }
        }
        p.oven = obs[self.oven_cell * CODE_CHANNELS + 4];
        p
    }

    /// Whether `cell` touches the oven.
    pub fn next_to_oven(&self, cell: usize) -> bool {
        self.oven_neighbours.contains(&cell)
    }
}

/// What happened in one episode (plain data for the metrics).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRecord {
    /// Target duration (steps).
    pub td: u32,
    /// Start cell `(row, col)`.
    pub start: (usize, usize),
    /// Seed of the episode.
    pub seed: u64,
    /// Total reward.
    pub reward: f32,
    /// Ended with a delivery paying ≥ 0.999.
    pub success: bool,
    /// Actions taken (codes 0–5).
    pub actions: Vec<u8>,
    /// `info` after every step.
    pub infos: Vec<Info>,
    /// Multi-oven task: every oven's state after every step (one per action; empty in the
    /// other tasks).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ovens: Vec<OvenSet>,
}

impl EpisodeRecord {
    /// Checks a record read from a file before any metric reads it: at least one step, one
    /// `info` per action, action codes `0..=5`, a finite reward and a positive TD. The
    /// error names the field.
    pub fn validate(&self) -> Result<(), String> {
        if self.actions.is_empty() {
            return Err("field `actions`: empty (an episode has at least one step)".into());
        }
        if self.actions.len() != self.infos.len() {
            return Err(format!(
                "field `infos`: {} entries for {} actions (one per step)",
                self.infos.len(),
                self.actions.len()
            ));
        }
        if !self.ovens.is_empty() && self.ovens.len() != self.actions.len() {
            return Err(format!(
                "field `ovens`: {} entries for {} actions (one per step, or none outside the \
                 multi-oven task)",
                self.ovens.len(),
                self.actions.len()
            ));
        }
        if let Some(a) = self.actions.iter().find(|&&a| a as usize >= Action::COUNT) {
            return Err(format!("field `actions`: code {a} (allowed: 0..=5)"));
        }
        if !self.reward.is_finite() {
            return Err("field `reward`: not a finite number".into());
        }
        // Every task pays 0..=1 per step (delivery, sink, window), never less than 0.
        let steps = self.actions.len() as f32;
        if !(-1e-4..=steps + 1e-4).contains(&self.reward) {
            return Err(format!(
                "field `reward`: {} (allowed: 0..={steps}, at most 1 per step of the episode)",
                self.reward
            ));
        }
        if self.td == 0 {
            return Err("field `td`: 0 (allowed: a positive number of steps)".into());
        }
        self.validate_steps()
    }

    /// The steps are one episode's, in order: `info.timestep` counts 1, 2, …, the episode's
    /// TD is every step's, the agent moves only by its step's action (from `start` on the
    /// first), and `success` agrees with the return and the last step.
    fn validate_steps(&self) -> Result<(), String> {
        let mut at = (self.start.0 as i64, self.start.1 as i64);
        for (k, info) in self.infos.iter().enumerate() {
            if info.timestep as usize != k + 1 {
                return Err(format!(
                    "field `infos`: step {} has timestep {} (the steps of one episode count \
                     1, 2, …)",
                    k + 1,
                    info.timestep
                ));
            }
            if info.td != self.td {
                return Err(format!(
                    "field `infos`: step {} has td {}, the episode {}",
                    k + 1,
                    info.td,
                    self.td
                ));
            }
            let next = (i64::from(info.agent.0), i64::from(info.agent.1));
            let moved = (next.0 - at.0, next.1 - at.1);
            // A move is the step's action (a blocked move, a wait or an interact: none).
            let action = Action::ALL[usize::from(self.actions[k]) % Action::COUNT];
            let (dr, dc) = action.delta();
            if moved != (0, 0) && moved != (i64::from(dr), i64::from(dc)) {
                return Err(format!(
                    "field `infos`: step {} moves the agent from {at:?} to {next:?}, which its \
                     action `{}` does not (the first step from `start`)",
                    k + 1,
                    action.name()
                ));
            }
            at = next;
        }
        // Outside the dual task every reward is a delivery's, so the episode's return and its
        // last step decide its success (multi-oven: the return is 1 exactly when every soup
        // paid); in the dual task the return mixes sink rewards, and only a delivery ends an
        // episode with success.
        if let Some(last) = self.infos.last() {
            let agrees = if last.sink_count > 0 {
                !self.success || last.events.has(Events::DELIVERY)
            } else {
                self.success == is_success(last, self.reward)
            };
            if !agrees {
                return Err(format!(
                    "field `success`: {} does not agree with the return {} and the last step \
                     (events {:?})",
                    self.success,
                    self.reward,
                    last.events.names()
                ));
            }
        }
        Ok(())
    }
}

/// Success criterion shared by training and evaluation: a delivery paying the full reward
/// available in the episode — 1, or, when the oven never readies itself (uncertainty task),
/// the reduced reward of a soup readied with the manual button; in the multi-oven task, the
/// delivery that completes the episode with every soup at the counter of its duration; in
/// the reproduction task, a delivery produced inside the reward window.
pub fn is_success(info: &Info, reward: f32) -> bool {
    info.events.has(Events::DELIVERY)
        && (reward >= 0.999
            || info.events.has(Events::IN_WINDOW)
            || info.events.has(Events::ALL_PAID)
            || (info.never_ready && info.manual_stop_time >= 0 && reward > 0.0))
}

/// Plays one episode of `env` with `agent` from a reset with `seed` and `options`;
/// records activity into `recorder` when given.
pub fn run_episode(
    env: &mut ChronoEnv,
    agent: &mut dyn Agent,
    seed: u64,
    options: &ResetOptions,
    mut recorder: Option<&mut TrialRecorder>,
) -> Result<EpisodeRecord, EnvError> {
    let info = env.reset(Some(seed), options)?;
    let start = (info.agent.0 as usize, info.agent.1 as usize);
    agent.begin_episode(env.obs_codes(), derive_seed(seed, 0xA6E7));
    if let Some(r) = recorder.as_deref_mut() {
        r.begin_trial(info.td, start);
        r.set_context(&env.state());
    }
    let mut rec = EpisodeRecord {
        td: info.td,
        start,
        seed,
        reward: 0.0,
        success: false,
        actions: Vec::new(),
        infos: Vec::new(),
        ovens: Vec::new(),
    };
    loop {
        agent.observe_state(&env.state());
        let action = agent.act(env.obs_codes());
        if let Some(r) = recorder.as_deref_mut() {
            agent.record(r.step_recorder());
        }
        let t = env.step(action)?;
        rec.actions.push(action.code());
        rec.infos.push(t.info);
        let ovens = env.ovens();
        rec.ovens.extend(ovens);
        rec.reward += t.reward;
        if is_success(&t.info, t.reward) {
            rec.success = true;
        }
        if let Some(r) = recorder.as_deref_mut() {
            r.end_step(
                &Marker::of_step(&t.info, ovens.as_ref(), t.reward),
                t.reward,
            );
        }
        agent.observe(t.reward, env.obs_codes(), t.terminated, t.truncated);
        if t.done() {
            break;
        }
    }
    if let Some(r) = recorder {
        r.end_trial(rec.success);
    }
    Ok(rec)
}

/// Records `repeats` × (every start cell × `tds`) greedy episodes of `agent` on `config`
/// into an activity dataset (`task` names the task in its metadata; repetition
/// `r` is seeded `seed + r`, so noisy models give different trials). On the reproduction
/// task each `ts` is played in every context that can hold it: under each prior whose
/// range contains it (drawn by the env when none does) and at each gain.
pub fn record_dataset(
    agent: &mut dyn Agent,
    config: &TaskConfig,
    task: &Task,
    tds: &[u32],
    repeats: u64,
    seed: u64,
) -> Result<crate::ActivityDataset, EnvError> {
    let meta = crate::activity::ActivityMeta::new(&agent.name(), task, seed);
    let mut rec = TrialRecorder::new(meta);
    let conditions = recording_conditions(config, tds);
    for r in 0..repeats.max(1) {
        play_conditions(
            agent,
            config,
            &conditions,
            seed.wrapping_add(r),
            Some(&mut rec),
        )?;
    }
    Ok(rec.finish())
}

/// The reset options (without a start cell) a recording plays for `tds`: one per TD, and
/// on a Ready-Set-Go task one per (prior containing the `ts`, gain).
fn recording_conditions(config: &TaskConfig, tds: &[u32]) -> Vec<ResetOptions> {
    let plain = |td: u32| ResetOptions {
        td: Some(td),
        ..ResetOptions::default()
    };
    let Ok(Some(rsg)) = config.ready_set_go() else {
        return tds.iter().map(|&td| plain(td)).collect();
    };
    let (ranges, gains) = (&rsg.priors, &rsg.gains);
    let mut out = Vec::new();
    for &ts in tds {
        let holding: Vec<Option<u8>> = ranges
            .iter()
            .enumerate()
            .filter(|&(_, &(lo, hi))| (lo..=hi).contains(&ts))
            .map(|(i, _)| Some(i as u8))
            .collect();
        let prior_choices = if holding.is_empty() {
            vec![None]
        } else {
            holding
        };
        for prior in prior_choices {
            for gain in 0..gains.len().max(1) {
                out.push(ResetOptions {
                    prior,
                    gain: Some(gain as u8),
                    ..plain(ts)
                });
            }
        }
    }
    out
}

/// Deterministic evaluation: one greedy episode per free start cell per TD in `tds`.
/// Returns the records (start cells in row-major order, TDs in the given order).
pub fn evaluate_agent(
    agent: &mut dyn Agent,
    config: &TaskConfig,
    tds: &[u32],
    seed: u64,
    recorder: Option<&mut TrialRecorder>,
) -> Result<Vec<EpisodeRecord>, EnvError> {
    let conditions: Vec<ResetOptions> = tds
        .iter()
        .map(|&td| ResetOptions {
            td: Some(td),
            ..ResetOptions::default()
        })
        .collect();
    play_conditions(agent, config, &conditions, seed, recorder)
}

/// One greedy episode per free start cell per condition (`conditions` without start
/// cells), in condition order; episode `i` of condition `k` is seeded
/// `derive_seed(seed, k·1000 + i)`.
fn play_conditions(
    agent: &mut dyn Agent,
    config: &TaskConfig,
    conditions: &[ResetOptions],
    seed: u64,
    mut recorder: Option<&mut TrialRecorder>,
) -> Result<Vec<EpisodeRecord>, EnvError> {
    let mut env = ChronoEnv::new(config)?;
    agent.set_training(false);
    let layout = env.layout().clone();
    let mut out = Vec::new();
    for (k, condition) in conditions.iter().enumerate() {
        for (i, &cell) in layout.free_cells().iter().enumerate() {
            let options = ResetOptions {
                start: Some(layout.coords(cell as usize)),
                ..*condition
            };
            let s = derive_seed(seed, (k * 1000 + i) as u64);
            out.push(run_episode(
                &mut env,
                agent,
                s,
                &options,
                recorder.as_deref_mut(),
            )?);
        }
    }
    Ok(out)
}

/// Fraction of successes among episodes (`records.iter().map(|r| r.success)`, or a PPO
/// evaluation's episodes); `None` without any episode — the rate of nothing is undefined,
/// and each caller says what it writes then. The one success rate of the lab.
pub fn success_rate(successes: impl IntoIterator<Item = bool>) -> Option<f64> {
    let (mut n, mut k) = (0usize, 0usize);
    for s in successes {
        n += 1;
        k += usize::from(s);
    }
    (n > 0).then(|| k as f64 / n as f64)
}

#[cfg(test)]
mod tests {
    use super::success_rate;

    #[test]
    fn the_success_rate_of_no_episode_is_undefined() {
        assert_eq!(success_rate([true, false, true, true]), Some(0.75));
        assert_eq!(success_rate([false; 3]), Some(0.0));
        assert_eq!(success_rate(std::iter::empty()), None);
    }
}
