//! Forward and backward passes of the whole actor–critic (trunk, core, heads) on a flat
//! parameter vector.

use super::core::{self, CoreCache};
use super::kernels::{
    Isa, Mat, add_bias, add_col_sums, matmul, matmul_nt, matmul_tn, relu_inplace, tanh_inplace,
};
use super::{Block, ParamLayout, SeqBatch, resize, resize_for_overwrite};
use crate::PolicyConfig;

/// Activations of the last forward pass (kept for the backward pass) and reusable
/// work buffers; outputs are read from [`Cache::logits`], [`Cache::values`] and
/// [`Cache::final_state`].
#[derive(Debug, Default, Clone)]
pub struct Cache {
    /// Rows computed: `T·B`, or the real rows only when padding is left out.
    rows: usize,
    /// Padded rows `T·B` of the outputs.
    padded: usize,
    /// Padded-layout index of each computed row (empty when every row is computed).
    real: Vec<usize>,
    keep: Vec<f32>,
    /// Outputs and output gradients of the computed rows (packed layout only).
    logits_p: Vec<f32>,
    values_p: Vec<f32>,
    steps: usize,
    batch: usize,
    x: Vec<f32>,
    a1: Vec<f32>,
    a2: Vec<f32>,
    f: Vec<f32>,
    xw: Vec<f32>,
    core: CoreCache,
    z: Vec<f32>,
    /// Action logits `[T·B, A]`.
    pub logits: Vec<f32>,
    /// State values `[T·B]`.
    pub values: Vec<f32>,
    dz: Vec<f32>,
    dlat: Vec<f32>,
    df: Vec<f32>,
    da2: Vec<f32>,
    da1: Vec<f32>,
    scratch: Vec<f32>,
}

impl Cache {
    /// The latent fed to the heads `[T·B, L]` (core output, or trunk features for CNN-MLP);
    /// with sequences that end early ([`SeqBatch::active`]) only their real rows, step
    /// after step.
    pub fn latent(&self) -> &[f32] {
        if self.core.is_empty() {
            &self.f
        } else {
            self.core.h()
        }
    }

    /// State after the last step: `(h [B, H], c [B, H] for the LSTM)` (empty for CNN-MLP).
    pub fn final_state(&self) -> (&[f32], Option<&[f32]>) {
        self.core.final_state()
    }
}

/// The native engine for one policy configuration.
#[derive(Debug, Clone)]
pub struct NativePolicy {
    cfg: PolicyConfig,
    layout: ParamLayout,
    detach_critic: bool,
    frozen_core: bool,
}

impl NativePolicy {
    /// The engine for policies built from `cfg`.
    pub fn new(cfg: &PolicyConfig) -> Self {
        NativePolicy {
            cfg: *cfg,
            layout: ParamLayout::new(cfg),
            detach_critic: false,
            frozen_core: false,
        }
    }

    /// The same engine for a core that is never trained (a reservoir): the backward
    /// pass still carries the gradient through the core to the trunk but leaves the
    /// core's own parameter gradients (input projection, `W_rec`, biases, τ) at zero and
    /// skips their products.
    pub fn with_frozen_core(mut self, frozen: bool) -> Self {
        self.frozen_core = frozen;
        self
    }

    /// The same engine whose critic reads a *detached* copy of the recurrent core's
    /// output (sb3-contrib `shared_lstm=True, enable_critic_lstm=False`): the value loss
    /// trains the value head only, never the core or the trunk. No effect on CNN-MLP
    /// (its critic shares the trunk, as in SB3's PPO).
    pub fn with_detached_critic(mut self, detach: bool) -> Self {
        self.detach_critic = detach;
        self
    }

    /// Parameter count (length of the flat vector).
    pub fn num_params(&self) -> usize {
        self.layout.total
    }

    /// Parameter layout.
    pub fn layout(&self) -> &ParamLayout {
        &self.layout
    }

    fn latent_dim(&self) -> usize {
        if self.cfg.arch.is_recurrent() {
            self.cfg.arch.hidden
        } else {
            self.cfg.trunk.features
        }
    }

    /// Forward pass of `batch` with parameters `theta`; fills `cache` (outputs and what
    /// [`NativePolicy::backward`] needs).
    pub fn forward(&self, theta: &[f32], batch: &SeqBatch<'_>, cache: &mut Cache) {
        match Isa::detect() {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX-512F, AVX2 and FMA (detected).
            Isa::Avx512 => unsafe { self.forward_avx512(theta, batch, cache) },
            _ => self.forward_impl(theta, batch, cache),
        }
    }

