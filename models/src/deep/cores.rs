//! Recurrent cores — LSTM, GRU, vanilla RNN and CTRNN — behind one step interface.
//!
//! Every core maps `(x [B, I], state, keep [B, 1]) → (h [B, H], state)`. `keep` is
//! `1 − episode_start`: the incoming state is multiplied by it, so an episode start
//! zeroes the state (values and gradients cannot cross it). Sequence forwards
//! (`[T, B, I]`) project the whole input in one matmul and then step.

use crate::deep::init::{InitRng, param, uniform};
use crate::fast_tanh as tanh;
use burn::module::{Module, Param};
use burn::nn::Linear;
use burn::tensor::activation::{sigmoid, softplus};
use burn::tensor::{Device, Tensor};
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// CTRNN leak of one unit: `α = min(dt / softplus(τ_raw), 1)` and `dα/dτ_raw`
/// (`−α σ(τ_raw) / softplus(τ_raw)` below the clamp, 0 on it), in `f64`. The one scalar
/// definition: the native engine and the stand-alone CTRNN
/// ([`crate::timing::ctrnn::Ctrnn`]) call it, and burn's tensor form
/// ([`Core::alpha`]) is tested equal to it (`softplus(x) = x` above 20, as in PyTorch).
pub fn ctrnn_alpha(tau_raw: f64, dt: f64) -> (f64, f64) {
    let softplus = if tau_raw > 20.0 {
        tau_raw
    } else {
        tau_raw.exp().ln_1p()
    };
    let a = dt / softplus;
    if a < 1.0 {
        let sig = 1.0 / (1.0 + (-tau_raw).exp());
        (a, -a / softplus * sig)
    } else {
        (1.0, 0.0)
    }
}

/// Which recurrence a core implements.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    Serialize,
    Deserialize,
    strum::IntoStaticStr,
    strum::Display,
)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum CoreKind {
    /// Long short-term memory (Hochreiter & Schmidhuber 1997), PyTorch gate order i, f, g, o.
    Lstm,
    /// Gated recurrent unit (Cho et al. 2014), PyTorch convention (reset gate on `W_hn h + b_hn`).
    Gru,
    /// Elman RNN: `h ← tanh(W_in x + W_rec h + b)`.
    Rnn,
    /// Continuous-time RNN (the paper's CTRNN cell): `h ← (1−α)h + α·tanh(W_in x + W_rec h + b)`, `α = dt/softplus(τ)`.
    Ctrnn,
}

impl CoreKind {
    /// All kinds, in zoo order.
    pub const ALL: [CoreKind; 4] = [
        CoreKind::Lstm,
        CoreKind::Gru,
        CoreKind::Rnn,
        CoreKind::Ctrnn,
    ];

    /// Lower-case name (`lstm`, `gru`, `rnn`, `ctrnn`).
    pub fn name(self) -> &'static str {
        self.into()
    }

    /// Gate blocks per unit (columns of the projections are `gates · H`).
    pub fn gates(self) -> usize {
        match self {
            CoreKind::Lstm => 4,
            CoreKind::Gru => 3,
            CoreKind::Rnn | CoreKind::Ctrnn => 1,
        }
    }
}

impl FromStr for CoreKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        CoreKind::ALL
            .into_iter()
            .find(|k| k.name() == s.to_ascii_lowercase())
            .ok_or_else(|| {
                let names: Vec<&str> = CoreKind::ALL.iter().map(|k| k.name()).collect();
                format!("unknown core `{s}` (allowed: {})", names.join(", "))
            })
    }
}

/// Recurrent state: hidden `h [B, H]`, and the cell `c [B, H]` for the LSTM.
#[derive(Debug, Clone)]
pub struct CoreState {
    /// Hidden state (the core's output) `[B, H]`.
    pub h: Tensor<2>,
    /// LSTM cell state `[B, H]` (`None` for the other cores).
    pub c: Option<Tensor<2>>,
}

impl CoreState {
    /// Multiplies the state by `keep [B, 1]` (0 at an episode start).
    pub fn masked(self, keep: &Tensor<2>) -> Self {
        CoreState {
            h: self.h * keep.clone(),
            c: self.c.map(|c| c * keep.clone()),
        }
    }

    /// Detached copy (cuts the autodiff graph).
    pub fn detach(self) -> Self {
        CoreState {
            h: self.h.detach(),
            c: self.c.map(Tensor::detach),
        }
    }

