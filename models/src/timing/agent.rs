//! Timing-model agents: a timing model ([`Timer`]) supplies the temporal representation
//! and, for drift-diffusion and SBF, a native "it is time" gate; a linear SARSA(λ) learner
//! over (discrete state × temporal features) learns where to go and what to do.
//!
//! What the agent knows: the codes observation only — its cell, what it carries, the
//! visible oven value (off / on / ready / cue) — and the layout. It never sees the hidden
//! oven timer. Its clock starts when it sees the oven turn on; the elapsed time it holds is
//! the timing model's state. The temporal features freeze when the interval ends (the
//! oven shows ready, or the soup is taken out), the model's memory of the interval. In
//! tasks whose oven shows a ready cue (bisection, uncertainty) the TD learner reads the
//! temporal features only while the interval runs and is not overdue; afterwards it sees
//! the model's categorical outputs:
//! * the interval has ended (the cue came, or the button readied the oven): what later
//!   choices need is the model's judgment of it (bisection counters), not a frozen clock —
//!   frozen features let values learned at the usual end time leak, by linear
//!   generalisation, into trials that ended at other times (a button-readied oven);
//! * the interval is overdue — past `overdue_factor ×` the model's expected time without
//!   the cue (drift-diffusion, SBF): the expected cue has been omitted. That is the
//!   time-out state of the uncertainty task, where the button is the way out; without it
//!   the linear readout of a ramp extrapolates the rising value of waiting past the
//!   expected time.
//!
//! Tasks without a cue (fixed interval, peak interval, multi-timer) keep the temporal
//! features throughout: the model's own checks are the only events there, and the peak
//! procedure's stop comes from the readout (both categorical replacements were measured
//! there and made the multi-timer and the peak-interval stop worse: RESULTS.md).
//!
//! Learning signals:
//! * TD: the env reward minus a small response cost per interact (effort), so checking
//!   the oven early is not free and the "when" is learnable from the features alone;
//! * native rules at reinforcement — drift-diffusion drift learning and SBF pattern storage
//!   at the reinforced time: the ready cue when the task shows it; otherwise the pickup time,
//!   exact when the successful check followed a failed one (the soup became available
//!   between them), and treated as `(1 − probe) ×` the time the model started responding
//!   when the first check succeeded (the soup may have been waiting: aim earlier next time).
//! * the gate: before the timing model responds, interacting with the oven is not among
//!   the actions (DDM: until `x ≥ z`; SBF: until the output matches the stored pattern).
//! * bisection: when the interval ends the timing model judges it short or long against
//!   its anchor memories ([`crate::timing::judgment`]); from then on the TD learner sees
//!   that judgment (two indicator features) instead of the frozen temporal features, so it
//!   learns only which counter each judgment goes to. The outcome of the choice tells the
//!   model the interval's category (the chosen counter if rewarded, the other if not),
//!   which trains its anchor memories.

//!
//! **Several ovens** (multi-oven bisection): one clock per oven. Each oven's interval is
//! timed by its own copy of the timing model, started when that oven is seen to turn on and
//! judged short or long against the model's one shared memory of the two anchors when it
//! shows ready — drift-diffusion an accumulator per oven, SBF a detector set per oven on the
//! same oscillator bank (each oven's onset resets its phase reference: the bank is read
//! relative to a remembered onset per oven), time cells a trace per oven. Independent
//! clocks predict no interference: each oven's Weber fraction and bisection point equal the
//! one-oven task's, whatever the number of ovens and their onset offsets (Meck & Church
//! 1984's simultaneous temporal processing). The soup carried shows its oven's code, so the
//! TD learner sees the judgment of the oven the soup came from; every delivery feeds back
//! that oven's category to the shared memory (unpaid: the other counter). The ovens show
//! ready, so no clock gates checks there.

mod config;
mod multi_oven;
mod reproduction;

pub use config::{NOISE_DRAWS, OVERDUE_FACTOR, RESPONSE_DELAY, TimingAgentConfig};
pub use reproduction::ReadySetGoCues;

