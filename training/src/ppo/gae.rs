//! Generalised advantage estimation (Schulman et al. 2016), SB3's convention.
//!
//! Arrays are time-major `[T, N]` flattened as `t·N + n`. `dones[t·N + n]` says the
//! episode of env `n` ended at step `t` (terminated *or* truncated); a truncation
//! must already have `γ·V(final_obs)` added to its reward (time-limit bootstrap),
//! so both kinds of ending cut the recursion the same way.

/// Advantages and returns (`returns = advantages + values`), each `[T, N]`.
///
/// `last_values [N]` are the values of the observations after the last step, used
/// where the episode did not end at `T − 1`.
pub fn compute_gae(
    rewards: &[f32],
    values: &[f32],
    dones: &[bool],
    last_values: &[f32],
    gamma: f32,
    lambda: f32,
) -> (Vec<f32>, Vec<f32>) {
    let n = last_values.len();
    let t_len = rewards.len() / n.max(1);
    assert_eq!(rewards.len(), t_len * n, "rewards must be [T, N]");
    assert_eq!(values.len(), rewards.len(), "values must be [T, N]");
    assert_eq!(dones.len(), rewards.len(), "dones must be [T, N]");
    let mut adv = vec![0f32; rewards.len()];
    let mut last = vec![0f32; n];
    for t in (0..t_len).rev() {
        for e in 0..n {
            let i = t * n + e;
            let not_done = if dones[i] { 0.0 } else { 1.0 };
            let next_value = if t + 1 == t_len {
                last_values[e]
            } else {
                values[i + n]
            };
            let delta = rewards[i] + gamma * next_value * not_done - values[i];
            last[e] = delta + gamma * lambda * not_done * last[e];
            adv[i] = last[e];
        }
    }
    let returns = adv.iter().zip(values).map(|(a, v)| a + v).collect();
    (adv, returns)
}

/// Explained variance `1 − Var(y − ŷ)/Var(y)` (NaN when `Var(y) = 0`), as SB3 logs it.
pub fn explained_variance(pred: &[f32], target: &[f32]) -> f64 {
    let n = target.len() as f64;
    if target.is_empty() {
        return f64::NAN;
    }
    let mean = |it: &mut dyn Iterator<Item = f64>| it.sum::<f64>() / n;
    let my = mean(&mut target.iter().map(|&y| y as f64));
    let var_y = mean(&mut target.iter().map(|&y| (y as f64 - my).powi(2)));
    let diff: Vec<f64> = target
        .iter()
        .zip(pred)
        .map(|(&y, &p)| (y - p) as f64)
        .collect();
    let md = diff.iter().sum::<f64>() / n;
    let var_d = diff.iter().map(|d| (d - md).powi(2)).sum::<f64>() / n;
    if var_y == 0.0 {
        f64::NAN
    } else {
        1.0 - var_d / var_y
    }
}
