//! Multi-oven bisection (reference `ChronoCookedBisectionMultiOven`, v2; public code, not in
//! the paper): 1–3 ovens, each soup to the short or the long counter.

use super::bisection::{any_td, category_counter, check_anchors};
use super::{Family, Growth, ResponseKind, RuleSet, TaskSpec, probe_range, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::{Rule, Spec};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{FIXED_TD, LONG, MAX_OVENS, SHORT, param};
use crate::task::reset_option::ResetOption;
use crate::task::{AUTO_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};
use serde_json::json;

/// The multi-oven family.
pub(crate) struct MultiOven;

const PARAMS: &[Spec] = &[
    SHORT,
    LONG,
    param(
        "ovens",
        &["n_ovens"],
        &["params", "ovens"],
        Rule::Int {
            lo: 1,
            hi: MAX_OVENS as u64,
        },
        "number of ovens (curriculum 1 -> 2 -> 3); only the first takes the onion",
    ),
    param(
        "asynchronous",
        &["async"],
        &["params", "asynchronous"],
        Rule::Bool,
        "false: the put starts every oven; true: the put starts the first oven and the others start by themselves at drawn on-times",
    ),
    FIXED_TD,
];

/// The reference multi-oven layout (4×3) with `n` ovens: short counter (0,0), onion (0,1),
/// long counter (0,2), oven i at (3,i).
fn layout(n: usize) -> &'static str {
    match n {
        0 | 1 => "SOL/.../.../V..",
        2 => "SOL/.../.../VW.",
        _ => "SOL/.../.../VWX",
    }
}

/// The number of ovens of multi-oven parameters (1 for any other family).
fn ovens(params: &TaskParams) -> usize {
    match params {
        TaskParams::MultiOven { ovens, .. } => *ovens as usize,
        _ => 1,
    }
}

impl Family for MultiOven {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "MultiOven-v0",
            family: TaskFamily::MultiOven,
            tags: &[
                "reference",
                "timing",
                "bisection",
                "concurrent",
                "curriculum",
            ],
            summary: "Multi-oven bisection: 1-3 ovens, each soup to the short or the long counter",
            description: "Layout 4x3 (reference): short counter (0,0) code 4, onion (0,1) code 3, long \
counter (0,2) code 5, oven i at (3,i) code 6+3i. Each oven's duration is short or long with \
probability 1/2 (reset options set a duration per oven). Only the first oven takes the onion, once; \
synchronous mode starts every oven at the put, asynchronous mode starts the first at the put and \
the others by themselves at on-times drawn without replacement from 0..=6+d0/2 (reset option \
on_times sets them). An oven shows ready (2) at the end of the step on which its timer == its \
duration; taking a ready soup empties the oven and the soup carries the oven's code (channel 3). A \
soup delivered to the counter that matches its oven's duration pays 1/ovens; the episode ends when \
every soup is delivered. Defaults: short=4, long=12 (the reference scripts: 4 and 8/12/18), \
ovens=2, asynchronous=false, max_timesteps=200; curriculum 1 -> 2 -> 3 ovens at 0.95 / 0.90.",
            source: "reference ChronoCookedBisectionMultiOven, v2 (public code; not in the paper)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            AUTO_LAYOUT,
            TaskParams::MultiOven {
                short: 4,
                long: 12,
                ovens: 2,
                asynchronous: false,
            },
        )
    }

    fn auto_layout(&self, params: &TaskParams) -> &'static str {
        layout(ovens(params))
    }

    fn required_objects(&self, params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        let mut v = vec![OnionDispenser, ShortCounter, LongCounter, Oven];
        v.extend(
            [Oven2, Oven3]
                .into_iter()
                .take(ovens(params).saturating_sub(1)),
        );
        v
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        match config.params {
            TaskParams::MultiOven { short, long, .. } => check_anchors(short, long),
            _ => Err(wrong_family("multi-oven", &config.params)),
        }
    }

    fn fixed_td_fits(&self, _params: &TaskParams, td: u32) -> bool {
        any_td(td)
    }

    fn shows_ready(&self) -> bool {
        true
    }

    /// The multi-oven reference writes the short and long counters as 4 and 5 and oven i
    /// as 3 + 3i.
    fn object_code(&self, kind: ObjectKind) -> u8 {
        match kind {
            ObjectKind::LongCounter => 5,
            ObjectKind::Oven => 6,
            _ => kind.code(),
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::MultiOven {
            short,
            long,
            ovens,
            asynchronous,
        } = config.params
        else {
            return Err(wrong_family("multi-oven", &config.params));
        };
        Ok(RuleSet::simple(
            Rules::MultiOven {
                short,
                long,
                n: ovens as u8,
                asynchronous,
            },
            short,
            vec![short, long],
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Categorise)
    }

    /// The start cell, one duration for every oven or one per oven, and the on-times.
    fn reset_options(&self) -> &'static [ResetOption] {
        &[
            ResetOption::Start,
            ResetOption::Td,
            ResetOption::OvenTds,
            ResetOption::OnTimes,
        ]
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::MultiOven
    }

    /// The reference's probes: TD 1 … L + 4, the same duration for every oven; with several
    /// ovens the same probes on one oven too (the agent's own baseline for the interference
    /// between ovens).
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::MultiOven { long, ovens, .. } = config.params else {
            return Err(wrong_family("multi-oven", &config.params));
        };
        let mut out = probe_range(ConditionKind::MultiOven, task, long);
        if ovens > 1 {
            let one = task.with_values(&[("ovens", json!(1))])?;
            out.extend(probe_range(ConditionKind::MultiOven, &one, long));
        }
        Ok(out)
    }

    fn delivery_kind(&self, params: &TaskParams, td: u32) -> ObjectKind {
        match params {
            TaskParams::MultiOven { short, long, .. } => category_counter(td, *short, *long),
            _ => ObjectKind::DeliveryCounter,
        }
    }

    /// The reference's curriculum: 1, 2, … ovens.
    fn growth(&self, params: &TaskParams) -> Option<Growth> {
        match params {
            TaskParams::MultiOven { ovens, .. } => Some(Growth {
                key: "ovens",
                first: 1,
                last: *ovens as usize,
            }),
            _ => None,
        }
    }

    fn grow(&self, params: &mut TaskParams, size: usize) {
        if let TaskParams::MultiOven { ovens, .. } = params {
            *ovens = size as u32;
        }
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        match params {
            TaskParams::MultiOven { short, long, .. } => vec![*short, *long],
            _ => Vec::new(),
        }
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        self.evaluation_tds(params)
            .into_iter()
            .map(|td| (td, None))
            .collect()
    }
}
