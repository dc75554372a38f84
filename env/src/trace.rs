//! JSON-lines episode traces, shared by `env replay`, `env play` and golden tests.
//!
//! Line 0 is the reset: `{"step":0,"action":null,"obs":…,"reward":0.0,
//! "terminated":false,"truncated":false,"info":{…},"task":…,"config":{…}}`.
//! Every later line is one step with the same keys (without task/config);
//! `obs` is the codes observation as nested `[row][col][channel]` integers. Multi-oven
//! lines add `"ovens":{…}`, every oven's state ([`OvenSet`]).
//! `env play` adds `"reset":{"seed":…,"options":{…}}` to its reset lines ([`ResetKey`]), so
//! a recording can be replayed and checked line by line ([`verify_recording`]).

use crate::action::Action;
use crate::env::ChronoEnv;
use crate::error::EnvError;
use crate::info::{Info, OvenSet};
use crate::kitchen::{ResetOptions, Transition};
use crate::task::TaskConfig;
use serde::{Deserialize, Serialize};

/// How the episode of a recorded reset line is reproduced: the seed its reset used
/// (`None`: the generator went on from the recording's previous episode, as `env play`
/// does after its first) and the reset options.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ResetKey {
    /// Seed of the reset (`None` after the first episode of a session).
    pub seed: Option<u64>,
    /// Reset options.
    pub options: ResetOptions,
}

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
    /// Multi-oven task: every oven's state after the step (absent for the other tasks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ovens: Option<OvenSet>,
    /// Task id (reset line only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
    /// Resolved configuration (reset line only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub config: Option<serde_json::Value>,
    /// How the reset is reproduced (reset lines of `env play` recordings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reset: Option<ResetKey>,
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
            ovens: env.ovens(),
            task: Some(env.config().id.clone()),
            config: serde_json::to_value(env.config()).ok(),
            reset: None,
        }
    }

    /// This reset line with the seed and options its reset used, so the episode can be
    /// replayed ([`verify_recording`]).
    pub fn with_reset_key(mut self, seed: Option<u64>, options: ResetOptions) -> Self {
        self.reset = Some(ResetKey { seed, options });
        self
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
            ovens: env.ovens(),
            task: None,
            config: None,
            reset: None,
        }
    }

    /// The task configuration of a reset line (its `config`); the error names the field.
    pub fn task_config(&self) -> Result<TaskConfig, String> {
        let value = self
            .config
            .clone()
            .ok_or_else(|| "reset line without `config`".to_string())?;
        serde_json::from_value(value).map_err(|e| format!("`config`: {e}"))
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

/// Checks a recording (`(line number, line)` pairs, in file order) against the task: every
/// episode whose reset line carries its [`ResetKey`] is replayed — the env rebuilt from the
/// line's config where the reset has a seed, the generator continued where it has none —
/// and every recorded line must equal the replay's. An edited reward, observation or info
/// field, a step after the episode ended, or an episode cut short before the session's next
/// one, is an error naming the line (and the field).
/// Episodes without a key (recordings made before keys were written) are not checked.
pub fn verify_recording(lines: &[(usize, TraceLine)]) -> Result<(), String> {
    let mut env: Option<ChronoEnv> = None;
    let mut replaying = false;
    for (n, line) in lines {
        let n = *n;
        match (line.action, line.reset) {
            (None, None) => replaying = false,
            (None, Some(key)) => {
                // `env play` continues its generator (no seed) only after an episode ended: a
                // continued reset after an unfinished episode means steps were cut out.
                if key.seed.is_none() && replaying && env.as_ref().is_some_and(|e| !e.is_done()) {
                    return Err(format!(
                        "line {n}: a new episode continues the session, but the episode before \
                         it did not end (its last steps are missing)"
                    ));
                }
                let config = line.task_config().map_err(|e| format!("line {n}: {e}"))?;
                let same_task = env.as_ref().is_some_and(|e| *e.config() == config);
                if key.seed.is_some() || !same_task {
                    if key.seed.is_none() {
                        return Err(format!(
                            "line {n}: `reset.seed` is null but no earlier episode of this \
                             task precedes it, so the episode cannot be replayed"
                        ));
                    }
                    env = Some(
                        ChronoEnv::new(&config).map_err(|e| format!("line {n}: `config`: {e}"))?,
                    );
                }
                let e = env.as_mut().expect("built above");
                let info = e
                    .reset(key.seed, &key.options)
                    .map_err(|err| format!("line {n}: `reset.options`: {err}"))?;
                let expect = TraceLine::reset(e, info).with_reset_key(key.seed, key.options);
                compare_lines(n, &expect, line)?;
                replaying = true;
            }
            (Some(code), _) if replaying => {
                let e = env.as_mut().expect("a replayed reset precedes");
                if e.is_done() {
                    return Err(format!("line {n}: a step after the episode ended"));
                }
                let a = Action::from_code(i64::from(code))
                    .map_err(|err| format!("line {n}: `action`: {err}"))?;
                let t = e.step(a).map_err(|err| format!("line {n}: {err}"))?;
                compare_lines(n, &TraceLine::step(e, a, &t), line)?;
            }
            (Some(_), _) => {}
        }
    }
    Ok(())
}

/// Equal lines, or an error naming line `n`'s first field that differs from the replay.
fn compare_lines(n: usize, expect: &TraceLine, got: &TraceLine) -> Result<(), String> {
    if expect == got {
        return Ok(());
    }
    let (e, g) = (
        serde_json::to_value(expect).unwrap_or_default(),
        serde_json::to_value(got).unwrap_or_default(),
    );
    let field = first_difference(&e, &g, "").unwrap_or_else(|| "the line".into());
    Err(format!(
        "line {n}: recorded `{field}` differs from the task's replay of this episode (the \
         recording was edited, or made by another version of the task)"
    ))
}

/// The path (`info.td`, `obs[2][3][0]`) of the first value that differs between two JSON
/// values, `None` when they are equal.
fn first_difference(a: &serde_json::Value, b: &serde_json::Value, path: &str) -> Option<String> {
    use serde_json::Value;
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            keys.into_iter().find_map(|k| {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                match (x.get(k), y.get(k)) {
                    (Some(u), Some(v)) => first_difference(u, v, &p),
                    _ => Some(p),
                }
            })
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .find_map(|(i, (u, v))| first_difference(u, v, &format!("{path}[{i}]"))),
        _ => (a != b).then(|| path.to_string()),
    }
}
