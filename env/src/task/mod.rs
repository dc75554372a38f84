//! Task configuration: families, their parameters, `key=value` overrides and validation.
//!
//! A [`TaskConfig`] is plain data (serialisable); [`TaskConfig::validate`] turns it
//! into a checked configuration that the env can run. Parameter names follow the
//! reference implementation where one exists, and the reference's own names are
//! accepted as aliases (`oven_duration` for `td`, `overcooked_buffer` for
//! `over_buffer`, …) so reference configurations can be passed unchanged. A chosen task
//! travels as a [`Task`] (its id and the typed values of the parameters set), which
//! [`Task::config`] turns into the checked [`TaskConfig`].

mod chosen;
pub mod params;

pub use chosen::{Task, make_config};

use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::settings::{self, Spec};
use params::{MAX_ANCHORS, MAX_TD, MAX_TIMESTEPS};
use serde::{Deserialize, Serialize};

/// Reference FI / multi-timer layout (5×3): onion (0,1), delivery (0,2), oven (2,0).
pub const FI_LAYOUT: &str = ".OD/.../V../.../...";
/// Reference bisection layout (4×3): short (0,0), onion (0,1), long (0,2), oven (3,1).
pub const BISECTION_LAYOUT: &str = "SOL/.../.../.V.";
/// Dual-task layout: the FI layout plus a reward sink at (4,2).
pub const DUAL_LAYOUT: &str = ".OD/.../V../.../..K";
/// Uncertainty layout: the FI layout plus a manual oven-off button at (4,1).
pub const UNCERTAINTY_LAYOUT: &str = ".OD/.../V../.../.B.";
/// Reproduction layout (5×3): delivery (0,2), oven (2,0); no onion (the oven is loaded).
pub const REPRODUCTION_LAYOUT: &str = "..D/.../V../.../...";
/// Multi-anchor and multi-oven tasks: the layout follows the active counters or ovens.
pub const AUTO_LAYOUT: &str = "auto";

/// The reference multi-anchor layout (4×3) with `k` counters: counter 1 (0,0), onion (0,1),
/// counter 2 (0,2), counter 3 (3,0), oven (3,1), counter 4 (3,2).
pub fn multi_anchor_layout(k: usize) -> &'static str {
    match k {
        0..=2 => "SOL/.../.../.V.",
        3 => "SOL/.../.../3V.",
        _ => "SOL/.../.../3V4",
    }
}

/// The reference multi-oven layout (4×3) with `n` ovens: short counter (0,0), onion (0,1),
/// long counter (0,2), oven i at (3,i).
pub fn multi_oven_layout(n: usize) -> &'static str {
    match n {
        0 | 1 => "SOL/.../.../V..",
        2 => "SOL/.../.../VW.",
        _ => "SOL/.../.../VWX",
    }
}

/// The task families of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TaskFamily {
    /// Fixed interval: soup available from timer ≥ TD, +1 on delivery.
    FixedInterval,
    /// Peak-interval probe: FI with the soup withheld until k·TD (or never).
    PeakInterval,
    /// Temporal bisection: deliver to the short or the long counter.
    Bisection,
    /// Multi-timer: cued TDs, reward window around TD.
    MultiTimer,
    /// Dual task: FI with a small-reward sink during the timing phase.
    Dual,
    /// Uncertainty: the oven may never become ready; a manual button readies it.
    Uncertainty,
    /// Multi-anchor categorization: one counter per anchor duration (2–4).
    MultiAnchor,
    /// Multi-oven bisection: 1–3 ovens, each soup to the short or the long counter.
    MultiOven,
    /// Temporal reproduction (Ready-Set-Go): reproduce the interval between two oven cues.
    Reproduction,
}

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

