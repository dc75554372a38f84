//! The timing agents on Ready-Set-Go (temporal reproduction) tasks.
//!
//! The oven flashes twice (Ready, Set: the value 2 for one step each) `ts` steps apart and
//! then shows "on" until the soup is taken; the production `tp` is the number of steps from
//! the Set step to the pickup. What the agent sees and does:
//! * **Ready** (the first flash): the timing model starts its measurement
//!   ([`Timer::begin_measurement`]) in the context the counter cues (prior and gain);
//! * **Set** (the next flash, `ts` observations later): the measurement ends and the model
//!   starts its production of `g · ts` with its own machinery
//!   ([`Timer::begin_production`]): drift-diffusion adapts its drift to the accumulator at
//!   Set (Simen et al. 2011), SBF stores the oscillator pattern at Set, the time cells
//!   start again and the TD learner reads the production from the running population and
//!   its snapshot at Set;
//! * the production clock reads 1 at the Set observation and `c` at the observation whose
//!   interact produces `tp = c`, so a model that responds when its clock reaches its
//!   measured interval reproduces `ts`.
//!
//! The gate and the TD learner are the fixed-interval agent's: drift-diffusion and SBF may
//! take the soup once they respond (the accumulator at threshold, the detector matching the
//! stored pattern); the time cells' TD learner decides from conjunctive features `m ⊗ p(t)`
//! — the population at Set (`m`, the measurement) times the running one (`p`), mixed
//! selectivity for "this much time has passed since Set, having measured that much" — as
//! one linear readout cannot compare two population vectors. The counter's cue enters the
//! learner's discrete state, so each context (prior, gain) has its own values. While the
//! soup is carried to the counter the learner keeps reading `m ⊗ p` as it was at the
//! response: the reward, paid at the delivery, is decided by the response, so the states
//! of the walk must carry it (a Markov state for TD). With zeros there, every carry state
//! valued the average delivery and the response's value learned only what the traces
//! brought back: measured on the default task (seeds 1–4), success 0.64–0.72 → 0.69–0.75
//! (delay line), 0.76–0.86 → 0.82–0.86 (Laplace), and the long prior's slopes 0.10 → 0.23
//! (Laplace), 0.40 → 0.42 (delay line).
//!
//! While training, the time cells explore later responses as one decision: with
//! probability ε a response the policy is about to make is delayed by a random
//! `1 ..= ⌈0.25 t⌉` steps ([`super::TimingAgentConfig::response_delay`]), and the waits in
//! between are not learned from. ε-greedy alone tries a later response only with two
//! exploratory actions in a row, so the learned production stayed 1–2 steps early at the
//! long end of a prior even without noise.
//!
//! Where a regression to the mean of the prior can come from, per model: drift-diffusion
//! only from memory averaging (`reproduction_rate` below 1 keeps part of the context's past
//! drifts); SBF from nothing (the trial's own pattern is matched); the time cells from
//! what TD learns: the values of responding at `t` after a measurement `m` average the
//! rewards over every `ts` that produced similar `m` (a learned prior, with the
//! population's blur and the clock noise as the likelihood).

use super::TimingAgent;
use crate::agent::Percept;
use crate::timing::timers::Timer;
use chronocooked_env::{Action, CODE_CHANNELS, ChronoEnv};
use rand::Rng;
use serde::{Deserialize, Serialize};

/// What a timing agent knows of a Ready-Set-Go task: where the context cue is shown and
/// the gain each cue value asks for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReadySetGoCues {
    /// Cell whose channel 4 shows the context cue (the delivery counter).
    pub cue_cell: usize,
    /// The task's gains `g` (`tp = g · ts`), in the task's order.
    pub gains: Vec<f64>,
}

impl ReadySetGoCues {
    /// The cues of `env`'s task, or `None` for a task without Ready-Set-Go mechanics.
    pub fn of(env: &ChronoEnv) -> Option<Self> {
        let rsg = env.ready_set_go()?;
        Some(ReadySetGoCues {
            cue_cell: rsg.counter,
            gains: (0..rsg.gains.len()).map(|g| rsg.gain(g)).collect(),
        })
    }

