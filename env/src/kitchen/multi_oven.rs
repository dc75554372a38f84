//! The multi-oven task's rules (reference `ChronoCookedBisectionMultiOven`, v2).
//!
//! Step order: `timestep += 1`; the action (move, or interact); asynchronous mode: an oven
//! whose on-time equals `timestep` starts (timer 0); every oven that is on gets `+1` and
//! shows ready when its timer equals its duration; then the episode ends once every oven's
//! soup is delivered, or at the time limit (`timestep > max_timesteps`).
//!
//! Interact, first rule that applies: take an onion (hands empty); put it into oven 1 (only
//! the first oven takes it, once: synchronous mode starts every oven, asynchronous mode only
//! the first); take the soup of an adjacent ready oven (the soup carries the oven's code in
//! channel 3 and empties that oven); deliver a held soup to the short or long counter, which
//! pays `1/n` iff that oven's duration is the counter's anchor.
//!
//! Reference quirks kept only in reference-compatible mode: an on-time of 0 never fires
//! (by default such an oven starts at reset, i.e. at the end of "step 0"); a second onion
//! can never be put down (by default it goes back at the dispenser); TD 0 is accepted as a
//! reset option and never becomes ready.

use super::{Kitchen, PerOven, ResetOptions, Rules, Transition};
use crate::action::Action;
use crate::error::EnvError;
use crate::info::{Carry, Counter, Events, OvenSet};
use crate::kitchen::CODE_CHANNELS;
use crate::layout::ObjectKind;
use rand::Rng;
use serde::{Deserialize, Serialize};

/// Every oven's dynamic state in a multi-oven episode (steps; −1 = off / never).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct MultiOvenState {
    /// Each oven's timer (−1 off or emptied).
    pub timer: [i32; 3],
    /// Each oven shows ready.
    pub ready: [bool; 3],
    /// Each oven's duration (steps).
    pub td: [u32; 3],
    /// Each oven's on-time (asynchronous mode, ovens 2…n; −1: started by the put).
    pub on_time: [i32; 3],
    /// Timer at which each oven's soup was taken out (−1 before).
    pub off_time: [i32; 3],
    /// Where each oven's soup went: 0 not delivered, 1 short, 2 long.
    pub delivered: [u8; 3],
    /// The oven the held soup came from.
    pub soup_from: u8,
    /// Bit `i`: oven `i`'s soup paid.
    pub paid: u8,
    /// The first oven has taken its onion (it takes one per episode).
    pub used: bool,
}

impl Default for MultiOvenState {
    fn default() -> Self {
        MultiOvenState {
            timer: [-1; 3],
            ready: [false; 3],
            td: [0; 3],
            on_time: [-1; 3],
            off_time: [-1; 3],
            delivered: [0; 3],
            soup_from: 0,
            paid: 0,
            used: false,
        }
    }
}

impl MultiOvenState {
    /// The per-oven part of a step's info.
    pub(crate) fn info(&self, rules: Rules) -> OvenSet {
        let n = match rules {
            Rules::MultiOven { n, .. } => n,
            _ => 0,
        };
        OvenSet {
            n,
            td: self.td,
            timer: self.timer,
            on_time: self.on_time,
            off_time: self.off_time,
            delivered: self.delivered,
            paid: self.paid,
        }
    }
}

/// The reference's on-time range for the ovens after the first: `0..=6 + d0/2` (steps).
pub(crate) fn on_time_limit(first_td: u32) -> u32 {
    6 + first_td / 2
}

impl Kitchen {
    fn oven_rules(&self) -> (u32, u32, usize, bool) {
        match self.spec.rules {
            Rules::MultiOven {
                short,
                long,
                n,
                asynchronous,
            } => (short, long, n as usize, asynchronous),
            _ => (0, 0, 0, false),
        }
    }

