//! Linear SARSA(λ) over (discrete state × temporal features).
//!
//! `Q(s, a) = θ_{s,a} · φ` where `s` is the discrete env state the agent sees (cell,
//! hands, visible oven) and `φ` the temporal features of its timing model (with a bias
//! unit). Replacing traces per `(s, a)` block (`e_{s,a} ← φ` on a visit, all traces
//! decay by `γλ`), step size `α / max(1, |φ|²)` (normalised LMS), ε-greedy exploration.
//! Weights are stored sparsely (only visited pairs), in a `BTreeMap` so that saved
//! agents are byte-identical across runs.

use rand::Rng;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Hyperparameters of [`SarsaLambda`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SarsaConfig {
    /// Learning rate `α`.
    pub alpha: f64,
    /// Discount `γ` per step.
    pub gamma: f64,
    /// Trace decay `λ`.
    pub lambda: f64,
}

impl Default for SarsaConfig {
    /// Ludvig et al.'s TD values: α 0.05, γ 0.97, λ 0.95.
    fn default() -> Self {
        SarsaConfig {
            alpha: 0.05,
            gamma: 0.97,
            lambda: 0.95,
        }
    }
}

/// Sparse linear SARSA(λ) with `actions` actions and `features` features per pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SarsaLambda {
    /// Hyperparameters.
    pub config: SarsaConfig,
    /// Number of actions.
    pub actions: usize,
    /// Features per state–action pair (bias included).
    pub features: usize,
    /// `θ` blocks keyed by `s · actions + a`.
    pub weights: BTreeMap<u32, Vec<f64>>,
    /// Initial bias weight of a pair not visited before (its `Q` before any update, with
    /// the bias feature first): 0, or optimistic (> 0) for systematic exploration —
    /// optimistic initial values, Sutton & Barto (2018) §2.6.
    #[serde(default)]
    pub q_init: f64,
    #[serde(skip)]
    traces: Vec<(u32, Vec<f64>)>,
}

impl SarsaLambda {
    /// An all-zero learner.
    pub fn new(config: SarsaConfig, actions: usize, features: usize) -> Self {
        SarsaLambda {
            config,
            actions,
            features,
            weights: BTreeMap::new(),
            q_init: 0.0,
            traces: Vec::new(),
        }
    }

    fn key(&self, state: u32, action: usize) -> u32 {
        state * self.actions as u32 + action as u32
    }

    /// `Q(s, a)` for features `phi`.
    pub fn q(&self, state: u32, action: usize, phi: &[f64]) -> f64 {
        self.weights
            .get(&self.key(state, action))
            .map(|w| w.iter().zip(phi).map(|(a, b)| a * b).sum())
            .unwrap_or_else(|| self.q_init * phi.first().copied().unwrap_or(0.0))
    }

    /// `Q(s, ·)` into `out`.
    pub fn q_all(&self, state: u32, phi: &[f64], out: &mut Vec<f64>) {
        out.clear();
        out.extend((0..self.actions).map(|a| self.q(state, a, phi)));
    }

    /// ε-greedy choice among `allowed` actions (ties broken at random); greedy with the
    /// lowest index on ties when `epsilon` is 0 and `rng` is not consulted.
    pub fn choose<R: Rng + ?Sized>(
        &self,
        q: &[f64],
        allowed: &[usize],
        epsilon: f64,
        rng: &mut R,
    ) -> usize {
        if epsilon > 0.0 && rng.random::<f64>() < epsilon {
            return allowed[rng.random_range(0..allowed.len())];
        }
        let best = allowed
            .iter()
            .map(|&a| q[a])
            .fold(f64::NEG_INFINITY, f64::max);
        let ties: Vec<usize> = allowed
            .iter()
            .copied()
            .filter(|&a| q[a] >= best - 1e-12)
            .collect();
        if epsilon > 0.0 && ties.len() > 1 {
            ties[rng.random_range(0..ties.len())]
        } else {
            ties[0]
        }
    }

    /// Clears the traces (start of an episode).
    pub fn clear_traces(&mut self) {
        self.traces.clear();
    }

    /// Marks `(s, a)` with features `phi` as just visited (replacing trace).
    pub fn visit(&mut self, state: u32, action: usize, phi: &[f64]) {
        let key = self.key(state, action);
        let base = state * self.actions as u32;
        self.traces
            .retain(|(k, _)| *k == key || *k < base || *k >= base + self.actions as u32);
        match self.traces.iter_mut().find(|(k, _)| *k == key) {
            Some((_, e)) => e.copy_from_slice(phi),
            None => self.traces.push((key, phi.to_vec())),
        }
    }

    /// Applies TD error `delta` along the traces (step `α/max(1, |φ|²)` for the
    /// features `phi` of the updated pair), then decays the traces by `γλ`.
    pub fn apply(&mut self, delta: f64, phi_norm2: f64) {
        let step = self.config.alpha / phi_norm2.max(1.0) * delta;
        let (n, q0) = (self.features, self.q_init);
        for (key, e) in &self.traces {
            let w = self.weights.entry(*key).or_insert_with(|| {
                let mut w = vec![0.0; n];
                w[0] = q0;
                w
            });
            for (wi, ei) in w.iter_mut().zip(e) {
                *wi += step * ei;
            }
        }
        let decay = self.config.gamma * self.config.lambda;
        for (_, e) in &mut self.traces {
            e.iter_mut().for_each(|v| *v *= decay);
        }
        self.traces
            .retain(|(_, e)| e.iter().any(|v| v.abs() > 1e-4));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unvisited_pairs_are_worth_q_init_and_updates_start_from_it() {
        let mut l = SarsaLambda::new(SarsaConfig::default(), 2, 3);
        let phi = [1.0, 0.0, 1.0]; // bias, two features
        assert_eq!(l.q(7, 1, &phi), 0.0);
        l.q_init = 1.0;
        assert_eq!(l.q(7, 1, &phi), 1.0, "optimistic before any visit");
        // One TD error δ on (7, 1): the new block starts at bias q_init, then moves by
        // α/|φ|² δ along the trace φ (normalised LMS).
        l.visit(7, 1, &phi);
        let delta = -0.5;
        l.apply(delta, 2.0);
        let step = 0.05 / 2.0 * delta;
        assert_eq!(l.weights[&(7 * 2 + 1)], vec![1.0 + step, 0.0, step]);
        assert!((l.q(7, 1, &phi) - (1.0 + 2.0 * step)).abs() < 1e-12);
        // Other pairs keep their optimism.
        assert_eq!(l.q(7, 0, &phi), 1.0);
    }
}
