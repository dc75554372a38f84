//! Linear TD(λ) over a feature vector (Sutton 1988; as used by Ludvig, Sutton & Kehoe 2008):
//! `V = w·φ`, `δ = r + γ V(φ') − V(φ)`, accumulating traces `e ← γλ e + φ`, `w ← w + α δ e`.

use serde::{Deserialize, Serialize};

/// A linear TD(λ) value learner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LinearTd {
    /// Weights `w`, one per feature.
    pub weights: Vec<f64>,
    /// Eligibility traces `e`.
    pub traces: Vec<f64>,
    /// Learning rate `α`.
    pub alpha: f64,
    /// Discount `γ` per step.
    pub gamma: f64,
    /// Trace decay `λ`.
    pub lambda: f64,
}

impl LinearTd {
    /// A learner over `n` features with Ludvig et al.'s defaults (α 0.05, γ 0.97, λ 0.95).
    pub fn new(n: usize) -> Self {
        LinearTd {
            weights: vec![0.0; n],
            traces: vec![0.0; n],
            alpha: 0.05,
            gamma: 0.97,
            lambda: 0.95,
        }
    }

    /// Value `w·φ`.
    pub fn value(&self, phi: &[f64]) -> f64 {
        self.weights.iter().zip(phi).map(|(w, x)| w * x).sum()
    }

    /// Clears the traces (start of a trial).
    pub fn clear_traces(&mut self) {
        self.traces.iter_mut().for_each(|e| *e = 0.0);
    }

    /// One TD(λ) update for the transition `φ → φ'` with reward `r`
    /// (`terminal`: `V(φ') = 0`). Returns the prediction error `δ`.
    pub fn update(&mut self, phi: &[f64], reward: f64, phi_next: &[f64], terminal: bool) -> f64 {
        let next = if terminal { 0.0 } else { self.value(phi_next) };
        let delta = reward + self.gamma * next - self.value(phi);
        let decay = self.gamma * self.lambda;
        for (e, x) in self.traces.iter_mut().zip(phi) {
            *e = decay * *e + x;
        }
        for (w, e) in self.weights.iter_mut().zip(&self.traces) {
            *w += self.alpha * delta * e;
        }
        delta
    }
}
