//! The simulation core: state, reference step order, interact rules and rewards.
//!
//! A [`Kitchen`] owns the state and the RNG of one environment but not its
//! observation buffer: it writes the "codes" observation incrementally into a
//! slice it is handed, so the scalar env and the vectorised env share one code
//! path and the vectorised env writes straight into its batch buffer.
//!
//! Step order (reference): apply the action (move, or interact — which may pay),
//! then if the oven is on `timer += 1`, then (tasks with a ready cue) the oven
//! shows ready if `timer == TD`; then the time limit (`timestep > max_timesteps`).
//! The multi-oven task has its own step in [`multi_oven`].

use crate::action::Action;
use crate::error::EnvError;
use crate::info::{Carry, Counter, Events, Info};
use crate::layout::ObjectKind;
pub(crate) use crate::rules::Rules;
pub(crate) use crate::spec::Spec;
pub use crate::spec::{CODE_CHANNELS, derive_seed};
use crate::task::{CueMode, RewardMode, TaskFamily, TaskParams};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::sync::Arc;

mod episode;
mod multi_oven;
mod ready_set_go;
mod reset;
mod snapshot;
pub use episode::{PerOven, ResetOptions, Transition};
pub use multi_oven::MultiOvenState;
pub use ready_set_go::RsgState;
pub use snapshot::KitchenSnapshot;

/// State and RNG of one environment.
#[derive(Debug, Clone)]
pub struct Kitchen {
    pub(crate) spec: Arc<Spec>,
    rng: Xoshiro256PlusPlus,
    num_timers: usize,
    agent: usize,
    carry: Carry,
    timer: i32,
    ready: bool,
    manual: bool,
    never_ready: bool,
    td: u32,
    timestep: u32,
    oven_off_time: i32,
    manual_stop_time: i32,
    sink_count: u32,
    last_sink_timer: i32,
    counter: Option<Counter>,
    done: bool,
    /// Every oven of a multi-oven episode (unused elsewhere).
    mo: MultiOvenState,
    /// The reproduction episode's context (unused elsewhere).
    rsg: RsgState,
}

impl Kitchen {
    pub(crate) fn new(spec: Arc<Spec>, seed: u64) -> Self {
        let num_timers = match &spec.config.params {
            TaskParams::MultiTimer { num_timers, .. } => *num_timers,
            _ => spec.tds.len(),
        };
        let agent = spec.layout.free_cells()[0] as usize;
        let td = spec.default_td;
        Kitchen {
            spec,
            rng: Xoshiro256PlusPlus::seed_from_u64(seed),
            num_timers,
            agent,
            carry: Carry::Nothing,
            timer: -1,
            ready: false,
            manual: false,
            never_ready: false,
            td,
            timestep: 0,
            oven_off_time: -1,
            manual_stop_time: -1,
            sink_count: 0,
            last_sink_timer: -1,
            counter: None,
            done: true,
            mo: MultiOvenState::default(),
            rsg: RsgState::default(),
        }
    }

    /// Whether this kitchen runs the multi-oven task.
    #[inline]
    pub(crate) fn is_multi_oven(&self) -> bool {
        matches!(self.spec.rules, Rules::MultiOven { .. })
    }

    /// The codes observation of the current state (`[R, C, 6]`).
    pub fn observation(&self) -> Vec<u8> {
        let mut obs = vec![0; self.spec.background.len()];
        self.write_full_obs(&mut obs);
        obs
    }

    /// Sets how many TDs of the multi-timer list are active (curricula); other tasks: no-op.
    pub fn set_num_timers(&mut self, n: usize) -> Result<(), EnvError> {
        if self.spec.family != TaskFamily::MultiTimer {
            return Ok(());
        }
        if n == 0 || n > self.spec.tds.len() {
            return Err(EnvError::param(
                "num_timers",
                n,
                format!("integer 1..={} (the length of tds)", self.spec.tds.len()),
            ));
        }
        self.num_timers = n;
        Ok(())
    }

    /// Active multi-timer TD count.
    pub fn num_timers(&self) -> usize {
        self.num_timers
    }

