//! The task families: one file per family, each implementing [`Family`], and the one
//! registry line per family (`FAMILIES`). A family defined outside this crate implements
//! the same trait and is added at run time with [`register`] (the `interval_production`
//! example of the repository does).
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
use super::{ExternalParams, Task, TaskConfig, TaskFamily, TaskParams};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::{CueMode, ReadySetGo, RewardMode, Rules};
use crate::settings::Spec;
use crate::task::reset_option::{BASIC_RESET_OPTIONS, ResetOption};
use serde::Serialize;
use std::sync::RwLock;

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
        let (layout, params) = by_id(self.id).defaults();
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

/// The kitchen's rules of one configuration, as the hot loop reads them. Built-in families
/// build any of the kitchen's rules; a family defined outside this crate composes its task
/// from the public constructors ([`RuleSet::fixed`], [`RuleSet::window`],
/// [`RuleSet::categories`], [`RuleSet::ready_set_go`]), which are the kitchen's mechanics.
pub struct RuleSet {
    /// The flattened rules.
    pub(crate) rules: Rules,
    /// TD of an episode before any draw (steps).
    pub(crate) default_td: u32,
    /// The TDs episodes draw from (steps; empty where the family draws otherwise).
    pub(crate) tds: Vec<u32>,
    /// What the oven's channel 4 shows while on (multi-timer).
    pub(crate) cue: Option<CueMode>,
    /// Ready-Set-Go: priors, gains, window and foreperiods.
    pub(crate) rsg: Option<ReadySetGo>,
}

impl RuleSet {
    /// Soup available from oven timer ≥ TD; delivery pays 1 (the fixed-interval mechanics).
    /// `tds`: the durations an episode draws from, uniformly (steps, non-empty).
    pub fn fixed(tds: Vec<u32>) -> Result<Self, EnvError> {
        let first = first_td(&tds)?;
        Ok(RuleSet::simple(Rules::Fixed, first, tds))
    }

    /// Soup available any time after the onion went in (`exact`) or from timer ≥ TD
    /// (`lower_bounded`); delivery pays 1 when the oven was turned off inside
    /// `[TD − under, TD + over]` (steps), `reduced` otherwise (the multi-timer mechanics, no
    /// cue: the oven shows only on/off). `tds`: the durations drawn uniformly (steps).
    pub fn window(
        tds: Vec<u32>,
        mode: RewardMode,
        under: u32,
        over: u32,
        reduced: f32,
    ) -> Result<Self, EnvError> {
        let first = first_td(&tds)?;
        Ok(RuleSet::simple(
            Rules::Window {
                mode,
                under,
                over,
                reduced,
            },
            first,
            tds,
        ))
    }

    /// Categorisation by counter: the oven shows ready at TD, the soup can be taken only
    /// when ready, and delivery to counter `i` pays 1 iff the episode's TD is `anchors[i]`
    /// (2–4 increasing anchors, steps; drawn uniformly; the layout needs counters `S`, `L`,
    /// then `3`, `4`). The multi-anchor mechanics.
    pub fn categories(anchors: &[u32]) -> Result<Self, EnvError> {
        if !(2..=4).contains(&anchors.len()) || anchors.windows(2).any(|w| w[0] >= w[1]) {
            return Err(EnvError::param(
                "anchors",
                format!("{anchors:?}"),
                "2 to 4 durations in increasing order",
            ));
        }
        let mut fixed = [0; 4];
        fixed[..anchors.len()].copy_from_slice(anchors);
        Ok(RuleSet::simple(
            Rules::Categories {
                anchors: fixed,
                k: anchors.len() as u8,
            },
            anchors[0],
            anchors.to_vec(),
        ))
    }

    /// Ready-Set-Go (temporal reproduction): no onion; the loaded oven flashes Ready after
    /// a foreperiod and Set `ts` steps later (`ts` drawn uniformly from the episode's
    /// prior), the counter cues the context (prior and gain), and a soup taken `tp` steps
    /// after Set pays when `|tp − g · ts|` is inside the window (the layout needs the oven
    /// and the delivery counter `D`, whose cell is `spec.counter`).
    pub fn ready_set_go(spec: ReadySetGo) -> Result<Self, EnvError> {
        let range = |lo: u32, hi: u32| 1 <= lo && lo < hi;
        if spec.priors.is_empty() || spec.priors.iter().any(|&(lo, hi)| !range(lo, hi)) {
            return Err(EnvError::param(
                "priors",
                format!("{:?}", spec.priors),
                "at least one range (lo, hi) of whole steps, 1 <= lo < hi",
            ));
        }
        if spec.gains.is_empty() || spec.gains.iter().any(|g| !(g.is_finite() && *g > 0.0)) {
            return Err(EnvError::param(
                "gains",
                format!("{:?}", spec.gains),
                "at least one finite gain > 0",
            ));
        }
        for (field, value) in [
            ("tolerance", spec.tolerance),
            ("tolerance_steps", spec.tolerance_steps),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(EnvError::param(field, value, "a finite number >= 0"));
            }
        }
        if spec.foreperiod.0 > spec.foreperiod.1 {
            return Err(EnvError::param(
                "foreperiod",
                format!("{:?}", spec.foreperiod),
                "a range (min, max) with min <= max (steps)",
            ));
        }
        Ok(RuleSet {
            rules: Rules::ReadySetGo,
            default_td: spec.priors[0].0,
            tds: Vec::new(),
            cue: None,
            rsg: Some(spec),
        })
    }

    /// Rules with one TD list and no cue or Ready-Set-Go part.
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