    /// [`NativePolicy::forward`] with its element-wise loops (masks, gates, CTRNN leak,
    /// ReLU, biases) compiled for AVX-512; the same IEEE operations (no contraction into
    /// FMA), so the same results.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2,fma")]
    fn forward_avx512(&self, theta: &[f32], batch: &SeqBatch<'_>, cache: &mut Cache) {
        self.forward_impl(theta, batch, cache);
    }

    #[inline(always)]
    fn forward_impl(&self, theta: &[f32], batch: &SeqBatch<'_>, cache: &mut Cache) {
        assert_eq!(theta.len(), self.layout.total, "parameter vector length");
        let t = &self.cfg.trunk;
        let l = &self.layout;
        let n = batch.steps * batch.batch;
        assert_eq!(
            batch.obs.len(),
            n * t.cells * t.channels,
            "observation length"
        );
        assert_eq!(batch.keep.len(), n, "keep mask length");
        // Sequences that end early (`active`): only their real rows are computed, step
        // after step (the recurrent core's packed layout), outputs scattered back.
        cache.real.clear();
        if let Some(a) = batch.active
            && a.iter().sum::<usize>() < n
        {
            let b = batch.batch;
            for (t, &bt) in a.iter().enumerate() {
                cache.real.extend((0..bt.min(b)).map(|j| t * b + j));
            }
        }
        let packed = !cache.real.is_empty();
        cache.padded = n;
        let n = if packed { cache.real.len() } else { n };
        cache.rows = n;
        cache.steps = batch.steps;
        cache.batch = batch.batch;
        if n == 0 {
            cache.core.clear();
            cache.logits.clear();
            cache.values.clear();
            return;
        }
        let nc = n * t.cells;
        cache.x.clear();
        if packed {
            let w = t.cells * t.channels;
            for &r in &cache.real {
                cache.x.extend_from_slice(&batch.obs[r * w..(r + 1) * w]);
            }
            cache.keep.clear();
            cache.keep.extend(cache.real.iter().map(|&r| batch.keep[r]));
        } else {
            cache.x.extend_from_slice(batch.obs);
        }
        // conv1 (per cell) + ReLU.
        resize_for_overwrite(&mut cache.a1, nc * t.conv1);
        let x = Mat::new(&cache.x, nc, t.channels);
        linear(x, theta, l.conv1, t.conv1, &mut cache.a1);
        relu_inplace(&mut cache.a1);
        // conv2 (per cell), no non-linearity; flattened cell-major.
        resize_for_overwrite(&mut cache.a2, nc * t.conv2);
        linear(
            Mat::new(&cache.a1, nc, t.conv1),
            theta,
            l.conv2,
            t.conv2,
            &mut cache.a2,
        );
        // dense + ReLU.
        resize_for_overwrite(&mut cache.f, n * t.features);
        let a2 = Mat::new(&cache.a2, n, t.cells * t.conv2);
        linear(a2, theta, l.dense, t.features, &mut cache.f);
        relu_inplace(&mut cache.f);
        // Recurrent core.
        if let Some((params, inp)) = self.core_params(theta) {
            let gh = params.kind.gates() * params.hidden;
            resize_for_overwrite(&mut cache.xw, n * gh);
            let f = Mat::new(&cache.f, n, t.features);
            linear(f, theta, inp, gh, &mut cache.xw);
            let core_batch = SeqBatch {
                keep: if packed { &cache.keep } else { batch.keep },
                ..*batch
            };
            core::forward(&params, &cache.xw, &core_batch, packed, &mut cache.core);
        } else {
            cache.core.clear();
        }
        // Heads: z = tanh(latent W_h + b_h) = [z_pi | z_vf].
        let hh = self.cfg.head_hidden;
        let lat_dim = self.latent_dim();
        resize_for_overwrite(&mut cache.z, n * 2 * hh);
        let latent = if cache.core.is_empty() {
            &cache.f
        } else {
            cache.core.h()
        };
        linear(
            Mat::new(latent, n, lat_dim),
            theta,
            l.hidden,
            2 * hh,
            &mut cache.z,
        );
        tanh_inplace(&mut cache.z);
        let a_n = self.cfg.actions;
        let (lg, vl) = if packed {
            (&mut cache.logits_p, &mut cache.values_p)
        } else {
            (&mut cache.logits, &mut cache.values)
        };
        resize_for_overwrite(lg, n * a_n);
        let z_pi = Mat::strided(&cache.z, n, hh, 2 * hh);
        linear(z_pi, theta, l.pi, a_n, lg);
        resize_for_overwrite(vl, n);
        let z_vf = Mat::strided(&cache.z[hh..], n, hh, 2 * hh);
        linear(z_vf, theta, l.vf, 1, vl);
        if packed {
            // Padding rows: zero outputs (their loss weight is zero).
            resize(&mut cache.logits, cache.padded * a_n);
            resize(&mut cache.values, cache.padded);
            for (i, &r) in cache.real.iter().enumerate() {
                cache.logits[r * a_n..(r + 1) * a_n]
                    .copy_from_slice(&cache.logits_p[i * a_n..(i + 1) * a_n]);
                cache.values[r] = cache.values_p[i];
            }
        }
    }