    /// The gain asked for by cue value `cue` (`1 + prior · gains + gain`; 0 = no cue: the
    /// only gain).
    pub fn gain(&self, cue: u8) -> f64 {
        if cue == 0 || self.gains.is_empty() {
            return self.gains.first().copied().unwrap_or(1.0);
        }
        self.gains[(usize::from(cue) - 1) % self.gains.len()]
    }
}

/// The exploration of later responses at one step of a production
/// ([`TimingAgent::explore_later_response`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LaterResponse {
    /// No delayed response: the policy's action, learned on-policy.
    None,
    /// The policy would respond; the agent waits instead, and the response is delayed.
    Begins,
    /// A delayed response is pending: the agent waits, and nothing is learned (the waits
    /// are exploratory, not the policy's: on-policy targets through them would teach the
    /// value of waiting from responses the policy never makes).
    Waiting,
    /// The delayed response is due: the agent responds, and learning resumes there, so
    /// the response's value is learned from its reward.
    Due,
}

impl LaterResponse {
    /// The action taken when the policy chose `chosen`.
    pub(super) fn action(self, chosen: usize) -> usize {
        match self {
            LaterResponse::None => chosen,
            LaterResponse::Begins | LaterResponse::Waiting => Action::Wait.code() as usize,
            LaterResponse::Due => Action::Interact.code() as usize,
        }
    }

    /// Whether the step's action is learned from (visited, and updated at the next step).
    pub(super) fn learns(self) -> bool {
        matches!(self, LaterResponse::None | LaterResponse::Due)
    }
}

/// The epochs of a reproduction episode as the agent sees them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) enum Epoch {
    /// Before Ready.
    #[default]
    Waiting,
    /// Between Ready and Set.
    Measuring,
    /// From Set to the pickup.
    Producing,
    /// The soup is out.
    Done,
}

impl TimingAgent {
    /// Whether the agent plays the reproduction task.
    pub(super) fn reproduces(&self) -> bool {
        self.reproduction.is_some()
    }

    /// Temporal features the learner sees for `timer` in the reproduction task: the time
    /// cells' conjunctive code `m ⊗ p` (`N²`), the other models' own features.
    pub(super) fn reproduction_features(timer: &Timer) -> usize {
        match timer {
            Timer::TimeCells(tc) => tc.cells.repr.size().pow(2),
            t => t.n_features(),
        }
    }

    /// The discrete state's oven level in the reproduction task: the oven's value (0 off,
    /// 1 on, 2 flash) and the context cue, `oven + 3 · cue` (at most 3 priors × 2 gains = 6
    /// cues: ≤ 20, below [`super::OVEN_LEVELS`]).
    pub(super) fn reproduction_oven_level(&self, p: &Percept) -> u8 {
        p.oven.min(2).saturating_add(self.ep.cue.saturating_mul(3))
    }

    /// Runs the epochs from what is visible: Ready starts the measurement, Set ends it and
    /// starts the production, the pickup ends the trial.
    pub(super) fn update_reproduction_clock(&mut self, p: &Percept, obs: &[u8]) {
        let Some(cues) = &self.reproduction else {
            return;
        };
        self.ep.cue = obs[cues.cue_cell * CODE_CHANNELS + 4];
        let gain = cues.gain(self.ep.cue);
        let Some(last) = self.ep.last else {
            return;
        };
        match self.ep.epoch {
            Epoch::Waiting if p.oven == 2 => {
                self.ep.ctx = self.ep.cue;
                self.timer.begin_measurement(self.ep.ctx, &mut self.rng);
                self.ep.epoch = Epoch::Measuring;
                self.ep.clock = 0;
            }
            Epoch::Measuring => {
                self.ep.clock += 1;
                self.timer.tick(self.ep.clock, &mut self.rng);
                if p.oven != 0 {
                    // Set (a flash, or the oven already on): the measured interval is
                    // `clock` steps.
                    let ts = f64::from(self.ep.clock);
                    let mut m = std::mem::take(&mut self.ep.measurement);
                    self.timer.features_into(false, &mut m);
                    self.ep.measurement = m;
                    self.timer
                        .begin_production(self.ep.ctx, ts, gain, &mut self.rng);
                    self.ep.epoch = Epoch::Producing;
                    self.ep.running = true;
                    self.ep.clock = 1;
                    self.ep.started = None;
                    self.ep.interval = None;
                    self.timer.tick(1, &mut self.rng);
                }
            }
            Epoch::Producing => {
                if p.carry == 2 && last.carry != 2 {
                    // The learner's features of the pickup step (bias first) hold the
                    // code the response was decided on: keep it for the walk.
                    let n = Self::reproduction_features(&self.timer);
                    self.ep.response_code.clear();
                    if let (Timer::TimeCells(_), Some(code)) = (&self.timer, self.phi.get(1..=n)) {
                        self.ep.response_code.extend_from_slice(code);
                    }
                    self.ep.running = false;
                    self.ep.interval = Some(self.ep.clock);
                    self.ep.epoch = Epoch::Done;
                    return;
                }
                self.ep.prev_check_failed = self.ep.last_was_check;
                self.ep.clock += 1;
                self.timer.tick(self.ep.clock, &mut self.rng);
            }
            _ => {}
        }
    }

