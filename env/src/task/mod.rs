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
pub mod condition;
pub mod family;
pub mod params;
pub mod reset_option;

pub use crate::rules::{CueMode, RewardMode};
use chosen::TaskFields;
pub use chosen::make_config;
pub use family::reproduction::{NAMED_PRIORS, parse_prior};
pub use family::{Growth, TaskSpec};

use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::settings::{self, Spec};
use params::MAX_TIMESTEPS;
use reset_option::ResetOption;
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
    /// A family defined outside this crate and registered at run time
    /// ([`family::register`]); its parameters are [`TaskParams::External`].
    External,
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
    /// A family defined outside this crate ([`family::register`]): its task's id and its
    /// parameters as the family's own table writes them (paths `params.values.<key>`).
    External(ExternalParams),
}

/// The parameters of a task of an externally defined family.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExternalParams {
    /// The registered task's id (e.g. `IntervalProduction-v0`): which family reads them.
    pub task: String,
    /// The values, keyed by the family's parameter keys.
    pub values: serde_json::Map<String, serde_json::Value>,
}

// The type a chosen task travels as is declared here, beside the configuration it checks,
// so that the task families (`family`) can name it; its methods are in `chosen`.
/// A registered task with its parameters: the id as given (`FixedInterval-v0`) and the
/// parameters set on it, typed (`td` = 6) and each checked against its table entry. The
/// cross-field rules (S < L, distinct anchors, the layout) are checked as a whole by
/// [`Task::config`], so parameters can be set in any order.
///
/// Serialised as two fields: `task` (the id) and `env` (the parameters set, as a map:
/// `{"td": 6}`). The older form, `env` as a list of `key=value` texts, still reads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "TaskFields", into = "TaskFields")]
pub struct Task {
    /// The id as given (a registry id or an alias of one).
    id: String,
    /// The registered defaults with every set parameter applied.
    config: TaskConfig,
    /// `(index in the family's table, value)` of every parameter set, in table order.
    set: Vec<(usize, serde_json::Value)>,
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

    /// The family's own parameters (the common ones are [`common_params`]); none for
    /// [`TaskFamily::External`], whose table its task's parameters name
    /// ([`TaskConfig::params_table`]).
    pub fn own_params(self) -> &'static [Spec] {
        family::of(self).params()
    }

    /// Whether the oven shows a "ready" state (ch4 = 2) in this family (for an external
    /// family: [`TaskConfig::shows_ready`]).
    pub fn shows_ready(self) -> bool {
        family::of(self).shows_ready()
    }
}

impl TaskParams {
    /// The single target duration of families that have one (FI, PI, dual, uncertainty).
    pub fn td(&self) -> Option<u32> {
        family::of_params(self).single_td(self)
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
        self.params.family()
    }

    /// The table entry of the parameter `key` (canonical key or reference alias); an unknown
    /// key is an error naming the task's keys.
    fn param(&self, key: &str) -> Result<Spec, EnvError> {
        let key = key.trim();
        let table = self.params_table();
        settings::find(&table, key)
            .copied()
            .ok_or_else(|| EnvError::UnknownParam {
                key: key.to_string(),
                task: self.id.clone(),
                known: table.iter().map(|p| p.key).collect::<Vec<_>>().join(", "),
            })
    }

