//! Uncertainty (paper: Dual task and uncertainty task; reference training trace): the oven
//! may never become ready by itself; a manual button readies it at a reduced reward.

use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::{Spec, UNIT};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{OVER, TD, param};
use crate::task::reset_option::ResetOption;
use crate::task::{Task, TaskConfig, TaskFamily, TaskParams, UNCERTAINTY_LAYOUT};

/// The uncertainty family.
pub(crate) struct Uncertainty;

const PARAMS: &[Spec] = &[
    TD,
    param(
        "never_ready_prob",
        &["oven_delay_prob"],
        &["params", "never_ready_prob"],
        UNIT,
        "probability that the oven never becomes ready by itself",
    ),
    OVER,
    param(
        "overcooked_reward",
        &[],
        &["params", "overcooked_reward"],
        UNIT,
        "reward when a self-readied soup is taken after TD+over_buffer",
    ),
    param(
        "manual_reward",
        &["undercooked_reward"],
        &["params", "manual_reward"],
        UNIT,
        "reward for soup readied with the manual button",
    ),
];

impl Family for Uncertainty {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "Uncertainty-v0",
            family: TaskFamily::Uncertainty,
            tags: &["paper", "timing", "uncertainty", "production", "curriculum"],
            summary: "Uncertainty: the oven may never ready itself; a manual button readies it at a reduced reward",
            description: "Layout 5x3 `.OD/.../V../.../.B.`: the FI layout plus a manual oven-off button (code 8) \
at (4,1), as in the reference training trace. The oven shows ready (2) when timer == TD, except in \
never-ready episodes (probability never_ready_prob, default 0.2; reference curriculum 0 -> 0.2). \
Pressing the button while the oven is on and not ready makes it ready at once. Soup can be taken \
only when ready. Delivery pays manual_reward (default 0.1, the reference's undercooked reward) for a \
button-readied soup, overcooked_reward (0.5) for a self-readied soup taken after TD+over_buffer, else 1. \
Defaults: td=9 (reference trace), over_buffer=0. Design decision: the optimal policy waits at the \
oven until TD and, if the oven stays dark, presses the button.",
            source: "paper: Dual task and uncertainty task; reference training trace (button, rewards)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            UNCERTAINTY_LAYOUT,
            TaskParams::Uncertainty {
                td: 9,
                never_ready_prob: 0.2,
                over_buffer: 0,
                overcooked_reward: 0.5,
                manual_reward: 0.1,
            },
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        UNCERTAINTY_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        vec![OnionDispenser, DeliveryCounter, Oven, OvenButton]
    }

    fn shows_ready(&self) -> bool {
        true
    }

    fn single_td(&self, params: &TaskParams) -> Option<u32> {
        match params {
            TaskParams::Uncertainty { td, .. } => Some(*td),
            _ => None,
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::Uncertainty {
            td,
            never_ready_prob,
            over_buffer,
            overcooked_reward,
            manual_reward,
        } = config.params
        else {
            return Err(wrong_family("uncertainty", &config.params));
        };
        Ok(RuleSet::simple(
            Rules::Uncertainty {
                p_never: never_ready_prob,
                over: over_buffer,
                overcooked: overcooked_reward,
                manual: manual_reward,
            },
            td,
            vec![td],
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn never_ready_prob(&self, params: &TaskParams) -> f32 {
        match params {
            TaskParams::Uncertainty {
                never_ready_prob, ..
            } => *never_ready_prob,
            _ => 0.0,
        }
    }

    fn set_never_ready_prob(&self, params: &mut TaskParams, p: f32) {
        if let TaskParams::Uncertainty {
            never_ready_prob, ..
        } = params
        {
            *never_ready_prob = p;
        }
    }

    /// The start cell, the duration, and whether the episode is never-ready.
    fn reset_options(&self) -> &'static [ResetOption] {
        &[ResetOption::Start, ResetOption::Td, ResetOption::NeverReady]
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Uncertainty
    }

    /// Normal and never-ready episodes at the trained TD.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let td = self
            .single_td(&config.params)
            .ok_or_else(|| wrong_family("uncertainty", &config.params))?;
        Ok([false, true]
            .into_iter()
            .map(|nr| self.played_condition(task.clone(), &config.params, td, nr))
            .collect())
    }

    fn played_condition(
        &self,
        task: Task,
        _params: &TaskParams,
        td: u32,
        never_ready: bool,
    ) -> Condition {
        let mut c = condition(ConditionKind::Uncertainty, &task, td);
        c.never_ready = Some(never_ready);
        c
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        self.single_td(params).into_iter().collect()
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        self.single_td(params)
            .map(|td| vec![(td, Some(false)), (td, Some(true))])
            .unwrap_or_default()
    }
}
