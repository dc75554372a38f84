//! What a kitchen episode starts from and what each step returns: the reset options (what
//! the task would otherwise draw at random: start cell, duration, per-oven durations and
//! on-times, reproduction context) and the step's transition.

use crate::error::EnvError;
use crate::info::Info;
use crate::task::reset_option::ResetOption;

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
    /// Ready-Set-Go tasks: the index of the episode's prior (drawn when `None`).
    pub prior: Option<u8>,
    /// Ready-Set-Go tasks: the index of the episode's gain (drawn when `None`).
    pub gain: Option<u8>,
}

impl ResetOptions {
    /// Whether these options set `option`.
    pub fn sets(&self, option: ResetOption) -> bool {
        match option {
            ResetOption::Start => self.start.is_some(),
            ResetOption::Td => self.td.is_some(),
            ResetOption::NeverReady => self.never_ready.is_some(),
            ResetOption::OvenTds => self.oven_tds.is_some(),
            ResetOption::OnTimes => self.on_times.is_some(),
            ResetOption::Prior => self.prior.is_some(),
            ResetOption::Gain => self.gain.is_some(),
        }
    }
}

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
