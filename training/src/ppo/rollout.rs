//! Rollout storage `[T, N]` and the BPTT chunking used by the PPO update.

/// Transitions of one rollout, time-major (`t·N + n`).
#[derive(Debug, Clone, Default)]
pub struct Rollout {
    /// Envs `N`.
    pub n_envs: usize,
    /// Steps per env `T`.
    pub n_steps: usize,
    /// Floats per observation.
    pub obs_len: usize,
    /// Encoded observations `[T, N, obs_len]`.
    pub obs: Vec<f32>,
    /// Actions `[T, N]`.
    pub actions: Vec<i64>,
    /// Log-probabilities of the actions under the rollout policy `[T, N]`.
    pub log_probs: Vec<f32>,
    /// Values of the observations `[T, N]`.
    pub values: Vec<f32>,
    /// Rewards (with the time-limit bootstrap added) `[T, N]`.
    pub rewards: Vec<f32>,
    /// Episode ended at this step `[T, N]`.
    pub dones: Vec<bool>,
    /// `1 − episode_start` of each observation `[T, N]`.
    pub keep: Vec<f32>,
    /// Recurrent state before step `k·S`, stored every `S` steps (`S` = the BPTT chunk
    /// length, or 1 for sequence minibatches): `(h [N, H], c [N, H])`.
    pub chunk_states: Vec<(Vec<f32>, Option<Vec<f32>>)>,
    /// GAE advantages `[T, N]`.
    pub advantages: Vec<f32>,
    /// GAE returns `[T, N]`.
    pub returns: Vec<f32>,
}

impl Rollout {
    /// Empty storage for `n_envs × n_steps` transitions of `obs_len` floats.
    pub fn new(n_envs: usize, n_steps: usize, obs_len: usize) -> Self {
        let m = n_envs * n_steps;
        Rollout {
            n_envs,
            n_steps,
            obs_len,
            obs: vec![0.0; m * obs_len],
            actions: vec![0; m],
            log_probs: vec![0.0; m],
            values: vec![0.0; m],
            rewards: vec![0.0; m],
            dones: vec![false; m],
            keep: vec![1.0; m],
            chunk_states: Vec::new(),
            advantages: vec![0.0; m],
            returns: vec![0.0; m],
        }
    }
}

/// One BPTT chunk: env `env`, steps `start .. start + len`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Chunk {
    /// Env index.
    pub env: usize,
    /// Chunk index `k` (starts at step `k·L`).
    pub index: usize,
    /// First step.
    pub start: usize,
    /// Steps in the chunk (≤ L; the last chunk of a rollout may be shorter).
    pub len: usize,
}

/// Every chunk of length `chunk_len` of every env (env-major within each chunk index).
pub fn chunks(n_envs: usize, n_steps: usize, chunk_len: usize) -> Vec<Chunk> {
    let l = chunk_len.clamp(1, n_steps.max(1));
    let k_count = n_steps.div_ceil(l);
    let mut v = Vec::with_capacity(k_count * n_envs);
    for index in 0..k_count {
        for env in 0..n_envs {
            let start = index * l;
            v.push(Chunk {
                env,
                index,
                start,
                len: l.min(n_steps - start),
            });
        }
    }
    v
}

/// sb3-contrib's recurrent minibatches for one epoch (`RecurrentRolloutBuffer.get`): the
/// buffer is flattened env-major (`env·T + t`), rotated to start at flat index `split`, and
/// cut into windows of `batch_size` consecutive transitions (the last one shorter). Each
/// window splits into sequences at its first transition, at every episode start (`keep` =
/// 0, time-major `[T, N]`) and wherever the env changes; a sequence is a [`Chunk`] whose
/// `index` is its first step (its initial state is the state stored before that step).
pub fn sequence_batches(
    keep: &[f32],
    n_envs: usize,
    n_steps: usize,
    batch_size: usize,
    split: usize,
) -> Vec<Vec<Chunk>> {
    let m = n_envs * n_steps;
    let bs = batch_size.max(1);
    let mut out = Vec::with_capacity(m.div_ceil(bs));
    let mut k = 0;
    while k < m {
        let end = (k + bs).min(m);
        let mut seqs: Vec<Chunk> = Vec::new();
        for pos in k..end {
            let flat = (split + pos) % m;
            let (env, t) = (flat / n_steps, flat % n_steps);
            let starts = pos == k || t == 0 || keep[t * n_envs + env] == 0.0;
            match seqs.last_mut() {
                Some(c) if !starts => c.len += 1,
                _ => seqs.push(Chunk {
                    env,
                    index: t,
                    start: t,
                    len: 1,
                }),
            }
        }
        out.push(seqs);
        k = end;
    }
    out
}
