//! JSON-lines episode traces, shared by `env replay`, `env play` and golden tests.
//!
//! Line 0 is the reset: `{"step":0,"action":null,"obs":…,"reward":0.0,
//! "terminated":false,"truncated":false,"info":{…},"task":…,"config":{…}}`.
//! Every later line is one step with the same keys (without task/config);
//! `obs` is the codes observation as nested `[row][col][channel]` integers.

use crate::action::Action;
use crate::env::ChronoEnv;
use crate::error::EnvError;
use crate::info::Info;
use crate::kitchen::{ResetOptions, Transition};
use serde::{Deserialize, Serialize};

/// One line of a trace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TraceLine {
    /// 0 for the reset line, then the step number.
    pub step: u32,
    /// Action code of this step (`None` on the reset line).
    pub action: Option<u8>,
    /// Codes observation after the step, `[row][col][channel]`.
    pub obs: Vec<Vec<Vec<u8>>>,
    /// Reward of the step.
    pub reward: f32,
    /// Terminal state reached.
    pub terminated: bool,
    /// Cut by the time limit.
    pub truncated: bool,
    /// Step info.
    pub info: Info,
    /// Task id (reset line only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
    /// Resolved configuration (reset line only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub config: Option<serde_json::Value>,
}

impl TraceLine {
    /// The reset line for `env` after `reset`.
    pub fn reset(env: &ChronoEnv, info: Info) -> Self {
        TraceLine {
            step: 0,
            action: None,
            obs: env.obs_nested(),
            reward: 0.0,
            terminated: false,
            truncated: false,
            info,
            task: Some(env.config().id.clone()),
            config: serde_json::to_value(env.config()).ok(),
        }
    }

    /// The line for a step of `env` with `action`.
    pub fn step(env: &ChronoEnv, action: Action, t: &Transition) -> Self {
        TraceLine {
            step: t.info.timestep,
            action: Some(action.code()),
            obs: env.obs_nested(),
            reward: t.reward,
            terminated: t.terminated,
            truncated: t.truncated,
            info: t.info,
            task: None,
            config: None,
        }
    }

    /// Serialises the line as compact JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
    }
}

/// Resets `env` with `options` and plays `actions`, stopping at the end of the episode.
///
/// Actions after the episode ended are an error (the trace would be meaningless).
pub fn replay(
    env: &mut ChronoEnv,
    seed: Option<u64>,
    options: &ResetOptions,
    actions: &[Action],
) -> Result<Vec<TraceLine>, EnvError> {
    let info = env.reset(seed, options)?;
    let mut lines = vec![TraceLine::reset(env, info)];
    for (i, &a) in actions.iter().enumerate() {
        if env.is_done() {
            return Err(EnvError::BadOverride {
                text: format!("action #{i} ({})", a.code()),
                reason: format!(
                    "the episode ended at step {}; {} action(s) left over",
                    i,
                    actions.len() - i
                ),
            });
        }
        let t = env.step(a)?;
        lines.push(TraceLine::step(env, a, &t));
    }
    Ok(lines)
}