use multi_oven::{OvenClock, OvenView};
use reproduction::LaterResponse;

use crate::activity::{StepRecorder, oven_suffix};
use crate::agent::{Agent, Percept, PerceptParser};
use crate::timing::judgment::{LONG, SHORT};
use crate::timing::sarsa::{Active, SarsaLambda};
use crate::timing::timers::Timer;
use chronocooked_env::TaskFamily;
use chronocooked_env::{Action, ChronoEnv, ObjectKind};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

/// Visible oven values told apart (larger cue values share the last level).
pub const OVEN_LEVELS: u32 = 32;

/// Judgment indicator features ("judged short", "judged long") after the temporal ones;
/// multi-anchor tasks have one per counter their family allows
/// ([`judgment_features`]).
pub const JUDGMENT_FEATURES: usize = 2;

/// Judgment indicator features of an agent for tasks with parameters `params`: one per
/// category its family can ask for at its largest size (so a curriculum that adds counters
/// keeps the learner's size), at least [`JUDGMENT_FEATURES`].
pub fn judgment_features(params: &chronocooked_env::TaskParams) -> usize {
    chronocooked_env::task::family::most_categories(params).max(JUDGMENT_FEATURES)
}

fn two() -> usize {
    2
}

/// The time-out indicator ("overdue") after the judgment features.
pub const OVERDUE_FEATURES: usize = 1;

#[derive(Debug, Clone, Default)]
struct EpisodeState {
    clocks: Vec<OvenClock>,
    view: OvenView,
    last: Option<Percept>,
    running: bool,
    clock: u32,
    ctx: u8,
    started: Option<u32>,
    responding: bool,
    last_was_check: bool,
    prev_check_failed: bool,
    interval: Option<u32>,
    judgment: Option<u8>,
    overdue: bool,
    pressed_button: bool,
    /// Ready-Set-Go: the epoch, the counter's cue, the temporal features at Set.
    epoch: reproduction::Epoch,
    cue: u8,
    measurement: Vec<f64>,
    /// Ready-Set-Go, time cells: the conjunctive code `m ⊗ p` at the response, held while
    /// the soup is carried to the counter.
    response_code: Vec<f64>,
    /// Ready-Set-Go, time cells, training: the production time at which a delayed
    /// (exploratory) response is made ([`TimingAgentConfig::response_delay`]).
    delayed_response: Option<u32>,
    /// The last step's state, action and features, learned from at the next step.
    pending: Option<(u32, usize, Active)>,
    reward: f64,
    value: f64,
    rpe: f64,
}

fn default_rng() -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(0)
}

/// A timing model playing a task through a linear SARSA(λ) learner.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TimingAgent {
    /// Zoo name (`ddm`, `sbf`, `timecells-csc`, …).
    pub name: String,
    /// The timing model.
    pub timer: Timer,
    /// The TD learner.
    pub learner: SarsaLambda,
    /// Observation parser of the task's layout.
    pub parser: PerceptParser,
    /// The task shows a ready cue.
    pub shows_ready: bool,
    /// Cells from which a counter is used, with its choice slot (0 short/main, 1 long).
    pub choice_cells: Vec<(usize, u8)>,
    /// The task asks for short/long judgments (it has a long counter: bisection).
    #[serde(default)]
    pub judges: bool,
    /// Categories the task asks for (choice slots: 2 in bisection, one per anchor in
    /// multi-anchor categorization).
    #[serde(default = "two")]
    pub categories: usize,
    /// Judgment indicator features the learner sees ([`judgment_features`]).
    #[serde(default = "two")]
    pub judgment_features: usize,
    /// Multi-oven task: the cell of each oven, in oven order (one clock each); empty in
    /// one-oven tasks.
    #[serde(default)]
    pub oven_cells: Vec<usize>,
    /// Ready-Set-Go tasks (temporal reproduction): where the context cue is shown and the
    /// gains; `None` in other tasks.
    #[serde(default)]
    pub reproduction: Option<ReadySetGoCues>,
    /// Cells from which the manual oven button is pressed (uncertainty task).
    #[serde(default)]
    pub button_cells: Vec<usize>,
    /// The layout has something besides the soup to act on during the interval (a reward
    /// sink or an oven button): the agent may leave the oven while timing.
    #[serde(default)]
    pub side_task: bool,
    /// Settings.
    pub config: TimingAgentConfig,
    /// Learned reward rate `ρ` (reward per step; with `config.opportunity_cost` > 0).
    #[serde(default)]
    pub reward_rate: f64,
    #[serde(skip)]
    training: bool,
    #[serde(skip)]
    ep: EpisodeState,
    #[serde(skip, default = "default_rng")]
    rng: Xoshiro256PlusPlus,
    #[serde(skip)]
    q: Vec<f64>,
    #[serde(skip)]
    phi: Vec<f64>,
}

