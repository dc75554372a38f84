//! Multi-timer (paper: Tasks / Multi-Timer; reference `MultiTimeProduction`): cued TDs,
//! reward 1 inside a window around TD, reduced outside.

use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::{CueMode, RewardMode, Rules};
use crate::settings::{self, Rule, Spec};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{CUE_TD_RULE, FIXED_TD_RULE, OVER, REDUCED, UNDER, param};
use crate::task::{FI_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};
use serde_json::json;

/// The multi-timer family.
pub(crate) struct MultiTimer;

const PARAMS: &[Spec] = &[
    param(
        "tds",
        &["oven_duration_list"],
        &["params", "tds"],
        Rule::List(&CUE_TD_RULE),
        "TD list (distinct; the value cue is a byte); an episode draws uniformly from the first num_timers",
    ),
    param(
        "num_timers",
        &[],
        &["params", "num_timers"],
        Rule::Int { lo: 1, hi: 255 },
        "active TDs, at most the length of tds (grows during a curriculum); setting tds lowers it to their count",
    ),
    param(
        "mode",
        &["undercooked_possible"],
        &["params", "mode"],
        Rule::Mapped {
            inner: &Rule::Choice(&["exact", "lower_bounded"]),
            synonyms: &[("true", "exact"), ("false", "lower_bounded")],
        },
        "exact: take the soup any time, reward 1 inside [TD-under, TD+over]; lower_bounded: take it at timer >= TD, reduced if later than TD+over",
    ),
    param(
        "cue",
        &[],
        &["params", "cue"],
        Rule::Mapped {
            inner: &Rule::Choice(&["value", "categorical"]),
            synonyms: &[("cat", "categorical")],
        },
        "oven channel-4 cue while on: the TD value (reference) or 1+index of the TD",
    ),
    UNDER,
    OVER,
    REDUCED,
    param(
        "td",
        &["oven_duration"],
        &["fixed_td"],
        FIXED_TD_RULE,
        "fix the TD of every episode (probes, OOD tests; value cue: at most 255, categorical cue: one of tds); none: drawn per episode",
    ),
];

fn distinct(values: &[u32]) -> bool {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    sorted.len() == values.len()
}

impl Family for MultiTimer {
    fn task(&self) -> TaskSpec {
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
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
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
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        FI_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        use ObjectKind::*;
        vec![OnionDispenser, DeliveryCounter, Oven]
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        let TaskParams::MultiTimer {
            tds, num_timers, ..
        } = &config.params
        else {
            return Err(wrong_family("multi-timer", &config.params));
        };
        if tds.is_empty() {
            return Err(EnvError::param("tds", "[]", "at least one TD in 1..=255"));
        }
        if !distinct(tds) {
            return Err(EnvError::param(
                "tds",
                settings::display(&serde_json::json!(tds)),
                "distinct integers 1..=255",
            ));
        }
        if *num_timers == 0 || *num_timers > tds.len() {
            return Err(EnvError::param(
                "num_timers",
                num_timers,
                format!("integer 1..={} (the length of tds)", tds.len()),
            ));
        }
        Ok(())
    }

    fn fixed_td_fits(&self, params: &TaskParams, td: u32) -> bool {
        match params {
            TaskParams::MultiTimer { cue, tds, .. } => match cue {
                CueMode::Value => (1..=255).contains(&td),
                CueMode::Categorical => tds.contains(&td),
            },
            _ => false,
        }
    }

    fn after_set(&self, params: &mut TaskParams, key: &str) {
        // Fewer TDs than active timers: the active count follows the list (as the
        // reference's curriculum never has more active timers than TDs).
        if let TaskParams::MultiTimer {
            tds, num_timers, ..
        } = params
            && key == "tds"
        {
            *num_timers = (*num_timers).min(tds.len()).max(1);
        }
    }

    fn rules(&self, config: &TaskConfig, _layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::MultiTimer {
            tds,
            mode,
            cue,
            under_buffer,
            over_buffer,
            reduced_reward,
            ..
        } = &config.params
        else {
            return Err(wrong_family("multi-timer", &config.params));
        };
        Ok(RuleSet {
            rules: Rules::Window {
                mode: *mode,
                under: *under_buffer,
                over: *over_buffer,
                reduced: *reduced_reward,
            },
            default_td: tds[0],
            tds: tds.clone(),
            cue: Some(*cue),
            rsg: None,
        })
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Produce)
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::MultiTimer
    }

    /// Every TD 1 … max(active) + 3 (out of distribution included; the active TDs only
    /// with the categorical cue, which has no code for others), and for every active TD the
    /// exact-window buffers 0, 25, 50 and 75% of TD.
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::MultiTimer {
            tds,
            num_timers,
            cue,
            ..
        } = &config.params
        else {
            return Err(wrong_family("multi-timer", &config.params));
        };
        let active = &tds[..(*num_timers).min(tds.len())];
        let max = active.iter().copied().max().unwrap_or(1);
        let probe: Vec<u32> = match cue {
            CueMode::Value => (1..=max + 3).collect(),
            CueMode::Categorical => active.to_vec(),
        };
        let mut out: Vec<Condition> = probe
            .into_iter()
            .map(|t| condition(ConditionKind::MultiTimer, task, t))
            .collect();
        for &t in active {
            for f in [0.0, 0.25, 0.5, 0.75] {
                let b = (f * f64::from(t)).round() as u32;
                let buffered = task.with_values(&[
                    ("mode", json!("exact")),
                    ("under_buffer", json!(b)),
                    ("over_buffer", json!(b)),
                ])?;
                let mut c = condition(ConditionKind::Buffer, &buffered, t);
                c.factor = Some(f);
                out.push(c);
            }
        }
        Ok(out)
    }

    /// The window's first paid step (exact mode) or TD (lower-bounded mode).
    fn paid_pickup_timer(&self, params: &TaskParams, td: u32) -> Option<i32> {
        let td = td as i32;
        match params {
            TaskParams::MultiTimer {
                mode: RewardMode::Exact,
                under_buffer,
                ..
            } => Some((td - *under_buffer as i32).max(1)),
            _ => Some(td),
        }
    }

    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        match params {
            TaskParams::MultiTimer {
                tds, num_timers, ..
            } => tds[..(*num_timers).min(tds.len())].to_vec(),
            _ => Vec::new(),
        }
    }

    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        match params {
            TaskParams::MultiTimer { tds, .. } => tds.iter().map(|&t| (t, None)).collect(),
            _ => Vec::new(),
        }
    }
}
