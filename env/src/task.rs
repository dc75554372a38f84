//! Task configuration: families, their parameters, `key=value` overrides and validation.
//!
//! A [`TaskConfig`] is plain data (serialisable); [`TaskConfig::validate`] turns it
//! into a checked configuration that the env can run. Parameter names follow the
//! reference implementation where one exists, and the reference's own names are
//! accepted as aliases (`oven_duration` for `td`, `overcooked_buffer` for
//! `over_buffer`, …) so reference configurations can be passed unchanged.

use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use serde::{Deserialize, Serialize};

/// Reference FI / multi-timer layout (5×3): onion (0,1), delivery (0,2), oven (2,0).
pub const FI_LAYOUT: &str = ".OD/.../V../.../...";
/// Reference bisection layout (4×3): short (0,0), onion (0,1), long (0,2), oven (3,1).
pub const BISECTION_LAYOUT: &str = "SOL/.../.../.V.";
/// Dual-task layout: the FI layout plus a reward sink at (4,2).
pub const DUAL_LAYOUT: &str = ".OD/.../V../.../..K";
/// Uncertainty layout: the FI layout plus a manual oven-off button at (4,1).
pub const UNCERTAINTY_LAYOUT: &str = ".OD/.../V../.../.B.";

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
}

impl TaskParams {
    /// The single target duration of families that have one (FI, PI, dual, uncertainty).
    pub fn td(&self) -> Option<u32> {
        match self {
            TaskParams::FixedInterval { td }
            | TaskParams::PeakInterval { td, .. }
            | TaskParams::Dual { td, .. }
            | TaskParams::Uncertainty { td, .. } => Some(*td),
            TaskParams::Bisection { .. } | TaskParams::MultiTimer { .. } => None,
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

/// Documentation of one configurable parameter.
#[derive(Debug, Clone, Serialize)]
pub struct ParamDoc {
    /// Canonical key.
    pub key: &'static str,
    /// Accepted aliases (reference names).
    pub aliases: &'static [&'static str],
    /// Allowed values.
    pub allowed: &'static str,
    /// What it does (with units).
    pub doc: &'static str,
}

const COMMON_PARAMS: &[ParamDoc] = &[
    ParamDoc {
        key: "max_timesteps",
        aliases: &["max_steps"],
        allowed: "integer 0..=1000000",
        doc: "episode stops when timestep > max_timesteps (so max_timesteps+1 steps), as in the reference",
    },
    ParamDoc {
        key: "reference_compat",
        aliases: &["reference"],
        allowed: "true|false",
        doc: "report the time-limit stop as terminated (reference) instead of truncated",
    },
    ParamDoc {
        key: "debug_timer_channel",
        aliases: &[],
        allowed: "true|false",
        doc: "DEBUG: expose the hidden oven timer (+1, 0 = off) in channel 5 at the oven",
    },
    ParamDoc {
        key: "layout",
        aliases: &[],
        allowed: "rows joined by '/', cells . O D V S L K B",
        doc: "grid layout; validated (no free cell next to two objects, connected)",
    },
];

const TD_PARAM: ParamDoc = ParamDoc {
    key: "td",
    aliases: &["oven_duration"],
    allowed: "integer 1..=10000",
    doc: "target duration in steps",
};
const FIXED_TD_PARAM: ParamDoc = ParamDoc {
    key: "td",
    aliases: &["oven_duration"],
    allowed: "integer 1..=10000 (multi-timer value cue: 1..=255; categorical: one of tds)",
    doc: "fix the TD of every episode (probes, OOD tests); default: drawn per episode",
};
const UNDER_PARAM: ParamDoc = ParamDoc {
    key: "under_buffer",
    aliases: &["undercooked_buffer"],
    allowed: "integer >= 0",
    doc: "early tolerance of the reward window (steps)",
};
const OVER_PARAM: ParamDoc = ParamDoc {
    key: "over_buffer",
    aliases: &["overcooked_buffer"],
    allowed: "integer >= 0",
    doc: "late tolerance of the reward window (steps)",
};
const REDUCED_PARAM: ParamDoc = ParamDoc {
    key: "reduced_reward",
    aliases: &[],
    allowed: "number in [0, 1]",
    doc: "reward for soup outside the window",
};

impl TaskFamily {
    /// Family-specific parameter docs (shared ones are in [`common_params`]).
    pub fn params(self) -> Vec<ParamDoc> {
        match self {
            TaskFamily::FixedInterval => vec![TD_PARAM],
            TaskFamily::PeakInterval => vec![
                TD_PARAM,
                ParamDoc {
                    key: "probe_factor",
                    aliases: &["k"],
                    allowed: "integer >= 0 (0 = never)",
                    doc: "soup becomes available at probe_factor x td; 0 withholds it for the whole episode",
                },
            ],
            TaskFamily::Bisection => vec![
                ParamDoc {
                    key: "short",
                    aliases: &["short_duration", "s"],
                    allowed: "integer 1..=10000, < long",
                    doc: "short anchor S (steps)",
                },
                ParamDoc {
                    key: "long",
                    aliases: &["long_duration", "l"],
                    allowed: "integer > short",
                    doc: "long anchor L (steps)",
                },
                FIXED_TD_PARAM,
            ],
            TaskFamily::MultiTimer => vec![
                ParamDoc {
                    key: "tds",
                    aliases: &["oven_duration_list"],
                    allowed: "comma-separated distinct integers 1..=255, e.g. 3,6,9",
                    doc: "TD list; an episode draws uniformly from the first num_timers",
                },
                ParamDoc {
                    key: "num_timers",
                    aliases: &[],
                    allowed: "integer 1..=len(tds)",
                    doc: "active TDs (grows during a curriculum)",
                },
                ParamDoc {
                    key: "mode",
                    aliases: &["undercooked_possible"],
                    allowed: "exact|lower_bounded (alias undercooked_possible=true|false)",
                    doc: "exact: take soup any time, reward 1 inside [TD-under, TD+over]; lower_bounded: take soup at timer >= TD, reduced if later than TD+over",
                },
                ParamDoc {
                    key: "cue",
                    aliases: &[],
                    allowed: "value|categorical",
                    doc: "oven channel-4 cue while on: the TD value (reference) or 1+index of the TD",
                },
                UNDER_PARAM,
                OVER_PARAM,
                REDUCED_PARAM,
                FIXED_TD_PARAM,
            ],
            TaskFamily::Dual => vec![
                TD_PARAM,
                UNDER_PARAM,
                OVER_PARAM,
                REDUCED_PARAM,
                ParamDoc {
                    key: "sink_reward",
                    aliases: &[],
                    allowed: "number in [0, 1]",
                    doc: "reward per sink interaction while the oven is on",
                },
            ],
            TaskFamily::Uncertainty => vec![
                TD_PARAM,
                ParamDoc {
                    key: "never_ready_prob",
                    aliases: &["oven_delay_prob"],
                    allowed: "number in [0, 1]",
                    doc: "probability that the oven never becomes ready by itself",
                },
                OVER_PARAM,
                ParamDoc {
                    key: "overcooked_reward",
                    aliases: &[],
                    allowed: "number in [0, 1]",
                    doc: "reward when a self-readied soup is taken after TD+over_buffer",
                },
                ParamDoc {
                    key: "manual_reward",
                    aliases: &["undercooked_reward"],
                    allowed: "number in [0, 1]",
                    doc: "reward for soup readied with the manual button",
                },
            ],
        }
    }

    /// Objects the family's layout must contain exactly once, and objects it must not contain.
    fn required_objects(self) -> &'static [ObjectKind] {
        use ObjectKind::*;
        match self {
            TaskFamily::FixedInterval | TaskFamily::PeakInterval | TaskFamily::MultiTimer => {
                &[OnionDispenser, DeliveryCounter, Oven]
            }
            TaskFamily::Bisection => &[OnionDispenser, ShortCounter, LongCounter, Oven],
            TaskFamily::Dual => &[OnionDispenser, DeliveryCounter, Oven, RewardSink],
            TaskFamily::Uncertainty => &[OnionDispenser, DeliveryCounter, Oven, OvenButton],
        }
    }

    /// Whether the oven shows a "ready" state (ch4 = 2) in this family.
    pub fn shows_ready(self) -> bool {
        matches!(self, TaskFamily::Bisection | TaskFamily::Uncertainty)
    }
}

/// Parameters every task accepts.
pub fn common_params() -> &'static [ParamDoc] {
    COMMON_PARAMS
}