    /// Value of observation channel 4 at the oven cell.
    #[inline]
    fn oven_code(&self) -> u8 {
        if self.timer < 0 {
            0
        } else if self.ready {
            2
        } else {
            match self.spec.cue {
                Some(CueMode::Value) => self.td as u8,
                Some(CueMode::Categorical) => {
                    1 + self
                        .spec
                        .tds
                        .iter()
                        .position(|&t| t == self.td)
                        .unwrap_or(0) as u8
                }
                None => 1,
            }
        }
    }

    fn write_full_obs(&self, obs: &mut [u8]) {
        obs.copy_from_slice(&self.spec.background);
        self.write_dynamic(obs, self.agent);
    }

    /// Writes the channels that change (agent, carrying, oven) after a move from `old`.
    #[inline]
    fn write_dynamic(&self, obs: &mut [u8], old: usize) {
        let o = old * CODE_CHANNELS;
        obs[o + 1] = 0;
        obs[o + 2] = 0;
        obs[o + 3] = 0;
        let a = self.agent * CODE_CHANNELS;
        obs[a + 1] = 1;
        obs[a + 2] = (self.carry == Carry::Onion) as u8;
        obs[a + 3] = (self.carry == Carry::Soup) as u8;
        if self.is_multi_oven() {
            self.write_ovens(obs);
            return;
        }
        if self.spec.rsg.is_some() {
            self.write_rsg(obs);
            return;
        }
        let v = self.spec.oven * CODE_CHANNELS;
        obs[v + 4] = self.oven_code();
        if self.spec.config.debug_timer_channel {
            obs[v + 5] = (self.timer + 1).clamp(0, 255) as u8;
        }
    }

    /// Whether the soup can be taken now (oven on, hands empty checked by the caller).
    #[inline]
    fn can_pickup(&self) -> bool {
        let t = self.timer as i64;
        match self.spec.rules {
            Rules::Fixed => t >= self.td as i64,
            Rules::Probe { factor } => factor > 0 && t >= factor as i64 * self.td as i64,
            Rules::Bisection { .. }
            | Rules::Uncertainty { .. }
            | Rules::Categories { .. }
            | Rules::MultiOven { .. } => self.ready,
            Rules::ReadySetGo => self.timer >= 0,
            Rules::Window { mode, .. } => match mode {
                RewardMode::Exact => true,
                RewardMode::LowerBounded => t >= self.td as i64,
            },
            Rules::Dual { .. } => true,
        }
    }

    /// Reward for delivering the soup to `counter`.
    #[inline]
    fn delivery_reward(&self, counter: Counter) -> f32 {
        let off = self.oven_off_time as i64;
        let td = self.td as i64;
        let window = |under: u32, over: u32, reduced: f32| {
            if off >= td - under as i64 && off <= td + over as i64 {
                1.0
            } else {
                reduced
            }
        };
        match self.spec.rules {
            Rules::Fixed | Rules::Probe { .. } => 1.0,
            Rules::Bisection { short, long } => match counter {
                Counter::Short if self.td == short => 1.0,
                Counter::Long if self.td == long => 1.0,
                _ => 0.0,
            },
            Rules::Categories { anchors, k } => match counter {
                Counter::Anchor(i) if i >= 1 && i <= k && self.td == anchors[i as usize - 1] => 1.0,
                _ => 0.0,
            },
            // Paid per oven in `multi_oven`, by the production in `reproduction`.
            Rules::MultiOven { .. } | Rules::ReadySetGo => 0.0,
            Rules::Window {
                mode,
                under,
                over,
                reduced,
            } => match mode {
                RewardMode::Exact => window(under, over, reduced),
                RewardMode::LowerBounded => {
                    if off > td + over as i64 {
                        reduced
                    } else {
                        1.0
                    }
                }
            },
            Rules::Dual {
                under,
                over,
                reduced,
                ..
            } => window(under, over, reduced),
            Rules::Uncertainty {
                over,
                overcooked,
                manual,
                ..
            } => {
                if self.manual {
                    manual
                } else if off > td + over as i64 {
                    overcooked
                } else {
                    1.0
                }
            }
        }
    }