    /// Gradient of `Σ d_logits·logits + Σ d_values·values` with respect to every parameter
    /// (written to `grad`, same layout as `theta`), for the last forward pass in `cache`.
    /// Gradients do not flow into the initial state.
    pub fn backward(
        &self,
        theta: &[f32],
        cache: &mut Cache,
        d_logits: &[f32],
        d_values: &[f32],
        grad: &mut [f32],
    ) {
        match Isa::detect() {
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX-512F, AVX2 and FMA (detected).
            Isa::Avx512 => unsafe { self.backward_avx512(theta, cache, d_logits, d_values, grad) },
            _ => self.backward_impl(theta, cache, d_logits, d_values, grad),
        }
    }

    /// [`NativePolicy::backward`] with its element-wise loops compiled for AVX-512 (same
    /// IEEE operations, same results).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx2,fma")]
    fn backward_avx512(
        &self,
        theta: &[f32],
        cache: &mut Cache,
        d_logits: &[f32],
        d_values: &[f32],
        grad: &mut [f32],
    ) {
        self.backward_impl(theta, cache, d_logits, d_values, grad);
    }

    #[inline(always)]
    fn backward_impl(
        &self,
        theta: &[f32],
        cache: &mut Cache,
        d_logits: &[f32],
        d_values: &[f32],
        grad: &mut [f32],
    ) {
        let n = cache.rows;
        let (t, l) = (&self.cfg.trunk, &self.layout);
        let (hh, a_n, lat_dim) = (self.cfg.head_hidden, self.cfg.actions, self.latent_dim());
        assert_eq!(grad.len(), l.total, "gradient vector length");
        assert_eq!(d_logits.len(), cache.padded * a_n, "logit gradient length");
        assert_eq!(d_values.len(), cache.padded, "value gradient length");
        // Packed layout: the output gradients of the computed rows (the forward pass's
        // packed outputs are not needed any more; their buffers are reused).
        let (mut dl_p, mut dv_p) = (
            std::mem::take(&mut cache.logits_p),
            std::mem::take(&mut cache.values_p),
        );
        let (d_logits, d_values) = if cache.real.is_empty() {
            (d_logits, d_values)
        } else {
            dl_p.clear();
            dv_p.clear();
            for &r in &cache.real {
                dl_p.extend_from_slice(&d_logits[r * a_n..(r + 1) * a_n]);
                dv_p.push(d_values[r]);
            }
            (&dl_p[..], &dv_p[..])
        };
        grad.fill(0.0);
        if n == 0 {
            return;
        }
        let s = &mut cache.scratch;
        // Output layers; their input gradients land side by side in dz = [dz_pi | dz_vf].
        resize_for_overwrite(&mut cache.dz, n * 2 * hh);
        let z_pi = Mat::strided(&cache.z, n, hh, 2 * hh);
        let z_vf = Mat::strided(&cache.z[hh..], n, hh, 2 * hh);
        let dlg = Mat::new(d_logits, n, a_n);
        linear_backward(
            z_pi,
            dlg,
            theta,
            l.pi,
            grad,
            Some((&mut cache.dz, 2 * hh)),
            s,
        );
        let dv = Mat::new(d_values, n, 1);
        linear_backward(
            z_vf,
            dv,
            theta,
            l.vf,
            grad,
            Some((&mut cache.dz[hh..], 2 * hh)),
            s,
        );
        // Through tanh, then the fused hidden layer.
        for (d, &z) in cache.dz.iter_mut().zip(&cache.z) {
            *d *= 1.0 - z * z;
        }
        let latent = if cache.core.is_empty() {
            &cache.f
        } else {
            cache.core.h()
        };
        resize_for_overwrite(&mut cache.dlat, n * lat_dim);
        linear_backward(
            Mat::new(latent, n, lat_dim),
            Mat::new(&cache.dz, n, 2 * hh),
            theta,
            l.hidden,
            grad,
            None,
            s,
        );
        // The latent's gradient; a detached critic passes back the policy half only.
        let cols = if self.detach_critic && !cache.core.is_empty() {
            hh
        } else {
            2 * hh
        };
        let w = Mat::strided(l.hidden.0.of(theta), lat_dim, cols, 2 * hh);
        let dz = Mat::strided(&cache.dz, n, cols, 2 * hh);
        matmul_nt(dz, w, &mut cache.dlat, lat_dim, false, s);
        // Core (BPTT) → gradient at the trunk features.
        resize_for_overwrite(&mut cache.df, n * t.features);
        if let (Some((params, inp)), Some(rec)) = (self.core_params(theta), l.core_rec) {
            core::backward(&params, &mut cache.core, &cache.dlat, grad, rec, l.tau, s);
            let gh = params.kind.gates() * params.hidden;
            let dxw = Mat::new(cache.core.dxw(), n, gh);
            if self.frozen_core {
                let w = Mat::new(inp.0.of(theta), t.features, gh);
                matmul_nt(dxw, w, &mut cache.df, t.features, false, s);
            } else {
                linear_backward(
                    Mat::new(&cache.f, n, t.features),
                    dxw,
                    theta,
                    inp,
                    grad,
                    Some((&mut cache.df, t.features)),
                    s,
                );
            }
        } else {
            cache.df.copy_from_slice(&cache.dlat);
        }
        // Trunk: dense ReLU, dense, conv2 (no non-linearity), conv1 ReLU, conv1.
        relu_backward(&mut cache.df, &cache.f);
        let nc = n * t.cells;
        resize_for_overwrite(&mut cache.da2, nc * t.conv2);
        linear_backward(
            Mat::new(&cache.a2, n, t.cells * t.conv2),
            Mat::new(&cache.df, n, t.features),
            theta,
            l.dense,
            grad,
            Some((&mut cache.da2, t.cells * t.conv2)),
            s,
        );
        resize_for_overwrite(&mut cache.da1, nc * t.conv1);
        linear_backward(
            Mat::new(&cache.a1, nc, t.conv1),
            Mat::new(&cache.da2, nc, t.conv2),
            theta,
            l.conv2,
            grad,
            Some((&mut cache.da1, t.conv1)),
            s,
        );
        relu_backward(&mut cache.da1, &cache.a1);
        linear_backward(
            Mat::new(&cache.x, nc, t.channels),
            Mat::new(&cache.da1, nc, t.conv1),
            theta,
            l.conv1,
            grad,
            None,
            s,
        );
        (cache.logits_p, cache.values_p) = (dl_p, dv_p);
    }

