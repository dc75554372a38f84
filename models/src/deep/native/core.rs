//! Recurrent cores of the native engine: forward over a time-major sequence and
//! back-propagation through time, for the LSTM, GRU, vanilla RNN and CTRNN (same
//! equations and gate order as [`crate::deep::cores`]).
//!
//! Notation per step: `x_t = x W_in + b_in` (given, `[B, G·H]`), `h̃ = keep·h_{t−1}` (the
//! masked incoming state), `r_t = h̃ W_rec (+ b_rec)`.

use super::kernels::{
    Mat, Packed, lstm_cell, matmul, matmul_packed, matmul_tn, sigmoid_inplace, tanh_inplace,
};
use super::{Block, SeqBatch, resize, resize_for_overwrite};
use crate::CoreKind;

/// Read-only parameters of a core.
pub(super) struct CoreParams<'a> {
    pub kind: CoreKind,
    pub hidden: usize,
    /// `W_rec [H, G·H]`.
    pub w_rec: &'a [f32],
    /// GRU recurrent bias `[G·H]`.
    pub b_rec: Option<&'a [f32]>,
    /// CTRNN `τ_raw [H]`.
    pub tau: Option<&'a [f32]>,
    /// CTRNN step.
    pub dt: f32,
    /// Whether the core's own gradients (`W_rec`, `b_rec`, `τ`) are wanted (not for a
    /// frozen reservoir, whose BPTT only carries the gradient on to the trunk).
    pub grads: bool,
}

impl CoreParams<'_> {
    /// CTRNN leak `α = min(dt/softplus(τ_raw), 1)` and `dα/dτ_raw` per unit.
    fn alpha(&self) -> (Vec<f32>, Vec<f32>) {
        let tau = self.tau.unwrap_or(&[]);
        tau.iter()
            .map(|&t| {
                let (a, da) = crate::deep::cores::ctrnn_alpha(t as f64, self.dt as f64);
                (a as f32, da as f32)
            })
            .unzip()
    }
}

/// Per-sequence activations and backward work buffers (reused across calls).
#[derive(Debug, Default, Clone)]
pub(crate) struct CoreCache {
    hidden: usize,
    active: bool,
    steps: usize,
    batch: usize,
    /// Rows held (`T·B`, or `Σ active` in the packed layout).
    rows: usize,
    keep: Vec<f32>,
    /// Outputs `h_t` `[N, H]`.
    h: Vec<f32>,
    /// Masked incoming states `h̃_t` `[N, H]`.
    h_prev: Vec<f32>,
    /// Activated gates `[N, G·H]` (LSTM i,f,g,o; GRU r,z,n; RNN/CTRNN: tanh target).
    gates: Vec<f32>,
    /// LSTM cell `c_t`, its tanh and the masked incoming cell `[N, H]`.
    c: Vec<f32>,
    tc: Vec<f32>,
    c_prev: Vec<f32>,
    /// GRU `h̃ W_hn + b_hn` `[N, H]`.
    hn: Vec<f32>,
    hw_step: Vec<f32>,
    dxw: Vec<f32>,
    dhw: Vec<f32>,
    dh: Vec<f32>,
    dh_carry: Vec<f32>,
    dc_carry: Vec<f32>,
    /// Real sequences per step `[T]` (a prefix of the batch; all when not given).
    active_rows: Vec<usize>,
    /// First row of each step `[T]`: `t·B` (padded layout) or the running sum of
    /// `active_rows` (packed layout: rows of ended sequences left out).
    off: Vec<usize>,
    /// `W_rec` prepared for the per-step products, and its transpose for the backward.
    w_pack: Packed,
    wt_pack: Packed,
}

impl CoreCache {
    /// Whether no core ran (CNN-MLP).
    pub fn is_empty(&self) -> bool {
        !self.active
    }

    /// Marks the cache as holding no core activations.
    pub fn clear(&mut self) {
        self.active = false;
    }

    /// Outputs `[N, H]`.
    pub fn h(&self) -> &[f32] {
        &self.h
    }

