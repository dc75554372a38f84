//! Adam with a global gradient-norm clip, on flat parameter vectors.
//!
//! Semantics of `torch.nn.utils.clip_grad_norm_` followed by `torch.optim.Adam`
//! (what Stable-Baselines3's PPO does): the L2 norm is taken over *all* gradients
//! together, then the bias-corrected Adam step is applied. Kept here rather than in
//! burn so that the state is plain data: checkpoints restore it bit for bit.

use serde::{Deserialize, Serialize};

/// Adam hyperparameters (PyTorch defaults, SB3's ε = 1e-5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AdamParams {
    /// First-moment decay β₁.
    pub beta1: f64,
    /// Second-moment decay β₂.
    pub beta2: f64,
    /// ε added to √v̂.
    pub eps: f64,
}

impl Default for AdamParams {
    fn default() -> Self {
        AdamParams {
            beta1: 0.9,
            beta2: 0.999,
            eps: 1e-5,
        }
    }
}

/// Adam state: moments and step count.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Adam {
    /// Hyperparameters.
    pub params: AdamParams,
    /// First moments, one per parameter.
    pub m: Vec<f32>,
    /// Second moments, one per parameter.
    pub v: Vec<f32>,
    /// Steps taken.
    pub t: u64,
}

/// L2 norm of a gradient vector (f64 sums; 16 interleaved partial sums so that the loop
/// vectorises — a fixed order, so deterministic).
pub fn global_norm(grads: &[f32]) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx512f") {
        // SAFETY: the CPU supports AVX-512F (checked just above).
        return unsafe { sum_squares_avx512(grads) }.sqrt();
    }
    sum_squares(grads).sqrt()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn sum_squares_avx512(x: &[f32]) -> f64 {
    sum_squares(x)
}

#[inline(always)]
fn sum_squares(x: &[f32]) -> f64 {
    let mut acc = [0f64; 16];
    let chunks = x.chunks_exact(16);
    let tail = chunks.remainder();
    for c in chunks {
        for (a, &g) in acc.iter_mut().zip(c) {
            *a += (g as f64) * (g as f64);
        }
    }
    let mut s: f64 = acc.iter().sum();
    for &g in tail {
        s += (g as f64) * (g as f64);
    }
    s
}

/// Scales `grads` in place so that their global L2 norm is at most `max_norm`
/// (PyTorch: factor `max_norm / (norm + 1e-6)`, applied only when below 1).
/// Returns the norm before clipping.
pub fn clip_global_norm(grads: &mut [f32], max_norm: f64) -> f64 {
    let norm = global_norm(grads);
    let coef = max_norm / (norm + 1e-6);
    if coef < 1.0 {
        grads
            .iter_mut()
            .for_each(|g| *g = (*g as f64 * coef) as f32);
    }
    norm
}

impl Adam {
    /// Checks a loaded state for `n` parameters: both moments of length `n`, finite
    /// (second moments ≥ 0), hyperparameters in range and a step count the bias correction
    /// can take. Errors give the field (`m`, `v`, `t`, `params`) and what it must be.
    pub fn validate(&self, n: usize) -> Result<(), (&'static str, String)> {
        for (field, values) in [("m", &self.m), ("v", &self.v)] {
            if values.len() != n {
                return Err((
                    field,
                    format!("{} values, the run needs exactly {n}", values.len()),
                ));
            }
            if let Some(i) = values.iter().position(|x| !x.is_finite()) {
                return Err((field, format!("value {i} is not a finite number")));
            }
        }
        if self.v.iter().any(|&x| x < 0.0) {
            return Err(("v", "second moments must be >= 0".into()));
        }
        if self.t >= i32::MAX as u64 {
            return Err(("t", format!("{} steps (at most {})", self.t, i32::MAX - 1)));
        }
        let AdamParams { beta1, beta2, eps } = self.params;
        if !((0.0..1.0).contains(&beta1)
            && (0.0..1.0).contains(&beta2)
            && eps > 0.0
            && eps.is_finite())
        {
            return Err(("params", "betas in [0, 1) and eps > 0".into()));
        }
        Ok(())
    }

    /// Fresh state for `n` parameters.
    pub fn new(n: usize, params: AdamParams) -> Self {
        Adam {
            params,
            m: vec![0.0; n],
            v: vec![0.0; n],
            t: 0,
        }
    }

