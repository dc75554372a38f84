//! The self-describing task registry: versioned ids → documented default configurations.

use crate::error::EnvError;
use crate::markdown::Table;
use crate::task::params;
use crate::task::{
    AUTO_LAYOUT, BISECTION_LAYOUT, CueMode, DUAL_LAYOUT, FI_LAYOUT, RewardMode, TaskConfig,
    TaskFamily, TaskParams, UNCERTAINTY_LAYOUT,
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
            TaskFamily::MultiAnchor => (
                AUTO_LAYOUT,
                TaskParams::MultiAnchor {
                    anchors: vec![4, 8, 12],
                    num_anchors: None,
                },
            ),
            TaskFamily::Reproduction => (
                AUTO_LAYOUT,
                TaskParams::Reproduction {
                    priors: vec!["short".into(), "long".into()],
                    prior_cue: true,
                    gains: vec![1.0],
                    tolerance: 0.2,
                    tolerance_steps: 1.0,
                    foreperiod_min: 2,
                    foreperiod_max: 6,
                },
            ),
            TaskFamily::MultiOven => (
                AUTO_LAYOUT,
                TaskParams::MultiOven {
                    short: 4,
                    long: 12,
                    ovens: 2,
                    asynchronous: false,
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
    },
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
    },
    TaskSpec {
        id: "Reproduction-v0",
        family: TaskFamily::Reproduction,
        tags: &["timing", "reproduction", "production", "ready-set-go"],
        summary: "Temporal reproduction (Ready-Set-Go): reproduce the interval between two oven cues",
        description: "Layout 5x3 `..D/.../V../.../...`: delivery (0,2) code 4, oven (2,0) code 5, loaded \
(no onion). Measurement: after a foreperiod (2-6 steps) the oven flashes Ready (channel 4 = 2 for one \
step), and ts steps later Set; ts is drawn uniformly from the episode's prior (default short 8-14 or \
long 14-20 steps, Jazayeri & Shadlen 2010's priors scaled to steps; the counter's channel 4 shows \
which, prior_cue=true). Production: the oven shows on (1) from Set; taking the soup out tp steps \
after Set produces tp, and delivering it pays max(0, 1 - |tp - g*ts| / w) with w = tolerance*g*ts \
+ tolerance_steps (linear in the error inside a window that scales with the interval, as Jazayeri \
& Shadlen 2010 rewarded; defaults 0.2 and 1 step, NeuroGym ReadySetGo's 0.2*t + c). Taking the soup \
before Set does nothing; a late soup is delivered unpaid (the episode ends at delivery or the \
time limit). Gains g (default 1; 1,1.5 \
as Remington et al. 2018) are cued on the counter. Design decisions (the public code has no \
reproduction task; the paper names it as future work): cues as oven flashes, the loaded oven, \
reward at delivery.",
        source: "paper Discussion (future work); Jazayeri & Shadlen 2010; Remington et al. 2018 (design decisions documented)",
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

/// The guide's table (docs/tasks.md) of every registered task's own parameters, then the common ones
/// (generated; a test compares it with docs/tasks.md). It lives with the registry, which
/// knows every task, so that the parameter tables (`task::params`) need not know the registry.
pub fn parameters_markdown() -> String {
    let mut table = Table::new([
        "task",
        "key (aliases)",
        "type",
        "default",
        "allowed",
        "meaning",
    ]);
    let mut line = |task: &str, r: &params::ParamRow| {
        let aliases = if r.aliases.is_empty() {
            String::new()
        } else {
            format!(" ({})", r.aliases.join(", "))
        };
        table.row([
            task.to_string(),
            format!("`{}`{aliases}", r.key),
            r.kind.clone(),
            format!("`{}`", r.default),
            r.allowed.clone(),
            r.doc.clone(),
        ]);
    };
    let mut common = Vec::new();
    for t in all_tasks() {
        let config = t.default_config();
        for r in params::rows(&config) {
            if params::COMMON.iter().any(|c| c.key == r.key) {
                if common.is_empty() || !common.iter().any(|c: &params::ParamRow| c.key == r.key) {
                    common.push(r);
                }
            } else {
                line(&format!("`{}`", t.id), &r);
            }
        }
    }
    for r in &common {
        line("every task", r);
    }
    table.render()
}
