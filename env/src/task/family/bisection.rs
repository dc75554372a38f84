//! Temporal bisection (paper: Tasks / Bisection task; reference
//! `ChronoCookedBisectionTask`): deliver to the short or the long counter.

use super::{Family, ResponseKind, RuleSet, TaskSpec, probe_range, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::Spec;
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{FIXED_TD, LONG, MAX_TD, SHORT};
use crate::task::{BISECTION_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The bisection family.
pub(crate) struct Bisection;

/// Checks the anchors' order, S < L (bisection and multi-oven).
pub(crate) fn check_anchors(short: u32, long: u32) -> Result<(), EnvError> {
    if long <= short {
        return Err(EnvError::param(
            "long",
            long,
            format!("integer > short ({short}): the anchors need S < L"),
        ));
    }
    Ok(())
}

/// Whether a fixed TD lies in the range every drawn-TD family accepts (1..=10000 steps).
pub(crate) fn any_td(td: u32) -> bool {
    (1..=MAX_TD as u32).contains(&td)
}

/// The optimal categorisation of `td` between anchors `short` and `long`: short below their
/// geometric mean (the ideal observer's boundary for scalar timing noise).
pub(crate) fn below_geometric_mean(td: u32, short: u32, long: u32) -> bool {
    u64::from(td) * u64::from(td) < u64::from(short) * u64::from(long)
}

/// The counter of the short or the long category (bisection and multi-oven).
pub(crate) fn category_counter(td: u32, short: u32, long: u32) -> ObjectKind {
    if below_geometric_mean(td, short, long) {
        ObjectKind::ShortCounter
    } else {
        ObjectKind::LongCounter
    }
}

impl Family for Bisection {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "Bisection-v0",
            family: TaskFamily::Bisection,
            tags: &["paper", "timing", "bisection", "discrimination"],
            summary: "Temporal bisection: deliver to the short (code 4) or long (code 8) counter",
            description: "Layout 4x3 `SOL/.../.../.V.`: short counter (0,0) code 4, onion (0,1) code 3, long \
counter (0,2) code 8, oven (3,1) code 5, 8 free cells. Training TD is short or long with probability \
1/2 (reset option td sets any probe duration). The oven shows on (1), then ready (2) at the end of the \
step on which timer == TD; the soup can be taken only when ready. Delivery to the short counter pays \
+1 iff TD == short, to the long counter +1 iff TD == long, else 0; any delivery ends the episode and \
info.counter records the counter. Defaults: short=4, long=12 (paper anchors 6-8, 4-8, 6-12, 4-12, \
6-18, 4-18).",
            source: "paper: Tasks / Bisection task; reference ChronoCookedBisectionTask",
        }
    }

    fn params(&self) -> &'static [Spec] {
        &[SHORT, LONG, FIXED_TD]
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            BISECTION_LAYOUT,
            TaskParams::Bisection { short: 4, long: 12 },
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        BISECTION_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        vec![OnionDispenser, ShortCounter, LongCounter, Oven]
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        match config.params {
            TaskParams::Bisection { short, long } => check_anchors(short, long),
            _ => Err(wrong_family("bisection", &config.params)),
        }
    }

    fn fixed_td_fits(&self, _params: &TaskParams, td: u32) -> bool {
        any_td(td)
    }

    fn shows_ready(&self) -> bool {
        true
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::Bisection { short, long } = config.params else {
            return Err(wrong_family("bisection", &config.params));
        };
        Ok(RuleSet::simple(
            Rules::Bisection { short, long },
            short,
            vec![short, long],
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Categorise)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Bisection
    }

    /// Probe durations 1 … L + 4 (the reference's).
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::Bisection { long, .. } = config.params else {
            return Err(wrong_family("bisection", &config.params));
        };
        Ok(probe_range(ConditionKind::Bisection, task, long))
    }

    fn delivery_kind(&self, params: &TaskParams, td: u32) -> ObjectKind {
        match params {
            TaskParams::Bisection { short, long } => category_counter(td, *short, *long),
            _ => ObjectKind::DeliveryCounter,
        }
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        match params {
            TaskParams::Bisection { short, long } => vec![*short, *long],
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