/// What an agent's response is in a task, as the timing models read it: they play a family
/// that declares one of these, and refuse one that declares none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ResponseKind {
    /// Produce an interval: take the soup out when the timed duration has elapsed (fixed
    /// interval, peak interval, multi-timer, dual, uncertainty).
    Produce,
    /// Categorise a duration: deliver the soup to the counter of its category (bisection,
    /// multi-anchor, multi-oven).
    Categorise,
    /// Reproduce a measured interval (`tp = g · ts`; Ready-Set-Go).
    Reproduce,
}

/// The first of a non-empty TD list.
fn first_td(tds: &[u32]) -> Result<u32, EnvError> {
    tds.first()
        .copied()
        .ok_or_else(|| EnvError::param("tds", "[]", "at least one duration (steps)"))
}

/// Everything a task family defines. One implementation per file of this folder; a family
/// defined elsewhere implements it too and is added with [`register`]. The required methods
/// are the checklist of a new family; the provided ones are the defaults of a
/// single-duration production task.
pub trait Family: Sync + Send {
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

    /// The most categories a task of the family can ask an agent to tell apart, at the
    /// largest size its parameters allow (a curriculum that adds counters keeps an agent's
    /// size); 2 (short or long) by default, which agents of tasks without categories keep.
    fn most_categories(&self) -> usize {
        2
    }

    /// How the task grows during a curriculum; `None` for tasks that do not grow.
    fn growth(&self, _params: &TaskParams) -> Option<Growth> {
        None
    }

    /// Sets the growing parameter to `size` (a no-op for tasks that do not grow).
    fn grow(&self, _params: &mut TaskParams, _size: usize) {}

    /// The reward window of a production, `(tolerance, tolerance_steps)` as the parameters
    /// hold them (relative, steps), for families whose window a curriculum may widen
    /// (`None`: no such window).
    fn reward_window(&self, _params: &TaskParams) -> Option<(f32, f32)> {
        None
    }

    /// Sets the reward window of [`Family::reward_window`] (a typed edit; a no-op for
    /// families without one).
    fn set_reward_window(&self, _params: &mut TaskParams, _tolerance: f32, _steps: f32) {}

    /// The share of never-ready episodes the parameters ask for (a probability in
    /// `[0, 1]`), for families with such episodes (0: none).
    fn never_ready_prob(&self, _params: &TaskParams) -> f32 {
        0.0
    }

    /// Sets the share of [`Family::never_ready_prob`] (a typed edit, e.g. a curriculum's
    /// ramp; a no-op for families without never-ready episodes).
    fn set_never_ready_prob(&self, _params: &mut TaskParams, _p: f32) {}

    /// The TDs a deterministic evaluation covers (steps).
    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32>;

    /// What an episode of this family measures, as a condition's kind.
    fn condition_kind(&self) -> ConditionKind;

    /// What a response is in this family, for the timing models; `None` for a task they
    /// cannot play (they refuse it, naming it).
    fn response_kind(&self) -> Option<ResponseKind>;

    /// The options `reset` takes in this family (what an episode would otherwise draw);
    /// `reset` refuses any other, naming the task's own, and Python's `reset(options=…)`
    /// reads this list.
    fn reset_options(&self) -> &'static [ResetOption] {
        BASIC_RESET_OPTIONS
    }

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

    /// The family's training presets, in the lab's preset format (`[fast]`,
    /// `[reference]`, … with their PPO settings, e.g. `total_steps`). `None`: the presets are
    /// a file of the training crate named by the task's id (the built-in families'); a task
    /// with neither is refused by `train --preset`, never trained on another's budget.
    fn preset(&self) -> Option<&'static str> {
        None
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

/// Families registered at run time ([`register`]).
static EXTERNAL: RwLock<Vec<&'static dyn Family>> = RwLock::new(Vec::new());

/// Every registered task (built-in, then registered at run time), refreshed by [`register`].
static TASKS: RwLock<Option<&'static [TaskSpec]>> = RwLock::new(None);

/// Registers a family defined outside this crate, so that its task id is found by
/// [`crate::registry::find_task`], listed by `env list` and built into environments.
/// Its [`TaskSpec::family`] must be [`TaskFamily::External`] and its default parameters
/// [`TaskParams::External`] naming its own id. Errors when the id is taken (case-insensitive).
pub fn register(family: &'static dyn Family) -> Result<(), EnvError> {
    let spec = family.task();
    let (_, params) = family.defaults();
    let named = matches!(&params, TaskParams::External(p) if p.task == spec.id);
    if spec.family != TaskFamily::External || !named {
        return Err(EnvError::param(
            "family",
            spec.id,
            "an external family: TaskSpec.family = External and default parameters TaskParams::External naming the task's id",
        ));
    }
    if registered_tasks()
        .iter()
        .any(|t| t.id.eq_ignore_ascii_case(spec.id))
    {
        return Err(EnvError::param(
            "id",
            spec.id,
            "an id no registered task has",
        ));
    }
    EXTERNAL
        .write()
        .unwrap_or_else(|e| e.into_inner())
        .push(family);
    *TASKS.write().unwrap_or_else(|e| e.into_inner()) = None;
    Ok(())
}

