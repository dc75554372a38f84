//! Peak-interval probe (paper: Tasks / Peak interval timing): the fixed-interval task with
//! the soup withheld until `probe_factor × TD` (or never).

use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::{Rule, Spec};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{MAX_PROBE_FACTOR, TD, param};
use crate::task::{FI_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The peak-interval family.
pub(crate) struct PeakInterval;

const PARAMS: &[Spec] = &[
    TD,
    param(
        "probe_factor",
        &["k"],
        &["params", "probe_factor"],
        Rule::Mapped {
            inner: &Rule::Int {
                lo: 0,
                hi: MAX_PROBE_FACTOR,
            },
            synonyms: &[("never", "0")],
        },
        "the soup becomes available at probe_factor x td; 0 withholds it for the whole episode",
    ),
];

impl Family for PeakInterval {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "PeakInterval-v0",
            family: TaskFamily::PeakInterval,
            tags: &["paper", "timing", "fixed-interval", "probe", "test-only"],
            summary: "Peak-interval probe: FI with the soup withheld until probe_factor x TD (0 = never)",
            description: "FI layout and rules, but the soup can be taken only from timer >= probe_factor*td \
(default 2, the paper's 2x; 5 for 5x; 0 = never, the classic unreinforced probe, episode runs to the \
time limit). Measure: oven-check (interact next to the oven) rate over oven time. Used at test time on \
FI-trained agents. Design decisions (the public code has no PI task): same observation as FI (the \
agent cannot tell probe from training trials); a released soup pays +1.",
            source: "paper: Tasks / Peak interval timing (design decision: release rule)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            FI_LAYOUT,
            TaskParams::PeakInterval {
                td: 12,
                probe_factor: 2,
            },
        )
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
            TaskParams::PeakInterval { td, .. } => Some(*td),
            _ => None,
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::PeakInterval { td, probe_factor } = config.params else {
            return Err(wrong_family("peak-interval", &config.params));
        };
        Ok(RuleSet::simple(
            Rules::Probe {
                factor: probe_factor,
            },
            td,
            vec![td],
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Pi
    }

    /// The probe itself, its release factor recorded.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::PeakInterval { td, .. } = config.params else {
            return Err(wrong_family("peak-interval", &config.params));
        };
        Ok(vec![self.played_condition(
            task.clone(),
            &config.params,
            td,
            false,
        )])
    }

    fn played_condition(
        &self,
        task: Task,
        params: &TaskParams,
        td: u32,
        _never_ready: bool,
    ) -> Condition {
        let factor = match params {
            TaskParams::PeakInterval { probe_factor, .. } => Some(f64::from(*probe_factor)),
            _ => None,
        };
        let mut c = condition(ConditionKind::Pi, &task, td);
        c.factor = factor;
        c
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