/// Family-specific parameters. Units: durations in env steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "family", rename_all = "snake_case")]
pub enum TaskParams {
    /// Fixed interval.
    FixedInterval {
        /// Target duration (steps).
        td: u32,
    },
    /// Peak-interval probe on the FI task.
    PeakInterval {
        /// Trained target duration (steps).
        td: u32,
        /// Soup released at `probe_factor × td`; 0 = never released.
        probe_factor: u32,
    },
    /// Temporal bisection.
    Bisection {
        /// Short anchor S (steps).
        short: u32,
        /// Long anchor L (steps), > S.
        long: u32,
    },
    /// Multi-timer.
    MultiTimer {
        /// Trainable TD list; an episode draws from the first `num_timers`.
        tds: Vec<u32>,
        /// How many TDs of `tds` are active (grows in a curriculum).
        num_timers: usize,
        /// Reward rule.
        mode: RewardMode,
        /// Oven cue.
        cue: CueMode,
        /// Early tolerance (steps).
        under_buffer: u32,
        /// Late tolerance (steps).
        over_buffer: u32,
        /// Reward outside the window.
        reduced_reward: f32,
    },
    /// Dual task.
    Dual {
        /// Target duration (steps).
        td: u32,
        /// Early tolerance (steps).
        under_buffer: u32,
        /// Late tolerance (steps).
        over_buffer: u32,
        /// Soup reward outside the window.
        reduced_reward: f32,
        /// Reward per sink interaction while the oven is on.
        sink_reward: f32,
    },
    /// Uncertainty.
    Uncertainty {
        /// Target duration (steps).
        td: u32,
        /// Probability that the oven never becomes ready by itself.
        never_ready_prob: f32,
        /// Late tolerance (steps) before a self-readied soup counts as overcooked.
        over_buffer: u32,
        /// Reward for overcooked soup.
        overcooked_reward: f32,
        /// Reward for soup readied with the manual button.
        manual_reward: f32,
    },
    /// Multi-anchor categorization.
    MultiAnchor {
        /// Anchor durations (steps), 2–4 distinct, increasing; counter i pays iff TD == anchors[i].
        anchors: Vec<u32>,
        /// Active anchors (the first `num_anchors` have counters and are drawn); `None`: all.
        #[serde(default)]
        num_anchors: Option<usize>,
    },
    /// Multi-oven bisection.
    MultiOven {
        /// Short anchor S (steps).
        short: u32,
        /// Long anchor L (steps), > S.
        long: u32,
        /// Number of ovens (1–3).
        ovens: u32,
        /// Ovens after the first start at their own on-times instead of at the put.
        asynchronous: bool,
    },
    /// Temporal reproduction (Ready-Set-Go).
    Reproduction {
        /// Priors of the sample interval: `short`, `intermediate`, `long` (Jazayeri &
        /// Shadlen 2010's three, scaled to steps) or `LO-HI` (every whole step from LO to HI).
        priors: Vec<String>,
        /// The counter shows which prior (and gain) the episode uses.
        prior_cue: bool,
        /// Gains `g` of the production `tp = g·ts` (Remington et al. 2018: 1 and 1.5).
        gains: Vec<f32>,
        /// Reward window half-width as a fraction of the target `g·ts`.
        tolerance: f32,
        /// Constant part of the window half-width (steps).
        tolerance_steps: f32,
        /// Shortest foreperiod before Ready (steps).
        foreperiod_min: u32,
        /// Longest foreperiod before Ready (steps).
        foreperiod_max: u32,
    },
}

/// The named priors of the reproduction task: Jazayeri & Shadlen 2010's short
/// (494–847 ms), intermediate (671–1023 ms) and long (847–1200 ms) priors at 1 step ≈ 59 ms,
/// 7 whole steps each, overlapping as theirs do (short and long share their end point).
pub const NAMED_PRIORS: [(&str, u32, u32); 3] =
    [("short", 8, 14), ("intermediate", 11, 17), ("long", 14, 20)];

/// Parses a prior (`short`, `intermediate`, `long` or `LO-HI`) into its inclusive range of
/// whole steps.
pub fn parse_prior(text: &str) -> Result<(u32, u32), EnvError> {
    let t = text.trim();
    if let Some(&(_, lo, hi)) = NAMED_PRIORS.iter().find(|(n, ..)| *n == t) {
        return Ok((lo, hi));
    }
    let bad = || {
        EnvError::param(
            "priors",
            t,
            "short, intermediate, long, or LO-HI with whole steps 1 <= LO < HI <= 1000",
        )
    };
    let (lo, hi) = t.split_once('-').ok_or_else(bad)?;
    let (lo, hi): (u32, u32) = (
        lo.trim().parse().map_err(|_| bad())?,
        hi.trim().parse().map_err(|_| bad())?,
    );
    if lo < 1 || hi <= lo || hi > 1000 {
        return Err(bad());
    }
    Ok((lo, hi))
}