    /// Rows `rows` of a batched state (`[B, H]` → `[rows.len(), H]`).
    pub fn select(&self, rows: burn::tensor::Tensor<1, burn::tensor::Int>) -> Self {
        CoreState {
            h: self.h.clone().select(0, rows.clone()),
            c: self.c.clone().map(|c| c.select(0, rows)),
        }
    }

    /// Copies the state to flat `f32` vectors `(h, c)` (row-major `[B, H]`).
    pub fn to_vecs(&self) -> (Vec<f32>, Option<Vec<f32>>) {
        let h = crate::to_vec(&self.h);
        let c = self.c.as_ref().map(crate::to_vec);
        (h, c)
    }

    /// Builds a state from flat vectors of `batch` rows.
    pub fn from_vecs(h: Vec<f32>, c: Option<Vec<f32>>, batch: usize, device: &Device) -> Self {
        let hidden = h.len() / batch.max(1);
        let mk = |v: Vec<f32>| {
            Tensor::from_data(burn::tensor::TensorData::new(v, [batch, hidden]), device)
        };
        CoreState {
            h: mk(h),
            c: c.map(mk),
        }
    }
}

/// What [`RecurrentCore::forward_seq_train`] needs after the first `backward`.
#[derive(Debug, Clone)]
pub struct SeqAux {
    /// Tracked input projection `[T, B, G·H]` (second graph).
    pub xw: Tensor<3>,
    /// Per-step leaves holding `xw_t` `[B, G·H]`.
    pub a_leaves: Vec<Tensor<2>>,
    /// Per-step zero leaves added to `h W_rec` `[B, G·H]`.
    pub z_leaves: Vec<Tensor<2>>,
    /// Inputs of the recurrent projection `[T·B, H]` (detached).
    pub h_prev: Tensor<2>,
    /// Parameter id of `W_rec`.
    pub weight_id: burn::module::ParamId,
}

impl SeqAux {
    /// From the first backward's gradients: `(∂L/∂W_rec [H, G·H], surrogate)`, where
    /// `surrogate.backward()` yields the gradients of `W_in`, `b_in` and everything before.
    pub fn finish(self, grads: &burn::tensor::Gradients) -> (Option<Tensor<2>>, Option<Tensor<1>>) {
        let grab = |leaves: &[Tensor<2>]| -> Option<Tensor<2>> {
            let g: Option<Vec<Tensor<2>>> = leaves.iter().map(|l| l.grad(grads)).collect();
            g.map(|v| Tensor::cat(v, 0))
        };
        let dw = grab(&self.z_leaves).map(|dz| self.h_prev.clone().inner().transpose().matmul(dz));
        let [t, b, gh] = self.xw.dims();
        let sur = grab(&self.a_leaves).map(|da| {
            let da: Tensor<3> = da.reshape([t, b, gh]);
            let da = Tensor::from_inner(da).detach();
            (self.xw * da).sum()
        });
        (dw, sur)
    }
}

/// One recurrent core (burn module): input projection, recurrent projection and,
/// for the CTRNN, the learnable time constants.
#[derive(Module, Debug)]
pub struct RecurrentCore {
    /// Input projection `x W_in + b`, `W_in: [I, G·H]`.
    pub input: Linear,
    /// Recurrent projection `h W_rec`, `W_rec: [H, G·H]` (GRU: with bias `b_h`).
    pub recurrent: Linear,
    /// CTRNN raw time constants `τ_raw [H]` (effective τ = softplus(τ_raw)).
    pub tau: Option<Param<Tensor<1>>>,
    /// Which recurrence.
    #[module(skip)]
    pub kind: CoreKind,
    /// Hidden units `H`.
    #[module(skip)]
    pub hidden: usize,
    /// CTRNN integration step `dt` (same time unit as τ).
    #[module(skip)]
    pub dt: f32,
}

/// Hyperparameters of a [`RecurrentCore`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoreConfig {
    /// Recurrence kind.
    pub kind: CoreKind,
    /// Input features `I`.
    pub input: usize,
    /// Hidden units `H` (the paper: 8, 125, 256).
    pub hidden: usize,
    /// CTRNN `dt` (reference 0.1).
    pub dt: f32,
    /// CTRNN initial raw τ (reference 1.0 → softplus 1.313).
    pub tau_init: f32,
    /// Initial weight distribution.
    pub init: CoreInit,
}

