//! The task families: one file per family, each implementing [`Family`], and the one
//! registry line per family ([`FAMILIES`]).
//!
//! A family's file holds everything the lab knows about it: its registered task and
//! documentation, its parameter table and defaults, its layout and objects, its
//! cross-field checks, the kitchen's rules it builds, and the TDs it is evaluated and
//! demonstrated at. The trait's required methods are the checklist of a new family.

mod bisection;
mod dual;
mod fixed_interval;
mod multi_anchor;
mod multi_oven;
mod multi_timer;
mod peak_interval;
pub(crate) mod reproduction;
mod uncertainty;

use super::condition::{Condition, ConditionKind};
use super::{Task, TaskConfig, TaskFamily, TaskParams};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::{CueMode, RsgSpec, Rules};
use crate::settings::Spec;
use serde::Serialize;

/// One registered task: id, tags and documentation.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TaskSpec {
    /// Versioned id, e.g. `FixedInterval-v0`.
    pub id: &'static str,
    /// Family of the task.
    pub family: TaskFamily,
    /// Tags for filtering (`paper`, `timing`, `bisection`, …).
    pub tags: &'static [&'static str],
    /// One-line summary.
    pub summary: &'static str,
    /// Layout, rewards and defaults in prose.
    pub description: &'static str,
    /// Source in the paper (or "design decision" for tasks the public code lacks).
    pub source: &'static str,
}

impl TaskSpec {
    /// The default configuration of this task: the family's defaults, a 200-step time limit
    /// (the paper's), the lab's own semantics (not the reference-compatible mode), no debug
    /// channel and TDs drawn per episode.
    pub fn default_config(&self) -> TaskConfig {
        let (layout, params) = of(self.family).defaults();
        TaskConfig {
            id: self.id.to_string(),
            layout: layout.to_string(),
            max_timesteps: 200,
            reference_compat: false,
            debug_timer_channel: false,
            fixed_td: None,
            params,
        }
    }
}

/// How a task grows during a curriculum (multi-anchor counters, multi-oven ovens).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Growth {
    /// The task parameter that grows (`num_anchors`, `ovens`).
    pub key: &'static str,
    /// Its value at the first level.
    pub first: usize,
    /// Its configured value (the last level).
    pub last: usize,
}

/// The kitchen's rules of one configuration, as the hot loop reads them.
pub(crate) struct RuleSet {
    /// The flattened rules.
    pub(crate) rules: Rules,
    /// TD of an episode before any draw (steps).
    pub(crate) default_td: u32,
    /// The TDs episodes draw from (steps; empty where the family draws otherwise).
    pub(crate) tds: Vec<u32>,
    /// What the oven's channel 4 shows while on (multi-timer).
    pub(crate) cue: Option<CueMode>,
    /// Reproduction: priors, gains, window and foreperiods.
    pub(crate) rsg: Option<RsgSpec>,
}

impl RuleSet {
    /// Rules with one TD list and no cue or reproduction part.
    pub(crate) fn simple(rules: Rules, default_td: u32, tds: Vec<u32>) -> Self {
        RuleSet {
            rules,
            default_td,
            tds,
            cue: None,
            rsg: None,
        }
    }
}

/// Everything a task family defines. One implementation per file of this folder.
pub(crate) trait Family: Sync {
    /// The registered task of the family (id, tags, documentation).
    fn task(&self) -> TaskSpec;

    /// The family's own parameters (the common ones are `params::COMMON`).
    fn params(&self) -> &'static [Spec];

