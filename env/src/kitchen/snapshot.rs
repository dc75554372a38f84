//! Checkpointing a [`Kitchen`]: its dynamic state (RNG included) as a serialisable
//! snapshot, the checks a snapshot read from a file must pass, and the restore.

use super::{Kitchen, MultiOvenState, RsgState};
use crate::error::EnvError;
use crate::info::{Carry, Counter};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

/// Serialisable dynamic state of a [`Kitchen`] (RNG included): what a training checkpoint
/// stores so that a resumed run continues exactly.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KitchenSnapshot {
    /// Saved `rng`.
    pub rng: Xoshiro256PlusPlus,
    /// Saved `num_timers`.
    pub num_timers: usize,
    /// Saved `agent`.
    pub agent: usize,
    /// Saved `carry`.
    pub carry: Carry,
    /// Saved `timer`.
    pub timer: i32,
    /// Saved `ready`.
    pub ready: bool,
    /// Saved `manual`.
    pub manual: bool,
    /// Saved `never_ready`.
    pub never_ready: bool,
    /// Saved `td`.
    pub td: u32,
    /// Saved `timestep`.
    pub timestep: u32,
    /// Saved `oven_off_time`.
    pub oven_off_time: i32,
    /// Saved `manual_stop_time`.
    pub manual_stop_time: i32,
    /// Saved `sink_count`.
    pub sink_count: u32,
    /// Saved `last_sink_timer`.
    pub last_sink_timer: i32,
    /// Saved `counter`.
    pub counter: Option<Counter>,
    /// Saved `done`.
    pub done: bool,
    /// Saved multi-oven state (absent for the other tasks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub multi_oven: Option<MultiOvenState>,
    /// Saved reproduction context (absent for the other tasks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reproduction: Option<RsgState>,
}

impl Kitchen {
    /// Captures the dynamic state (episode and RNG).
    pub fn snapshot(&self) -> KitchenSnapshot {
        KitchenSnapshot {
            rng: self.rng.clone(),
            num_timers: self.num_timers,
            agent: self.agent,
            carry: self.carry,
            timer: self.timer,
            ready: self.ready,
            manual: self.manual,
            never_ready: self.never_ready,
            td: self.td,
            timestep: self.timestep,
            oven_off_time: self.oven_off_time,
            manual_stop_time: self.manual_stop_time,
            sink_count: self.sink_count,
            last_sink_timer: self.last_sink_timer,
            counter: self.counter,
            done: self.done,
            multi_oven: self.is_multi_oven().then_some(self.mo),
            reproduction: self.spec.rsg.is_some().then_some(self.rsg),
        }
    }

    /// Checks that a snapshot (read from a checkpoint) fits this kitchen's task: the agent
    /// on a free cell, the active TDs and the TD among the task's.
    pub fn check_snapshot(&self, s: &KitchenSnapshot) -> Result<(), EnvError> {
        let free = self.spec.layout.free_cells();
        if !free.iter().any(|&c| c as usize == s.agent) {
            return Err(EnvError::param(
                "agent",
                s.agent,
                format!("a free cell of the layout ({free:?})"),
            ));
        }
        // As `Kitchen::new` sets it: 1..=|tds| active timers, none for a task without
        // TDs (reproduction draws its intervals from priors).
        let max_timers = self.spec.tds.len();
        let min_timers = max_timers.min(1);
        if s.num_timers < min_timers || s.num_timers > max_timers {
            return Err(EnvError::param(
                "num_timers",
                s.num_timers,
                format!("{min_timers}..={max_timers}"),
            ));
        }
        if s.td == 0 && !self.spec.config.reference_compat {
            return Err(EnvError::param("td", 0, "a positive number of steps"));
        }
        if self.is_multi_oven() != s.multi_oven.is_some() {
            return Err(EnvError::param(
                "multi_oven",
                if s.multi_oven.is_some() {
                    "present"
                } else {
                    "absent"
                },
                "present exactly for the multi-oven task",
            ));
        }
        Ok(())
    }

    /// Restores a state captured by [`Kitchen::snapshot`] (same task spec assumed; a
    /// snapshot read from a file is checked with [`Kitchen::check_snapshot`] first).
    pub fn restore(&mut self, s: &KitchenSnapshot) {
        self.rng = s.rng.clone();
        self.num_timers = s.num_timers;
        self.agent = s.agent;
        self.carry = s.carry;
        self.timer = s.timer;
        self.ready = s.ready;
        self.manual = s.manual;
        self.never_ready = s.never_ready;
        self.td = s.td;
        self.timestep = s.timestep;
        self.oven_off_time = s.oven_off_time;
        self.manual_stop_time = s.manual_stop_time;
        self.sink_count = s.sink_count;
        self.last_sink_timer = s.last_sink_timer;
        self.counter = s.counter;
        self.done = s.done;
        self.mo = s.multi_oven.unwrap_or_default();
        self.rsg = s.reproduction.unwrap_or_default();
    }
}