    /// One update of `theta` with gradient `grad` and learning rate `lr`.
    pub fn step(&mut self, theta: &mut [f32], grad: &[f32], lr: f64) {
        assert_eq!(theta.len(), self.m.len(), "parameter count changed");
        assert_eq!(grad.len(), self.m.len(), "gradient length differs");
        self.t += 1;
        let AdamParams { beta1, beta2, eps } = self.params;
        let bc1 = 1.0 - beta1.powi(self.t as i32);
        let bc2 = 1.0 - beta2.powi(self.t as i32);
        let k = StepConsts::new(beta1, beta2, eps, lr / bc1, bc2.sqrt());
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU supports AVX-512F (checked just above). Same IEEE operations
            // in the same order (no FMA contraction), so results equal the baseline build's.
            unsafe { adam_avx512(theta, grad, &mut self.m, &mut self.v, &k) };
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above). Same IEEE operations in
            // the same order (no FMA contraction), so results equal the baseline build's.
            unsafe { adam_avx2(theta, grad, &mut self.m, &mut self.v, &k) };
            return;
        }
        adam_loop(theta, grad, &mut self.m, &mut self.v, &k);
    }
}

/// Per-step constants of the Adam update, in the f32 the moments and parameters are kept in
/// (PyTorch's Adam computes them in f64 and applies them to f32 tensors likewise).
struct StepConsts {
    beta1: f32,
    beta2: f32,
    eps: f32,
    step_size: f32,
    bc2_sqrt: f32,
}

impl StepConsts {
    fn new(beta1: f64, beta2: f64, eps: f64, step_size: f64, bc2_sqrt: f64) -> Self {
        StepConsts {
            beta1: beta1 as f32,
            beta2: beta2 as f32,
            eps: eps as f32,
            step_size: step_size as f32,
            bc2_sqrt: bc2_sqrt as f32,
        }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn adam_avx512(theta: &mut [f32], grad: &[f32], m: &mut [f32], v: &mut [f32], k: &StepConsts) {
    adam_loop(theta, grad, m, v, k);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn adam_avx2(theta: &mut [f32], grad: &[f32], m: &mut [f32], v: &mut [f32], k: &StepConsts) {
    adam_loop(theta, grad, m, v, k);
}

/// The element-wise update in f32, PyTorch's order of operations (`m ← β₁m + (1−β₁)g`,
/// `v ← β₂v + (1−β₂)g²`, `θ ← θ − step·m / (√v / √bc₂ + ε)`), written to vectorise: 16 lanes
/// of AVX-512 with single-precision `sqrt` and `div`. It was f64 arithmetic on f32 storage
/// until session 17 — 6% of an LSTM125 update on the reference protocol (`perf`), for
/// rounding the stored f32 moments discarded anyway.
#[inline(always)]
fn adam_loop(theta: &mut [f32], grad: &[f32], m: &mut [f32], v: &mut [f32], k: &StepConsts) {
    let n = theta.len();
    let (grad, m, v) = (&grad[..n], &mut m[..n], &mut v[..n]);
    let (one_b1, one_b2) = (1.0 - k.beta1, 1.0 - k.beta2);
    for i in 0..n {
        let g = grad[i];
        let mi = k.beta1 * m[i] + one_b1 * g;
        let vi = k.beta2 * v[i] + one_b2 * (g * g);
        m[i] = mi;
        v[i] = vi;
        let denom = vi.sqrt() / k.bc2_sqrt + k.eps;
        theta[i] -= k.step_size * mi / denom;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_step_moves_each_parameter_by_lr() {
        // With bias correction, |Δθ| = lr · |g| / (|g| + ε) ≈ lr on the first step.
        let mut a = Adam::new(3, AdamParams::default());
        let mut th = vec![1.0f32, -2.0, 0.5];
        a.step(&mut th, &[0.3, -4.0, 2.0], 0.01);
        for (x, want) in th.iter().zip([0.99f32, -1.99, 0.49]) {
            assert!((x - want).abs() < 1e-4, "{x} vs {want}");
        }
    }

    #[test]
    fn global_clip_scales_all_gradients_together() {
        let mut g = vec![3.0f32, 4.0];
        let n = clip_global_norm(&mut g, 0.5);
        assert!((n - 5.0).abs() < 1e-9);
        assert!((global_norm(&g) - 0.5).abs() < 1e-5);
        assert!((g[0] / g[1] - 0.75).abs() < 1e-6, "direction kept");
        let mut small = vec![0.1f32, 0.1];
        clip_global_norm(&mut small, 0.5);
        assert_eq!(small, vec![0.1, 0.1]);
    }
}