/// How a recurrent core's weights are drawn at initialisation (τ always starts at
/// `tau_init`). Both give the same architecture; only the starting point differs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CoreInit {
    /// The lab's: input weights U(±1/√H), recurrent weights orthogonal (gain 1) per gate
    /// block, zero biases (LSTM forget-gate bias 1).
    #[default]
    Lab,
    /// PyTorch's defaults for the paper's modules (sb3-contrib creates its LSTM after SB3's
    /// orthogonal initialisation, and the paper's `CTRNNCell` uses plain `nn.Linear`s):
    /// LSTM / GRU / RNN every weight and both biases U(±1/√H) (the lab's single input bias
    /// is the sum `b_ih + b_hh`; the GRU keeps `b_hh` as its recurrent bias); CTRNN input
    /// weight and bias U(±1/√I) (`nn.Linear(I, H)`), recurrent weight U(±1/√H) without bias.
    Torch,
}

impl CoreConfig {
    /// A core of `kind` with `input` features and `hidden` units, reference CTRNN constants.
    pub fn new(kind: CoreKind, input: usize, hidden: usize) -> Self {
        CoreConfig {
            kind,
            input,
            hidden,
            dt: 0.1,
            tau_init: 1.0,
            init: CoreInit::Lab,
        }
    }

    /// Initialises the core: input weights U(±1/√H) (PyTorch's RNN default), recurrent
    /// weights orthogonal (gain 1) per gate block, zero biases (LSTM forget-gate bias 1).
    pub fn init(&self, rng: &mut InitRng, device: &Device) -> RecurrentCore {
        if self.init == CoreInit::Torch {
            return self.init_torch(rng, device);
        }
        let (i, h, g) = (self.input, self.hidden, self.kind.gates());
        let bound = 1.0 / (h as f64).sqrt();
        let mut b_in = vec![0f32; g * h];
        if self.kind == CoreKind::Lstm {
            b_in[h..2 * h].fill(1.0);
        }
        let input = Linear {
            weight: param(uniform(i * g * h, bound, rng), [i, g * h], device),
            bias: Some(param(b_in, [g * h], device)),
        };
        // Orthogonal recurrent blocks, laid side by side: W_rec[:, k·H..(k+1)·H].
        let mut w_rec = vec![0f32; h * g * h];
        for k in 0..g {
            let block = crate::deep::init::orthogonal(h, h, 1.0, rng);
            for r in 0..h {
                w_rec[r * g * h + k * h..r * g * h + (k + 1) * h]
                    .copy_from_slice(&block[r * h..(r + 1) * h]);
            }
        }
        let recurrent = Linear {
            weight: param(w_rec, [h, g * h], device),
            bias: (self.kind == CoreKind::Gru).then(|| param(vec![0.0; g * h], [g * h], device)),
        };
        let tau =
            (self.kind == CoreKind::Ctrnn).then(|| param(vec![self.tau_init; h], [h], device));
        RecurrentCore {
            input,
            recurrent,
            tau,
            kind: self.kind,
            hidden: h,
            dt: self.dt,
        }
    }

    /// [`CoreInit::Torch`]: PyTorch's default initialisation of the paper's modules.
    fn init_torch(&self, rng: &mut InitRng, device: &Device) -> RecurrentCore {
        let (i, h, g) = (self.input, self.hidden, self.kind.gates());
        let kh = 1.0 / (h as f64).sqrt();
        let (w_in, b_in, w_rec, b_rec) = if self.kind == CoreKind::Ctrnn {
            let ki = 1.0 / (i as f64).sqrt();
            let w_in = uniform(i * h, ki, rng);
            let b_in = uniform(h, ki, rng);
            (w_in, b_in, uniform(h * h, kh, rng), None)
        } else {
            let w_in = uniform(i * g * h, kh, rng);
            let w_rec = uniform(h * g * h, kh, rng);
            let b_ih = uniform(g * h, kh, rng);
            let b_hh = uniform(g * h, kh, rng);
            if self.kind == CoreKind::Gru {
                (w_in, b_ih, w_rec, Some(b_hh))
            } else {
                let b: Vec<f32> = b_ih.iter().zip(&b_hh).map(|(a, b)| a + b).collect();
                (w_in, b, w_rec, None)
            }
        };
        RecurrentCore {
            input: Linear {
                weight: param(w_in, [i, g * h], device),
                bias: Some(param(b_in, [g * h], device)),
            },
            recurrent: Linear {
                weight: param(w_rec, [h, g * h], device),
                bias: b_rec.map(|b| param(b, [g * h], device)),
            },
            tau: (self.kind == CoreKind::Ctrnn).then(|| param(vec![self.tau_init; h], [h], device)),
            kind: self.kind,
            hidden: h,
            dt: self.dt,
        }
    }
}

