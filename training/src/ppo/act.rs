//! Acting with a policy on CPU buffers: batched forward, sampling and log-probabilities.

use burn::tensor::{Device, Tensor, TensorData};
use chronocooked_models::{ActorCritic, CoreState};
use rand::Rng;

/// One batched policy step on plain buffers.
///
/// `obs [N, cells, C]`, `keep [N]` (0 at an episode start). Returns logits `[N, A]`,
/// values `[N]` and the new recurrent state.
pub fn policy_step(
    model: &ActorCritic,
    obs: &[f32],
    cells: usize,
    channels: usize,
    keep: &[f32],
    state: Option<CoreState>,
    device: &Device,
) -> (Vec<f32>, Vec<f32>, Option<CoreState>) {
    let n = keep.len();
    let x: Tensor<3> =
        Tensor::from_data(TensorData::new(obs.to_vec(), [n, cells, channels]), device);
    let k = keep
        .iter()
        .any(|&v| v != 1.0)
        .then(|| Tensor::<2>::from_data(TensorData::new(keep.to_vec(), [n, 1]), device));
    let out = model.forward_step(x, state, k.as_ref());
    let a = out.logits.dims()[1];
    let both = crate::ppo::params::tensor_to_vec(&Tensor::cat(vec![out.logits, out.values], 1));
    let mut logits = Vec::with_capacity(n * a);
    let mut values = Vec::with_capacity(n);
    for row in both.chunks_exact(a + 1) {
        logits.extend_from_slice(&row[..a]);
        values.push(row[a]);
    }
    (logits, values, out.state)
}

/// Log-softmax of one row of logits (f64 for accuracy).
pub fn log_softmax(logits: &[f32]) -> Vec<f64> {
    let max = logits.iter().copied().fold(f32::NEG_INFINITY, f32::max) as f64;
    let lse = logits
        .iter()
        .map(|&l| (l as f64 - max).exp())
        .sum::<f64>()
        .ln()
        + max;
    logits.iter().map(|&l| l as f64 - lse).collect()
}

/// Samples an action from categorical `logits`; returns `(action, log-probability)`.
pub fn sample<R: Rng>(logits: &[f32], rng: &mut R) -> (usize, f32) {
    let lp = log_softmax(logits);
    let u: f64 = rng.random::<f64>();
    let mut acc = 0.0;
    for (a, l) in lp.iter().enumerate() {
        acc += l.exp();
        if u < acc {
            return (a, *l as f32);
        }
    }
    let a = lp.len() - 1;
    (a, lp[a] as f32)
}

/// The most probable action (lowest index on ties).
pub fn argmax(logits: &[f32]) -> usize {
    let mut best = 0;
    for (i, &l) in logits.iter().enumerate() {
        if l > logits[best] {
            best = i;
        }
    }
    best
}

/// Recurrent state as flat vectors `(h [N, H], c [N, H] for the LSTM)`; both empty
/// (`(vec![], None)`) for CNN-MLP.
pub type FlatState = (Vec<f32>, Option<Vec<f32>>);