    /// The default layout text and parameters of the registered task.
    fn defaults(&self) -> (&'static str, TaskParams);

    /// The layout an `auto` layout stands for, given the parameters.
    fn auto_layout(&self, params: &TaskParams) -> &'static str;

    /// Objects the layout must contain exactly once (every other kind must be absent).
    fn required_objects(&self, params: &TaskParams) -> Vec<ObjectKind>;

    /// The cross-field rules, after every parameter passed its own table entry.
    fn check(&self, _config: &TaskConfig) -> Result<(), EnvError> {
        Ok(())
    }

    /// Whether `td` may be fixed for every episode (`fixed_td`; probes, OOD tests).
    fn fixed_td_fits(&self, _params: &TaskParams, _td: u32) -> bool {
        false
    }

    /// Whether the oven shows a "ready" state (channel 4 = 2).
    fn shows_ready(&self) -> bool {
        false
    }

    /// The single target duration of families that have one (steps).
    fn single_td(&self, _params: &TaskParams) -> Option<u32> {
        None
    }

    /// The channel-0 code the family's reference writes for `kind`.
    fn object_code(&self, kind: ObjectKind) -> u8 {
        kind.code()
    }

    /// Keeps the parameters consistent after `key` was set (e.g. the active count follows
    /// a shorter list).
    fn after_set(&self, _params: &mut TaskParams, _key: &str) {}

    /// The kitchen's rules of a validated configuration.
    fn rules(&self, config: &TaskConfig, layout: &Layout) -> Result<RuleSet, EnvError>;

    /// Oracle: the oven timer (at action time) of the rewarded pickup the optimal policy
    /// makes at `td` (steps); `None` if no pickup pays.
    fn paid_pickup_timer(&self, _params: &TaskParams, td: u32) -> Option<i32> {
        Some(td as i32)
    }

    /// Oracle: the counter a soup of an episode of duration `td` is delivered to.
    fn delivery_kind(&self, _params: &TaskParams, _td: u32) -> ObjectKind {
        ObjectKind::DeliveryCounter
    }

    /// How the task grows during a curriculum; `None` for tasks that do not grow.
    fn growth(&self, _params: &TaskParams) -> Option<Growth> {
        None
    }

    /// Sets the growing parameter to `size` (a no-op for tasks that do not grow).
    fn grow(&self, _params: &mut TaskParams, _size: usize) {}

    /// The TDs a deterministic evaluation covers (steps).
    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32>;

    /// What an episode of this family measures, as a condition's kind.
    fn condition_kind(&self) -> ConditionKind;

    /// The reference evaluation conditions of an agent trained on `task` (`config` is its
    /// checked configuration): the probes docs/metrics.md lists for the family.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError>;

    /// The condition of an episode played (by a person, or replayed) on `task` (whose
    /// parameters are `params`) at `td`, with the episode's never-ready flag (uncertainty).
    fn played_condition(
        &self,
        task: Task,
        _params: &TaskParams,
        td: u32,
        _never_ready: bool,
    ) -> Condition {
        condition(self.condition_kind(), &task, td)
    }

    /// The TDs (and never-ready flags) the environment demo plays (steps).
    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)>;
}

/// The registry: one line per family, in the order `env list` shows them.
static FAMILIES: [&dyn Family; 9] = [
    &fixed_interval::FixedInterval,
    &peak_interval::PeakInterval,
    &bisection::Bisection,
    &multi_timer::MultiTimer,
    &dual::Dual,
    &uncertainty::Uncertainty,
    &multi_anchor::MultiAnchor,
    &multi_oven::MultiOven,
    &reproduction::Reproduction,
];

/// Every registered family's task, in registry order.
pub(crate) fn registered() -> impl Iterator<Item = TaskSpec> {
    FAMILIES.iter().map(|f| f.task())
}

/// The implementation of `family`.
pub(crate) fn of(family: TaskFamily) -> &'static dyn Family {
    FAMILIES
        .iter()
        .copied()
        .find(|f| f.task().family == family)
        .unwrap_or(FAMILIES[0])
}

impl TaskParams {
    /// The family these parameters belong to.
    pub fn family(&self) -> TaskFamily {
        match self {
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
}

/// A condition of `kind` on `task` at `td` with no reset option, factor or context.
pub(crate) fn condition(kind: ConditionKind, task: &Task, td: u32) -> Condition {
    Condition {
        kind,
        task: task.clone(),
        td,
        never_ready: None,
        factor: None,
        context: None,
    }
}

/// Every probe duration `1 ..= longest + 4` (steps): the reference's bisection,
/// multi-anchor and multi-oven probes.
pub(crate) fn probe_range(kind: ConditionKind, task: &Task, longest: u32) -> Vec<Condition> {
    (1..=longest + 4)
        .map(|t| condition(kind, task, t))
        .collect()
}

/// A parameter error for a configuration of the wrong family (a family's method called
/// with another family's parameters: a bug of the caller, reported, never a panic).
pub(crate) fn wrong_family(family: &str, params: &TaskParams) -> EnvError {
    EnvError::param(
        "family",
        format!("{:?}", params.family()),
        format!("{family} parameters"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_family_is_registered_once_and_found_by_its_own_name() {
        let all = [
            TaskFamily::FixedInterval,
            TaskFamily::PeakInterval,
            TaskFamily::Bisection,
            TaskFamily::MultiTimer,
            TaskFamily::Dual,
            TaskFamily::Uncertainty,
            TaskFamily::MultiAnchor,
            TaskFamily::MultiOven,
            TaskFamily::Reproduction,
        ];
        for family in all {
            let n = FAMILIES
                .iter()
                .filter(|f| f.task().family == family)
                .count();
            assert_eq!(n, 1, "{family:?} registered {n} times");
            assert_eq!(of(family).task().family, family);
            let (_, params) = of(family).defaults();
            assert_eq!(params.family(), family, "defaults of {family:?}");
        }
    }
}