    /// Checks the per-oven reset options against the task.
    pub(crate) fn check_oven_options(&self, options: &ResetOptions) -> Result<(), EnvError> {
        if !self.is_multi_oven() {
            for (field, given) in [
                ("oven_tds", options.oven_tds.is_some()),
                ("on_times", options.on_times.is_some()),
            ] {
                if given {
                    return Err(EnvError::reset_option(
                        field,
                        "given",
                        "only the multi-oven task has per-oven options (use td)",
                    ));
                }
            }
            return Ok(());
        }
        let (_, _, n, asynchronous) = self.oven_rules();
        if let Some(tds) = options.oven_tds {
            if options.td.is_some() {
                return Err(EnvError::reset_option(
                    "oven_tds",
                    format!("{:?}", tds.as_slice()),
                    "either td (every oven) or oven_tds (one per oven), not both",
                ));
            }
            if tds.as_slice().len() != n {
                return Err(EnvError::reset_option(
                    "oven_tds",
                    format!("{:?}", tds.as_slice()),
                    format!("{n} durations, one per oven"),
                ));
            }
            for &td in tds.as_slice() {
                self.check_td_option(td)?;
            }
        }
        if let Some(on) = options.on_times {
            let text = format!("{:?}", on.as_slice());
            if !asynchronous {
                return Err(EnvError::reset_option(
                    "on_times",
                    text,
                    "only in asynchronous mode (asynchronous=true)",
                ));
            }
            if on.as_slice().len() + 1 != n {
                return Err(EnvError::reset_option(
                    "on_times",
                    text,
                    format!("{} on-times, one per oven after the first", n - 1),
                ));
            }
            let max = self.spec.config.max_timesteps;
            if on.as_slice().iter().any(|&t| t > max) {
                return Err(EnvError::reset_option(
                    "on_times",
                    text,
                    format!("steps 0..={max} (inside the episode)"),
                ));
            }
            if n == 3 && on.as_slice()[0] == on.as_slice()[1] {
                return Err(EnvError::reset_option(
                    "on_times",
                    text,
                    "distinct steps (the reference draws them without replacement)",
                ));
            }
        }
        Ok(())
    }

    /// Draws (or takes from the options) every oven's duration and on-time. Draw order:
    /// each oven's duration (short or long, 1/2 each), then the on-times.
    pub(crate) fn reset_ovens(
        &mut self,
        td: Option<u32>,
        oven_tds: Option<PerOven>,
        on_times: Option<PerOven>,
    ) {
        let (short, long, n, asynchronous) = self.oven_rules();
        let mut mo = MultiOvenState::default();
        let fixed = td.or(self.spec.config.fixed_td);
        for i in 0..n {
            mo.td[i] = match (oven_tds, fixed) {
                (Some(tds), _) => tds.as_slice()[i],
                (None, Some(td)) => td,
                (None, None) => {
                    if self.rng.random_bool(0.5) {
                        long
                    } else {
                        short
                    }
                }
            };
        }
        if asynchronous && n > 1 {
            let drawn: Vec<u32> = match on_times {
                Some(on) => on.as_slice().to_vec(),
                None => {
                    let range = on_time_limit(mo.td[0]) as usize + 1;
                    rand::seq::index::sample(&mut self.rng, range, n - 1)
                        .into_iter()
                        .map(|t| t as u32)
                        .collect()
                }
            };
            for (i, &t) in drawn.iter().enumerate() {
                mo.on_time[i + 1] = t as i32;
                if t == 0 && !self.spec.config.reference_compat {
                    mo.timer[i + 1] = 0;
                }
            }
        }
        self.mo = mo;
        self.sync_first_oven();
    }

    /// Mirrors the first oven into the single-oven fields that `info` and `state` report.
    fn sync_first_oven(&mut self) {
        self.td = self.mo.td[0];
        self.timer = self.mo.timer[0];
        self.ready = self.mo.ready[0];
        self.oven_off_time = self.mo.off_time[0];
    }

    /// Writes the held soup's oven code (channel 3) and every oven's state (channel 4).
    pub(crate) fn write_ovens(&self, obs: &mut [u8]) {
        let (_, _, n, _) = self.oven_rules();
        if self.carry == Carry::Soup {
            let kind = [ObjectKind::Oven, ObjectKind::Oven2, ObjectKind::Oven3]
                [self.mo.soup_from as usize];
            obs[self.agent * CODE_CHANNELS + 3] = crate::spec::object_code(kind, self.spec.family);
        }
        for i in 0..n {
            let v = self.spec.ovens[i] * CODE_CHANNELS;
            obs[v + 4] = if self.mo.timer[i] < 0 {
                0
            } else if self.mo.ready[i] {
                2
            } else {
                1
            };
            if self.spec.config.debug_timer_channel {
                obs[v + 5] = (self.mo.timer[i] + 1).clamp(0, 255) as u8;
            }
        }
    }