impl TimingAgent {
    /// An untrained agent with `timer` for the task of `env`.
    pub fn new(name: &str, timer: Timer, env: &ChronoEnv, config: TimingAgentConfig) -> Self {
        let layout = env.layout();
        // Free cells next to an object, with what `f` makes of the object.
        let next_to = |f: &dyn Fn(ObjectKind) -> Option<u8>| -> Vec<(usize, u8)> {
            layout
                .free_cells()
                .iter()
                .filter_map(|&c| {
                    let (kind, _) = layout.adjacent_object(c as usize)?;
                    f(kind).map(|v| (c as usize, v))
                })
                .collect()
        };
        // Counter i of a multi-anchor kitchen is slot i (short 0, long 1, then 2, 3).
        let choice_cells = next_to(&|k| match k {
            ObjectKind::DeliveryCounter => Some(SHORT),
            k => k.anchor_index().map(|i| i as u8),
        });
        let button_cells = next_to(&|k| (k == ObjectKind::OvenButton).then_some(0))
            .into_iter()
            .map(|(c, _)| c)
            .collect();
        let side_task = !next_to(&|k| {
            matches!(k, ObjectKind::RewardSink | ObjectKind::OvenButton).then_some(0)
        })
        .is_empty();
        let judgment_features = judgment_features(&env.config().params);
        let reproduction = ReadySetGoCues::of(env);
        let temporal = if reproduction.is_some() {
            Self::reproduction_features(&timer)
        } else {
            timer.n_features()
        };
        let features = temporal + 1 + judgment_features + OVERDUE_FEATURES;
        let judges = choice_cells.iter().any(|&(_, slot)| slot == LONG);
        let categories = choice_cells
            .iter()
            .map(|&(_, slot)| usize::from(slot) + 1)
            .max()
            .unwrap_or(1);
        let oven_cells = if env.family() == TaskFamily::MultiOven {
            [ObjectKind::Oven, ObjectKind::Oven2, ObjectKind::Oven3]
                .iter()
                .filter_map(|&k| layout.cells_of(k).first().copied())
                .collect()
        } else {
            Vec::new()
        };
        TimingAgent {
            name: name.to_string(),
            learner: SarsaLambda::new(config.sarsa.clone(), Action::COUNT, features),
            timer,
            parser: PerceptParser::new(layout),
            shows_ready: env.config().shows_ready(),
            choice_cells,
            judges,
            categories,
            judgment_features,
            oven_cells,
            reproduction,
            button_cells,
            side_task,
            config,
            reward_rate: 0.0,
            training: false,
            ep: EpisodeState::default(),
            rng: default_rng(),
            q: Vec::new(),
            phi: Vec::new(),
        }
    }

