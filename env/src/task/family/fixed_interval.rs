//! Fixed interval (paper: Tasks / Fixed interval timing; reference `TimeProductionBasic`):
//! the soup is available from oven timer ≥ TD, +1 on delivery.

use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::Spec;
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::TD;
use crate::task::{FI_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The fixed-interval family.
pub(crate) struct FixedInterval;

impl Family for FixedInterval {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "FixedInterval-v0",
            family: TaskFamily::FixedInterval,
            tags: &["paper", "timing", "fixed-interval", "production"],
            summary: "Fixed interval: soup available from oven timer >= TD; +1 on delivery",
            description: "Layout 5x3 `.OD/.../V../.../...`: onion (0,1) code 3, delivery (0,2) code 4, \
oven (2,0) code 5, 12 free cells. The oven shows only on (1) / off (0), never ready. Interacting \
with the oven before the timer reaches TD does nothing; from timer >= TD it hands out the soup. \
Reward +1 on delivery, 0 otherwise. Defaults: td=12 (paper: 4, 6, 9, 12, 18, 24, one TD per run), \
max_timesteps=200.",
            source: "paper: Tasks / Fixed interval timing; reference TimeProductionBasic",
        }
    }

    fn params(&self) -> &'static [Spec] {
        &[TD]
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (FI_LAYOUT, TaskParams::FixedInterval { td: 12 })
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        FI_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        vec![OnionDispenser, DeliveryCounter, Oven]
    }

    fn single_td(&self, params: &TaskParams) -> Option<u32> {
        match params {
            TaskParams::FixedInterval { td } => Some(*td),
            _ => None,
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::FixedInterval { td } = config.params else {
            return Err(wrong_family("fixed-interval", &config.params));
        };
        Ok(RuleSet::simple(Rules::Fixed, td, vec![td]))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Fi
    }

    /// The trained TD, and peak-interval probes with the soup released at 2× and 5× TD.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::FixedInterval { td } = config.params else {
            return Err(wrong_family("fixed-interval", &config.params));
        };
        let mut out = vec![condition(ConditionKind::Fi, task, td)];
        for k in [2u32, 5] {
            let probe = Task::parse(
                "PeakInterval-v0",
                &[format!("td={td}"), format!("probe_factor={k}")],
            )?;
            let mut c = condition(ConditionKind::Pi, &probe, td);
            c.factor = Some(f64::from(k));
            out.push(c);
        }
        Ok(out)
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