    /// Applies one `key=value` override (canonical key or reference alias), parsed and
    /// range-checked by the family's parameter table ([`params`]).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), EnvError> {
        let spec = self.param(key)?;
        let parsed = spec
            .rule
            .parse(value)
            .ok_or_else(|| EnvError::param(spec.key, value, spec.rule.allowed()))?;
        self.set_value(key, parsed)
    }

    /// Sets one parameter (canonical key or reference alias) to a typed value (as `env`
    /// maps hold them: `json!(3)`, `json!("exact")`, `json!([4, 8])`), checked by its rule in
    /// the family's parameter table; the family then updates the fields that follow it.
    pub fn set_value(&mut self, key: &str, value: serde_json::Value) -> Result<(), EnvError> {
        let spec = self.param(key)?;
        let text = settings::display(&value);
        if !spec.rule.accepts(&value) {
            return Err(EnvError::param(spec.key, text, spec.rule.allowed()));
        }
        // Errors name the canonical key (`td` for `oven_duration`).
        settings::set_value(self, &spec, spec.key, &text, value)?;
        family::of_params(&self.params).after_set(&mut self.params, spec.key);
        Ok(())
    }

    /// The layout text the env runs: [`TaskConfig::layout`], or for `auto` the reference
    /// layout of the active counters (multi-anchor) or ovens (multi-oven).
    pub fn resolved_layout(&self) -> &str {
        if self.layout.trim() != AUTO_LAYOUT {
            return &self.layout;
        }
        family::of_params(&self.params).auto_layout(&self.params)
    }

    /// Checks every parameter against its table entry, then the cross-field constraints,
    /// and parses the layout.
    pub fn validate(&self) -> Result<Layout, EnvError> {
        let family = family::of_params(&self.params);
        settings::check(&self.params_table(), self)?;
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
        family.check(self)?;
        if let Some(td) = self.fixed_td {
            let fits = family.fixed_td_fits(&self.params, td);
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

    /// Every parameter of this configuration's family, its own first, then the common ones.
    pub fn params_table(&self) -> Vec<Spec> {
        let own = family::of_params(&self.params).params();
        own.iter().chain(params::COMMON).copied().collect()
    }

    /// Whether the oven shows a "ready" state (ch4 = 2) in this configuration's family.
    pub fn shows_ready(&self) -> bool {
        family::of_params(&self.params).shows_ready()
    }

    /// What a response is in this configuration's family, for the timing models (`None`:
    /// they cannot play it).
    pub fn response_kind(&self) -> Option<family::ResponseKind> {
        family::of_params(&self.params).response_kind()
    }

    /// The Ready-Set-Go mechanics this configuration runs (temporal reproduction: priors,
    /// gains, reward window, cues), `None` for a task without them; an error when the
    /// configuration is invalid.
    pub fn ready_set_go(&self) -> Result<Option<crate::rules::ReadySetGo>, EnvError> {
        let layout = self.validate()?;
        Ok(family::of_params(&self.params).rules(self, &layout)?.rsg)
    }

    /// The reward window of a production, `(tolerance, tolerance_steps)` as the parameters
    /// hold them (relative, steps); `None` for a task without one a curriculum may widen.
    pub fn reward_window(&self) -> Option<(f32, f32)> {
        family::of_params(&self.params).reward_window(&self.params)
    }

    /// This configuration with the reward window `(tolerance, steps)` (a typed edit of the
    /// parameters [`TaskConfig::reward_window`] reads), checked; an error naming `tolerance`
    /// for a task without one.
    pub fn with_reward_window(&self, tolerance: f32, steps: f32) -> Result<TaskConfig, EnvError> {
        let family = family::of_params(&self.params);
        if family.reward_window(&self.params).is_none() {
            return Err(EnvError::param(
                "tolerance",
                tolerance,
                format!("a task with a reward window to set ({} has none)", self.id),
            ));
        }
        let mut edited = self.clone();
        family.set_reward_window(&mut edited.params, tolerance, steps);
        edited.validate()?;
        Ok(edited)
    }

    /// The TDs a deterministic evaluation covers (steps): bisection and multi-oven → both
    /// anchors; multi-timer → the active TDs; multi-anchor → the active anchors;
    /// reproduction → every sample interval of its priors; other tasks → their TD.
    pub fn evaluation_tds(&self) -> Vec<u32> {
        family::of_params(&self.params).evaluation_tds(&self.params)
    }

    /// The share of never-ready episodes this configuration plays (a probability; 0 for a
    /// family without them).
    pub fn never_ready_prob(&self) -> f32 {
        family::of_params(&self.params).never_ready_prob(&self.params)
    }

    /// Sets the share of never-ready episodes (a typed edit; a no-op for a family without
    /// them).
    pub fn set_never_ready_prob(&mut self, p: f32) {
        family::of_params(&self.params).set_never_ready_prob(&mut self.params, p);
    }

    /// The options of `reset` this configuration's family declares.
    pub fn reset_options(&self) -> &'static [ResetOption] {
        family::of_params(&self.params).reset_options()
    }

    /// How this task grows during a curriculum (multi-anchor counters, multi-oven ovens);
    /// `None` for tasks that do not grow.
    pub fn growth(&self) -> Option<Growth> {
        family::of_params(&self.params).growth(&self.params)
    }

    /// This configuration with its growing parameter at `size` (a typed edit), checked.
    pub fn at_growth_size(&self, size: usize) -> Result<TaskConfig, EnvError> {
        let mut level = self.clone();
        family::of_params(&self.params).grow(&mut level.params, size);
        level.validate()?;
        Ok(level)
    }

    /// The curriculum's levels, from the first size to the configured one; the
    /// configuration itself for a task that does not grow (or starts at its first size).
    pub fn growth_levels(&self) -> Result<Vec<TaskConfig>, EnvError> {
        match self.growth() {
            Some(g) if g.last > g.first => {
                (g.first..=g.last).map(|n| self.at_growth_size(n)).collect()
            }
            _ => Ok(vec![self.clone()]),
        }
    }

    /// The reference evaluation conditions of an agent trained on `task` (this is its checked
    /// configuration), as the family declares them.
    pub fn conditions(&self, task: &Task) -> Result<Vec<condition::Condition>, EnvError> {
        family::of_params(&self.params).conditions(task, self)
    }

    /// The condition of an episode played on this configuration at `td` (human play,
    /// replays): the family's kind, with every parameter as played.
    pub fn played_condition(
        &self,
        td: u32,
        never_ready: bool,
    ) -> Result<condition::Condition, EnvError> {
        let task = Task::from_config(self)?;
        Ok(family::of_params(&self.params).played_condition(task, &self.params, td, never_ready))
    }

    /// The TDs (steps) and never-ready flags the environment demo plays: every TD a task
    /// draws (each prior's ends for reproduction; both oven kinds for uncertainty).
    pub fn demo_conditions(&self) -> Vec<(u32, Option<bool>)> {
        family::of_params(&self.params).demo_conditions(&self.params)
    }
}