    /// Gradient at the input projection `x W_in + b_in` `[N, G·H]` (after `backward`).
    pub fn dxw(&self) -> &[f32] {
        &self.dxw
    }

    /// State after the last step, of the sequences that run to the last step.
    pub fn final_state(&self) -> (&[f32], Option<&[f32]>) {
        let Some((&o, &bt)) = self.off.last().zip(self.active_rows.last()) else {
            return (&[], None);
        };
        if !self.active {
            return (&[], None);
        }
        let h = self.hidden;
        let range = o * h..(o + bt) * h;
        let c = (!self.c.is_empty()).then(|| &self.c[range.clone()]);
        (&self.h[range], c)
    }
}

/// Copies `src` rows scaled by their keep value into `dst` (`[B, H]`).
#[inline(always)]
fn masked_copy(dst: &mut [f32], src: &[f32], keep: &[f32], h: usize) {
    for ((d, s), &k) in dst.chunks_exact_mut(h).zip(src.chunks_exact(h)).zip(keep) {
        if k == 1.0 {
            d.copy_from_slice(s);
        } else {
            d.iter_mut().zip(s).for_each(|(d, &s)| *d = s * k);
        }
    }
}

/// Runs the core over the sequence: `xw [N, G·H]` is the input projection (with bias).
/// Only the first `batch.active[t]` sequences are stepped at step `t`. With `packed` the
/// rows of the others are absent (`xw`, `batch.keep` and every output hold `Σ active`
/// rows, step after step); otherwise they stay in place (`[T·B]` rows) and are left at
/// zero.
#[inline(always)]
pub(super) fn forward(
    p: &CoreParams<'_>,
    xw: &[f32],
    batch: &SeqBatch<'_>,
    packed: bool,
    cc: &mut CoreCache,
) {
    let (h, g) = (p.hidden, p.kind.gates());
    let (t_len, b) = (batch.steps, batch.batch);
    let gh = g * h;
    assert_eq!(batch.h0.len(), b * h, "initial hidden state length");
    if let Some(c0) = batch.c0 {
        assert_eq!(c0.len(), b * h, "initial cell state length");
    }
    cc.active = true;
    cc.hidden = h;
    cc.steps = t_len;
    cc.batch = b;
    cc.keep.clear();
    cc.keep.extend_from_slice(batch.keep);
    cc.active_rows.clear();
    match batch.active {
        Some(a) => {
            assert_eq!(a.len(), t_len, "active rows per step");
            assert!(
                a.iter().all(|&x| x <= b) && a.windows(2).all(|w| w[1] <= w[0]),
                "active rows must not grow along the sequence"
            );
            cc.active_rows.extend_from_slice(a);
        }
        None => cc.active_rows.resize(t_len, b),
    }
    cc.off.clear();
    let mut n = 0;
    for (t, &bt) in cc.active_rows.iter().enumerate() {
        cc.off.push(if packed { n } else { t * b });
        n = if packed { n + bt } else { (t + 1) * b };
    }
    cc.rows = n;
    assert_eq!(xw.len(), n * g * h, "input projection rows");
    assert_eq!(batch.keep.len(), n, "keep mask rows");
    // Every row is stepped (packed layout, or every sequence active at every step): each
    // buffer below is overwritten in full, so its kept part need not be zeroed first.
    let every_row = packed || cc.active_rows.iter().all(|&bt| bt == b);
    let size: fn(&mut Vec<f32>, usize) = if every_row {
        resize_for_overwrite
    } else {
        resize
    };
    size(&mut cc.h, n * h);
    size(&mut cc.h_prev, n * h);
    size(&mut cc.gates, n * gh);
    let lstm = p.kind == CoreKind::Lstm;
    if lstm {
        size(&mut cc.c, n * h);
        size(&mut cc.tc, n * h);
        size(&mut cc.c_prev, n * h);
    } else {
        cc.c.clear();
    }
    if p.kind == CoreKind::Gru {
        size(&mut cc.hn, n * h);
        resize_for_overwrite(&mut cc.hw_step, b * gh);
    }
    let (alpha, _) = p.alpha();
    let zero_c = vec![0f32; b * h];
    let w_rec = Mat::new(p.w_rec, h, gh);
    // Several steps: W_rec is prepared once (packed panels) for every step's product.
    let w_packed = t_len > 1;
    if w_packed {
        cc.w_pack.pack(w_rec, false);
    }
    for t in 0..t_len {
        let (bt, o) = (cc.active_rows[t], cc.off[t]);
        let (r0, r1) = (o * h, (o + bt) * h);
        let keep = &batch.keep[o..o + bt];
        let src = if t == 0 {
            &batch.h0[..bt * h]
        } else {
            let q = cc.off[t - 1];
            &cc.h[q * h..(q + bt) * h]
        };
        masked_copy(&mut cc.h_prev[r0..r1], src, keep, h);
        let hp = Mat::new(&cc.h_prev[r0..r1], bt, h);
        let xw_t = &xw[o * gh..(o + bt) * gh];
        match p.kind {
            CoreKind::Gru => gru_step(p, cc, t, bt, xw_t),
            kind => {
                // Pre-activations x_t + h̃ W_rec, then the kind's non-linearity.
                let pre = &mut cc.gates[o * gh..(o + bt) * gh];
                pre.copy_from_slice(xw_t);
                if w_packed {
                    matmul_packed(hp, &cc.w_pack, pre, gh, true);
                } else {
                    matmul(hp, w_rec, pre, gh, true);
                }
                match kind {
                    CoreKind::Lstm => lstm_step(cc, t, bt, h, keep, batch.c0, &zero_c),
                    CoreKind::Rnn => {
                        tanh_inplace(pre);
                        cc.h[r0..r1].copy_from_slice(pre);
                    }
                    _ => {
                        // CTRNN: h = h̃ + α(tanh(pre) − h̃).
                        tanh_inplace(pre);
                        let hp = &cc.h_prev[r0..r1];
                        let rows = cc.h[r0..r1].chunks_exact_mut(h);
                        for ((out, tg), hv) in rows.zip(pre.chunks_exact(h)).zip(hp.chunks_exact(h))
                        {
                            for j in 0..h {
                                out[j] = hv[j] + alpha[j] * (tg[j] - hv[j]);
                            }
                        }
                    }
                }
            }
        }
    }
}

