//! Neural metrics on recorded activity aligned to an event (usually oven-on):
//! ramping units, time cells, temporal information, sequentiality index and elapsed-time
//! decoding (cross-validated ridge and Bayesian decoders).
//!
//! Input is a [`Cube`]: `[trials, time, units]`, NaN where a trial had ended (as produced by
//! `ActivityDataset::aligned`).
//!
//! Submodules: [`decode`] — the decoders of elapsed time; [`oscillation`] — Welch spectra,
//! autocorrelation, phase coherence and the oscillation test; [`shape`] — monotone and
//! unimodal fits, periodograms; [`categories`] — the mutually exclusive unit categories
//! (ramp, time field, oscillating, mixed, untuned, beyond the window) with surrogate tests; [`summary`] — the
//! per-population neural summary (`record --summary`, the leaderboard's neural columns);
//! [`speed`] — KiNeT timing by speed; [`production`] — KiNeT on a reproduction dataset's
//! trajectories after Set.

pub mod categories;
pub mod decode;
pub mod dynamics;
pub mod geometry;
mod locking;
pub mod oscillation;
pub mod probe;
pub mod production;
pub mod shape;
pub mod speed;
pub mod summary;

use crate::behaviour::foc::linear_fit;
use ndarray::Array3;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

/// Activity `[trials, time, units]` (an `ndarray` array in standard, row-major layout);
/// NaN = missing.
#[derive(Debug, Clone, PartialEq)]
pub struct Cube {
    data: Array3<f64>,
}

impl Cube {
    /// From row-major values `[trials, time, units]`; `None` when `data` does not hold
    /// `trials × time × units` values.
    pub fn new(trials: usize, time: usize, units: usize, data: Vec<f64>) -> Option<Self> {
        Array3::from_shape_vec((trials, time, units), data)
            .ok()
            .map(|data| Cube { data })
    }

    /// From an aligned `f32` buffer `[trials, time, units]` (as the activity datasets
    /// align trials; its length must be `trials × time × units`).
    pub fn from_f32(data: &[f32], trials: usize, time: usize, units: usize) -> Self {
        let values = data.iter().map(|&v| f64::from(v)).collect();
        Cube::new(trials, time, units, values)
            .expect("an aligned buffer holds trials × time × units values")
    }

    /// Number of trials.
    pub fn trials(&self) -> usize {
        self.data.dim().0
    }

    /// Number of time bins (steps).
    pub fn time(&self) -> usize {
        self.data.dim().1
    }

    /// Number of units.
    pub fn units(&self) -> usize {
        self.data.dim().2
    }

    /// The values `[trials, time, units]`.
    pub fn array(&self) -> &Array3<f64> {
        &self.data
    }

    /// The values, row-major `[trials, time, units]` flattened.
    pub fn values(&self) -> &[f64] {
        self.data
            .as_slice()
            .expect("a cube is built in standard layout")
    }

    /// The first `time` bins of the units `units` (indices along the unit axis), every
    /// trial: a new cube `[trials, time, units.len()]`.
    pub fn select(&self, time: usize, units: &[usize]) -> Cube {
        let sub = self
            .data
            .slice(ndarray::s![.., ..time, ..])
            .select(ndarray::Axis(2), units);
        Cube {
            data: sub.as_standard_layout().into_owned(),
        }
    }

    /// Value at (trial, t, unit).
    pub fn at(&self, k: usize, t: usize, i: usize) -> f64 {
        self.data[[k, t, i]]
    }

    /// Trial average `[time, units]` (row-major) over `trials` (NaN ignored; NaN where no
    /// trial has data).
    pub fn average_over(&self, trials: impl Iterator<Item = usize> + Clone) -> Vec<f64> {
        let (time, units) = (self.time(), self.units());
        let mut out = vec![f64::NAN; time * units];
        for t in 0..time {
            for i in 0..units {
                let (mut s, mut n) = (0.0, 0);
                for k in trials.clone() {
                    let v = self.at(k, t, i);
                    if v.is_finite() {
                        s += v;
                        n += 1;
                    }
                }
                if n > 0 {
                    out[t * units + i] = s / n as f64;
                }
            }
        }
        out
    }

