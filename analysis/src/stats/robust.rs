//! Few-run statistics as the RL field reports them (rliable; Agarwal et al. 2021, "Deep
//! Reinforcement Learning at the Edge of the Statistical Precipice"):
//!
//! * [`iqm`] — the interquartile mean: the mean of the middle 50% of the runs (the
//!   `⌊n/4⌋` lowest and highest values cut, as `scipy.stats.trim_mean(x, 0.25)`);
//! * [`stratified_bootstrap_ci`] — a percentile bootstrap confidence interval of a
//!   statistic, the runs resampled with replacement within each stratum (e.g. each task
//!   setting a row's runs were trained at), every stratum keeping its size;
//! * [`probability_of_improvement`] — `P(X > Y)` for a random run of X and one of Y, ties
//!   counting one half (the Mann–Whitney U statistic over `n·m`).

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Bootstrap resamples of the leaderboard's confidence intervals (a 95% interval's ends to
/// about ±0.5% of the statistic's spread; rliable's default is 50,000).
pub const BOOTSTRAP_RESAMPLES: usize = 2000;

/// The interquartile mean of `values` (non-finite ones left out; NaN for none): `⌊n/4⌋`
/// values cut at each end, the rest averaged.
pub fn iqm(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let cut = v.len() / 4;
    let kept = &v[cut..v.len() - cut];
    kept.iter().sum::<f64>() / kept.len() as f64
}

/// The `q`-quantile (0–1) of sorted values, linearly interpolated between order statistics
/// (numpy's default).
pub fn quantile_sorted(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let pos = q.clamp(0.0, 1.0) * (sorted.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    sorted[lo] + (pos - lo as f64) * (sorted[hi] - sorted[lo])
}

/// Percentile bootstrap `(lo, hi)` interval at `level` (e.g. 0.95) of `statistic` over
/// `values` with `strata[i]` the stratum of `values[i]`: each of `resamples` resamples
/// draws, within every stratum, as many values as it has, with replacement (seeded by
/// `seed`). Non-finite values are left out first; `None` below 2 values, and when no
/// stratum has two (a row of one run per task setting has nothing to resample).
pub fn stratified_bootstrap_ci(
    values: &[f64],
    strata: &[String],
    statistic: impl Fn(&[f64]) -> f64,
    level: f64,
    resamples: usize,
    seed: u64,
) -> Option<(f64, f64)> {
    let mut groups: Vec<(&str, Vec<f64>)> = Vec::new();
    for (v, s) in values.iter().zip(strata) {
        if !v.is_finite() {
            continue;
        }
        match groups.iter_mut().find(|(k, _)| *k == s.as_str()) {
            Some((_, g)) => g.push(*v),
            None => groups.push((s.as_str(), vec![*v])),
        }
    }
    let n: usize = groups.iter().map(|(_, g)| g.len()).sum();
    // With one value per stratum every resample is the sample itself: no interval.
    if n < 2 || resamples == 0 || groups.iter().all(|(_, g)| g.len() < 2) {
        return None;
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut stats = Vec::with_capacity(resamples);
    let mut draw = Vec::with_capacity(n);
    for _ in 0..resamples {
        draw.clear();
        for (_, g) in &groups {
            draw.extend((0..g.len()).map(|_| g[rng.random_range(0..g.len())]));
        }
        stats.push(statistic(&draw));
    }
    stats.retain(|s| s.is_finite());
    stats.sort_by(f64::total_cmp);
    let tail = (1.0 - level) / 2.0;
    Some((
        quantile_sorted(&stats, tail),
        quantile_sorted(&stats, 1.0 - tail),
    ))
}

/// `P(X > Y)`: the share of pairs (one value of `x`, one of `y`) in which `x`'s is larger,
/// ties counting one half (non-finite values left out; NaN when either side is empty).
pub fn probability_of_improvement(x: &[f64], y: &[f64]) -> f64 {
    let x: Vec<f64> = x.iter().copied().filter(|v| v.is_finite()).collect();
    let y: Vec<f64> = y.iter().copied().filter(|v| v.is_finite()).collect();
    if x.is_empty() || y.is_empty() {
        return f64::NAN;
    }
    let mut score = 0.0;
    for a in &x {
        for b in &y {
            score += if a > b {
                1.0
            } else if a == b {
                0.5
            } else {
                0.0
            };
        }
    }
    score / (x.len() * y.len()) as f64
}
