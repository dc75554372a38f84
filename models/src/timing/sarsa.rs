//! Linear SARSA(λ) over (discrete state × temporal features).
//!
//! `Q(s, a) = θ_{s,a} · φ` where `s` is the discrete env state the agent sees (cell,
//! hands, visible oven) and `φ` the temporal features of its timing model (with a bias
//! unit). Replacing traces per `(s, a)` block (`e_{s,a} ← φ` on a visit, all traces
//! decay by `γλ`), step size `α / max(1, |φ|²)` (normalised LMS), ε-greedy exploration.
//! Optionally each weight's step has a floor that falls with how often its feature was
//! active in the pair, `max(α, nᵢ^−ω) / max(1, |φ|²)`: Even-Dar & Mansour's (2003)
//! polynomial learning rate `1/n(s, a)^ω`, ω ∈ (1/2, 1), per feature
//! ([`SarsaLambda::set_visit_power`]); for one-hot features it is their per-pair rate.
//! Weights are stored sparsely (only visited pairs), in a `BTreeMap` so that saved
//! agents are byte-identical across runs. Features travel as their nonzero entries
//! ([`Active`]): traces store only those, and `Q`, the updates and the decay read only those.
//! The time cells' conjunctive code on the reproduction task (`[cells²]` features, one or two
//! of them nonzero for the delay line) is otherwise read whole by every trace on every step.
//! Skipping a zero feature adds nothing a dense sum would not (`w + 0·e = w`, and the bias
//! feature comes first), so the values are the same bit for bit.

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
    traces: Vec<Trace>,
    /// Exponent ω of the visit-count step floor (0 = off); set for a training run only.
    #[serde(skip)]
    visit_power: f64,
    /// Per pair, per feature: the summed squared activity `nᵢ = Σ φᵢ²` over the pair's
    /// visits and the step floor `max(1, nᵢ)^−ω` it gives.
    #[serde(skip)]
    visits: BTreeMap<u32, Visits>,
}

/// The nonzero entries of a feature vector `φ` (`[features]`): their indices, increasing,
/// and their values.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Active {
    /// Indices `i` with `φᵢ ≠ 0`, increasing.
    index: Vec<u32>,
    /// `φᵢ` at those indices.
    value: Vec<f64>,
}

impl Active {
    /// The nonzero entries of `phi`.
    pub fn of(phi: &[f64]) -> Self {
        let mut active = Active::default();
        active.fill(phi);
        active
    }

    /// Replaces the entries with the nonzero entries of `phi` (keeping the allocations).
    pub fn fill(&mut self, phi: &[f64]) {
        self.index.clear();
        self.value.clear();
        for (i, &x) in phi.iter().enumerate() {
            if x != 0.0 {
                self.index.push(i as u32);
                self.value.push(x);
            }
        }
    }

    /// `|φ|²`.
    pub fn norm2(&self) -> f64 {
        self.value.iter().map(|v| v * v).sum()
    }

    /// `w · φ` for weights `w` (`[features]`), summed in index order.
    fn dot(&self, w: &[f64]) -> f64 {
        self.index
            .iter()
            .zip(&self.value)
            .map(|(&i, v)| w[i as usize] * v)
            .sum()
    }

    /// The first feature's value (the bias), 0 when it is not active.
    fn first(&self) -> f64 {
        match self.index.first() {
            Some(0) => self.value[0],
            _ => 0.0,
        }
    }
}

/// The eligibility trace of one state–action pair: its nonzero entries (every other entry
/// is exactly 0, and decaying keeps it so).
#[derive(Debug, Clone, PartialEq)]
struct Trace {
    /// The pair's key (`s · actions + a`).
    key: u32,
    /// `e`'s nonzero entries.
    e: Active,
}

