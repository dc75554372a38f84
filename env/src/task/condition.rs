//! Evaluation conditions: what a condition measures ([`ConditionKind`]) and the task, TD
//! and reset options its episodes are played with ([`Condition`]). Each task family
//! declares the conditions an agent trained on it is tested under (`task::family`); the
//! evaluation protocol plays them and writes one record per episode.

use super::Task;
use serde::{Deserialize, Serialize};

/// What an evaluation condition measures (serialised in snake case: `fi`, `pi`,
/// `bisection`, `multi_timer`, `buffer`, `dual`, `uncertainty`).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    strum::IntoStaticStr,
    strum::Display,
)]
#[serde(rename_all = "snake_case")]
#[strum(serialize_all = "snake_case")]
pub enum ConditionKind {
    /// Fixed interval at the trained TD.
    Fi,
    /// Peak-interval probe (soup released late or never).
    Pi,
    /// Bisection probe duration.
    Bisection,
    /// Multi-timer TD (trained or out of distribution).
    MultiTimer,
    /// Multi-timer exact-window buffer probe.
    Buffer,
    /// Dual task at the trained TD.
    Dual,
    /// Uncertainty task (normal or never-ready ovens).
    Uncertainty,
    /// Multi-anchor categorization probe duration.
    MultiAnchor,
    /// Multi-oven bisection probe duration (every oven).
    MultiOven,
    /// Reproduction: one sample interval of one prior and gain.
    Reproduction,
}

impl ConditionKind {
    /// Every kind, in the order of the NPZ export's `condition` codes.
    pub const ALL: [ConditionKind; 10] = [
        ConditionKind::Fi,
        ConditionKind::Pi,
        ConditionKind::Bisection,
        ConditionKind::MultiTimer,
        ConditionKind::Buffer,
        ConditionKind::Dual,
        ConditionKind::Uncertainty,
        ConditionKind::MultiAnchor,
        ConditionKind::MultiOven,
        ConditionKind::Reproduction,
    ];

    /// The serialised name (`fi`, `multi_timer`, …).
    pub fn as_str(self) -> &'static str {
        self.into()
    }
}

impl std::str::FromStr for ConditionKind {
    type Err = String;

    /// Parses a serialised name; the error lists the allowed ones.
    fn from_str(s: &str) -> Result<Self, String> {
        ConditionKind::ALL
            .into_iter()
            .find(|k| k.as_str() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = ConditionKind::ALL.iter().map(|k| k.as_str()).collect();
                format!(
                    "unknown condition kind `{s}` (allowed: {})",
                    names.join(", ")
                )
            })
    }
}

/// One evaluation condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Condition {
    /// What this condition measures.
    pub kind: ConditionKind,
    /// Task played, with its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Target duration of the episodes (steps).
    pub td: u32,
    /// Uncertainty: force never-ready episodes (true) or normal ones (false).
    pub never_ready: Option<bool>,
    /// PI: release factor; multi-timer buffers: buffer as a fraction of TD; reproduction:
    /// the gain `g`.
    pub factor: Option<f64>,
    /// Reproduction: `[prior index, gain index]` of the episodes (reset options).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub context: Option<[u8; 2]>,
}