impl RecurrentCore {
    /// Zero state for `batch` sequences.
    pub fn zero_state(&self, batch: usize, device: &Device) -> CoreState {
        CoreState {
            h: Tensor::zeros([batch, self.hidden], device),
            c: (self.kind == CoreKind::Lstm).then(|| Tensor::zeros([batch, self.hidden], device)),
        }
    }

    /// CTRNN leak `α = dt / softplus(τ_raw)` as `[1, H]` (clamped to ≤ 1 so the Euler step stays stable).
    pub fn alpha(&self) -> Option<Tensor<2>> {
        self.tau.as_ref().map(|tau| {
            let tau_eff = softplus(tau.val(), 1.0);
            (tau_eff.recip() * self.dt).clamp_max(1.0).unsqueeze_dim(0)
        })
    }

    /// One step: `x [B, I]`, state and `keep [B, 1]` (`None`: no episode starts) →
    /// output `[B, H]` and the new state.
    pub fn step(
        &self,
        x: Tensor<2>,
        state: CoreState,
        keep: Option<&Tensor<2>>,
    ) -> (Tensor<2>, CoreState) {
        let xw = self.input.forward(x);
        let alpha = self.alpha();
        let state = match keep {
            Some(k) => state.masked(k),
            None => state,
        };
        let s = self.cell(xw, state, alpha.as_ref());
        (s.h.clone(), s)
    }

    /// Sequence forward: `x [T, B, I]`, initial state and per-step `keep [B, 1]`
    /// (`None` where no sequence starts an episode) → outputs `[T, B, H]` and the final state.
    pub fn forward_seq(
        &self,
        x: Tensor<3>,
        state: CoreState,
        keep: &[Option<Tensor<2>>],
    ) -> (Tensor<3>, CoreState) {
        let [t_len, batch, _] = x.dims();
        assert_eq!(keep.len(), t_len, "one keep mask (or None) per step");
        let xw = self.input.forward(x);
        let alpha = self.alpha();
        let mut state = state;
        let mut outs = Vec::with_capacity(t_len);
        for (t, xt) in xw.split(1, 0).into_iter().enumerate() {
            let xt: Tensor<2> = xt.reshape([batch, self.kind.gates() * self.hidden]);
            if let Some(k) = &keep[t] {
                state = state.masked(k);
            }
            state = self.cell(xt, state, alpha.as_ref());
            outs.push(state.h.clone());
        }
        (Tensor::stack(outs, 0), state)
    }