    /// Replaces the model's temporal features by what the learner reads in the
    /// reproduction task: during the production, the time cells' `m ⊗ p(t)` (the other
    /// models' features as they are); while the soup is carried, the time cells' code at
    /// the response, held; before Set and otherwise nothing (zeros).
    pub(super) fn reproduction_features_into(&mut self, features: &mut Vec<f64>, p: &Percept) {
        // The time cells' conjunctive code is read where the production is decided: next
        // to the oven, empty-handed. Elsewhere the learner sees the discrete state alone,
        // so the way to the oven is learned once, not once per (measurement, time) pair
        // (measured: with the code everywhere, agents that reached the oven after Set
        // wandered in the production epoch, 2–40% success).
        let at_oven = p.carry == 0 && self.parser.next_to_oven(p.cell);
        let producing = self.ep.epoch == Epoch::Producing
            && (at_oven || !matches!(self.timer, Timer::TimeCells(_)));
        if let Timer::TimeCells(_) = self.timer {
            let running = std::mem::take(features);
            let n = running.len();
            if producing && self.ep.measurement.len() == n {
                for &mi in &self.ep.measurement {
                    features.extend(running.iter().map(|&pj| mi * pj));
                }
            } else if self.ep.epoch == Epoch::Done
                && p.carry == 2
                && self.ep.response_code.len() == n * n
            {
                features.extend_from_slice(&self.ep.response_code);
            } else {
                features.resize(n * n, 0.0);
            }
        } else if !producing {
            features.iter_mut().for_each(|v| *v = 0.0);
        }
    }

    /// Training, time cells at the oven during a production: the exploration of later
    /// responses ([`super::TimingAgentConfig::response_delay`]) around the action the
    /// policy `chosen`.
    pub(super) fn explore_later_response(&mut self, chosen: usize, hold: bool) -> LaterResponse {
        let respond = Action::Interact.code() as usize;
        let producing = hold && self.ep.epoch == Epoch::Producing && !self.timer.has_gate();
        if !producing || self.config.response_delay <= 0.0 {
            self.ep.delayed_response = None;
            return LaterResponse::None;
        }
        if let Some(due) = self.ep.delayed_response {
            if self.ep.clock < due {
                return LaterResponse::Waiting;
            }
            self.ep.delayed_response = None;
            return LaterResponse::Due;
        }
        if chosen == respond && self.rng.random::<f64>() < self.config.epsilon {
            let span = (self.config.response_delay * f64::from(self.ep.clock)).ceil();
            let span = (span as u32).max(1);
            self.ep.delayed_response = Some(self.ep.clock + self.rng.random_range(1..=span));
            return LaterResponse::Begins;
        }
        LaterResponse::None
    }

    /// Whether the agent is timing (measuring or producing): it waits at the oven then.
    pub(super) fn reproduction_timing(&self) -> bool {
        matches!(self.ep.epoch, Epoch::Measuring | Epoch::Producing)
    }
}

#[cfg(test)]
mod tests {
    use super::Epoch;
    use crate::agent::Agent;
    use crate::timing::zoo::make_timing_agent;
    use chronocooked_env::Action;
    use chronocooked_env::{ChronoEnv, Oracle, ResetOptions, make_config};

