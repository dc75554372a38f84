//! The conditions a deterministic evaluation covers, for every kind of run (PPO policies in
//! [`crate::ppo::evaluate`], timing agents in [`crate::timing_run`]).

use chronocooked_env::{TaskConfig, TaskParams};

/// The TDs the deterministic evaluation covers: bisection → both anchors; multi-timer →
/// the active TDs; multi-anchor → the active anchors; multi-oven → the short and the long
/// anchor (every oven at that TD); reproduction → every sample interval of its priors;
/// other tasks → their TD.
pub fn eval_tds(config: &TaskConfig) -> Vec<u32> {
    match &config.params {
        TaskParams::Bisection { short, long, .. } | TaskParams::MultiOven { short, long, .. } => {
            vec![*short, *long]
        }
        TaskParams::MultiTimer {
            tds, num_timers, ..
        } => tds[..(*num_timers).min(tds.len())].to_vec(),
        TaskParams::MultiAnchor { .. } => config.params.active_anchors().unwrap_or(&[]).to_vec(),
        TaskParams::Reproduction { priors, .. } => {
            let mut ts: Vec<u32> = priors
                .iter()
                .filter_map(|p| chronocooked_env::task::parse_prior(p).ok())
                .flat_map(|(lo, hi)| lo..=hi)
                .collect();
            ts.sort_unstable();
            ts.dedup();
            ts
        }
        p => vec![p.td().unwrap_or(12)],
    }
}