    /// Trial average over all trials `[time, units]`.
    pub fn average(&self) -> Vec<f64> {
        self.average_over(0..self.trials())
    }
}

/// Column `i` of a `[time, units]` matrix, keeping only finite values with their times.
fn unit_series(avg: &[f64], units: usize, i: usize) -> (Vec<f64>, Vec<f64>) {
    avg.chunks_exact(units)
        .enumerate()
        .filter(|(_, row)| row[i].is_finite())
        .map(|(t, row)| (t as f64, row[i]))
        .unzip()
}

/// Two-sided p-value of a Pearson correlation `r` over `n` points (Student t, n − 2 df).
pub fn correlation_p(r: f64, n: usize) -> f64 {
    if n < 3 || !r.is_finite() {
        return f64::NAN;
    }
    if r.abs() >= 1.0 {
        return 0.0;
    }
    let df = (n - 2) as f64;
    let t2 = r * r * df / (1.0 - r * r);
    // P(|T| > t) = I_{df/(df+t²)}(df/2, 1/2).
    statrs::function::beta::beta_reg(0.5 * df, 0.5, df / (df + t2))
}

/// Ramp classification of one unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RampUnit {
    /// Unit index.
    pub unit: usize,
    /// Pearson r of trial-averaged activity vs time.
    pub r: f64,
    /// OLS slope (activity per step).
    pub slope: f64,
    /// Two-sided p of r.
    pub p: f64,
    /// `|r| ≥ r_min` and `p ≤ p_max`.
    pub ramping: bool,
}

/// Ramping units (the paper's rule: OLS of trial-averaged activity vs time, `|r| ≥ 0.9`, `p ≤ 0.05`)
/// of a `[time, units]` average.
pub fn classify_ramps(avg: &[f64], units: usize, r_min: f64, p_max: f64) -> Vec<RampUnit> {
    (0..units)
        .map(|i| {
            let (t, y) = unit_series(avg, units, i);
            let (slope, _, r2) = linear_fit(&t, &y);
            let r = r2.sqrt() * slope.signum();
            let p = correlation_p(r, t.len());
            RampUnit {
                unit: i,
                r,
                slope,
                p,
                ramping: r.abs() >= r_min && p <= p_max,
            }
        })
        .collect()
}

/// Index of the largest value (the first on ties; 0 for an empty slice).
pub fn argmax(v: &[f64]) -> usize {
    v.iter()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |b, (t, &x)| if x > b.1 { (t, x) } else { b },
        )
        .0
}

/// `(min, max)` of the finite values (`(∞, −∞)` when there are none).
pub fn finite_range(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        })
}

/// Min–max normalised copy of every unit's series (constant units → all 0).
fn normalise_units(avg: &[f64], units: usize) -> Vec<f64> {
    let mut out = avg.to_vec();
    for i in 0..units {
        let (lo, hi) = finite_range(avg.iter().skip(i).step_by(units).copied());
        for v in out.iter_mut().skip(i).step_by(units) {
            *v = if v.is_finite() && hi > lo {
                (*v - lo) / (hi - lo)
            } else {
                0.0
            };
        }
    }
    out
}

fn entropy(p: impl Iterator<Item = f64>) -> f64 {
    -p.filter(|&x| x > 0.0).map(|x| x * x.ln()).sum::<f64>()
}