    /// Moves the trained agent to the task of `env` (a layout with the same grid, e.g. FI →
    /// uncertainty): the percept parser, choice cells and ready-cue flag follow the new
    /// layout; learned weights and timer memories are kept.
    pub fn transfer_to(&mut self, env: &ChronoEnv) {
        let fresh = TimingAgent::new(&self.name, self.timer.clone(), env, self.config.clone());
        self.parser = fresh.parser;
        self.shows_ready = fresh.shows_ready;
        self.choice_cells = fresh.choice_cells;
        self.judges = fresh.judges;
        self.categories = fresh.categories.min(self.judgment_features);
        self.oven_cells = fresh.oven_cells;
        // A reproduction agent's time cells read `N²` conjunctive features: the mode moves
        // only where the learner's size allows (the other models read the same features).
        if fresh.learner.features == self.learner.features {
            self.reproduction = fresh.reproduction;
        }
        self.button_cells = fresh.button_cells;
        self.side_task = fresh.side_task;
    }

    /// Sets the exploration rate (training schedule).
    pub fn set_epsilon(&mut self, epsilon: f64) {
        self.config.epsilon = epsilon;
    }

    fn state_index(&self, p: &Percept) -> u32 {
        let level = if self.reproduces() {
            self.reproduction_oven_level(p)
        } else {
            p.oven
        };
        let oven = u32::from(level).min(OVEN_LEVELS - 1);
        ((p.cell as u32 * 3 + u32::from(p.carry)) * OVEN_LEVELS) + oven
    }

    /// Tracks the oven from what is visible; runs the timer and its native learning.
    fn update_clock(&mut self, p: &Percept) {
        let Some(last) = self.ep.last else {
            return;
        };
        if last.oven == 0 && p.oven != 0 && p.carry != 2 {
            self.ep.ctx = if self.shows_ready { 1 } else { p.oven };
            self.timer
                .onset(self.ep.ctx, self.categories, &mut self.rng);
            self.ep.running = true;
            self.ep.clock = 1;
            self.ep.started = None;
            self.ep.interval = None;
            self.ep.overdue = false;
            self.ep.prev_check_failed = false;
            self.timer.tick(1, &mut self.rng);
            if self.shows_ready && p.oven == 2 {
                // A one-step interval: the oven went on and showed ready between two
                // observations, so the interval ends at its onset (clock 1). Without this the
                // interval never ended and the choice had no judgment (1-step bisection
                // probes went to whichever counter the bias preferred).
                self.end_at_ready();
            }
            return;
        }
        if !self.ep.running {
            return;
        }
        if p.carry == 2 && last.carry != 2 {
            // The soup came out on the last action, taken at `clock`.
            self.ep.running = false;
            self.ep.interval = Some(self.ep.clock);
            self.judge();
            if !self.shows_ready && self.training {
                let exact = self.ep.prev_check_failed;
                let t = if exact {
                    self.ep.clock as f64
                } else {
                    // The soup may have been waiting since before the model responded:
                    // aim earlier than the response time (not the pickup, which comes a
                    // walk later; that lag would hold the timer above short intervals).
                    let responded = self.ep.started.unwrap_or(self.ep.clock);
                    responded as f64 * (1.0 - self.config.probe)
                };
                self.timer.reinforce(self.ep.ctx, t, exact, &mut self.rng);
            }
            return;
        }
        self.ep.prev_check_failed = self.ep.last_was_check;
        self.ep.clock += 1;
        self.timer.tick(self.ep.clock, &mut self.rng);
        if self.shows_ready && p.oven == 2 {
            self.end_at_ready();
        }
    }

    /// The oven shows ready: the interval ends at the current clock (steps), the model
    /// judges it (bisection) and, in training, learns the ready time.
    fn end_at_ready(&mut self) {
        self.ep.running = false;
        self.ep.interval = Some(self.ep.clock);
        self.judge();
        // A ready the agent made itself (manual button) is not the oven's interval:
        // drift-diffusion (one drift per context) learns only from the oven's own
        // ready; SBF stores every reinforced time, so the button time joins its
        // reference memory as a second, later remembered time (its time-out).
        let own_ready = !self.ep.pressed_button || !matches!(self.timer, Timer::Ddm(_));
        if self.training && own_ready {
            let t = self.ep.clock as f64;
            self.timer.reinforce(self.ep.ctx, t, true, &mut self.rng);
        }
    }