impl TaskParams {
    /// The single target duration of families that have one (FI, PI, dual, uncertainty).
    pub fn td(&self) -> Option<u32> {
        match self {
            TaskParams::FixedInterval { td }
            | TaskParams::PeakInterval { td, .. }
            | TaskParams::Dual { td, .. }
            | TaskParams::Uncertainty { td, .. } => Some(*td),
            TaskParams::Bisection { .. }
            | TaskParams::MultiTimer { .. }
            | TaskParams::MultiAnchor { .. }
            | TaskParams::MultiOven { .. }
            | TaskParams::Reproduction { .. } => None,
        }
    }

    /// Multi-anchor: the active anchors (steps), in counter order.
    pub fn active_anchors(&self) -> Option<&[u32]> {
        match self {
            TaskParams::MultiAnchor {
                anchors,
                num_anchors,
            } => Some(&anchors[..num_anchors.unwrap_or(anchors.len()).min(anchors.len())]),
            _ => None,
        }
    }
}

/// Everything needed to build an env: task family parameters plus shared settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskConfig {
    /// Registry id the config came from (e.g. `FixedInterval-v0`).
    pub id: String,
    /// Layout text (see [`Layout::parse`]).
    pub layout: String,
    /// Time limit: the episode stops once `timestep > max_timesteps` (reference rule).
    pub max_timesteps: u32,
    /// Report the time-limit stop as `terminated` (reference behaviour) instead of `truncated`.
    pub reference_compat: bool,
    /// Debug only: write the hidden oven timer into channel 5 (leaks time; off by default).
    pub debug_timer_channel: bool,
    /// Bisection / multi-timer: fix the TD of every episode (test probes, OOD TDs) instead of
    /// drawing it; `None` draws per task. (FI-like tasks have `td` in their params.)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fixed_td: Option<u32>,
    /// Family parameters.
    pub params: TaskParams,
}

impl TaskFamily {
    /// Every parameter of the family, its own first (the settings table of
    /// [`params`]).
    pub fn params(self) -> Vec<Spec> {
        params::table(self)
    }

    /// Objects the family's layout must contain exactly once (every other kind must be
    /// absent), for the given parameters.
    fn required_objects(self, params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        match self {
            TaskFamily::FixedInterval | TaskFamily::PeakInterval | TaskFamily::MultiTimer => {
                vec![OnionDispenser, DeliveryCounter, Oven]
            }
            TaskFamily::Bisection => vec![OnionDispenser, ShortCounter, LongCounter, Oven],
            TaskFamily::Dual => vec![OnionDispenser, DeliveryCounter, Oven, RewardSink],
            TaskFamily::Uncertainty => vec![OnionDispenser, DeliveryCounter, Oven, OvenButton],
            TaskFamily::MultiAnchor => {
                let k = params.active_anchors().map_or(2, <[u32]>::len);
                let mut v = vec![OnionDispenser, Oven, ShortCounter, LongCounter];
                v.extend([Counter3, Counter4].into_iter().take(k.saturating_sub(2)));
                v
            }
            TaskFamily::MultiOven => {
                let n = match params {
                    TaskParams::MultiOven { ovens, .. } => *ovens as usize,
                    _ => 1,
                };
                let mut v = vec![OnionDispenser, ShortCounter, LongCounter, Oven];
                v.extend([Oven2, Oven3].into_iter().take(n.saturating_sub(1)));
                v
            }
            TaskFamily::Reproduction => vec![DeliveryCounter, Oven],
        }
    }

    /// Whether the oven shows a "ready" state (ch4 = 2) in this family.
    pub fn shows_ready(self) -> bool {
        matches!(
            self,
            TaskFamily::Bisection
                | TaskFamily::Uncertainty
                | TaskFamily::MultiAnchor
                | TaskFamily::MultiOven
        )
    }
}

/// Parameters every task accepts.
pub fn common_params() -> &'static [Spec] {
    params::COMMON
}

impl From<settings::SettingError> for EnvError {
    fn from(e: settings::SettingError) -> Self {
        EnvError::InvalidParam {
            field: e.key,
            value: e.value,
            allowed: e.allowed,
        }
    }
}