/// Sequentiality index (Zhou, Masmanidis & Buonomano 2020): `√(PE × TS)` on the
/// `[time, units]` average with each unit min–max normalised. PE = entropy of the
/// distribution of peak times over the `M` time bins / ln M; TS = mean over time of
/// `1 − H(activity across units at t)/ln N`. 1 for a one-hot sequence tiling the window
/// (N = M), ≈ 0 when all units peak together (identical ramps).
pub fn sequentiality_index(avg: &[f64], units: usize) -> f64 {
    let time = avg.len() / units.max(1);
    if time < 2 || units < 2 {
        return f64::NAN;
    }
    let a = normalise_units(avg, units);
    let mut counts = vec![0.0; time];
    let mut active = 0.0;
    for i in 0..units {
        let col: Vec<f64> = a.iter().skip(i).step_by(units).copied().collect();
        if col.iter().all(|&v| v <= 0.0) {
            continue;
        }
        counts[argmax(&col)] += 1.0;
        active += 1.0;
    }
    if active == 0.0 {
        return 0.0;
    }
    let pe = entropy(counts.iter().map(|c| c / active)) / (time as f64).ln();
    let ts = a
        .chunks_exact(units)
        .map(|row| {
            let s: f64 = row.iter().sum();
            if s <= 0.0 {
                return 1.0;
            }
            1.0 - entropy(row.iter().map(|v| v / s)) / (units as f64).ln()
        })
        .sum::<f64>()
        / time as f64;
    (pe * ts).max(0.0).sqrt()
}

/// Temporal (Skaggs) information per unit, bits per step-bin: `Σ_t (1/T)(λ_t/λ̄) log₂(λ_t/λ̄)`
/// on the min–max normalised average.
pub fn temporal_information(avg: &[f64], units: usize) -> Vec<f64> {
    let a = normalise_units(avg, units);
    let time = a.len() / units.max(1);
    (0..units)
        .map(|i| {
            let col: Vec<f64> = a.iter().skip(i).step_by(units).copied().collect();
            let mean = col.iter().sum::<f64>() / time as f64;
            if mean <= 0.0 {
                return 0.0;
            }
            col.iter()
                .filter(|&&v| v > 0.0)
                .map(|&v| (v / mean) * (v / mean).log2() / time as f64)
                .sum()
        })
        .collect()
}

/// Time-cell classification of one unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimeCellUnit {
    /// Unit index.
    pub unit: usize,
    /// Peak time of the trial average (steps after the event).
    pub peak_time: usize,
    /// Ridge-to-background ratio: mean activity within ±`half_width` of the peak over the
    /// mean elsewhere (normalised activity).
    pub ratio: f64,
    /// Fraction of circular-shift shuffles with a ratio at least as large.
    pub p: f64,
    /// Correlation of the odd-trial and even-trial averages.
    pub reliability: f64,
    /// `p < 0.05`, reliability > 0.5 and the peak inside the window (at least `half_width`
    /// steps from either edge: a ramp that peaks at the window's end is not a time field).
    pub time_cell: bool,
}

fn ridge_ratio(col: &[f64], half_width: usize) -> (usize, f64) {
    let peak = argmax(col);
    let (mut ridge, mut nr, mut back, mut nb) = (0.0, 0, 0.0, 0);
    for (t, &v) in col.iter().enumerate() {
        if t.abs_diff(peak) <= half_width {
            ridge += v;
            nr += 1;
        } else {
            back += v;
            nb += 1;
        }
    }
    let back = if nb > 0 { back / nb as f64 } else { 0.0 };
    (peak, (ridge / nr.max(1) as f64) / back.max(1e-9))
}