    /// The interval just ended: the timing model's category judgment (bisection and
    /// multi-anchor categorization only).
    fn judge(&mut self) {
        if self.judges {
            self.ep.judgment = self.timer.judge(self.categories);
        }
    }

    /// Number of discrete states of the TD learner (its weight blocks are keyed by
    /// `state × actions + action`): cell × carry × visible oven level, or in the
    /// multi-oven task cell × (empty, onion, soup of oven 1–3) × each of three ovens off /
    /// on / ready / absent.
    pub fn state_count(&self) -> u32 {
        let cells = u32::try_from(self.parser.cells).unwrap_or(u32::MAX);
        let per_cell = if self.multi_oven() {
            5 * 64
        } else {
            3 * OVEN_LEVELS
        };
        cells.saturating_mul(per_cell)
    }

    fn learn(&mut self, next_q: Option<f64>) {
        if let Some((s, a, phi)) = self.ep.pending.take() {
            let q_old = self.learner.q_active(s, a, &phi);
            // `reward_rate` stays 0 unless the opportunity cost is on.
            let target = self.ep.reward - self.reward_rate
                + next_q.map_or(0.0, |q| self.learner.config.gamma * q);
            let delta = target - q_old;
            self.ep.rpe = delta;
            if self.training {
                let norm2 = phi.norm2();
                self.learner.apply(delta, norm2);
                let beta = self.config.opportunity_cost;
                if beta > 0.0 {
                    self.reward_rate += beta * (self.ep.reward - self.reward_rate);
                }
            }
        }
    }
}

impl Agent for TimingAgent {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn noise_draws(&self) -> usize {
        if self.timer.is_noisy() {
            NOISE_DRAWS
        } else {
            1
        }
    }

    fn begin_episode(&mut self, obs: &[u8], seed: u64) {
        self.rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        self.ep = EpisodeState {
            last: Some(self.parser.parse(obs)),
            ..EpisodeState::default()
        };
        self.timer.clear();
        self.learner.clear_traces();
    }

