//! The kitchen's rules of one task configuration, flattened for the hot loop, and the
//! reward and cue modes they read. Each task family builds them from its parameters
//! (`task::family`); the kitchen runs them.

use serde::{Deserialize, Serialize};

/// Multi-timer reward rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RewardMode {
    /// Soup can be taken any time after the onion went in (undercooking possible);
    /// reward 1 iff `TD − under_buffer ≤ oven_off_time ≤ TD + over_buffer`.
    Exact,
    /// Soup can be taken only when timer ≥ TD; reward 1 unless
    /// `oven_off_time > TD + over_buffer`.
    LowerBounded,
}

/// What the oven shows in observation channel 4 while on (multi-timer).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CueMode {
    /// The TD value itself (reference behaviour; orders TDs, used for OOD tests).
    Value,
    /// `1 + index` of the TD in the trained list (no ordering information).
    Categorical,
}

/// Task rules, flattened to a small `Copy` value for the hot loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Rules {
    Fixed,
    Probe {
        factor: u32,
    },
    Bisection {
        short: u32,
        long: u32,
    },
    Window {
        mode: RewardMode,
        under: u32,
        over: u32,
        reduced: f32,
    },
    Dual {
        under: u32,
        over: u32,
        reduced: f32,
        sink: f32,
    },
    Uncertainty {
        p_never: f32,
        over: u32,
        overcooked: f32,
        manual: f32,
    },
    /// Categorisation by counter ([`crate::task::family::RuleSet::categories`]): the first
    /// `k` of `anchors` are active (counters 1…k); delivery to counter `i` pays iff the
    /// episode's TD is `anchors[i]`.
    Categories {
        anchors: [u32; 4],
        k: u8,
    },
    /// Ready-Set-Go (temporal reproduction): the oven flashes Ready and Set `ts` apart and a
    /// production `g · ts` after Set is paid inside a window ([`ReadySetGo`]).
    ReadySetGo,
    /// Multi-oven: `n` ovens, each soup short or long.
    MultiOven {
        short: u32,
        long: u32,
        n: u8,
        asynchronous: bool,
    },
}

impl Rules {
    /// The ovens the extended codes view shows (its own channel layout, `Box(0, 20)`, for
    /// categorisation by counter and for several ovens), or `None` for the basic view.
    pub(crate) fn extended_ovens(&self) -> Option<usize> {
        match *self {
            Rules::Categories { .. } => Some(1),
            Rules::MultiOven { n, .. } => Some(usize::from(n)),
            _ => None,
        }
    }
}

/// The Ready-Set-Go mechanics of a task (temporal reproduction; Jazayeri & Shadlen 2010):
/// what an episode draws, what the counter cues and which production is paid. A family
/// declares them with [`crate::task::family::RuleSet::ready_set_go`]; the kitchen, the
/// oracle, the Bayesian observers and the timing agents read them from the environment
/// ([`crate::ChronoEnv::ready_set_go`]), never from a family's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadySetGo {
    /// Each prior's inclusive range of sample intervals `ts` (steps; `1 <= lo < hi`).
    pub priors: Vec<(u32, u32)>,
    /// Gains `g` of the production `tp = g · ts` (as the task stores them).
    pub gains: Vec<f32>,
    /// Relative half-width of the reward window: `tolerance · target + tolerance_steps`
    /// (the decimal as given, to 1e-6: an `f32` 0.2 would widen the window by 3e-9 and pay
    /// an edge response).
    pub tolerance: f64,
    /// Constant part of the window's half-width (steps).
    pub tolerance_steps: f64,
    /// Foreperiod range, Ready's delay after the episode starts (steps, inclusive).
    pub foreperiod: (u32, u32),
    /// Whether the counter cues the prior (as well as the gain).
    pub prior_cue: bool,
    /// Cell whose channel 4 shows the context cue (the delivery counter).
    pub counter: usize,
}

impl ReadySetGo {
    /// Contexts shown on the counter: `prior · gains + gain` (+1 in the observation), or
    /// none when there is nothing to cue.
    pub fn cued_contexts(&self) -> usize {
        let priors = if self.prior_cue { self.priors.len() } else { 1 };
        let n = priors * self.gains.len();
        if n > 1 { n } else { 0 }
    }

    /// The cue value of `(prior, gain)` (0: no cue).
    pub fn cue(&self, prior: u8, gain: u8) -> u8 {
        if self.cued_contexts() == 0 {
            return 0;
        }
        let p = if self.prior_cue { prior as usize } else { 0 };
        (1 + p * self.gains.len() + gain as usize) as u8
    }

    /// Gain `gain` (an index into `gains`) as the decimal it was written as (an `f32` 1.1
    /// is not 1.1: rounded to 1e-6).
    pub fn gain(&self, gain: usize) -> f64 {
        decimal(f64::from(self.gains[gain]))
    }

    /// The target production `g · ts` and the window half-width (steps).
    pub fn target(&self, ts: u32, gain: u8) -> (f64, f64) {
        let target = self.gain(usize::from(gain)) * f64::from(ts);
        (target, self.tolerance * target + self.tolerance_steps)
    }
}

/// An `f32` setting as the decimal it was written as (rounded to 1e-6).
pub(crate) fn decimal(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}