fn parse_u32(field: &str, value: &str, min: u32, max: u32) -> Result<u32, EnvError> {
    let allowed = if max == u32::MAX {
        format!("integer >= {min}")
    } else {
        format!("integer {min}..={max}")
    };
    match value.trim().parse::<i64>() {
        Ok(v) if v >= min as i64 && v <= max as i64 => Ok(v as u32),
        _ => Err(EnvError::param(field, value, allowed)),
    }
}

fn parse_unit(field: &str, value: &str) -> Result<f32, EnvError> {
    match value.trim().parse::<f32>() {
        Ok(v) if v.is_finite() && (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(EnvError::param(field, value, "number in [0, 1]")),
    }
}

fn parse_bool(field: &str, value: &str) -> Result<bool, EnvError> {
    match value.trim().to_ascii_lowercase().as_str() {
        "true" | "1" | "yes" | "on" => Ok(true),
        "false" | "0" | "no" | "off" => Ok(false),
        _ => Err(EnvError::param(field, value, "true|false")),
    }
}

fn parse_list(field: &str, value: &str) -> Result<Vec<u32>, EnvError> {
    let inner = value.trim().trim_start_matches('[').trim_end_matches(']');
    let items: Result<Vec<u32>, EnvError> = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| parse_u32(field, s, 1, 255))
        .collect();
    let items = items.map_err(|_| {
        EnvError::param(
            field,
            value,
            "comma-separated distinct integers 1..=255, e.g. 3,6,9",
        )
    })?;
    Ok(items)
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
        }
    }

    /// Applies one `key=value` override (canonical key or reference alias).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), EnvError> {
        let family = self.family();
        let canonical = canonical_key(family, key).ok_or_else(|| {
            let mut known: Vec<&str> = COMMON_PARAMS.iter().map(|p| p.key).collect();
            known.extend(family.params().iter().map(|p| p.key));
            EnvError::UnknownParam {
                key: key.to_string(),
                task: self.id.clone(),
                known: known.join(", "),
            }
        })?;
        match canonical {
            "max_timesteps" => self.max_timesteps = parse_u32(canonical, value, 0, 1_000_000)?,
            "reference_compat" => self.reference_compat = parse_bool(canonical, value)?,
            "debug_timer_channel" => self.debug_timer_channel = parse_bool(canonical, value)?,
            "layout" => {
                Layout::parse(value)?;
                self.layout = value.trim().to_string();
            }
            _ => self.set_family_param(canonical, value)?,
        }
        Ok(())
    }

    fn set_family_param(&mut self, key: &str, value: &str) -> Result<(), EnvError> {
        let td = |v: &str| parse_u32("td", v, 1, 10_000);
        match (&mut self.params, key) {
            (TaskParams::FixedInterval { td: t }, "td")
            | (TaskParams::PeakInterval { td: t, .. }, "td")
            | (TaskParams::Dual { td: t, .. }, "td")
            | (TaskParams::Uncertainty { td: t, .. }, "td") => *t = td(value)?,
            (TaskParams::Bisection { .. } | TaskParams::MultiTimer { .. }, "td") => {
                self.fixed_td = Some(td(value)?)
            }
            (TaskParams::PeakInterval { probe_factor, .. }, "probe_factor") => {
                *probe_factor = if value.trim() == "never" {
                    0
                } else {
                    parse_u32(key, value, 0, 1000)?
                }
            }
            (TaskParams::Bisection { short, .. }, "short") => {
                *short = parse_u32(key, value, 1, 10_000)?
            }
            (TaskParams::Bisection { long, .. }, "long") => {
                *long = parse_u32(key, value, 1, 10_000)?
            }
            (
                TaskParams::MultiTimer {
                    tds, num_timers, ..
                },
                "tds",
            ) => {
                *tds = parse_list(key, value)?;
                *num_timers = (*num_timers).min(tds.len()).max(1);
            }
            (TaskParams::MultiTimer { num_timers, .. }, "num_timers") => {
                *num_timers = parse_u32(key, value, 1, 255)? as usize
            }
            (TaskParams::MultiTimer { mode, .. }, "mode") => {
                *mode = match value.trim().to_ascii_lowercase().as_str() {
                    "exact" | "true" => RewardMode::Exact,
                    "lower_bounded" | "false" => RewardMode::LowerBounded,
                    _ => {
                        return Err(EnvError::param(
                            "mode",
                            value,
                            "exact|lower_bounded (or undercooked_possible=true|false)",
                        ));
                    }
                }
            }
            (TaskParams::MultiTimer { cue, .. }, "cue") => {
                *cue = match value.trim().to_ascii_lowercase().as_str() {
                    "value" => CueMode::Value,
                    "categorical" | "cat" => CueMode::Categorical,
                    _ => return Err(EnvError::param("cue", value, "value|categorical")),
                }
            }
            (
                TaskParams::MultiTimer {
                    under_buffer: b, ..
                },
                "under_buffer",
            )
            | (
                TaskParams::Dual {
                    under_buffer: b, ..
                },
                "under_buffer",
            )
            | (TaskParams::MultiTimer { over_buffer: b, .. }, "over_buffer")
            | (TaskParams::Dual { over_buffer: b, .. }, "over_buffer")
            | (TaskParams::Uncertainty { over_buffer: b, .. }, "over_buffer") => {
                *b = parse_u32(key, value, 0, u32::MAX)?
            }
            (
                TaskParams::MultiTimer {
                    reduced_reward: r, ..
                },
                "reduced_reward",
            )
            | (
                TaskParams::Dual {
                    reduced_reward: r, ..
                },
                "reduced_reward",
            )
            | (TaskParams::Dual { sink_reward: r, .. }, "sink_reward")
            | (
                TaskParams::Uncertainty {
                    never_ready_prob: r,
                    ..
                },
                "never_ready_prob",
            )
            | (
                TaskParams::Uncertainty {
                    overcooked_reward: r,
                    ..
                },
                "overcooked_reward",
            )
            | (
                TaskParams::Uncertainty {
                    manual_reward: r, ..
                },
                "manual_reward",
            ) => *r = parse_unit(key, value)?,
            _ => unreachable_key(key)?,
        }
        Ok(())
    }

    /// Applies `key=value` overrides in order.
    pub fn apply_overrides<S: AsRef<str>>(&mut self, overrides: &[S]) -> Result<(), EnvError> {
        for text in overrides {
            let text = text.as_ref();
            let (k, v) = text.split_once('=').ok_or_else(|| EnvError::BadOverride {
                text: text.to_string(),
                reason: "expected key=value".into(),
            })?;
            self.set(k.trim(), v.trim())?;
        }
        Ok(())
    }

    /// Checks every cross-field constraint and parses the layout.
    pub fn validate(&self) -> Result<Layout, EnvError> {
        let layout = Layout::parse(&self.layout)?;
        let family = self.family();
        for &kind in family.required_objects() {
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
        for kind in ObjectKind::ALL {
            if !family.required_objects().contains(&kind) && !layout.cells_of(kind).is_empty() {
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
        if self.max_timesteps > 1_000_000 {
            return Err(EnvError::param(
                "max_timesteps",
                self.max_timesteps,
                "integer 0..=1000000",
            ));
        }
        match &self.params {
            TaskParams::FixedInterval { td }
            | TaskParams::PeakInterval { td, .. }
            | TaskParams::Dual { td, .. }
            | TaskParams::Uncertainty { td, .. } => check_td(*td)?,
            TaskParams::Bisection { short, long } => {
                check_td(*short)
                    .map_err(|_| EnvError::param("short", short, "integer 1..=10000"))?;
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
                if let Some(&bad) = tds.iter().find(|&&t| t == 0 || t > 255) {
                    return Err(EnvError::param(
                        "tds",
                        bad,
                        "integers 1..=255 (the cue is a u8)",
                    ));
                }
                let mut sorted = tds.clone();
                sorted.sort_unstable();
                sorted.dedup();
                if sorted.len() != tds.len() {
                    return Err(EnvError::param(
                        "tds",
                        format!("{tds:?}"),
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
        }
        if let Some(td) = self.fixed_td {
            let fits = match &self.params {
                TaskParams::MultiTimer { cue, tds, .. } => match cue {
                    CueMode::Value => (1..=255).contains(&td),
                    CueMode::Categorical => tds.contains(&td),
                },
                TaskParams::Bisection { .. } => (1..=10_000).contains(&td),
                _ => false,
            };
            if !fits {
                return Err(EnvError::param(
                    "td",
                    td,
                    "a fixed TD is for bisection (1..=10000) and multi-timer (value cue 1..=255, categorical: one of tds)",
                ));
            }
        }
        Ok(layout)
    }
}

fn check_td(td: u32) -> Result<(), EnvError> {
    if (1..=10_000).contains(&td) {
        Ok(())
    } else {
        Err(EnvError::param("td", td, "integer 1..=10000"))
    }
}

fn unreachable_key(key: &str) -> Result<(), EnvError> {
    Err(EnvError::BadOverride {
        text: key.to_string(),
        reason: "parameter not supported by this task".into(),
    })
}

/// Resolves a key or alias to its canonical name for `family`.
fn canonical_key(family: TaskFamily, key: &str) -> Option<&'static str> {
    let key = key.trim();
    let family_params = family.params();
    COMMON_PARAMS
        .iter()
        .chain(family_params.iter())
        .find(|p| p.key == key || p.aliases.contains(&key))
        .map(|p| p.key)
}