    /// Sequence forward for training, in two autodiff graphs.
    ///
    /// `xw [T, B, G·H]` is the tracked input projection of the whole sequence. The loop
    /// works on per-step *leaves*: `a_t` (the value of `xw_t`) and a zero `z_t` added to
    /// `h W_rec` computed with a detached `W_rec`. After `backward` of the loss,
    /// [`SeqAux::finish`] forms `∂L/∂W_rec = Σ_t h_{t−1}ᵀ ∂L/∂z_t` in one matmul and a
    /// second surrogate `Σ xw·∂L/∂a` whose `backward` reaches `W_in` and the trunk. This
    /// avoids burn's per-step slice backward, which allocates and adds a full `[T, B, G·H]`
    /// gradient for every step (O(T²) memory traffic), and T small `dW` accumulations.
    pub fn forward_seq_train(
        &self,
        xw: Tensor<3>,
        state: CoreState,
        keep: &[Option<Tensor<2>>],
    ) -> (Tensor<3>, CoreState, SeqAux) {
        let [t_len, batch, gh] = xw.dims();
        assert_eq!(keep.len(), t_len, "one keep mask (or None) per step");
        let device = xw.device();
        let alpha = self.alpha();
        let w_det = self.recurrent.weight.val().detach();
        let b_h = self
            .recurrent
            .bias
            .as_ref()
            .map(|b| b.val().unsqueeze_dim::<2>(0));
        let xw_values = xw.clone().detach();
        let mut state = state;
        let mut outs = Vec::with_capacity(t_len);
        let mut h_prev = Vec::with_capacity(t_len);
        let mut a_leaves = Vec::with_capacity(t_len);
        let mut z_leaves = Vec::with_capacity(t_len);
        for (t, xt) in xw_values.split(1, 0).into_iter().enumerate() {
            let a_t: Tensor<2> = xt.reshape([batch, gh]).require_grad();
            let z_t: Tensor<2> = Tensor::<2>::zeros([batch, gh], &device).require_grad();
            if let Some(k) = &keep[t] {
                state = state.masked(k);
            }
            h_prev.push(state.h.clone().detach());
            let mut hw = state.h.clone().matmul(w_det.clone()) + z_t.clone();
            if let Some(b) = &b_h {
                hw = hw + b.clone();
            }
            state = self.cell_with(a_t.clone(), hw, state, alpha.as_ref());
            outs.push(state.h.clone());
            a_leaves.push(a_t);
            z_leaves.push(z_t);
        }
        (
            Tensor::stack(outs, 0),
            state,
            SeqAux {
                xw,
                a_leaves,
                z_leaves,
                h_prev: Tensor::cat(h_prev, 0),
                weight_id: self.recurrent.weight.id,
            },
        )
    }

    /// `[1, 4H]` column scale `[1…1, 1…1, 2…2, 1…1]` for the LSTM's fused gate sigmoid.
    fn lstm_gate_scale(&self, device: &Device) -> Tensor<2> {
        let h = self.hidden;
        let mut v = vec![1f32; 4 * h];
        v[2 * h..3 * h].fill(2.0);
        Tensor::from_data(burn::tensor::TensorData::new(v, [1, 4 * h]), device)
    }

    /// The recurrence proper, on the already-projected input `xw [B, G·H]` and a masked state.
    fn cell(&self, xw: Tensor<2>, state: CoreState, alpha: Option<&Tensor<2>>) -> CoreState {
        let hw = self.recurrent.forward(state.h.clone());
        self.cell_with(xw, hw, state, alpha)
    }

    /// The recurrence given both projections `xw = x W_in + b` and `hw = h W_rec (+ b_h)`.
    fn cell_with(
        &self,
        xw: Tensor<2>,
        hw: Tensor<2>,
        state: CoreState,
        alpha: Option<&Tensor<2>>,
    ) -> CoreState {
        let h = self.hidden;
        match self.kind {
            CoreKind::Lstm => {
                // One sigmoid over all four gates; the g block is pre-scaled by 2 so that
                // tanh(g) = 2σ(2g) − 1 comes out of the same op.
                let s = sigmoid((xw + hw) * self.lstm_gate_scale(&state.h.device()));
                let i = s.clone().narrow(1, 0, h);
                let f = s.clone().narrow(1, h, h);
                let g = s.clone().narrow(1, 2 * h, h) * 2.0 - 1.0;
                let o = s.narrow(1, 3 * h, h);
                let c_prev = state.c.unwrap_or_else(|| state.h.zeros_like());
                let c = f * c_prev + i * g;
                let h_new = o * tanh(c.clone());
                CoreState {
                    h: h_new,
                    c: Some(c),
                }
            }
            CoreKind::Gru => {
                let rz = sigmoid(xw.clone().narrow(1, 0, 2 * h) + hw.clone().narrow(1, 0, 2 * h));
                let r = rz.clone().narrow(1, 0, h);
                let z = rz.narrow(1, h, h);
                let n = tanh(xw.narrow(1, 2 * h, h) + r * hw.narrow(1, 2 * h, h));
                let h_new = n.clone() + z * (state.h - n);
                CoreState { h: h_new, c: None }
            }
            CoreKind::Rnn => CoreState {
                h: tanh(xw + hw),
                c: None,
            },
            CoreKind::Ctrnn => {
                let target = tanh(xw + hw);
                let a = alpha.cloned().unwrap_or_else(|| target.ones_like());
                // (1−α)h + α·target = h + α(target − h)
                let h_new = state.h.clone() + a * (target - state.h);
                CoreState { h: h_new, c: None }
            }
        }
    }
}
