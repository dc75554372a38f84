//! The conditions a deterministic evaluation covers, for every kind of run (PPO policies in
//! [`crate::ppo::evaluate`], timing agents in [`crate::timing_run`]).

use chronocooked_env::TaskConfig;

/// The TDs the deterministic evaluation covers, as the task's family declares them
/// ([`TaskConfig::evaluation_tds`]): bisection → both anchors; multi-timer → the active TDs;
/// multi-anchor → the active anchors; multi-oven → the short and the long anchor (every
/// oven at that TD); reproduction → every sample interval of its priors; other tasks →
/// their TD.
pub fn eval_tds(config: &TaskConfig) -> Vec<u32> {
    config.evaluation_tds()
}
