//! Stand-alone continuous-time RNN — the same cell as the PPO agent's CTRNN core
//! (the paper's CTRNN cell, `ctrnn_policy.py` of its code): `h ← (1−α) h + α · tanh(W_in x + W_rec h + b) + σ_rec √α ξ`,
//! `α = dt / softplus(τ)` per unit (clamped to ≤ 1), `ξ ~ N(0, 1)` optional recurrent noise.

use rand::Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// A CTRNN with `n` units and `m` inputs; matrices row-major.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ctrnn {
    /// Input weights `[n, m]`.
    pub w_in: Vec<f32>,
    /// Recurrent weights `[n, n]`.
    pub w_rec: Vec<f32>,
    /// Bias `[n]`.
    pub bias: Vec<f32>,
    /// Raw time constants `[n]` (`softplus(τ_raw)` is the time constant).
    pub tau_raw: Vec<f32>,
    /// Integration step `dt`.
    pub dt: f32,
    /// Recurrent noise SD `σ_rec` (0 = deterministic).
    pub noise: f32,
    /// Number of inputs `m`.
    pub inputs: usize,
}

impl Ctrnn {
    /// A CTRNN with zero weights, `τ_raw` = 1 (softplus = 1.31) and `dt` = 0.1.
    pub fn zeros(n: usize, inputs: usize) -> Self {
        Ctrnn {
            w_in: vec![0.0; n * inputs],
            w_rec: vec![0.0; n * n],
            bias: vec![0.0; n],
            tau_raw: vec![1.0; n],
            dt: 0.1,
            noise: 0.0,
            inputs,
        }
    }

    /// Number of units.
    pub fn size(&self) -> usize {
        self.bias.len()
    }

    /// Per-unit `α = dt / softplus(τ_raw)`, clamped to `(0, 1]`.
    pub fn alpha(&self) -> Vec<f32> {
        self.tau_raw
            .iter()
            .map(|&t| crate::deep::cores::ctrnn_alpha(f64::from(t), f64::from(self.dt)).0 as f32)
            .collect()
    }

    /// One Euler step of the hidden state `h` `[n]` with input `x` `[m]`.
    pub fn step<R: Rng + ?Sized>(&self, h: &mut [f32], x: &[f32], rng: &mut R) {
        let n = self.size();
        let alpha = self.alpha();
        let mut pre = self.bias.clone();
        for (i, p) in pre.iter_mut().enumerate() {
            let wi = &self.w_in[i * self.inputs..(i + 1) * self.inputs];
            *p += wi.iter().zip(x).map(|(w, v)| w * v).sum::<f32>();
            let wr = &self.w_rec[i * n..(i + 1) * n];
            *p += wr.iter().zip(h.iter()).map(|(w, v)| w * v).sum::<f32>();
        }
        for i in 0..n {
            let a = alpha[i];
            let mut v = (1.0 - a) * h[i] + a * pre[i].tanh();
            if self.noise > 0.0 {
                let xi: f32 = rng.sample(StandardNormal);
                v += self.noise * a.sqrt() * xi;
            }
            h[i] = v;
        }
    }
}
