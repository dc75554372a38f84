//! The self-describing task registry: versioned ids → documented default configurations.

use crate::error::EnvError;
use crate::task::{
    BISECTION_LAYOUT, CueMode, DUAL_LAYOUT, FI_LAYOUT, RewardMode, TaskConfig, TaskFamily,
    TaskParams, UNCERTAINTY_LAYOUT,
};
use serde::Serialize;

/// One registered task: id, tags and documentation.
#[derive(Debug, Clone, Serialize)]
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
    /// The default configuration of this task.
    pub fn default_config(&self) -> TaskConfig {
        let (layout, params) = match self.family {
            TaskFamily::FixedInterval => (FI_LAYOUT, TaskParams::FixedInterval { td: 12 }),
            TaskFamily::PeakInterval => (
                FI_LAYOUT,
                TaskParams::PeakInterval {
                    td: 12,
                    probe_factor: 2,
                },
            ),
            TaskFamily::Bisection => (
                BISECTION_LAYOUT,
                TaskParams::Bisection { short: 4, long: 12 },
            ),
            TaskFamily::MultiTimer => (
                FI_LAYOUT,
                TaskParams::MultiTimer {
                    tds: vec![3, 6, 9, 12, 15],
                    num_timers: 1,
                    mode: RewardMode::Exact,
                    cue: CueMode::Value,
                    under_buffer: 0,
                    over_buffer: 0,
                    reduced_reward: 0.1,
                },
            ),
            TaskFamily::Dual => (
                DUAL_LAYOUT,
                TaskParams::Dual {
                    td: 12,
                    under_buffer: 0,
                    over_buffer: 0,
                    reduced_reward: 0.1,
                    sink_reward: 0.01,
                },
            ),
            TaskFamily::Uncertainty => (
                UNCERTAINTY_LAYOUT,
                TaskParams::Uncertainty {
                    td: 9,
                    never_ready_prob: 0.2,
                    over_buffer: 0,
                    overcooked_reward: 0.5,
                    manual_reward: 0.1,
                },
            ),
        };
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

static TASKS: &[TaskSpec] = &[
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
    },
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
    },
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
    },
    TaskSpec {
        id: "MultiTimer-v0",
        family: TaskFamily::MultiTimer,
        tags: &["paper", "timing", "multi-timer", "production", "curriculum"],
        summary: "Multi-timer: cued TDs; reward 1 inside [TD-under, TD+over], reduced outside",
        description: "FI layout. Each episode draws one of the first num_timers TDs of `tds`; while on, the \
oven's channel 4 shows the cue: the TD value (cue=value, reference) or 1+index (cue=categorical). \
mode=exact: soup can be taken any time after the onion went in; reward 1 iff TD-under_buffer <= \
oven_off_time <= TD+over_buffer, else reduced_reward. mode=lower_bounded: soup only at timer >= TD; \
reward reduced_reward iff oven_off_time > TD+over_buffer, else 1. Defaults: tds=3,6,9,12,15 (reference \
curriculum; a TD is added when the mean reward over 100 episodes passes 0.95, 0.95, 0.9, 0.9, 0.9), \
num_timers=1, mode=exact, cue=value, buffers 0, reduced_reward=0.1.",
        source: "paper: Tasks / Multi-Timer; reference MultiTimeProduction",
    },
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
    },
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
    },
];

/// Every registered task.
pub fn all_tasks() -> &'static [TaskSpec] {
    TASKS
}

/// Tasks carrying `tag`.
pub fn tasks_with_tag(tag: &str) -> Vec<&'static TaskSpec> {
    TASKS.iter().filter(|t| t.tags.contains(&tag)).collect()
}

/// Looks up a task by id (case-insensitive; the `-v0` suffix may be omitted).
pub fn find_task(id: &str) -> Result<&'static TaskSpec, EnvError> {
    let want = id.trim().to_ascii_lowercase();
    TASKS
        .iter()
        .find(|t| {
            let tid = t.id.to_ascii_lowercase();
            tid == want || tid.strip_suffix("-v0") == Some(want.as_str())
        })
        .ok_or_else(|| EnvError::UnknownTask {
            id: id.to_string(),
            known: TASKS.iter().map(|t| t.id).collect::<Vec<_>>().join(", "),
        })
}

/// Default config of `id` with `key=value` overrides applied and validated.
pub fn make_config<S: AsRef<str>>(id: &str, overrides: &[S]) -> Result<TaskConfig, EnvError> {
    let mut cfg = find_task(id)?.default_config();
    cfg.apply_overrides(overrides)?;
    cfg.validate()?;
    Ok(cfg)
}
