//! Deterministic evaluation of a policy from every free start cell (the reference protocol's
//! core): one episode per start cell per evaluated TD, greedy actions.

use crate::ppo::act::{argmax, policy_step};
use crate::ppo::config::ObsEncoding;
use crate::ppo::obs::ObsEncoder;
use chronocooked_env::{
    Action, Autoreset, EnvError, ResetOption, ResetOptions, TaskConfig, VecEnv,
};
use chronocooked_models::ActorCritic;
use serde::{Deserialize, Serialize};

/// Result of one evaluation episode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EvalEpisode {
    /// Start cell `(row, col)`.
    pub start: (usize, usize),
    /// Target duration of the episode.
    pub td: u32,
    /// Undiscounted return.
    pub ret: f32,
    /// Steps taken.
    pub len: u32,
    /// Ended in a success (`chronocooked_models::agent::is_success`).
    pub success: bool,
}

/// Runs one greedy episode per (free start cell × TD) in `tds`, all in one batch.
pub fn evaluate_policy(
    policy: &ActorCritic,
    config: &TaskConfig,
    encoding: ObsEncoding,
    tds: &[u32],
) -> Result<Vec<EvalEpisode>, EnvError> {
    let free: Vec<(usize, usize)> = {
        let env = chronocooked_env::ChronoEnv::new(config)?;
        env.layout().free_coords()
    };
    let conds: Vec<((usize, usize), u32)> = tds
        .iter()
        .flat_map(|&td| free.iter().map(move |&s| (s, td)))
        .collect();
    let n = conds.len();
    let mut envs = VecEnv::new(config, n, Autoreset::Disabled)?;
    for (i, &(start, td)) in conds.iter().enumerate() {
        let opts = ResetOptions {
            start: Some(start),
            td: Some(td),
            // Normal episodes only, where the task has never-ready ones.
            never_ready: config
                .reset_options()
                .contains(&ResetOption::NeverReady)
                .then_some(false),
            ..ResetOptions::default()
        };
        envs.reset_one(i, Some(chronocooked_env::derive_seed(7, i as u64)), &opts)?;
    }
    let mut encoder = ObsEncoder::new(encoding, &envs)
        .for_input(policy.input_channels())
        .map_err(|why| EnvError::InvalidParam {
            field: "policy".into(),
            value: format!("{} input channels", policy.input_channels()),
            allowed: why,
        })?;
    let (cells, ch) = (encoder.cells(), encoder.input_channels());
    let device = chronocooked_models::cpu();
    let mut state = policy.zero_state(n, &device);
    let mut obs = vec![0f32; n * encoder.len()];
    let keep = vec![1f32; n];
    let mut out: Vec<EvalEpisode> = conds
        .iter()
        .map(|&(start, td)| EvalEpisode {
            start,
            td,
            ret: 0.0,
            len: 0,
            success: false,
        })
        .collect();
    let mut done = vec![false; n];
    while done.iter().any(|d| !d) {
        encoder.encode_batch(&envs.obs, &mut obs);
        let (logits, _, st) = policy_step(policy, &obs, cells, ch, &keep, state, &device);
        state = st;
        // Finished episodes are skipped (their action is ignored).
        let actions: Vec<u8> = (0..n)
            .map(|i| {
                if done[i] {
                    0
                } else {
                    argmax(&logits[i * Action::COUNT..(i + 1) * Action::COUNT]) as u8
                }
            })
            .collect();
        envs.step_masked(&actions, &done)?;
        for i in 0..n {
            if done[i] {
                continue;
            }
            let e = &mut out[i];
            e.ret += envs.rewards[i];
            e.len += 1;
            if envs.terminated[i] || envs.truncated[i] {
                done[i] = true;
                e.success = chronocooked_models::agent::is_success(&envs.infos[i], envs.rewards[i]);
            }
        }
    }
    Ok(out)
}