/// GRU step `t`: `r, z = σ(x_{r,z} + (h̃ W_rec + b_rec)_{r,z})`, `n = tanh(x_n + r ⊙ ĥ_n)` with
/// `ĥ_n = (h̃ W_rec + b_rec)_n`, `h = n + z ⊙ (h̃ − n)`.
#[inline(always)]
fn gru_step(p: &CoreParams<'_>, cc: &mut CoreCache, t: usize, bt: usize, xw_t: &[f32]) {
    let h = p.hidden;
    let gh = 3 * h;
    let o = cc.off[t];
    let r0 = o * h;
    let hw = &mut cc.hw_step[..bt * gh];
    let hp = Mat::new(&cc.h_prev[r0..r0 + bt * h], bt, h);
    if cc.steps > 1 {
        matmul_packed(hp, &cc.w_pack, hw, gh, false);
    } else {
        matmul(hp, Mat::new(p.w_rec, h, gh), hw, gh, false);
    }
    if let Some(bias) = p.b_rec {
        super::kernels::add_bias(hw, bias);
    }
    let pre = &mut cc.gates[o * gh..(o + bt) * gh];
    pre.copy_from_slice(xw_t);
    for (bi, (row, hw_row)) in pre
        .chunks_exact_mut(gh)
        .zip(hw.chunks_exact(gh))
        .enumerate()
    {
        let (rz, nn) = row.split_at_mut(2 * h);
        rz.iter_mut()
            .zip(&hw_row[..2 * h])
            .for_each(|(x, &y)| *x += y);
        sigmoid_inplace(rz);
        let o = r0 + bi * h;
        let hn = &mut cc.hn[o..o + h];
        hn.copy_from_slice(&hw_row[2 * h..]);
        for j in 0..h {
            nn[j] += rz[j] * hn[j];
        }
        tanh_inplace(nn);
        let (out, hpr) = (&mut cc.h[o..o + h], &cc.h_prev[o..o + h]);
        for j in 0..h {
            out[j] = nn[j] + rz[h + j] * (hpr[j] - nn[j]);
        }
    }
}

