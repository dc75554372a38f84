//! Per-step information for metrics: events, timers, counters — no need to reach into internals.

use serde::{Deserialize, Serialize, Serializer};

/// What the agent holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Carry {
    /// Empty hands.
    #[default]
    Nothing,
    /// An onion.
    Onion,
    /// A soup.
    Soup,
}

/// Which delivery counter received the soup.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Counter {
    /// The single delivery counter (FI, PI, multi-timer, dual, uncertainty).
    Main,
    /// Bisection short counter (code 4).
    Short,
    /// Bisection long counter (code 8); the multi-oven task's long counter.
    Long,
    /// Multi-anchor: the counter of anchor `i` (1-based, as the reference's
    /// `delivery_counter_used`).
    Anchor(u8),
}

impl Counter {
    /// The counter as the reference numbers it (multi-anchor: 1…4; bisection and multi-oven:
    /// 1 short, 2 long; the single counter: 1).
    pub fn number(self) -> u8 {
        match self {
            Counter::Main | Counter::Short => 1,
            Counter::Long => 2,
            Counter::Anchor(i) => i,
        }
    }
}

/// Per-oven state of a multi-oven step (`n == 0` in every other task). It is kept out of
/// [`Info`], which every task's step returns: read it with `ChronoEnv::ovens` after a step,
/// from an episode record's `ovens`, or from a trace line's `ovens`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct OvenSet {
    /// Number of ovens of the task (0: not a multi-oven task).
    pub n: u8,
    /// Each oven's duration (steps).
    pub td: [u32; 3],
    /// Each oven's timer (−1 off or emptied).
    pub timer: [i32; 3],
    /// Each oven's on-time (step at whose end it starts by itself; −1: started by the put).
    pub on_time: [i32; 3],
    /// Timer at which each oven's soup was taken out (−1 before).
    pub off_time: [i32; 3],
    /// Where each oven's soup went: 0 not delivered, 1 short counter, 2 long counter.
    pub delivered: [u8; 3],
    /// Bit `i` set: oven `i`'s soup went to the counter of its duration (it paid 1/n).
    pub paid: u8,
}

impl OvenSet {
    /// Whether this is not a multi-oven step (serialisation skips it then).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Every oven's soup is delivered, each to the counter of its duration.
    pub fn all_paid(&self) -> bool {
        self.n > 0 && self.paid == (1u8 << self.n) - 1
    }
}

/// Bit set of the events that happened during one step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Events(pub u16);

impl Events {
    /// Took an onion from the dispenser.
    pub const ONION_TAKEN: u16 = 1;
    /// Put the onion in the oven (oven on, timer := 0).
    pub const ONION_IN: u16 = 1 << 1;
    /// Interacted next to a running oven with empty hands (an oven check; includes the pickup).
    pub const OVEN_CHECK: u16 = 1 << 2;
    /// Took the soup out of the oven.
    pub const PICKUP: u16 = 1 << 3;
    /// Delivered the soup (episode ends).
    pub const DELIVERY: u16 = 1 << 4;
    /// The oven became ready by itself at the end of this step (timer == TD).
    pub const OVEN_READY: u16 = 1 << 5;
    /// A paid interaction with the reward sink (dual task).
    pub const SINK: u16 = 1 << 6;
    /// The manual button readied the oven (uncertainty task).
    pub const BUTTON: u16 = 1 << 7;
    /// An interact that changed nothing.
    pub const NO_EFFECT: u16 = 1 << 8;
    /// Ready-Set-Go: the oven flashed a cue (Ready or Set) at the end of this step.
    pub const CUE: u16 = 1 << 9;
    /// Ready-Set-Go: the delivered soup was produced inside the reward window.
    pub const IN_WINDOW: u16 = 1 << 10;
    /// Multi-oven: this delivery completed the episode with every oven's soup at the
    /// counter of its duration (each paid 1/n).
    pub const ALL_PAID: u16 = 1 << 11;

