//! What a kitchen episode starts from and what each step returns: the reset options (what
//! the task would otherwise draw at random: start cell, duration, per-oven durations and
//! on-times, reproduction context) and the step's transition.

use crate::error::EnvError;
use crate::info::Info;

/// Options of [`super::Kitchen::reset`]: fix what the task would otherwise draw at random.
/// Serialised (in `env play` recordings) with every field optional.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ResetOptions {
    /// Start cell `(row, col)`; must be free. Drawn uniformly when `None`.
    pub start: Option<(usize, usize)>,
    /// Target duration (steps) of this episode (multi-oven: of every oven). Drawn per task
    /// when `None`.
    pub td: Option<u32>,
    /// Uncertainty task: force a never-ready (true) or normal (false) episode.
    pub never_ready: Option<bool>,
    /// Multi-oven task: each oven's duration (steps), one per oven.
    pub oven_tds: Option<PerOven>,
    /// Asynchronous multi-oven task: the on-times of ovens 2…n (the step at whose end each
    /// starts by itself), one per oven after the first.
    pub on_times: Option<PerOven>,
    /// Reproduction task: the index of the episode's prior (drawn when `None`).
    pub prior: Option<u8>,
    /// Reproduction task: the index of the episode's gain (drawn when `None`).
    pub gain: Option<u8>,
}

/// One option of [`ResetOptions`], as a task family declares the options its episodes take
/// (`Family::reset_options`); Python's `reset(options=…)` and the checks of `reset` read the
/// declaration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResetOption {
    /// `start`: the start cell.
    Start,
    /// `td`: the episode's duration.
    Td,
    /// `never_ready`: a never-ready or a normal episode.
    NeverReady,
    /// `oven_tds`: one duration per oven.
    OvenTds,
    /// `on_times`: the on-times of the ovens after the first.
    OnTimes,
    /// `prior`: the index of the episode's prior.
    Prior,
    /// `gain`: the index of the episode's gain.
    Gain,
}

impl ResetOption {
    /// Every option, in the order of [`ResetOptions`]' fields.
    pub const ALL: [ResetOption; 7] = [
        ResetOption::Start,
        ResetOption::Td,
        ResetOption::NeverReady,
        ResetOption::OvenTds,
        ResetOption::OnTimes,
        ResetOption::Prior,
        ResetOption::Gain,
    ];

    /// The option's key (the field of [`ResetOptions`], and Python's `options` key).
    pub fn key(self) -> &'static str {
        match self {
            ResetOption::Start => "start",
            ResetOption::Td => "td",
            ResetOption::NeverReady => "never_ready",
            ResetOption::OvenTds => "oven_tds",
            ResetOption::OnTimes => "on_times",
            ResetOption::Prior => "prior",
            ResetOption::Gain => "gain",
        }
    }

    /// The option's value and meaning, for help texts and errors.
    pub fn doc(self) -> &'static str {
        match self {
            ResetOption::Start => "(row, col): the start cell (a free cell)",
            ResetOption::Td => "integer (steps): the episode's target duration",
            ResetOption::NeverReady => "bool: a never-ready (true) or normal (false) episode",
            ResetOption::OvenTds => "list of integers (steps): one duration per oven",
            ResetOption::OnTimes => {
                "list of integers (steps): the step at whose end each oven after the first starts"
            }
            ResetOption::Prior => "integer: the index of the episode's prior",
            ResetOption::Gain => "integer: the index of the episode's gain",
        }
    }

    /// The option whose key is `key`.
    pub fn from_key(key: &str) -> Option<ResetOption> {
        ResetOption::ALL.into_iter().find(|o| o.key() == key)
    }

    /// Whether `options` sets this option.
    pub fn is_set(self, options: &ResetOptions) -> bool {
        match self {
            ResetOption::Start => options.start.is_some(),
            ResetOption::Td => options.td.is_some(),
            ResetOption::NeverReady => options.never_ready.is_some(),
            ResetOption::OvenTds => options.oven_tds.is_some(),
            ResetOption::OnTimes => options.on_times.is_some(),
            ResetOption::Prior => options.prior.is_some(),
            ResetOption::Gain => options.gain.is_some(),
        }
    }
}

/// The options every task takes: the start cell and the duration.
pub const BASIC_RESET_OPTIONS: &[ResetOption] = &[ResetOption::Start, ResetOption::Td];

/// Up to three values, one per oven (durations or on-times, in steps); serialised as a list.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(into = "Vec<u32>", try_from = "Vec<u32>")]
pub struct PerOven {
    len: u8,
    values: [u32; 3],
}

impl PerOven {
    /// The values of `items` (at most 3).
    pub fn new(field: &str, items: &[u32]) -> Result<Self, EnvError> {
        if items.len() > 3 {
            return Err(EnvError::reset_option(
                field,
                format!("{items:?}"),
                "at most 3 values (one per oven)",
            ));
        }
        let mut values = [0; 3];
        values[..items.len()].copy_from_slice(items);
        Ok(PerOven {
            len: items.len() as u8,
            values,
        })
    }

    /// The values.
    pub fn as_slice(&self) -> &[u32] {
        &self.values[..self.len as usize]
    }
}

impl From<PerOven> for Vec<u32> {
    fn from(v: PerOven) -> Self {
        v.as_slice().to_vec()
    }
}

impl TryFrom<Vec<u32>> for PerOven {
    type Error = EnvError;

    fn try_from(items: Vec<u32>) -> Result<Self, EnvError> {
        PerOven::new("per-oven values", &items)
    }
}

/// Result of one step (the observation is written to the caller's buffer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition {
    /// Reward of this step.
    pub reward: f32,
    /// The episode reached a terminal state (delivery; or the time limit in reference mode).
    pub terminated: bool,
    /// The episode was cut by the time limit (default mode).
    pub truncated: bool,
    /// Step information.
    pub info: Info,
}

impl Transition {
    /// Whether the episode is over.
    #[inline]
    pub fn done(&self) -> bool {
        self.terminated || self.truncated
    }
}