/// Every registered task, built-in first, in registry order.
pub(crate) fn registered_tasks() -> &'static [TaskSpec] {
    if let Some(tasks) = *TASKS.read().unwrap_or_else(|e| e.into_inner()) {
        return tasks;
    }
    let mut all: Vec<TaskSpec> = FAMILIES.iter().map(|f| f.task()).collect();
    all.extend(externals().iter().map(|f| f.task()));
    // Leaked once per registration: the list lives as long as the program.
    let all: &'static [TaskSpec] = Vec::leak(all);
    *TASKS.write().unwrap_or_else(|e| e.into_inner()) = Some(all);
    all
}

fn externals() -> Vec<&'static dyn Family> {
    EXTERNAL.read().unwrap_or_else(|e| e.into_inner()).clone()
}

/// The reset options of the registered task `id` (its exact id; `None` if unknown).
pub fn reset_options_of(id: &str) -> Option<&'static [ResetOption]> {
    FAMILIES
        .iter()
        .copied()
        .chain(externals())
        .find(|f| f.task().id == id)
        .map(|f| f.reset_options())
}

/// The registered tasks whose episodes take `option`.
pub fn tasks_with_reset_option(option: ResetOption) -> Vec<&'static str> {
    FAMILIES
        .iter()
        .copied()
        .chain(externals())
        .filter(|f| f.reset_options().contains(&option))
        .map(|f| f.task().id)
        .collect()
}

/// The training presets the registered task `id` declares itself ([`Family::preset`]).
pub fn declared_preset(id: &str) -> Option<&'static str> {
    by_id(id).preset()
}

/// The most categories a task with parameters `params` can ask for
/// ([`Family::most_categories`]).
pub fn most_categories(params: &TaskParams) -> usize {
    of_params(params).most_categories()
}

/// The built-in implementation of `family` (`None` for [`TaskFamily::External`]).
fn builtin(family: TaskFamily) -> Option<&'static dyn Family> {
    FAMILIES.iter().copied().find(|f| f.task().family == family)
}

/// The implementation of the registered task `id` (exact id).
pub(crate) fn by_id(id: &str) -> &'static dyn Family {
    FAMILIES
        .iter()
        .copied()
        .chain(externals())
        .find(|f| f.task().id == id)
        .unwrap_or(&Unregistered)
}

/// The implementation that reads `params`: its built-in family, or the registered
/// external family its [`ExternalParams::task`] names ([`Unregistered`] when none is).
pub(crate) fn of_params(params: &TaskParams) -> &'static dyn Family {
    match params {
        TaskParams::External(p) => by_id(&p.task),
        other => builtin(other.family()).unwrap_or(&Unregistered),
    }
}

/// The implementation of a built-in family ([`Unregistered`] for an external one, whose
/// implementation only its parameters name: use [`of_params`]).
pub(crate) fn of(family: TaskFamily) -> &'static dyn Family {
    builtin(family).unwrap_or(&Unregistered)
}

/// The stand-in for a family this program does not know (an external family's task read
/// by a program that did not register it): every check fails, naming the task.
struct Unregistered;

impl Unregistered {
    fn error(params: &TaskParams) -> EnvError {
        let task = match params {
            TaskParams::External(ExternalParams { task, .. }) => task.clone(),
            other => format!("{:?}", other.family()),
        };
        EnvError::UnknownTask {
            id: task,
            known: "the tasks this program registers (an external family is registered by the program that defines it, e.g. `cargo run --example interval_production`)".into(),
        }
    }
}

impl Family for Unregistered {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "unregistered",
            family: TaskFamily::External,
            tags: &[],
            summary: "a task of a family this program does not register",
            description: "",
            source: "",
        }
    }

    fn params(&self) -> &'static [Spec] {
        &[]
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            "auto",
            TaskParams::External(ExternalParams {
                task: "unregistered".into(),
                values: Default::default(),
            }),
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        super::FI_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        Vec::new()
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        Err(Unregistered::error(&config.params))
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        Err(Unregistered::error(&config.params))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        None
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Fi
    }

    fn conditions(&self, _task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        Err(Unregistered::error(&config.params))
    }

    fn evaluation_tds(&self, _params: &TaskParams) -> Vec<u32> {
        Vec::new()
    }

    fn demo_conditions(&self, _params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        Vec::new()
    }
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
            TaskParams::External(_) => TaskFamily::External,
        }
    }
}

/// A condition of `kind` on `task` at `td` with no reset option, factor or context.
pub fn condition(kind: ConditionKind, task: &Task, td: u32) -> Condition {
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
pub fn probe_range(kind: ConditionKind, task: &Task, longest: u32) -> Vec<Condition> {
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