impl TaskConfig {
    /// The family of this configuration.
    pub fn family(&self) -> TaskFamily {
        match self.params {
            TaskParams::FixedInterval { .. } => TaskFamily::FixedInterval,
            TaskParams::PeakInterval { .. } => TaskFamily::PeakInterval,
            TaskParams::Bisection { .. } => TaskFamily::Bisection,
            TaskParams::MultiTimer { .. } => TaskFamily::MultiTimer,
            TaskParams::Dual { .. } => TaskFamily::Dual,
            TaskParams::Uncertainty { .. } => TaskFamily::Uncertainty,
            TaskParams::MultiAnchor { .. } => TaskFamily::MultiAnchor,
            TaskParams::MultiOven { .. } => TaskFamily::MultiOven,
            TaskParams::Reproduction { .. } => TaskFamily::Reproduction,
        }
    }

    /// Applies one `key=value` override (canonical key or reference alias), parsed and
    /// range-checked by the family's parameter table ([`params`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), EnvError> {
        let key = key.trim();
        let table = params::table(self.family());
        let spec = settings::find(&table, key).ok_or_else(|| EnvError::UnknownParam {
            key: key.to_string(),
            task: self.id.clone(),
            known: table.iter().map(|p| p.key).collect::<Vec<_>>().join(", "),
        })?;
        // Errors name the canonical key (`td` for `oven_duration`).
        settings::set_field(self, spec, spec.key, value)?;
        // Fewer TDs than active timers: the active count follows the list (as the
        // reference's curriculum never has more active timers than TDs).
        if let TaskParams::MultiTimer {
            tds, num_timers, ..
        } = &mut self.params
            && spec.key == "tds"
        {
            *num_timers = (*num_timers).min(tds.len()).max(1);
        }
        Ok(())
    }

    /// The layout text the env runs: [`TaskConfig::layout`], or for `auto` the reference
    /// layout of the active counters (multi-anchor) or ovens (multi-oven).
    pub fn resolved_layout(&self) -> &str {
        if self.layout.trim() != AUTO_LAYOUT {
            return &self.layout;
        }
        match &self.params {
            TaskParams::MultiAnchor { .. } => {
                multi_anchor_layout(self.params.active_anchors().map_or(2, <[u32]>::len))
            }
            TaskParams::MultiOven { ovens, .. } => multi_oven_layout(*ovens as usize),
            TaskParams::Bisection { .. } => BISECTION_LAYOUT,
            TaskParams::Dual { .. } => DUAL_LAYOUT,
            TaskParams::Uncertainty { .. } => UNCERTAINTY_LAYOUT,
            TaskParams::Reproduction { .. } => REPRODUCTION_LAYOUT,
            _ => FI_LAYOUT,
        }
    }

    /// Checks every parameter against its table entry, then the cross-field constraints,
    /// and parses the layout.
    pub fn validate(&self) -> Result<Layout, EnvError> {
        let family = self.family();
        settings::check(&params::table(family), self)?;
        let layout = Layout::parse(self.resolved_layout())?;
        let required = family.required_objects(&self.params);
        for &kind in &required {
            let n = layout.cells_of(kind).len();
            if n != 1 {
                return Err(EnvError::InvalidLayout {
                    reason: format!(
                        "task {} needs exactly one `{}` ({:?}) but the layout has {n}",
                        self.id,
                        kind.symbol(),
                        kind
                    ),
                });
            }
        }
        for kind in ObjectKind::EVERY {
            if !required.contains(&kind) && !layout.cells_of(kind).is_empty() {
                return Err(EnvError::InvalidLayout {
                    reason: format!(
                        "task {} does not use `{}` ({:?}); remove it from the layout",
                        self.id,
                        kind.symbol(),
                        kind
                    ),
                });
            }
        }
        if self.max_timesteps as u64 > MAX_TIMESTEPS {
            return Err(EnvError::param(
                "max_timesteps",
                self.max_timesteps,
                format!("integer 0..={MAX_TIMESTEPS}"),
            ));
        }
        match &self.params {
            TaskParams::FixedInterval { .. }
            | TaskParams::PeakInterval { .. }
            | TaskParams::Dual { .. }
            | TaskParams::Uncertainty { .. } => {}
            TaskParams::Bisection { short, long } | TaskParams::MultiOven { short, long, .. } => {
                if long <= short {
                    return Err(EnvError::param(
                        "long",
                        long,
                        format!("integer > short ({short}): the anchors need S < L"),
                    ));
                }
            }
            TaskParams::MultiTimer {
                tds, num_timers, ..
            } => {
                if tds.is_empty() {
                    return Err(EnvError::param("tds", "[]", "at least one TD in 1..=255"));
                }
                if !distinct(tds) {
                    return Err(EnvError::param(
                        "tds",
                        settings::display(&serde_json::json!(tds)),
                        "distinct integers 1..=255",
                    ));
                }
                if *num_timers == 0 || *num_timers > tds.len() {
                    return Err(EnvError::param(
                        "num_timers",
                        num_timers,
                        format!("integer 1..={} (the length of tds)", tds.len()),
                    ));
                }
            }
            TaskParams::Reproduction {
                priors,
                gains,
                foreperiod_min,
                foreperiod_max,
                tolerance,
                tolerance_steps,
                ..
            } => {
                if priors.is_empty() || priors.len() > 3 {
                    return Err(EnvError::param(
                        "priors",
                        priors.join(","),
                        "1 to 3 priors (short, intermediate, long or LO-HI)",
                    ));
                }
                let mut longest = 0;
                for p in priors {
                    longest = longest.max(parse_prior(p)?.1);
                }
                if gains.is_empty() || gains.len() > 2 || !distinct_f32(gains) {
                    return Err(EnvError::param(
                        "gains",
                        settings::display(&serde_json::json!(gains)),
                        "1 or 2 distinct gains in [0.5, 3]",
                    ));
                }
                if foreperiod_min > foreperiod_max {
                    return Err(EnvError::param(
                        "foreperiod_max",
                        foreperiod_max,
                        format!("integer >= foreperiod_min ({foreperiod_min})"),
                    ));
                }
                // The latest response the window pays must fit in the episode.
                let g = gains.iter().copied().fold(0.0f32, f32::max) as f64;
                let target = g * f64::from(longest);
                let latest = f64::from(*foreperiod_max)
                    + f64::from(longest)
                    + target
                    + f64::from(*tolerance) * target
                    + f64::from(*tolerance_steps);
                if latest.ceil() as u64 + 1 > u64::from(self.max_timesteps) {
                    return Err(EnvError::param(
                        "max_timesteps",
                        self.max_timesteps,
                        format!(
                            "at least {} (foreperiod + longest ts + the latest paid production)",
                            latest.ceil() as u64 + 1
                        ),
                    ));
                }
            }
            TaskParams::MultiAnchor {
                anchors,
                num_anchors,
            } => {
                let text = settings::display(&serde_json::json!(anchors));
                if !(2..=MAX_ANCHORS).contains(&anchors.len()) {
                    return Err(EnvError::param(
                        "anchors",
                        text,
                        format!("2 to {MAX_ANCHORS} durations (one counter each)"),
                    ));
                }
                if anchors.windows(2).any(|w| w[0] >= w[1]) {
                    return Err(EnvError::param(
                        "anchors",
                        text,
                        "distinct durations in increasing order (counter i is the i-th shortest)",
                    ));
                }
                if let Some(k) = num_anchors
                    && !(2..=anchors.len()).contains(k)
                {
                    return Err(EnvError::param(
                        "num_anchors",
                        k,
                        format!("none, or 2..={} (the number of anchors)", anchors.len()),
                    ));
                }
            }
        }
        if let Some(td) = self.fixed_td {
            let fits = match &self.params {
                TaskParams::MultiTimer { cue, tds, .. } => match cue {
                    CueMode::Value => (1..=255).contains(&td),
                    CueMode::Categorical => tds.contains(&td),
                },
                TaskParams::Bisection { .. }
                | TaskParams::MultiAnchor { .. }
                | TaskParams::MultiOven { .. }
                | TaskParams::Reproduction { .. } => (1..=MAX_TD as u32).contains(&td),
                _ => false,
            };
            if !fits {
                return Err(EnvError::param(
                    "td",
                    td,
                    "a fixed TD is for bisection, multi-anchor, multi-oven, reproduction (1..=10000) and multi-timer (value cue 1..=255, categorical: one of tds)",
                ));
            }
        }
        Ok(layout)
    }
}

fn distinct_f32(values: &[f32]) -> bool {
    values
        .iter()
        .enumerate()
        .all(|(i, a)| values[i + 1..].iter().all(|b| a != b))
}

fn distinct(values: &[u32]) -> bool {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    sorted.len() == values.len()
}
