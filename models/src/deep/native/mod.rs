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
//! (`params::flat_params` in the training crate) — see [`ParamLayout`].

mod core;
pub mod kernels;
mod net;

pub use net::{Cache, NativePolicy};

use crate::PolicyConfig;

/// Gives `v` length `len`, every element zero (caches whose rows are not all written).
fn resize(v: &mut Vec<f32>, len: usize) {
    v.clear();
    v.resize(len, 0.0);
}

/// Gives `v` length `len` for an operation that overwrites every element (a product with
/// `accumulate == false`, a pass over every row): the kept part is not zeroed first.
/// Zeroing every cache of a minibatch was `memset` at 2–3% of an LSTM125 update (`perf`,
/// session 17).
fn resize_for_overwrite(v: &mut Vec<f32>, len: usize) {
    v.resize(len, 0.0);
}

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

/// A batch of `B` sequences of `T` steps, time-major (row `t·B + b`).
#[derive(Debug, Clone, Copy)]
pub struct SeqBatch<'a> {
    /// Observations `[T, B, cells, C]`.
    pub obs: &'a [f32],
    /// Steps `T`.
    pub steps: usize,
    /// Sequences `B`.
    pub batch: usize,
    /// `[T, B]`: 0 where an episode starts (the incoming state is zeroed), else 1.
    pub keep: &'a [f32],
    /// Initial hidden state `[B, H]` (empty for CNN-MLP).
    pub h0: &'a [f32],
    /// Initial LSTM cell state `[B, H]` (`None` for the other models).
    pub c0: Option<&'a [f32]>,
    /// `[T]`: how many sequences are real at step `t` — a prefix of the batch, never
    /// growing with `t` (sequences sorted longest first, padding after each one's end).
    /// The core steps only those; the rows of ended sequences get zero state and must
    /// have zero output gradients. `None`: every sequence runs every step.
    pub active: Option<&'a [usize]>,
}

/// Where each parameter lives in the flat vector, in the order and shapes of
/// [`crate::deep::spec::param_spec`] (burn's visiting order).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParamLayout {
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

impl ParamLayout {
    /// The flat range of the recurrent core's parameters (input projection, recurrent
    /// weights, CTRNN τ; contiguous in the visiting order), `None` for CNN-MLP.
    pub fn core_range(&self) -> Option<std::ops::Range<usize>> {
        let (w_in, _) = self.core_in?;
        let end = self.hidden.0.offset;
        Some(w_in.offset..end)
    }

    /// The layout of the policy `cfg` builds, derived from its parameter specification
    /// ([`crate::deep::spec::param_spec`]): each block starts where the previous ends.
    pub fn new(cfg: &PolicyConfig) -> Self {
        let spec = crate::deep::spec::param_spec(cfg);
        let mut at = 0;
        let blocks: Vec<(&str, Block)> = spec
            .iter()
            .map(|p| {
                let b = Block {
                    offset: at,
                    len: p.len(),
                };
                at += p.len();
                (p.name, b)
            })
            .collect();
        let get = |name: &str| blocks.iter().find(|(n, _)| *n == name).map(|(_, b)| *b);
        let pair = |w: &str, b: &str| {
            (
                get(w).expect("spec has the weight"),
                get(b).expect("spec has the bias"),
            )
        };
        ParamLayout {
            conv1: pair("trunk.conv1.weight", "trunk.conv1.bias"),
            conv2: pair("trunk.conv2.weight", "trunk.conv2.bias"),
            dense: pair("trunk.dense.weight", "trunk.dense.bias"),
            core_in: get("core.input.weight").map(|_| pair("core.input.weight", "core.input.bias")),
            core_rec: get("core.recurrent.weight").map(|w| (w, get("core.recurrent.bias"))),
            tau: get("core.tau"),
            hidden: pair("head.hidden.weight", "head.hidden.bias"),
            pi: pair("head.pi.weight", "head.pi.bias"),
            vf: pair("head.vf.weight", "head.vf.bias"),
            total: at,
        }
    }
}