/// Time cells: ridge-to-background ratio against `shuffles` circular shifts of every trial
/// (seeded), plus odd/even reliability. Missing (NaN) values count as 0 after normalisation.
pub fn time_cells(cube: &Cube, half_width: usize, shuffles: usize, seed: u64) -> Vec<TimeCellUnit> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let nt = cube.time();
    (0..cube.units())
        .map(|i| {
            let series = |k: usize| -> Vec<f64> {
                (0..nt)
                    .map(|t| cube.at(k, t, i))
                    .map(|v| if v.is_finite() { v } else { 0.0 })
                    .collect()
            };
            let trials: Vec<Vec<f64>> = (0..cube.trials()).map(series).collect();
            let (lo, hi) = finite_range(trials.iter().flatten().copied());
            let span = (hi - lo).max(1e-12);
            let norm: Vec<Vec<f64>> = trials
                .iter()
                .map(|s| s.iter().map(|v| (v - lo) / span).collect())
                .collect();
            let avg = |sel: &mut dyn Iterator<Item = &Vec<f64>>| {
                let mut acc = vec![0.0; nt];
                let mut n = 0.0f64;
                for s in sel {
                    acc.iter_mut().zip(s).for_each(|(a, v)| *a += v);
                    n += 1.0;
                }
                acc.iter_mut().for_each(|a| *a /= n.max(1.0));
                acc
            };
            let mean = avg(&mut norm.iter());
            let (peak_time, ratio) = ridge_ratio(&mean, half_width);
            let mut exceed = 0;
            for _ in 0..shuffles {
                let shifted: Vec<Vec<f64>> = norm
                    .iter()
                    .map(|s| {
                        let k = rng.random_range(0..nt);
                        (0..nt).map(|t| s[(t + k) % nt]).collect()
                    })
                    .collect();
                if ridge_ratio(&avg(&mut shifted.iter()), half_width).1 >= ratio {
                    exceed += 1;
                }
            }
            let p = (exceed as f64 + 1.0) / (shuffles as f64 + 1.0);
            let odd = avg(&mut norm.iter().skip(1).step_by(2));
            let even = avg(&mut norm.iter().step_by(2));
            let (slope, _, r2) = linear_fit(&odd, &even);
            let reliability = r2.sqrt() * slope.signum();
            TimeCellUnit {
                unit: i,
                peak_time,
                ratio,
                p,
                reliability,
                time_cell: p < 0.05
                    && reliability > 0.5
                    && peak_time >= half_width.max(1)
                    && peak_time + half_width.max(1) < nt,
            }
        })
        .collect()
}

/// Temporal scaling between two responses of a unit (e.g. trial averages at two TDs):
/// the factor `s` (grid search over `[0.25, 4]`: `1.01^k`, 1 included) for which `b(t) ≈ a(t/s)`
/// (linear interpolation of `a`; compared over `t < len(b)` where `t/s` is inside `a`),
/// and the R² of that match. `s ≈ TD_b / TD_a` for a unit that scales with the interval.
/// Index `t` is time `t` (origin 0); see [`scaling_factor_from`].
pub fn scaling_factor(a: &[f64], b: &[f64]) -> (f64, f64) {
    scaling_factor_from(a, b, 0.0)
}

/// [`scaling_factor`] with sample `i` of `a` and `b` at time `i + origin` (steps since the
/// event; e.g. 1 when an aligned window starts one step after oven-on): `b(τ) ≈ a(τ/s)`.
/// A factor counts when it pairs at least half of the shorter series' samples (and 3).
/// `(NaN, −∞)` when either series has fewer than 2 samples or no factor overlaps enough.
pub fn scaling_factor_from(a: &[f64], b: &[f64], origin: f64) -> (f64, f64) {
    let interp = |t: f64| -> Option<f64> {
        if t < 0.0 || t > (a.len() - 1) as f64 {
            return None;
        }
        let i = t.floor() as usize;
        let f = t - i as f64;
        let hi = a.get(i + 1).copied().unwrap_or(a[i]);
        Some(a[i] * (1.0 - f) + hi * f)
    };
    let mut best = (f64::NAN, f64::NEG_INFINITY);
    if a.len() < 2 || b.len() < 2 {
        return best;
    }
    // Factors 1.01^k from 1/4 to 4 (1 itself on the grid).
    let steps = (4f64.ln() / 0.01f64.ln_1p()).floor() as i32;
    for k in -steps..=steps {
        let s = 1.01f64.powi(k);
        let pairs: Vec<(f64, f64)> = b
            .iter()
            .enumerate()
            .filter_map(|(t, &y)| interp((t as f64 + origin) / s - origin).map(|x| (x, y)))
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        if pairs.len() < a.len().min(b.len()).div_ceil(2).max(3) {
            continue;
        }
        let my = pairs.iter().map(|p| p.1).sum::<f64>() / pairs.len() as f64;
        let ss: f64 = pairs.iter().map(|p| (p.1 - my).powi(2)).sum();
        let sse: f64 = pairs.iter().map(|p| (p.1 - p.0).powi(2)).sum();
        let r2 = if ss > 0.0 { 1.0 - sse / ss } else { f64::NAN };
        if r2 > best.1 {
            best = (s, r2);
        }
    }
    best
}