    /// The core's parameters in `theta` and its input-projection blocks (`None` for CNN-MLP).
    fn core_params<'a>(&self, theta: &'a [f32]) -> Option<(core::CoreParams<'a>, (Block, Block))> {
        let l = &self.layout;
        let (kind, inp, rec) = (self.cfg.arch.core?, l.core_in?, l.core_rec?);
        let params = core::CoreParams {
            kind,
            hidden: self.cfg.arch.hidden,
            w_rec: rec.0.of(theta),
            b_rec: rec.1.map(|b| b.of(theta)),
            tau: l.tau.map(|b| b.of(theta)),
            dt: self.cfg.ctrnn_dt,
            grads: !self.frozen_core,
        };
        Some((params, inp))
    }
}

/// Backward of `y = x W + b` (blocks `(w, b)` of `theta`) given `dy`: writes `∂W = xᵀ dy`
/// and `∂b = Σ_rows dy` into `grad` and, when asked, `dx = dy Wᵀ` (row stride given).
fn linear_backward(
    x: Mat<'_>,
    dy: Mat<'_>,
    theta: &[f32],
    (w, b): (Block, Block),
    grad: &mut [f32],
    dx: Option<(&mut [f32], usize)>,
    scratch: &mut Vec<f32>,
) {
    matmul_tn(x, dy, w.of_mut(grad), false, scratch);
    add_col_sums(dy, b.of_mut(grad));
    if let Some((dx, ldx)) = dx {
        let w = Mat::new(w.of(theta), x.cols, dy.cols);
        matmul_nt(dy, w, dx, ldx, false, scratch);
    }
}

/// Zeroes `d` where the ReLU output `y` is 0 (its derivative).
#[inline(always)]
fn relu_backward(d: &mut [f32], y: &[f32]) {
    for (d, &y) in d.iter_mut().zip(y) {
        if y <= 0.0 {
            *d = 0.0;
        }
    }
}

/// `out [M, out_dim] = x W + b` for the weight/bias blocks `(w, b)` of `theta`.
fn linear(x: Mat<'_>, theta: &[f32], (w, b): (Block, Block), out_dim: usize, out: &mut [f32]) {
    let w = Mat::new(w.of(theta), x.cols, out_dim);
    matmul(x, w, out, out_dim, false);
    add_bias(out, b.of(theta));
}
