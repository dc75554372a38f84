//! The options of `reset` a task family declares ([`crate::task::family::Family::reset_options`]):
//! what an episode would otherwise draw, by name. The values themselves are
//! [`crate::ResetOptions`] (the kitchen's).

/// One option of `reset` ([`crate::ResetOptions`]), as a task family declares the options its episodes take
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
}

/// The options every task takes: the start cell and the duration.
pub const BASIC_RESET_OPTIONS: &[ResetOption] = &[ResetOption::Start, ResetOption::Td];
