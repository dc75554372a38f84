//! Multi-anchor categorization (reference `ChronoCookedBisectionMultiAnchors`; public code,
//! not in the paper): one counter per anchor duration (2–4); deliver to the counter of the
//! episode's TD.

use super::bisection::{any_td, below_geometric_mean};
use super::{Family, Growth, ResponseKind, RuleSet, TaskSpec, probe_range, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::Rules;
use crate::settings::{self, Rule, Spec};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{FIXED_TD, MAX_ANCHORS, TD_RULE, param};
use crate::task::{AUTO_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The multi-anchor family.
pub(crate) struct MultiAnchor;

const PARAMS: &[Spec] = &[
    param(
        "anchors",
        &[],
        &["params", "anchors"],
        Rule::List(&TD_RULE),
        "anchor durations (steps), 2 to 4 distinct values in increasing order; counter i pays 1 iff TD == anchors[i]",
    ),
    param(
        "num_anchors",
        &[],
        &["params", "num_anchors"],
        Rule::Optional(&Rule::Int { lo: 2, hi: 4 }),
        "active anchors: the first num_anchors of anchors have counters and are drawn (curriculum 2 -> 3 -> 4); none: all",
    ),
    FIXED_TD,
];

/// The reference multi-anchor layout (4×3) with `k` counters: counter 1 (0,0), onion (0,1),
/// counter 2 (0,2), counter 3 (3,0), oven (3,1), counter 4 (3,2).
fn layout(k: usize) -> &'static str {
    match k {
        0..=2 => "SOL/.../.../.V.",
        3 => "SOL/.../.../3V.",
        _ => "SOL/.../.../3V4",
    }
}

impl TaskParams {
    /// Multi-anchor: the active anchors (steps), in counter order.
    pub fn active_anchors(&self) -> Option<&[u32]> {
        match self {
            TaskParams::MultiAnchor {
                anchors,
                num_anchors,
            } => Some(&anchors[..num_anchors.unwrap_or(anchors.len()).min(anchors.len())]),
            _ => None,
        }
    }
}

impl Family for MultiAnchor {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "MultiAnchor-v0",
            family: TaskFamily::MultiAnchor,
            tags: &[
                "reference",
                "timing",
                "categorization",
                "bisection",
                "curriculum",
            ],
            summary: "Multi-anchor categorization: one counter per anchor duration; deliver to the counter of the TD",
            description: "Layout 4x3 (reference): counter 1 (0,0) code 7, onion (0,1) code 3, counter 2 (0,2) \
code 8, counter 3 (3,0) code 9, oven (3,1) code 4, counter 4 (3,2) code 10; only the counters of the \
active anchors are in the kitchen (2 anchors: 8 free cells, 3: 7, 4: 6). Each episode draws the TD \
uniformly from the active anchors (reset option td sets any probe). The oven shows on (1), then ready \
(2) at the end of the step on which timer == TD; the soup can be taken only when ready. Delivery to \
counter i pays 1 iff TD == anchors[i], else 0; any delivery ends the episode and info.counter records \
the counter. Defaults: anchors=4,8,12 (the reference class; its scripts train 3,10,20,25 and \
4,12,18,25 with the curriculum 2 -> 3 -> 4 anchors at 0.98 / 0.96), max_timesteps=200.",
            source: "reference ChronoCookedBisectionMultiAnchors (public code; not in the paper)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            AUTO_LAYOUT,
            TaskParams::MultiAnchor {
                anchors: vec![4, 8, 12],
                num_anchors: None,
            },
        )
    }

    fn auto_layout(&self, params: &TaskParams) -> &'static str {
        layout(params.active_anchors().map_or(2, <[u32]>::len))
    }

    fn required_objects(&self, params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        let k = params.active_anchors().map_or(2, <[u32]>::len);
        let mut v = vec![OnionDispenser, Oven, ShortCounter, LongCounter];
        v.extend([Counter3, Counter4].into_iter().take(k.saturating_sub(2)));
        v
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        let TaskParams::MultiAnchor {
            anchors,
            num_anchors,
        } = &config.params
        else {
            return Err(wrong_family("multi-anchor", &config.params));
        };
        let text = settings::display(&serde_json::json!(anchors));
        if !(2..=MAX_ANCHORS).contains(&anchors.len()) {
            return Err(EnvError::param(
                "anchors",
                text,
                format!("2 to {MAX_ANCHORS} durations (one counter each)"),
            ));
        }
        if anchors.windows(2).any(|w| w[0] >= w[1]) {
            return Err(EnvError::param(
                "anchors",
                text,
                "distinct durations in increasing order (counter i is the i-th shortest)",
            ));
        }
        if let Some(k) = num_anchors
            && !(2..=anchors.len()).contains(k)
        {
            return Err(EnvError::param(
                "num_anchors",
                k,
                format!("none, or 2..={} (the number of anchors)", anchors.len()),
            ));
        }
        Ok(())
    }

    fn fixed_td_fits(&self, _params: &TaskParams, td: u32) -> bool {
        any_td(td)
    }

    fn shows_ready(&self) -> bool {
        true
    }

    /// The multi-anchor reference writes the oven as 4 and counter i as 6 + i.
    fn object_code(&self, kind: ObjectKind) -> u8 {
        match kind {
            ObjectKind::Oven => 4,
            ObjectKind::ShortCounter => 7,
            ObjectKind::LongCounter => 8,
            _ => kind.code(),
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let active = config
            .params
            .active_anchors()
            .ok_or_else(|| wrong_family("multi-anchor", &config.params))?;
        let mut anchors = [0; 4];
        anchors[..active.len()].copy_from_slice(active);
        Ok(RuleSet::simple(
            Rules::Categories {
                anchors,
                k: active.len() as u8,
            },
            active[0],
            active.to_vec(),
        ))
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Categorise)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::MultiAnchor
    }

    /// The reference's probes: every integer 1 … (largest active anchor) + 4.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let active = config
            .params
            .active_anchors()
            .ok_or_else(|| wrong_family("multi-anchor", &config.params))?;
        let largest = active.last().copied().unwrap_or(1);
        Ok(probe_range(ConditionKind::MultiAnchor, task, largest))
    }

    /// The counter of the first pair of neighbouring anchors whose geometric mean lies above
    /// `td` (the last counter if none).
    fn delivery_kind(&self, params: &TaskParams, td: u32) -> ObjectKind {
        let anchors = params.active_anchors().unwrap_or(&[]);
        let category = anchors
            .windows(2)
            .position(|w| below_geometric_mean(td, w[0], w[1]))
            .unwrap_or(anchors.len().saturating_sub(1));
        [
            ObjectKind::ShortCounter,
            ObjectKind::LongCounter,
            ObjectKind::Counter3,
            ObjectKind::Counter4,
        ][category.min(3)]
    }

    /// The reference's curriculum: 2, 3, … active anchors.
    fn most_categories(&self) -> usize {
        MAX_ANCHORS
    }

    fn growth(&self, params: &TaskParams) -> Option<Growth> {
        let last = params.active_anchors()?.len();
        Some(Growth {
            key: "num_anchors",
            first: 2,
            last,
        })
    }

    fn grow(&self, params: &mut TaskParams, size: usize) {
        if let TaskParams::MultiAnchor { num_anchors, .. } = params {
            *num_anchors = Some(size);
        }
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        params.active_anchors().unwrap_or(&[]).to_vec()
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        self.evaluation_tds(params)
            .into_iter()
            .map(|td| (td, None))
            .collect()
    }
}