    /// Applies the interact rules (reference order) and returns the reward.
    #[inline]
    fn interact(&mut self, events: &mut u16) -> f32 {
        let Some((kind, _)) = self.spec.layout.adjacent_object(self.agent) else {
            *events |= Events::NO_EFFECT;
            return 0.0;
        };
        let oven_on = self.timer >= 0;
        match (kind, self.carry) {
            (ObjectKind::OnionDispenser, Carry::Nothing) => {
                self.carry = Carry::Onion;
                *events |= Events::ONION_TAKEN;
            }
            // The reference deadlocks on a second onion (it can never be put down); by
            // default the multi-anchor task takes it back at the dispenser.
            (ObjectKind::OnionDispenser, Carry::Onion) if self.returns_onion() => {
                self.carry = Carry::Nothing;
            }
            (ObjectKind::Oven, Carry::Onion) if !oven_on => {
                self.timer = 0;
                self.ready = false;
                self.carry = Carry::Nothing;
                *events |= Events::ONION_IN;
            }
            (ObjectKind::Oven, Carry::Nothing) if oven_on => {
                *events |= Events::OVEN_CHECK;
                if self.can_pickup() {
                    self.carry = Carry::Soup;
                    self.oven_off_time = self.timer;
                    self.timer = -1;
                    self.ready = false;
                    *events |= Events::PICKUP;
                } else {
                    *events |= Events::NO_EFFECT;
                }
            }
            (
                ObjectKind::DeliveryCounter
                | ObjectKind::ShortCounter
                | ObjectKind::LongCounter
                | ObjectKind::Counter3
                | ObjectKind::Counter4,
                Carry::Soup,
            ) => {
                let counter = match (kind, kind.anchor_index()) {
                    (_, Some(i)) if matches!(self.spec.rules, Rules::Categories { .. }) => {
                        Counter::Anchor(i as u8 + 1)
                    }
                    (ObjectKind::ShortCounter, _) => Counter::Short,
                    (ObjectKind::LongCounter, _) => Counter::Long,
                    _ => Counter::Main,
                };
                self.carry = Carry::Nothing;
                self.counter = Some(counter);
                *events |= Events::DELIVERY;
                return self.delivery_reward(counter);
            }
            (ObjectKind::RewardSink, _) if oven_on => {
                if let Rules::Dual { sink, .. } = self.spec.rules {
                    self.sink_count += 1;
                    self.last_sink_timer = self.timer;
                    *events |= Events::SINK;
                    return sink;
                }
                *events |= Events::NO_EFFECT;
            }
            (ObjectKind::OvenButton, _) if oven_on && !self.ready => {
                self.ready = true;
                self.manual = true;
                self.manual_stop_time = self.timer;
                *events |= Events::BUTTON;
            }
            _ => *events |= Events::NO_EFFECT,
        }
        0.0
    }

    /// Advances one step and updates `obs` in place (it must hold this env's last observation).
    #[inline]
    pub fn step(&mut self, action: Action, obs: &mut [u8]) -> Result<Transition, EnvError> {
        if self.done {
            return Err(EnvError::EpisodeOver);
        }
        Ok(self.step_unchecked(action, obs))
    }

    /// Whether a held onion goes back at the dispenser (the multi-anchor and multi-oven
    /// tasks outside reference-compatible mode: the fix of the reference's deadlock).
    #[inline]
    fn returns_onion(&self) -> bool {
        !self.spec.config.reference_compat
            && matches!(
                self.spec.rules,
                Rules::Categories { .. } | Rules::MultiOven { .. }
            )
    }

    #[inline]
    pub(crate) fn step_unchecked(&mut self, action: Action, obs: &mut [u8]) -> Transition {
        if self.is_multi_oven() {
            return self.step_multi_oven(action, obs);
        }
        if self.spec.rsg.is_some() {
            return self.step_ready_set_go(action, obs);
        }
        let (old, timer_at_action, next_to_oven) = self.step_context();
        let mut events = 0u16;
        let reward = self.act_or_move(action, &mut events, Self::interact);
        if self.timer >= 0 {
            self.timer += 1;
            if self.spec.shows_ready
                && !self.ready
                && !self.never_ready
                && self.timer == self.td as i32
            {
                self.ready = true;
                events |= Events::OVEN_READY;
            }
        }
        let delivered = events & Events::DELIVERY != 0;
        self.finish_step(
            delivered,
            reward,
            events,
            (old, timer_at_action, next_to_oven),
            obs,
        )
    }