/// LSTM gate activations and cell update for step `t` (pre-activations already in `gates`)
/// of the first `bt` of `b` sequences, fused per sequence ([`lstm_cell`]).
#[inline(always)]
fn lstm_step(
    cc: &mut CoreCache,
    t: usize,
    bt: usize,
    h: usize,
    keep: &[f32],
    c0: Option<&[f32]>,
    zero: &[f32],
) {
    let o = cc.off[t];
    let (r0, r1) = (o * h, (o + bt) * h);
    let src = if t == 0 {
        &c0.unwrap_or(zero)[..bt * h]
    } else {
        let q = cc.off[t - 1];
        &cc.c[q * h..(q + bt) * h]
    };
    masked_copy(&mut cc.c_prev[r0..r1], src, keep, h);
    let gh = 4 * h;
    let pre = &mut cc.gates[o * gh..(o + bt) * gh];
    let rows = pre
        .chunks_exact_mut(gh)
        .zip(cc.c_prev[r0..r1].chunks_exact(h))
        .zip(cc.c[r0..r1].chunks_exact_mut(h))
        .zip(cc.tc[r0..r1].chunks_exact_mut(h))
        .zip(cc.h[r0..r1].chunks_exact_mut(h));
    for ((((g, cp), c), tc), hv) in rows {
        lstm_cell(g, cp, c, tc, hv);
    }
}

