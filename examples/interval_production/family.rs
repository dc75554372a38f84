//! Interval production with a reward window: a task family defined outside the lab's
//! crates, by implementing [`Family`] and registering it.
//!
//! The kitchen is the fixed-interval kitchen (onion, delivery counter, oven), but the soup
//! can be taken out at any time after the onion went in, as in a human interval-production
//! trial (the participant presses when they judge the interval has elapsed; Rakitin et al.
//! 1998, Jazayeri & Shadlen 2010's production epoch). Delivery pays 1 when the oven was
//! turned off within `window` steps of the target `td`, and `missed_reward` otherwise. Unlike
//! the fixed-interval task, an early response is possible and is not paid, so the
//! agent's production times show its timing error on both sides of the target.
//!
//! Everything the lab needs to know is here: the registered task and its documentation,
//! the parameter table and defaults, the layout and its objects, the cross-field check, the
//! kitchen's rules (the window mechanics, [`RuleSet::window`]), the conditions an agent is
//! evaluated under, and the training preset.

use chronocooked_env::error::EnvError;
use chronocooked_env::layout::{Layout, ObjectKind};
use chronocooked_env::settings::{Rule, Spec, UNIT};
use chronocooked_env::task::condition::{Condition, ConditionKind};
use chronocooked_env::task::family::{
    Family, ResponseKind, RuleSet, TaskSpec, condition, register,
};
use chronocooked_env::task::{ExternalParams, FI_LAYOUT};
use chronocooked_env::{RewardMode, Task, TaskConfig, TaskFamily, TaskParams};
use serde::Deserialize;

/// The registered id of the task.
pub const ID: &str = "IntervalProduction-v0";

/// The interval-production family.
pub struct IntervalProduction;

/// The task's parameters, typed (read from the values its table writes).
#[derive(Debug, Clone, Copy, Deserialize)]
struct Params {
    /// Target duration (steps).
    td: u32,
    /// Half-width of the paid window (steps).
    window: u32,
    /// Reward for a soup turned off outside the window (default 0.1, the reduced reward of the
    /// reference's multi-timer task: without it nothing but a hit in the window pays, and
    /// neither PPO nor the timing models find the window by exploration).
    missed_reward: f32,
}

impl Params {
    /// The typed parameters of `params` (`None` for another family's).
    fn of(params: &TaskParams) -> Option<Params> {
        match params {
            TaskParams::External(ExternalParams { task, values }) if task == ID => {
                serde_json::from_value(serde_json::Value::Object(values.clone())).ok()
            }
            _ => None,
        }
    }
}

/// The parameter table: keys, accepted values and meaning. Values live at
/// `params.values.<key>` of the task's configuration.
const PARAMS: &[Spec] = &[
    Spec {
        key: "td",
        aliases: &["oven_duration"],
        path: &["params", "values", "td"],
        rule: Rule::Int { lo: 1, hi: 10_000 },
        doc: "target duration (steps)",
        only_with: None,
    },
    Spec {
        key: "window",
        aliases: &[],
        path: &["params", "values", "window"],
        rule: Rule::Int { lo: 0, hi: 10_000 },
        doc: "half-width of the paid window around td (steps), < td",
        only_with: None,
    },
    Spec {
        key: "missed_reward",
        aliases: &[],
        path: &["params", "values", "missed_reward"],
        rule: UNIT,
        doc: "reward for a soup turned off outside the window",
        only_with: None,
    },
];

/// The family's training presets (the lab's preset format: `[fast]`, `[reference]`, …):
/// the fixed-interval task's budgets, as the task is as hard to learn.
const PRESET: &str = "\
[reference]
total_steps = 900000

[fast]
total_steps = 300000
";

fn wrong() -> EnvError {
    EnvError::param("family", "another family", format!("{ID} parameters"))
}

impl Family for IntervalProduction {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: ID,
            family: TaskFamily::External,
            tags: &["example", "timing", "production"],
            summary: "Interval production: take the soup out within +-window of TD (early responses possible, unpaid)",
            description: "FI layout `.OD/.../V../.../...`. The soup can be taken out any time after the onion \
went in; delivery pays 1 when the oven was turned off within `window` steps of `td`, \
`missed_reward` otherwise. Defaults: td=12, window=2, missed_reward=0.1 (the reference multi-timer's reduced reward). Defined outside the lab's \
crates (examples/interval_production) to show how a task family is added.",
            source: "example family (Rakitin et al. 1998; Jazayeri & Shadlen 2010, production epoch)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        let values = serde_json::json!({"td": 12, "window": 2, "missed_reward": 0.1});
        let serde_json::Value::Object(values) = values else {
            unreachable!("a JSON object literal")
        };
        (
            FI_LAYOUT,
            TaskParams::External(ExternalParams {
                task: ID.into(),
                values,
            }),
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        FI_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        vec![
            ObjectKind::OnionDispenser,
            ObjectKind::DeliveryCounter,
            ObjectKind::Oven,
        ]
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        let p = Params::of(&config.params).ok_or_else(wrong)?;
        if p.window >= p.td {
            return Err(EnvError::param(
                "window",
                p.window,
                format!(
                    "integer < td ({}): an early response must be possible",
                    p.td
                ),
            ));
        }
        Ok(())
    }

    fn single_td(&self, params: &TaskParams) -> Option<u32> {
        Params::of(params).map(|p| p.td)
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let p = Params::of(&config.params).ok_or_else(wrong)?;
        RuleSet::window(
            vec![p.td],
            RewardMode::Exact,
            p.window,
            p.window,
            p.missed_reward,
        )
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        self.single_td(params).into_iter().collect()
    }

    /// The timing models play it as interval production.
    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::MultiTimer
    }

    /// The trained TD, and the same TD with windows of 0, 25, 50 and 75% of it (how reward
    /// falls as the window narrows: the agent's production spread).
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let p = Params::of(&config.params).ok_or_else(wrong)?;
        let mut out = vec![condition(ConditionKind::MultiTimer, task, p.td)];
        for f in [0.0, 0.25, 0.5, 0.75] {
            let w = ((f * f64::from(p.td)).round() as u32).min(p.td - 1);
            let narrowed = task.with_values(&[("window", serde_json::json!(w))])?;
            let mut c = condition(ConditionKind::Buffer, &narrowed, p.td);
            c.factor = Some(f);
            out.push(c);
        }
        Ok(out)
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        self.single_td(params)
            .map(|td| (td, None))
            .into_iter()
            .collect()
    }

    fn preset(&self) -> Option<&'static str> {
        Some(PRESET)
    }
}

/// Registers the family once (later calls do nothing).
pub fn register_once() -> Result<(), EnvError> {
    static DONE: std::sync::OnceLock<Result<(), String>> = std::sync::OnceLock::new();
    DONE.get_or_init(|| register(&IntervalProduction).map_err(|e| e.to_string()))
        .clone()
        .map_err(|message| EnvError::param("family", ID, message))
}