    /// Names of the flags, in bit order.
    pub const NAMES: [(u16, &'static str); 12] = [
        (Self::ONION_TAKEN, "onion_taken"),
        (Self::ONION_IN, "onion_in"),
        (Self::OVEN_CHECK, "oven_check"),
        (Self::PICKUP, "pickup"),
        (Self::DELIVERY, "delivery"),
        (Self::OVEN_READY, "oven_ready"),
        (Self::SINK, "sink"),
        (Self::BUTTON, "button"),
        (Self::NO_EFFECT, "no_effect"),
        (Self::CUE, "cue"),
        (Self::IN_WINDOW, "in_window"),
        (Self::ALL_PAID, "all_paid"),
    ];

    /// Whether `flag` is set.
    #[inline]
    pub fn has(self, flag: u16) -> bool {
        self.0 & flag != 0
    }

    /// Names of the set flags.
    pub fn names(self) -> Vec<&'static str> {
        Self::NAMES
            .iter()
            .filter(|(f, _)| self.has(*f))
            .map(|(_, n)| *n)
            .collect()
    }

    /// Parses flag names back into a set (unknown names are ignored).
    pub fn from_names<S: AsRef<str>>(names: &[S]) -> Self {
        let mut bits = 0;
        for n in names {
            if let Some((f, _)) = Self::NAMES.iter().find(|(_, name)| *name == n.as_ref()) {
                bits |= f;
            }
        }
        Events(bits)
    }
}

impl Serialize for Events {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.names().serialize(s)
    }
}

impl<'de> Deserialize<'de> for Events {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let names = Vec::<String>::deserialize(d)?;
        Ok(Events::from_names(&names))
    }
}

/// Step information (gymnasium's `info`). Timers are in steps; −1 means "off / never".
///
/// The multi-oven task's per-oven state is not part of it ([`OvenSet`]): every step of
/// every task copies an `Info`, and that state would more than double its size (44 → 100
/// bytes, measured as 13% of the vector env's step time; BENCHMARKS.md).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Info {
    /// Steps taken in this episode (0 after reset).
    pub timestep: u32,
    /// Target duration of this episode (steps).
    pub td: u32,
    /// Hidden oven timer after this step (−1 when off).
    pub oven_timer: i32,
    /// Oven timer when this step's action was taken (−1 when off); FOC uses this.
    pub timer_at_action: i32,
    /// Visible oven state after the step: 0 off, 1 on, 2 ready.
    pub oven_state: u8,
    /// Timer value at which the soup was taken out (−1 before pickup).
    pub oven_off_time: i32,
    /// Counter that received the soup, once delivered.
    pub counter: Option<Counter>,
    /// Events of this step.
    pub events: Events,
    /// Whether the agent stood next to the oven when the action was taken.
    pub next_to_oven: bool,
    /// Agent cell `(row, col)` after the step.
    pub agent: (u8, u8),
    /// What the agent holds after the step.
    pub carrying: Carry,
    /// Uncertainty task: this episode's oven never readies by itself.
    pub never_ready: bool,
    /// Uncertainty task: timer at which the button readied the oven (−1 if never).
    pub manual_stop_time: i32,
    /// Dual task: paid sink interactions so far in this episode.
    pub sink_count: u32,
    /// Dual task: timer at the last paid sink interaction (−1 if none).
    pub last_sink_timer: i32,
}

/// Keys every serialised `info` object carries (checked by the conformance tests).
pub const INFO_KEYS: [&str; 15] = [
    "timestep",
    "td",
    "oven_timer",
    "timer_at_action",
    "oven_state",
    "oven_off_time",
    "counter",
    "events",
    "next_to_oven",
    "agent",
    "carrying",
    "never_ready",
    "manual_stop_time",
    "sink_count",
    "last_sink_timer",
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Every step of every task builds an `Info` and the vector env copies it twice, so its
    /// size is env speed: the per-oven state inside it (100 bytes) cost 13% of the vector
    /// env's step time (BENCHMARKS.md). Task-specific state goes beside it, as `OvenSet`.
    #[test]
    fn the_step_info_stays_small() {
        assert!(
            std::mem::size_of::<Info>() <= 48,
            "Info is {} bytes",
            std::mem::size_of::<Info>()
        );
    }
}
