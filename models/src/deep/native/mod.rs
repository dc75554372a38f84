//! The native engine: the [`ActorCritic`](crate::ActorCritic) network evaluated and
//! differentiated by hand on a flat parameter vector, for PPO training on CPU.
//!
//! The burn modules stay the definition of the model (initialisation, saving, loading,
//! evaluation, recording); this engine computes the *same function* and its exact
//! gradient with fused kernels and no per-op allocation, which is what small networks
//! trained on minibatches of 64–256 samples need to run fast on one core (burn's autodiff
//! spends most of its time in per-op bookkeeping at these sizes). The tests check forward
//! outputs and parameter gradients against burn's autodiff for every core kind.
//!
//! Parameters are read from the flat vector in the module's visiting order
//! (`params::flat_params` in the training crate) — see [`Layout`].

mod core;
pub mod kernels;
mod net;

pub use net::{Cache, NativePolicy, SeqBatch};

use crate::{CoreKind, PolicyConfig};

/// A parameter block: offset and length in the flat vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Block {
    /// First element.
    pub offset: usize,
    /// Elements.
    pub len: usize,
}

impl Block {
    /// The block's slice of `theta`.
    pub fn of<'a>(&self, theta: &'a [f32]) -> &'a [f32] {
        &theta[self.offset..self.offset + self.len]
    }

    /// The block's mutable slice of `grad`.
    pub fn of_mut<'a>(&self, grad: &'a mut [f32]) -> &'a mut [f32] {
        &mut grad[self.offset..self.offset + self.len]
    }
}

/// Where each parameter lives in the flat vector (burn's visiting order: trunk conv1
/// weight `[C, 8]` and bias, conv2 `[8, 6]`, dense `[cells·6, 64]`; core input `[64, G·H]`
/// and bias, recurrent `[H, G·H]` (GRU: and bias), CTRNN `τ_raw [H]`; fused head hidden
/// layer `[L, 2·64]`, policy output `[64, A]`, value output `[64, 1]`; each weight
/// followed by its bias).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// Conv1 weight and bias.
    pub conv1: (Block, Block),
    /// Conv2 weight and bias.
    pub conv2: (Block, Block),
    /// Dense weight and bias.
    pub dense: (Block, Block),
    /// Core input projection weight and bias.
    pub core_in: Option<(Block, Block)>,
    /// Core recurrent weight (and GRU bias).
    pub core_rec: Option<(Block, Option<Block>)>,
    /// CTRNN raw time constants.
    pub tau: Option<Block>,
    /// Fused head hidden layer weight and bias.
    pub hidden: (Block, Block),
    /// Policy output weight and bias.
    pub pi: (Block, Block),
    /// Value output weight and bias.
    pub vf: (Block, Block),
    /// Total parameters.
    pub total: usize,
}

impl Layout {
    /// The flat range of the recurrent core's parameters (input projection, recurrent
    /// weights, CTRNN τ; contiguous in the visiting order), `None` for CNN-MLP.
    pub fn core_range(&self) -> Option<std::ops::Range<usize>> {
        let (w_in, _) = self.core_in?;
        let end = self.hidden.0.offset;
        Some(w_in.offset..end)
    }

    /// The layout of the policy `cfg` builds.
    pub fn new(cfg: &PolicyConfig) -> Self {
        let mut at = 0;
        let mut take = |len: usize| {
            let b = Block { offset: at, len };
            at += len;
            b
        };
        let t = &cfg.trunk;
        let conv1 = (take(t.channels * t.conv1), take(t.conv1));
        let conv2 = (take(t.conv1 * t.conv2), take(t.conv2));
        let dense = (take(t.cells * t.conv2 * t.features), take(t.features));
        let (mut core_in, mut core_rec, mut tau) = (None, None, None);
        let mut latent = t.features;
        if let Some(kind) = cfg.arch.core {
            let (h, g) = (cfg.arch.hidden, kind.gates());
            core_in = Some((take(t.features * g * h), take(g * h)));
            let w = take(h * g * h);
            core_rec = Some((w, (kind == CoreKind::Gru).then(|| take(g * h))));
            tau = (kind == CoreKind::Ctrnn).then(|| take(h));
            latent = h;
        }
        let hh = cfg.head_hidden;
        let hidden = (take(latent * 2 * hh), take(2 * hh));
        let pi = (take(hh * cfg.actions), take(cfg.actions));
        let vf = (take(hh), take(1));
        Layout {
            conv1,
            conv2,
            dense,
            core_in,
            core_rec,
            tau,
            hidden,
            pi,
            vf,
            total: at,
        }
    }
}