    fn interact_multi_oven(&mut self, events: &mut u16) -> f32 {
        let (short, long, n, asynchronous) = self.oven_rules();
        let Some((kind, _)) = self.spec.layout.adjacent_object(self.agent) else {
            *events |= Events::NO_EFFECT;
            return 0.0;
        };
        let oven = kind.oven_index();
        match (kind, oven, self.carry) {
            (ObjectKind::OnionDispenser, _, Carry::Nothing) => {
                self.carry = Carry::Onion;
                *events |= Events::ONION_TAKEN;
            }
            (ObjectKind::OnionDispenser, _, Carry::Onion) if self.returns_onion() => {
                self.carry = Carry::Nothing;
            }
            (_, Some(0), Carry::Onion) if self.mo.timer[0] == -1 && !self.mo.used => {
                let started = if asynchronous { 1 } else { n };
                for timer in &mut self.mo.timer[..started] {
                    *timer = 0;
                }
                self.mo.used = true;
                self.carry = Carry::Nothing;
                *events |= Events::ONION_IN;
            }
            (_, Some(i), Carry::Nothing) if self.mo.timer[i] >= 0 => {
                *events |= Events::OVEN_CHECK;
                if self.mo.ready[i] {
                    self.mo.off_time[i] = self.mo.timer[i];
                    self.mo.timer[i] = -1;
                    self.mo.ready[i] = false;
                    self.mo.soup_from = i as u8;
                    self.carry = Carry::Soup;
                    *events |= Events::PICKUP;
                } else {
                    *events |= Events::NO_EFFECT;
                }
            }
            (ObjectKind::ShortCounter | ObjectKind::LongCounter, _, Carry::Soup) => {
                let (counter, anchor, code) = if kind == ObjectKind::ShortCounter {
                    (Counter::Short, short, 1)
                } else {
                    (Counter::Long, long, 2)
                };
                let from = self.mo.soup_from as usize;
                self.mo.delivered[from] = code;
                self.carry = Carry::Nothing;
                self.counter = Some(counter);
                *events |= Events::DELIVERY;
                if self.mo.td[from] == anchor {
                    self.mo.paid |= 1 << from;
                    if self.mo.paid == (1u8 << n) - 1 {
                        *events |= Events::ALL_PAID;
                    }
                    return 1.0 / n as f32;
                }
            }
            _ => *events |= Events::NO_EFFECT,
        }
        0.0
    }

    /// One step of the multi-oven task.
    pub(crate) fn step_multi_oven(&mut self, action: Action, obs: &mut [u8]) -> Transition {
        let (_, _, n, asynchronous) = self.oven_rules();
        let old = self.agent;
        let adjacent_oven = self
            .spec
            .layout
            .adjacent_object(old)
            .and_then(|(k, _)| k.oven_index());
        let timer_at_action = self.mo.timer[adjacent_oven.unwrap_or(0)];
        let mut events = 0u16;
        let reward = self.act_or_move(action, &mut events, Self::interact_multi_oven);
        if asynchronous {
            for i in 1..n {
                if self.mo.on_time[i] == self.timestep as i32 {
                    self.mo.timer[i] = 0;
                }
            }
        }
        for i in 0..n {
            if self.mo.timer[i] >= 0 {
                self.mo.timer[i] += 1;
                if !self.mo.ready[i] && self.mo.timer[i] == self.mo.td[i] as i32 {
                    self.mo.ready[i] = true;
                    events |= Events::OVEN_READY;
                }
            }
        }
        self.sync_first_oven();
        let all_delivered = self.mo.delivered[..n].iter().all(|&d| d != 0);
        let context = (old, timer_at_action, adjacent_oven.is_some());
        self.finish_step(all_delivered, reward, events, context, obs)
    }

    /// The multi-oven state (`None` for the other tasks).
    pub fn multi_oven(&self) -> Option<&MultiOvenState> {
        self.is_multi_oven().then_some(&self.mo)
    }

    /// Every oven's state after the last step or reset (`None` for the other tasks).
    pub fn ovens(&self) -> Option<OvenSet> {
        self.is_multi_oven().then(|| self.mo.info(self.spec.rules))
    }
}