    fn act(&mut self, obs: &[u8]) -> Action {
        if self.multi_oven() {
            return self.act_multi_oven(obs);
        }
        let p = self.parser.parse(obs);
        if self.reproduces() {
            self.update_reproduction_clock(&p, obs);
        } else {
            self.update_clock(&p);
        }
        self.ep.responding = self.ep.running
            && self
                .timer
                .respond(self.ep.clock, self.ep.started)
                .then(|| self.ep.started.get_or_insert(self.ep.clock))
                .is_some();
        let mut features = std::mem::take(&mut self.phi);
        self.timer.features_into(self.ep.responding, &mut features);
        if self.reproduces() {
            self.reproduction_features_into(&mut features, &p);
        }
        // Categorical states replace the temporal features: the interval has ended (its
        // judgment, in bisection, is what later choices need) or is overdue (time-out).
        let k = self.config.overdue_factor;
        // A category, once reached, holds for the rest of the interval (a noisy ramp may dip
        // back below k z).
        self.ep.overdue |= k > 0.0 && self.shows_ready && self.ep.running && self.timer.overdue(k);
        let overdue = self.ep.overdue && self.ep.running;
        let ended_category = self.judges || (self.shows_ready && k > 0.0);
        if (self.ep.interval.is_some() && ended_category) || overdue {
            features.iter_mut().for_each(|v| *v = 0.0);
        }
        for slot in 0..self.judgment_features {
            features.push(f64::from(self.ep.judgment == Some(slot as u8)));
        }
        features.push(f64::from(overdue));
        features.insert(0, 1.0);
        let s = self.state_index(&p);
        let active = Active::of(&features);
        let mut q = std::mem::take(&mut self.q);
        self.learner.q_all_active(s, &active, &mut q);
        let gated = self.timer.has_gate()
            && self.ep.running
            && !self.ep.responding
            && p.carry == 0
            && self.parser.next_to_oven(p.cell);
        // Waiting at the oven while timing (see `TimingAgentConfig::wait_at_oven`).
        // A gated model whose responding has stopped (the peak procedure's "stop": the
        // interval is long past its expected time) is timing nothing: it may leave.
        let stopped = self.timer.has_gate() && self.ep.started.is_some() && !self.ep.responding;
        let hold = self.config.wait_at_oven
            && !self.side_task
            && (self.ep.running || self.reproduction_timing())
            && !stopped
            && p.carry == 0
            && self.parser.next_to_oven(p.cell);
        let allowed: Vec<usize> = (0..Action::COUNT)
            .filter(|&a| !(gated && a == Action::Interact.code() as usize))
            .filter(|&a| !(hold && Action::ALL[a].delta() != (0, 0)))
            .collect();
        let eps = if self.training {
            self.config.epsilon
        } else {
            0.0
        };
        // Break-and-run (see `TimingAgentConfig::break_and_run`): within a run of checks, a
        // check is preferred unless waiting is worth more by over one response cost. The
        // learner still learns from the unbiased values.
        let run = self.config.break_and_run
            && hold
            && !self.shows_ready
            && !self.timer.has_gate()
            && self.ep.last_was_check;
        let check = Action::Interact.code() as usize;
        let q_check = q[check];
        if run {
            q[check] += self.config.response_cost;
        }
        let chosen = self.learner.choose(&q, &allowed, eps, &mut self.rng);
        let delay = if self.reproduces() && self.training {
            self.explore_later_response(chosen, hold)
        } else {
            LaterResponse::None
        };
        let a = delay.action(chosen);
        q[check] = q_check;
        match delay {
            // The decision to explore is off-policy: the step before it learns the value
            // of the action the policy chose, and no trace reaches back past it.
            LaterResponse::Begins => {
                self.learn(Some(q[chosen]));
                self.learner.clear_traces();
            }
            LaterResponse::Waiting => {}
            LaterResponse::None | LaterResponse::Due => self.learn(Some(q[a])),
        }
        self.ep.value = q[a];
        if self.training && delay.learns() {
            self.learner.visit_active(s, a, &active);
        }
        let action = Action::ALL[a];
        self.ep.pressed_button |=
            self.ep.running && action == Action::Interact && self.button_cells.contains(&p.cell);
        self.ep.last_was_check = self.ep.running
            && action == Action::Interact
            && p.carry == 0
            && self.parser.next_to_oven(p.cell);
        self.ep.pending = delay.learns().then_some((s, a, active));
        self.ep.last = Some(p);
        self.phi = features;
        self.q = q;
        action
    }

    fn observe(&mut self, reward: f32, next_obs: &[u8], terminated: bool, truncated: bool) {
        let interacted = self
            .ep
            .pending
            .as_ref()
            .is_some_and(|(_, a, _)| *a == Action::Interact.code() as usize);
        self.ep.reward = f64::from(reward)
            - if interacted {
                self.config.response_cost
            } else {
                0.0
            };
        if self.multi_oven() {
            self.oven_delivery_feedback(reward, next_obs);
        } else if terminated && self.judges && self.training {
            let cell = self.ep.last.map_or(usize::MAX, |p| p.cell);
            if let (Some(&(_, chosen)), Some(t)) = (
                self.choice_cells.iter().find(|(c, _)| *c == cell),
                self.ep.interval,
            ) {
                // Rewarded: the chosen counter was right. Not rewarded: in bisection the
                // other one; among more counters only "not this one" is known, and nothing
                // is stored.
                let category = if reward > 0.0 {
                    Some(chosen)
                } else if self.categories == 2 {
                    Some(LONG - chosen)
                } else {
                    None
                };
                if let Some(category) = category {
                    if let (Some(judged), true) = (self.ep.judgment, self.categories == 2) {
                        self.timer
                            .judgment_feedback(judged == LONG, category == LONG);
                    }
                    self.timer
                        .reinforce_choice(category, t as f64, &mut self.rng);
                }
            }
        }
        // A production cut off by the time limit is a trial without a response: aborted
        // unrewarded, as in Ready-Set-Go (the animal's trial ends, not the session), so its
        // return is 0. Bootstrapping there instead left the values of waiting past the
        // window unanchored and the greedy agent waited out the episode.
        let aborted = truncated && self.reproduces() && self.reproduction_timing();
        if terminated || aborted {
            self.learn(None);
        } else if truncated {
            self.ep.pending = None;
        }
        let _ = next_obs;
    }