    /// The start of a single-oven task's step (the reproduction task's too): the agent's
    /// cell, the oven timer and whether the agent stands next to the oven when it acts.
    #[inline]
    pub(crate) fn step_context(&self) -> (usize, i32, bool) {
        let next_to_oven = matches!(
            self.spec.layout.adjacent_object(self.agent),
            Some((ObjectKind::Oven, _))
        );
        (self.agent, self.timer, next_to_oven)
    }

    /// Counts the step, then applies `action`: `interact` (the task's interact rules) or a
    /// move. Returns the action's reward.
    #[inline]
    pub(crate) fn act_or_move(
        &mut self,
        action: Action,
        events: &mut u16,
        interact: fn(&mut Self, &mut u16) -> f32,
    ) -> f32 {
        self.timestep += 1;
        if action == Action::Interact {
            interact(self, events)
        } else {
            self.agent = self.spec.layout.move_from(self.agent, action);
            0.0
        }
    }

    /// The end of every task's step: `ended` (the task's own end: a delivery, the last soup)
    /// or the time limit (`timestep > max_timesteps`: `terminated` in reference mode,
    /// `truncated` otherwise), the observation update from the agent's `old` cell, and the
    /// step's info.
    #[inline]
    pub(crate) fn finish_step(
        &mut self,
        ended: bool,
        reward: f32,
        events: u16,
        (old, timer_at_action, next_to_oven): (usize, i32, bool),
        obs: &mut [u8],
    ) -> Transition {
        let time_up = self.timestep > self.spec.config.max_timesteps;
        let (terminated, truncated) = if ended {
            (true, false)
        } else if time_up {
            if self.spec.config.reference_compat {
                (true, false)
            } else {
                (false, true)
            }
        } else {
            (false, false)
        };
        self.done = terminated || truncated;
        self.write_dynamic(obs, old);
        Transition {
            reward,
            terminated,
            truncated,
            info: self.info(Events(events), timer_at_action, next_to_oven),
        }
    }

    #[inline]
    fn info(&self, events: Events, timer_at_action: i32, next_to_oven: bool) -> Info {
        let (r, c) = self.spec.layout.coords(self.agent);
        Info {
            timestep: self.timestep,
            td: self.td,
            oven_timer: self.timer,
            timer_at_action,
            oven_state: if self.timer < 0 {
                0
            } else if self.ready {
                2
            } else {
                1
            },
            oven_off_time: self.oven_off_time,
            counter: self.counter,
            events,
            next_to_oven,
            agent: (r as u8, c as u8),
            carrying: self.carry,
            never_ready: self.never_ready,
            manual_stop_time: self.manual_stop_time,
            sink_count: self.sink_count,
            last_sink_timer: self.last_sink_timer,
        }
    }

    /// Whether the current episode has ended.
    pub fn is_done(&self) -> bool {
        self.done
    }

    /// A read-only view of the hidden state (for oracles, tests and debugging; never an observation).
    pub fn state(&self) -> KitchenState {
        KitchenState {
            agent: self.spec.layout.coords(self.agent),
            carry: self.carry,
            timer: self.timer,
            ready: self.ready,
            manual: self.manual,
            never_ready: self.never_ready,
            td: self.td,
            timestep: self.timestep,
            oven_off_time: self.oven_off_time,
            done: self.done,
            multi_oven: self.is_multi_oven().then_some(self.mo),
            reproduction: self.spec.rsg.is_some().then_some(self.rsg),
        }
    }
}

/// Snapshot of the hidden state of a [`Kitchen`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct KitchenState {
    /// Agent `(row, col)`.
    pub agent: (usize, usize),
    /// What the agent holds.
    pub carry: Carry,
    /// Oven timer (−1 off).
    pub timer: i32,
    /// Oven shows ready.
    pub ready: bool,
    /// Ready was forced by the manual button.
    pub manual: bool,
    /// Never-ready episode (uncertainty).
    pub never_ready: bool,
    /// Episode TD (steps).
    pub td: u32,
    /// Steps taken.
    pub timestep: u32,
    /// Timer at which the soup was taken out (−1 before pickup).
    pub oven_off_time: i32,
    /// The episode has ended.
    pub done: bool,
    /// Multi-oven task: every oven's state (`None` elsewhere).
    pub multi_oven: Option<MultiOvenState>,
    /// Ready-Set-Go tasks: the episode's prior, gain and foreperiod (`None` elsewhere).
    pub reproduction: Option<RsgState>,
}
