//! The Ready-Set-Go rules (temporal reproduction in the kitchen), which the reproduction
//! task and any family built with `RuleSet::ready_set_go` run.
//!
//! Reset draws, in order: the start cell, the prior (uniform over the priors), the gain
//! (uniform over the gains), `ts` (uniform over the prior's whole steps) and the foreperiod
//! `f` (uniform over `foreperiod_min..=foreperiod_max`).
//!
//! Step: `timestep += 1`; the action (move, or interact: take the soup from the oven once
//! Set has flashed — the production `tp` is the number of steps from the Set step to this
//! one; deliver it: `max(0, 1 − |tp − g·ts| / w)`, `w = tolerance·g·ts + tolerance_steps`);
//! then the clock: the production timer counts on, the oven flashes Ready at the end of step
//! `f` and Set at the end of step `f + ts` (channel 4 = 2 for that step), and shows on (1)
//! from Set until the soup is taken. A response outside the window is delivered unpaid (as
//! Jazayeri & Shadlen's subjects responded late unrewarded); the episode ends at the
//! delivery or the time limit, so no production is cut off by the task (a censored late
//! tail would bias every fit of the productions).

use super::{Kitchen, ResetOptions, Transition};
use crate::action::Action;
use crate::error::EnvError;
use crate::info::{Carry, Counter, Events};
use crate::kitchen::CODE_CHANNELS;
use crate::layout::ObjectKind;
use rand::Rng;
use serde::{Deserialize, Serialize};

/// The reproduction episode's context and schedule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub struct RsgState {
    /// Index of the episode's prior.
    pub prior: u8,
    /// Index of the episode's gain.
    pub gain: u8,
    /// Foreperiod: Ready flashes at the end of this step.
    pub foreperiod: u32,
}

impl Kitchen {
    /// Checks the reproduction reset options (prior and gain indices).
    pub(crate) fn check_rsg_options(&self, options: &ResetOptions) -> Result<(), EnvError> {
        let Some(rsg) = &self.spec.rsg else {
            for (field, given) in [
                ("prior", options.prior.is_some()),
                ("gain", options.gain.is_some()),
            ] {
                if given {
                    return Err(EnvError::reset_option(
                        field,
                        "given",
                        "only Ready-Set-Go (reproduction) tasks have priors and gains",
                    ));
                }
            }
            return Ok(());
        };
        if let Some(p) = options.prior
            && p as usize >= rsg.priors.len()
        {
            return Err(EnvError::reset_option(
                "prior",
                p,
                format!("a prior index 0..={}", rsg.priors.len() - 1),
            ));
        }
        if let Some(g) = options.gain
            && g as usize >= rsg.gains.len()
        {
            return Err(EnvError::reset_option(
                "gain",
                g,
                format!("a gain index 0..={}", rsg.gains.len() - 1),
            ));
        }
        Ok(())
    }

    /// Draws (or takes from the options) the prior, the gain, `ts` and the foreperiod.
    pub(crate) fn reset_rsg(&mut self, td: Option<u32>, prior: Option<u8>, gain: Option<u8>) {
        let Some(rsg) = self.spec.rsg.clone() else {
            return;
        };
        let prior = prior.unwrap_or_else(|| self.rng.random_range(0..rsg.priors.len()) as u8);
        let gain = gain.unwrap_or_else(|| self.rng.random_range(0..rsg.gains.len()) as u8);
        let (lo, hi) = rsg.priors[prior as usize];
        self.td = match td.or(self.spec.config.fixed_td) {
            Some(ts) => ts,
            None => self.rng.random_range(lo..=hi),
        };
        let (fmin, fmax) = rsg.foreperiod;
        self.rsg = RsgState {
            prior,
            gain,
            foreperiod: self.rng.random_range(fmin..=fmax),
        };
    }

    /// The context cue on the counter (channel 4) and the oven's state.
    pub(crate) fn write_rsg(&self, obs: &mut [u8]) {
        let Some(rsg) = &self.spec.rsg else {
            return;
        };
        obs[rsg.counter * CODE_CHANNELS + 4] = rsg.cue(self.rsg.prior, self.rsg.gain);
        obs[self.spec.oven * CODE_CHANNELS + 4] = if self.ready {
            2
        } else if self.timer >= 0 {
            1
        } else {
            0
        };
    }

    fn interact_rsg(&mut self, events: &mut u16) -> f32 {
        let Some((kind, _)) = self.spec.layout.adjacent_object(self.agent) else {
            *events |= Events::NO_EFFECT;
            return 0.0;
        };
        match (kind, self.carry) {
            (ObjectKind::Oven, Carry::Nothing) => {
                *events |= Events::OVEN_CHECK;
                if self.timer >= 0 {
                    self.oven_off_time = self.timer + 1;
                    self.timer = -1;
                    self.carry = Carry::Soup;
                    *events |= Events::PICKUP;
                } else {
                    *events |= Events::NO_EFFECT;
                }
            }
            (ObjectKind::DeliveryCounter, Carry::Soup) => {
                self.carry = Carry::Nothing;
                self.counter = Some(Counter::Main);
                *events |= Events::DELIVERY;
                let reward = self.production_reward(self.oven_off_time);
                if reward > 0.0 {
                    *events |= Events::IN_WINDOW;
                }
                return reward;
            }
            _ => *events |= Events::NO_EFFECT,
        }
        0.0
    }

    /// `max(0, 1 − |tp − g·ts| / w)`.
    fn production_reward(&self, tp: i32) -> f32 {
        let Some(rsg) = &self.spec.rsg else {
            return 0.0;
        };
        let (target, w) = rsg.target(self.td, self.rsg.gain);
        (1.0 - (f64::from(tp) - target).abs() / w).max(0.0) as f32
    }

    /// One step of the reproduction task.
    pub(crate) fn step_ready_set_go(&mut self, action: Action, obs: &mut [u8]) -> Transition {
        let (old, timer_at_action, next_to_oven) = self.step_context();
        let mut events = 0u16;
        let reward = self.act_or_move(action, &mut events, Self::interact_rsg);
        self.ready = false;
        if self.timer >= 0 {
            self.timer += 1;
        }
        let f = self.rsg.foreperiod;
        if self.timestep == f {
            self.ready = true;
            events |= Events::CUE;
        }
        if self.timestep == f + self.td && self.oven_off_time < 0 {
            self.ready = true;
            self.timer = 0;
            events |= Events::CUE;
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
}
