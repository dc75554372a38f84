//! Dual task (paper: Dual task and uncertainty task): the fixed-interval task with a
//! small-reward sink that competes with the oven during the timing phase.

use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::{Spec, UNIT};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{OVER, REDUCED, TD, UNDER, param};
use crate::task::{DUAL_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The dual-task family.
pub(crate) struct Dual;

const PARAMS: &[Spec] = &[
    TD,
    UNDER,
    OVER,
    REDUCED,
    param(
        "sink_reward",
        &[],
        &["params", "sink_reward"],
        UNIT,
        "reward per sink interaction while the oven is on",
    ),
];

impl Family for Dual {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "DualTask-v0",
            family: TaskFamily::Dual,
            tags: &["paper", "timing", "dual", "production"],
            summary: "Dual task: a small-reward sink competes with the oven during the timing phase",
            description: "Layout 5x3 `.OD/.../V../.../..K`: the FI layout plus a reward sink (code 6) at (4,2), \
two moves from the oven's neighbours. While the oven is on each interact with the sink pays \
sink_reward (default 0.01); the soup follows the multi-timer exact rule (take any time; 1 inside \
[TD-under_buffer, TD+over_buffer], reduced_reward outside). info records sink visits; the metrics use \
time at the sink and the leave time. Design decisions (not in the public code): sink placement, \
per-interact payment only while the oven is on (so sink use cannot replace timing), defaults td=12, \
buffers 0, reduced_reward=0.1.",
            source: "paper: Dual task and uncertainty task (design decisions documented)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            DUAL_LAYOUT,
            TaskParams::Dual {
                td: 12,
                under_buffer: 0,
                over_buffer: 0,
                reduced_reward: 0.1,
                sink_reward: 0.01,
            },
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        DUAL_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        vec![OnionDispenser, DeliveryCounter, Oven, RewardSink]
    }

    fn single_td(&self, params: &TaskParams) -> Option<u32> {
        match params {
            TaskParams::Dual { td, .. } => Some(*td),
            _ => None,
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::Dual {
            td,
            under_buffer,
            over_buffer,
            reduced_reward,
            sink_reward,
        } = config.params
        else {
            return Err(wrong_family("dual", &config.params));
        };
        Ok(RuleSet::simple(
            Rules::Dual {
                under: under_buffer,
                over: over_buffer,
                reduced: reduced_reward,
                sink: sink_reward,
            },
            td,
            vec![td],
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Dual
    }

    /// The trained TD.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let td = self
            .single_td(&config.params)
            .ok_or_else(|| wrong_family("dual", &config.params))?;
        Ok(vec![condition(ConditionKind::Dual, task, td)])
    }

    /// The latest rewarded pickup: every extra step of cooking is one more sink payment.
    fn paid_pickup_timer(&self, params: &TaskParams, td: u32) -> Option<i32> {
        match params {
            TaskParams::Dual { over_buffer, .. } => Some(td as i32 + *over_buffer as i32),
            _ => Some(td as i32),
        }
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        self.single_td(params).into_iter().collect()
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        self.single_td(params)
            .map(|td| (td, None))
            .into_iter()
            .collect()
    }
}