/// Back-propagation through time from `dlat = ∂L/∂h_t` `[N, H]`: accumulates the
/// recurrent weight (and GRU bias, CTRNN τ) gradients into `grad` at the blocks `rec`
/// and `tau`, and leaves `∂L/∂(x W_in + b_in)` in the cache ([`CoreCache::dxw`]).
#[inline(always)]
pub(super) fn backward(
    p: &CoreParams<'_>,
    cc: &mut CoreCache,
    dlat: &[f32],
    grad: &mut [f32],
    rec: (Block, Option<Block>),
    tau: Option<Block>,
    scratch: &mut Vec<f32>,
) {
    let (h, g) = (p.hidden, p.kind.gates());
    let gh = g * h;
    let (t_len, b) = (cc.steps, cc.batch);
    let n = cc.rows;
    resize(&mut cc.dxw, n * gh);
    let gru = p.kind == CoreKind::Gru;
    if gru {
        resize(&mut cc.dhw, n * gh);
    }
    resize(&mut cc.dh, b * h);
    resize(&mut cc.dh_carry, b * h);
    resize(&mut cc.dc_carry, b * h);
    cc.wt_pack.pack(Mat::new(p.w_rec, h, gh), true);
    let (alpha, dalpha_dtau) = p.alpha();
    let mut dalpha = vec![0f64; alpha.len()];
    for t in (0..t_len).rev() {
        let (bt, o) = (cc.active_rows[t], cc.off[t]);
        let (r0, r1) = (o * h, (o + bt) * h);
        for ((d, &l), &c) in cc.dh[..bt * h]
            .iter_mut()
            .zip(&dlat[r0..r1])
            .zip(&cc.dh_carry)
        {
            *d = l + c;
        }
        let gates = &cc.gates[o * gh..(o + bt) * gh];
        let dx = &mut cc.dxw[o * gh..(o + bt) * gh];
        let hp = &cc.h_prev[r0..r1];
        // `direct`: the part of ∂L/∂h̃ that does not pass through W_rec. Rows past the
        // active ones stay zero (their sequences have ended: no gradient flows back).
        cc.dh_carry.fill(0.0);
        match p.kind {
            CoreKind::Lstm => {
                for bi in 0..bt {
                    let gr = &gates[bi * gh..(bi + 1) * gh];
                    let dr = &mut dx[bi * gh..(bi + 1) * gh];
                    let o0 = r0 + bi * h;
                    for j in 0..h {
                        let (i, f, gg, o) = (gr[j], gr[h + j], gr[2 * h + j], gr[3 * h + j]);
                        let tc = cc.tc[o0 + j];
                        let dh = cc.dh[bi * h + j];
                        let dc = dh * o * (1.0 - tc * tc) + cc.dc_carry[bi * h + j];
                        dr[j] = dc * gg * i * (1.0 - i);
                        dr[h + j] = dc * cc.c_prev[o0 + j] * f * (1.0 - f);
                        dr[2 * h + j] = dc * i * (1.0 - gg * gg);
                        dr[3 * h + j] = dh * tc * o * (1.0 - o);
                        cc.dc_carry[bi * h + j] = dc * f;
                    }
                }
            }
            CoreKind::Gru => {
                let dhw = &mut cc.dhw[o * gh..(o + bt) * gh];
                for bi in 0..bt {
                    let gr = &gates[bi * gh..(bi + 1) * gh];
                    let o0 = r0 + bi * h;
                    for j in 0..h {
                        let (r, z, nn) = (gr[j], gr[h + j], gr[2 * h + j]);
                        let dh = cc.dh[bi * h + j];
                        let dnp = dh * (1.0 - z) * (1.0 - nn * nn);
                        let drp = dnp * cc.hn[o0 + j] * r * (1.0 - r);
                        let dzp = dh * (hp[bi * h + j] - nn) * z * (1.0 - z);
                        let k = bi * gh;
                        dx[k + j] = drp;
                        dx[k + h + j] = dzp;
                        dx[k + 2 * h + j] = dnp;
                        dhw[k + j] = drp;
                        dhw[k + h + j] = dzp;
                        dhw[k + 2 * h + j] = dnp * r;
                        cc.dh_carry[bi * h + j] = dh * z;
                    }
                }
            }
            CoreKind::Rnn => {
                for ((d, &dh), &y) in dx.iter_mut().zip(&cc.dh).zip(&cc.h[r0..r1]) {
                    *d = dh * (1.0 - y * y);
                }
            }
            CoreKind::Ctrnn => {
                for (k, ((d, &dh), &tg)) in dx.iter_mut().zip(&cc.dh).zip(gates).enumerate() {
                    let j = k % h;
                    *d = dh * alpha[j] * (1.0 - tg * tg);
                    dalpha[j] += (dh * (tg - hp[k])) as f64;
                    cc.dh_carry[k] = dh * (1.0 - alpha[j]);
                }
            }
        }
        // ∂L/∂h̃ = direct + (∂L/∂r_t) W_recᵀ, then through the episode-start mask.
        let dr = if gru {
            Mat::new(&cc.dhw[o * gh..(o + bt) * gh], bt, gh)
        } else {
            Mat::new(&cc.dxw[o * gh..(o + bt) * gh], bt, gh)
        };
        matmul_packed(dr, &cc.wt_pack, &mut cc.dh_carry, h, true);
        let keep = &cc.keep[o..o + bt];
        for (bi, &k) in keep.iter().enumerate() {
            if k != 1.0 {
                cc.dh_carry[bi * h..(bi + 1) * h]
                    .iter_mut()
                    .for_each(|v| *v *= k);
                cc.dc_carry[bi * h..(bi + 1) * h]
                    .iter_mut()
                    .for_each(|v| *v *= k);
            }
        }
    }
    if !p.grads {
        return;
    }
    let drec = if gru { &cc.dhw } else { &cc.dxw };
    let drec = Mat::new(drec, n, gh);
    matmul_tn(
        Mat::new(&cc.h_prev, n, h),
        drec,
        rec.0.of_mut(grad),
        false,
        scratch,
    );
    if let Some(bb) = rec.1 {
        super::kernels::add_col_sums(drec, bb.of_mut(grad));
    }
    if let Some(tb) = tau {
        for ((gt, &da), &dd) in tb.of_mut(grad).iter_mut().zip(&dalpha).zip(&dalpha_dtau) {
            *gt = (da * dd as f64) as f32;
        }
    }
}