    /// The time cells' learner reads, on the way to the counter, exactly the conjunctive
    /// code it read at the oven when the soup was taken — the response that decides the
    /// reward — and, before Set, nothing.
    #[test]
    fn the_time_cells_carry_their_response_code_to_the_counter() {
        let config = make_config("Reproduction-v0", &["priors=9-15"]).unwrap();
        let mut env = ChronoEnv::new(&config).unwrap();
        let oracle = Oracle::new(&env);
        let mut agent = make_timing_agent("timecells-csc", &env, 3).unwrap();
        agent.set_training(false);
        for ts in [9, 12, 15] {
            let options = ResetOptions {
                td: Some(ts),
                ..Default::default()
            };
            env.reset(Some(u64::from(ts)), &options).unwrap();
            agent.begin_episode(env.obs_codes(), u64::from(ts));
            let (mut at_response, mut carried, mut before_set) = (None, 0, 0);
            loop {
                let _ = agent.act(env.obs_codes());
                let code = agent.phi[1..].to_vec();
                match agent.ep.epoch {
                    Epoch::Producing if code.iter().any(|&v| v != 0.0) => {
                        at_response = Some(code);
                    }
                    Epoch::Done => {
                        let held = at_response.as_ref().expect("a response before the carry");
                        assert_eq!(&code, held, "ts {ts}: the carry reads the response's code");
                        carried += 1;
                    }
                    Epoch::Waiting | Epoch::Measuring => {
                        assert!(
                            code.iter().all(|&v| v == 0.0),
                            "ts {ts}: no code before Set"
                        );
                        before_set += 1;
                    }
                    Epoch::Producing => {}
                }
                let t = env.step(oracle.act(&env.state())).unwrap();
                agent.observe(t.reward, env.obs_codes(), t.terminated, t.truncated);
                if t.terminated || t.truncated {
                    assert!(t.reward > 0.0, "ts {ts}: the oracle's production is paid");
                    break;
                }
            }
            assert!(
                carried >= 1 && before_set >= ts as usize,
                "ts {ts}: {carried} {before_set}"
            );
        }
    }

    /// While training, a response the time cells are about to make is sometimes delayed:
    /// the agent waits and responds at the drawn time, `1 ..= ⌈0.25 t0⌉` steps after the
    /// production time `t0` where the policy would have responded, and the waits in between
    /// teach the learner nothing (they are not the policy's).
    #[test]
    fn a_delayed_response_comes_within_its_span_and_its_waits_teach_nothing() {
        let config = make_config("Reproduction-v0", &["priors=9-15"]).unwrap();
        let mut env = ChronoEnv::new(&config).unwrap();
        let mut agent = make_timing_agent("timecells-csc", &env, 3).unwrap();
        assert!(agent.config.response_delay > 0.0);
        agent.set_training(true);
        agent.set_epsilon(0.3);
        let (mut delays, mut quiet_waits) = (0, 0);
        for episode in 0..600u64 {
            env.reset(Some(episode), &ResetOptions::default()).unwrap();
            agent.begin_episode(env.obs_codes(), episode);
            loop {
                let pending = agent.ep.delayed_response;
                let learner = pending.map(|_| agent.learner.clone());
                let action = agent.act(env.obs_codes());
                let t = env.step(action).unwrap();
                agent.observe(t.reward, env.obs_codes(), t.terminated, t.truncated);
                match (pending, agent.ep.delayed_response) {
                    (None, Some(due)) => {
                        let t0 = agent.ep.clock;
                        let span = (0.25 * f64::from(t0)).ceil() as u32;
                        assert_eq!(action, Action::Wait);
                        assert!(due > t0 && due <= t0 + span.max(1), "t0 {t0}, due {due}");
                        delays += 1;
                    }
                    (Some(_), Some(_)) => {
                        assert_eq!(action, Action::Wait);
                        assert!(
                            learner.as_ref() == Some(&agent.learner),
                            "a delaying wait changed the values"
                        );
                        quiet_waits += 1;
                    }
                    (Some(due), None) if agent.ep.epoch == Epoch::Producing || t.terminated => {
                        assert_eq!(action, Action::Interact);
                        assert_eq!(agent.ep.clock, due);
                    }
                    _ => {}
                }
                if t.terminated || t.truncated {
                    break;
                }
            }
        }
        assert!(
            delays >= 20 && quiet_waits >= 1,
            "{delays} delays, {quiet_waits} waits"
        );
    }
}