    fn record(&self, rec: &mut StepRecorder) {
        if self.multi_oven() {
            // One population per oven: oven 1 under the plain names, the others suffixed
            // (`_oven2`, `_oven3`); an oven not yet on shows the idle timer.
            for i in 0..self.oven_cells.len() {
                let timer = self
                    .ep
                    .clocks
                    .get(i)
                    .and_then(|c| c.timer.as_ref())
                    .unwrap_or(&self.timer);
                timer.record_as(rec, &oven_suffix(i + 1));
            }
        } else {
            self.timer.record(rec);
        }
        rec.scalar("value", self.ep.value as f32);
        rec.scalar("rpe", self.ep.rpe as f32);
    }

    fn set_training(&mut self, on: bool) {
        self.training = on;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::timing::train::{TimingTrainConfig, train_timing_agent};
    use crate::timing::zoo::make_timing_agent;
    use chronocooked_env::{ChronoEnv, ResetOptions, make_config};

    #[test]
    fn a_one_step_bisection_probe_ends_its_interval_and_is_judged_short() {
        // On a 1-step probe the oven goes on and shows ready between two observations. The
        // interval must end there (clock 1) and be judged against the anchors; before the
        // fix it never ended, the choice had no judgment and went wherever the choice
        // values' bias pointed (measured: microstimuli 6-8 seed 7 sent every 1-step probe
        // to the long counter).
        let sets = |extra: &[&str]| {
            let mut v = vec!["short=4".to_string(), "long=12".to_string()];
            v.extend(extra.iter().map(|s| s.to_string()));
            v
        };
        let config = make_config("Bisection-v0", &sets(&[])).unwrap();
        let env = ChronoEnv::new(&config).unwrap();
        let mut agent = make_timing_agent("timecells-csc", &env, 1).unwrap();
        let train = TimingTrainConfig {
            episodes: 1500,
            eval_every: 0,
            ..Default::default()
        };
        train_timing_agent(&mut agent, &config, &train, &[], 1, |_| {}).unwrap();
        let probe = make_config("Bisection-v0", &sets(&["td=1"])).unwrap();
        let mut env = ChronoEnv::new(&probe).unwrap();
        agent.transfer_to(&env);
        agent.set_training(false);
        for seed in 0..8 {
            env.reset(Some(seed), &ResetOptions::default()).unwrap();
            agent.begin_episode(env.obs_codes(), seed);
            // Play until the agent has seen the oven go on; the interval must already be
            // over at that observation (not later, at the pickup).
            for _ in 0..200 {
                let action = agent.act(env.obs_codes());
                if agent.ep.running || agent.ep.interval.is_some() {
                    break;
                }
                let t = env.step(action).unwrap();
                agent.observe(t.reward, env.obs_codes(), t.terminated, t.truncated);
                assert!(
                    !t.terminated && !t.truncated,
                    "seed {seed}: oven never went on"
                );
            }
            assert!(
                !agent.ep.running,
                "seed {seed}: the interval is still running"
            );
            assert_eq!(agent.ep.interval, Some(1), "seed {seed}");
            assert_eq!(
                agent.ep.judgment,
                Some(SHORT),
                "seed {seed}: 1 step vs 4-12"
            );
        }
    }
}