/// How often each feature of one state–action pair was active ([`SarsaLambda::visit`]).
#[derive(Debug, Clone, PartialEq)]
struct Visits {
    /// `nᵢ = Σ φᵢ²` over the pair's visits.
    count: Vec<f64>,
    /// `max(1, nᵢ)^−ω`.
    floor: Vec<f64>,
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
            visit_power: 0.0,
            visits: BTreeMap::new(),
        }
    }

    /// Turns the visit-count step floor on with exponent `power` (ω; 0 turns it off) and
    /// forgets every count. With it a weight steps by `max(α, nᵢ^−ω) / max(1, |φ|²)` where
    /// `nᵢ` is its feature's summed squared activity over the pair's visits: a feature
    /// seen a few times learns from its first samples at a rate near `1/n` (for a lone
    /// feature with ω = 1 the weight is the sample average of its targets), one seen
    /// thousands of times at the annealed `α`. Under one global step size annealed by
    /// episode, a pair first visited late starts from its initial value at a small `α` and
    /// stays near it for hundreds of visits (Even-Dar & Mansour 2003: polynomial rates
    /// `1/n^ω`, ω ∈ (1/2, 1), converge in time polynomial in `1/(1 − γ)`). The counts are
    /// not saved with the learner: the floor belongs to one training run.
    pub fn set_visit_power(&mut self, power: f64) {
        self.visit_power = power;
        self.visits.clear();
    }

    fn key(&self, state: u32, action: usize) -> u32 {
        state * self.actions as u32 + action as u32
    }

    /// `Q(s, a)` for features `phi`.
    pub fn q(&self, state: u32, action: usize, phi: &[f64]) -> f64 {
        self.q_active(state, action, &Active::of(phi))
    }

    /// `Q(s, a)` for the features whose nonzero entries are `phi`.
    pub fn q_active(&self, state: u32, action: usize, phi: &Active) -> f64 {
        self.weights
            .get(&self.key(state, action))
            .map(|w| phi.dot(w))
            .unwrap_or_else(|| self.q_init * phi.first())
    }

    /// `Q(s, ·)` into `out`.
    pub fn q_all(&self, state: u32, phi: &[f64], out: &mut Vec<f64>) {
        self.q_all_active(state, &Active::of(phi), out);
    }

    /// `Q(s, ·)` into `out`, for the features whose nonzero entries are `phi`.
    pub fn q_all_active(&self, state: u32, phi: &Active, out: &mut Vec<f64>) {
        out.clear();
        out.extend((0..self.actions).map(|a| self.q_active(state, a, phi)));
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
        self.visit_active(state, action, &Active::of(phi));
    }

    /// Marks `(s, a)` with the features whose nonzero entries are `phi` as just visited
    /// (replacing trace).
    pub fn visit_active(&mut self, state: u32, action: usize, phi: &Active) {
        let key = self.key(state, action);
        let base = state * self.actions as u32;
        self.traces
            .retain(|t| t.key == key || t.key < base || t.key >= base + self.actions as u32);
        if self.visit_power > 0.0 {
            let (n, power) = (self.features, self.visit_power);
            let v = self.visits.entry(key).or_insert_with(|| Visits {
                count: vec![0.0; n],
                floor: vec![1.0; n],
            });
            for (&i, x) in phi.index.iter().zip(&phi.value) {
                let c = &mut v.count[i as usize];
                *c += x * x;
                v.floor[i as usize] = c.max(1.0).powf(-power);
            }
        }
        match self.traces.iter_mut().find(|t| t.key == key) {
            Some(t) => t.e.clone_from(phi),
            None => self.traces.push(Trace {
                key,
                e: phi.clone(),
            }),
        }
    }

    /// Applies TD error `delta` along the traces (step `α/max(1, |φ|²)` for the
    /// features `phi` of the updated pair, or `max(α, nᵢ^−ω)/max(1, |φ|²)` per weight with
    /// the visit-count floor), then decays the traces by `γλ`.
    pub fn apply(&mut self, delta: f64, phi_norm2: f64) {
        let norm = phi_norm2.max(1.0);
        let alpha = self.config.alpha;
        let step = alpha / norm * delta;
        let (n, q0) = (self.features, self.q_init);
        for Trace { key, e } in &self.traces {
            let w = self.weights.entry(*key).or_insert_with(|| {
                let mut w = vec![0.0; n];
                w[0] = q0;
                w
            });
            // Off: no count lookup on the hot path.
            let floor = if self.visit_power > 0.0 {
                self.visits.get(key)
            } else {
                None
            };
            let entries = e.index.iter().zip(&e.value);
            match floor {
                Some(v) => {
                    for (&i, ei) in entries {
                        let i = i as usize;
                        w[i] += v.floor[i].max(alpha) / norm * delta * ei;
                    }
                }
                // Every feature active: one pass over the block (vectorised).
                None if e.index.len() == w.len() => {
                    for (wi, ei) in w.iter_mut().zip(&e.value) {
                        *wi += step * ei;
                    }
                }
                None => {
                    for (&i, ei) in entries {
                        w[i as usize] += step * ei;
                    }
                }
            }
        }
        let decay = self.config.gamma * self.config.lambda;
        for t in &mut self.traces {
            t.e.value.iter_mut().for_each(|v| *v *= decay);
        }
        self.traces
            .retain(|t| t.e.value.iter().any(|v| v.abs() > 1e-4));
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

    /// With ω = 1 a lone feature's weight is the sample average of its targets — the
    /// textbook `1/n` rule (Sutton & Barto 2018 §2.4) — whatever the (tiny) `α`; with the
    /// floor off it moves by `α δ` per update; with ω = 0.85 it steps by `n^−0.85` until
    /// that falls below `α`, and by `α` after.
    #[test]
    fn the_visit_count_floor_gives_sample_averages_at_power_one_and_alpha_after() {
        let targets = [0.3, 1.0, 0.0, 0.7, 0.2, 0.9, 0.4];
        let config = SarsaConfig {
            alpha: 1e-6,
            ..SarsaConfig::default()
        };
        let run = |power: f64, targets: &[f64]| {
            let mut l = SarsaLambda::new(config.clone(), 1, 1);
            l.set_visit_power(power);
            let mut steps = Vec::new();
            for &r in targets {
                l.clear_traces();
                l.visit(0, 0, &[1.0]);
                let before = l.q(0, 0, &[1.0]);
                let delta = r - before;
                l.apply(delta, 1.0);
                steps.push((l.q(0, 0, &[1.0]) - before) / delta);
            }
            (l.q(0, 0, &[1.0]), steps)
        };
        let (avg, _) = run(1.0, &targets);
        let mean = targets.iter().sum::<f64>() / targets.len() as f64;
        assert!((avg - mean).abs() < 1e-12, "{avg} vs mean {mean}");
        let (off, _) = run(0.0, &targets[..1]);
        assert!((off - 1e-6 * 0.3).abs() < 1e-15, "{off}");
        let (_, steps) = run(0.85, &[1.0, 3.0, -2.0, 5.0, 0.5, 4.0]);
        for (i, s) in steps.iter().enumerate() {
            let expected = ((i + 1) as f64).powf(-0.85);
            assert!(
                (s - expected).abs() < 1e-9,
                "visit {}: {s} vs {expected}",
                i + 1
            );
        }
        // A learner with step size `alpha` and the floor at ω = 0.85, whose pair (0, 0) was
        // visited `visits` times with features `seen`.
        let visited = |alpha: f64, seen: &[f64], visits: usize| {
            let config = SarsaConfig {
                alpha,
                ..SarsaConfig::default()
            };
            let mut l = SarsaLambda::new(config, 1, seen.len());
            l.set_visit_power(0.85);
            for _ in 0..visits {
                l.clear_traces();
                l.visit(0, 0, seen);
            }
            l.clear_traces();
            l
        };
        // Where the floor falls below α, α rules.
        let mut l = visited(0.05, &[1.0], 100);
        l.visit(0, 0, &[1.0]);
        l.apply(1.0, 1.0);
        assert!(
            (l.q(0, 0, &[1.0]) - 0.05).abs() < 1e-12,
            "101 visits: step α"
        );
        // A one-hot feature seen once, beside a bias seen on every visit: its own weight
        // takes the large step, the bias the annealed one (normalised by |φ|² = 2).
        let mut l = visited(0.01, &[1.0, 1.0, 0.0], 500);
        l.visit(0, 0, &[1.0, 0.0, 1.0]);
        l.apply(1.0, 2.0);
        let w = &l.weights[&0];
        assert!(
            (w[0] - 0.01 / 2.0).abs() < 1e-12 && (w[2] - 0.5).abs() < 1e-12,
            "{w:?}"
        );
        assert_eq!(w[1], 0.0);
        // Turning it off (or on again) forgets the counts.
        l.set_visit_power(0.0);
        assert!(l.visits.is_empty());
    }

    /// The textbook dense SARSA(λ) of the module's formulas (every trace read whole), the
    /// reference the sparse learner must equal bit for bit.
    struct Dense {
        weights: BTreeMap<u32, Vec<f64>>,
        traces: Vec<(u32, Vec<f64>)>,
    }

    impl Dense {
        fn q(&self, key: u32, phi: &[f64], q_init: f64) -> f64 {
            self.weights
                .get(&key)
                .map(|w| w.iter().zip(phi).map(|(a, b)| a * b).sum())
                .unwrap_or(q_init * phi[0])
        }
    }

    proptest::proptest! {
        /// Random episodes over sparse and dense features (mostly zeros, or mostly not),
        /// with and without the visit-count floor: the same `Q` and weights as the dense
        /// reference, bit for bit.
        #[test]
        fn sparse_traces_equal_the_dense_reference_bit_for_bit(
            steps in proptest::collection::vec(
                (0u32..3, 0usize..2, proptest::collection::vec(
                    proptest::prop_oneof![4 => proptest::strategy::Just(0.0), 1 => -1.0f64..1.0],
                    7,
                ), -1.0f64..1.0, proptest::bool::weighted(0.1)),
                1..60,
            ),
            power in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.5f64..1.0],
        ) {
            let config = SarsaConfig { alpha: 0.1, gamma: 0.9, lambda: 0.8 };
            let mut l = SarsaLambda::new(config.clone(), 2, 8);
            l.q_init = 0.25;
            l.set_visit_power(power);
            let mut d = Dense { weights: BTreeMap::new(), traces: Vec::new() };
            let mut counts: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
            let mut q = Vec::new();
            for (state, action, rest, delta, new_episode) in steps {
                if new_episode {
                    l.clear_traces();
                    d.traces.clear();
                }
                let mut phi = vec![1.0];
                phi.extend(rest);
                l.q_all(state, &phi, &mut q);
                for (a, q) in q.iter().enumerate() {
                    let expected = d.q(state * 2 + a as u32, &phi, 0.25);
                    proptest::prop_assert_eq!(q.to_bits(), expected.to_bits());
                }
                l.visit(state, action, &phi);
                let key = state * 2 + action as u32;
                d.traces.retain(|(k, _)| *k == key || *k / 2 != state);
                match d.traces.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, e)) => e.copy_from_slice(&phi),
                    None => d.traces.push((key, phi.clone())),
                }
                let c = counts.entry(key).or_insert_with(|| vec![0.0; 8]);
                for (ci, x) in c.iter_mut().zip(&phi) {
                    *ci += x * x;
                }
                let norm2: f64 = phi.iter().map(|v| v * v).sum();
                l.apply(delta, norm2);
                let norm = norm2.max(1.0);
                for (k, e) in &d.traces {
                    let w = d.weights.entry(*k).or_insert_with(|| {
                        let mut w = vec![0.0; 8];
                        w[0] = 0.25;
                        w
                    });
                    for (i, (wi, ei)) in w.iter_mut().zip(e).enumerate() {
                        let rate = if power > 0.0 {
                            counts[k][i].max(1.0).powf(-power).max(config.alpha)
                        } else {
                            config.alpha
                        };
                        if *ei != 0.0 {
                            *wi += rate / norm * delta * ei;
                        }
                    }
                }
                for (_, e) in &mut d.traces {
                    e.iter_mut().for_each(|v| *v *= config.gamma * config.lambda);
                }
                d.traces.retain(|(_, e)| e.iter().any(|v| v.abs() > 1e-4));
            }
            let bits = |w: &BTreeMap<u32, Vec<f64>>| -> Vec<(u32, Vec<u64>)> {
                w.iter().map(|(k, v)| (*k, v.iter().map(|x| x.to_bits()).collect())).collect()
            };
            proptest::prop_assert_eq!(bits(&l.weights), bits(&d.weights));
        }
    }
}
