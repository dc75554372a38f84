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
    /// Bisection long counter (code 8).
    Long,
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

    /// Names of the flags, in bit order.
    pub const NAMES: [(u16, &'static str); 9] = [
        (Self::ONION_TAKEN, "onion_taken"),
        (Self::ONION_IN, "onion_in"),
        (Self::OVEN_CHECK, "oven_check"),
        (Self::PICKUP, "pickup"),
        (Self::DELIVERY, "delivery"),
        (Self::OVEN_READY, "oven_ready"),
        (Self::SINK, "sink"),
        (Self::BUTTON, "button"),
        (Self::NO_EFFECT, "no_effect"),
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
