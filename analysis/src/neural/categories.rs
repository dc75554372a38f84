//! Mutually exclusive unit categories — `ramp`, `time_field`, `oscillating`, `mixed`,
//! `untuned` — on a window of `W` steps after an event (`[trials, W, units]`, usually
//! `W = 2 × TD` on peak-interval probe trials), each decided by a test with a stated
//! false-positive rate.
//!
//! 1. **Tuned** (time-locked to the event): the variance over time of the unit's trial
//!    average, `S = Σ_t (m(t) − m̄)²`, against `surrogates` per-trial circular time shifts
//!    (each trial rotated by its own uniform random offset within its recorded steps: every
//!    trial keeps its values and its autocorrelation, the alignment to the event is
//!    destroyed). `p = (1 + #{S* ≥ S}) / (1 + surrogates)`; tuned when `p ≤ alpha`. Under
//!    the null (activity not locked to the event) this is a permutation test: its
//!    false-positive rate is `alpha` (5%; measured on white and AR(1) noise in
//!    `analysis/tests/neural_categories.rs`).
//! 2. Shape tests on the trial average of a tuned unit:
//!    * **ramp**: its best monotone (isotonic) fit explains ≥ `monotone_r2` (90%) of the
//!      variance — rising or falling through the window, extreme at an edge;
//!    * **time field**: its best unimodal (rise-then-fall) fit explains ≥ `unimodal_r2`
//!      (90%), the maximum is interior (not the first or last step) and the activity falls
//!      by at least half its range on both sides of the maximum. A ramp's maximum is at an
//!      edge, so a unit cannot pass both tests with the same maximum; one that passes both
//!      (possible only with noise) is `mixed`;
//!    * **oscillating**: a rhythm in the single trials, by three conditions: (a) the
//!      trial-averaged single-trial periodogram's largest bin with at least `min_cycles`
//!      (2) cycles in the window is significantly above a red-noise (AR(1)) null fitted to
//!      the same trials (the bin's power over the null's is `χ²₂ₖ/2K`-distributed for K
//!      trials; Bonferroni over the tested bins, level `alpha` — the test of Torrence &
//!      Compo 1998; a circular shift keeps every trial's spectrum, so it cannot serve
//!      here); (b) that bin is a spectral peak (above the bin just below it: the spectra of
//!      ramps and bumps fall from the lowest frequencies on); (c) the mean single-trial
//!      autocorrelation repeats itself within half the window — a trough ≤ −0.25, then a
//!      peak ≥ 0.25 ([`crate::neural::oscillation::acf_repeats`]), which a single bump,
//!      however narrow, never shows. Single trials rather than the trial average, so a
//!      rhythm whose phase drifts from trial to trial (clock noise) after starting locked
//!      to the event still counts;
//! 3. Category: not tuned → `untuned`; exactly one shape → that shape; two or more shapes,
//!    or tuned with none of them (time-locked but complex: e.g. a transient with less than
//!    two cycles, a rise-fall-rise) → `mixed`.
//!
//! Undefined tests are reported as errors, never as "false": fewer than `min_trials`
//! trials (a circular shift of one trial leaves its average's variance unchanged) or a
//! window shorter than `min_window` steps. The rhythm test of a unit is run on the longest
//! stretch after the event that `min_trials` trials cover; when that is shorter than
//! `min_window` (trials that end early, off probe trials) it is undefined for the unit
//! (`spectral_p` NaN) and the summaries count those units (`rhythm_undefined`).

use crate::neural::oscillation::{acf_repeats, autocorrelation};
use crate::neural::shape::{monotone_r2, periodogram, spectral_peak, unimodal_r2};
use crate::neural::{Cube, argmax};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// A unit's category (mutually exclusive).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, strum::IntoStaticStr)]
#[serde(rename_all = "snake_case")]
#[strum(serialize_all = "snake_case")]
pub enum Category {
    /// Monotone over the window.
    Ramp,
    /// One interior peak, falling by half its range on both sides.
    TimeField,
    /// A significant spectral peak with at least two cycles in the window.
    Oscillating,
    /// Time-locked, with two or more of the shapes or none of them.
    Mixed,
    /// Not time-locked to the event (surrogate test not significant).
    Untuned,
}

/// Every category, in report order.
pub const CATEGORIES: [Category; 5] = [
    Category::Ramp,
    Category::TimeField,
    Category::Oscillating,
    Category::Mixed,
    Category::Untuned,
];

impl Category {
    /// The JSON / column name (`ramp`, `time_field`, `oscillating`, `mixed`, `untuned`).
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// Thresholds of the category tests.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CategoryConfig {
    /// Significance level of the surrogate tests (false-positive rate), default 0.05.
    pub alpha: f64,
    /// Circular-shift surrogates per unit, default 199.
    pub surrogates: usize,
    /// Variance explained by the monotone fit for a ramp, default 0.9.
    pub monotone_r2: f64,
    /// Variance explained by the unimodal fit for a time field, default 0.9.
    pub unimodal_r2: f64,
    /// Cycles in the window a rhythm must show, default 2.
    pub min_cycles: f64,
    /// Fewest trials for the surrogate tests, default 4.
    pub min_trials: usize,
    /// Shortest window (steps) for the tests, default 8.
    pub min_window: usize,
    /// Seed of the surrogates.
    pub seed: u64,
}

impl Default for CategoryConfig {
    fn default() -> Self {
        CategoryConfig {
            alpha: 0.05,
            surrogates: 199,
            monotone_r2: 0.9,
            unimodal_r2: 0.9,
            min_cycles: 2.0,
            min_trials: 4,
            min_window: 8,
            seed: 0,
        }
    }
}

/// Why the categories could not be decided.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, thiserror::Error)]
pub enum CategoryError {
    /// Too few trials for the surrogate tests.
    #[error("{trials} trials: the surrogate tests need at least {min}")]
    TooFewTrials {
        /// Trials available.
        trials: usize,
        /// Trials needed.
        min: usize,
    },
    /// The window is too short for the shape and spectral tests.
    #[error("window of {window} steps: the tests need at least {min}")]
    WindowTooShort {
        /// Window (steps).
        window: usize,
        /// Steps needed.
        min: usize,
    },
}

/// The tests of one unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitTests {
    /// Unit index (column of the cube).
    pub unit: usize,
    /// Surrogate p of the trial average's variance over time (tuning).
    pub tuning_p: f64,
    /// Variance explained by the best monotone fit.
    pub monotone_r2: f64,
    /// Variance explained by the best unimodal fit.
    pub unimodal_r2: f64,
    /// Step of the trial average's maximum (steps after the event).
    pub peak_time: usize,
    /// Width (steps) of the peak at half its height above the window's minimum (NaN when
    /// it does not fall to half on both sides).
    pub peak_width: f64,
    /// Frequency of the largest bin with ≥ `min_cycles` cycles of the trial-averaged
    /// single-trial periodogram (cycles per step).
    pub spectral_peak: f64,
    /// p of that bin's power against the AR(1) null (Bonferroni over the tested bins);
    /// NaN when the rhythm test is undefined (fewer than `min_trials` trials cover
    /// `min_window` steps): such a unit cannot be `oscillating`, and summaries count it.
    pub spectral_p: f64,
    /// Whether that bin is a spectral peak (above the bin just below it) and the mean
    /// single-trial autocorrelation repeats itself.
    pub narrowband: bool,
    /// Passed the ramp test.
    pub ramp: bool,
    /// Passed the time-field test.
    pub time_field: bool,
    /// Passed the oscillation test.
    pub oscillating: bool,
    /// The category.
    pub category: Category,
}

/// One unit's recorded steps per trial (finite prefix: NaN marks the end of a trial).
fn unit_trials(cube: &Cube, i: usize) -> Vec<Vec<f64>> {
    (0..cube.trials)
        .map(|k| {
            (0..cube.time)
                .map(|t| cube.at(k, t, i))
                .take_while(|v| v.is_finite())
                .collect()
        })
        .collect()
}

/// Trial average of `trials` rotated by `shifts` (NaN-aware; NaN where no trial reaches).
fn rotated_average(trials: &[Vec<f64>], shifts: &[usize], len: usize) -> Vec<f64> {
    let mut sum = vec![0.0; len];
    let mut n = vec![0usize; len];
    for (x, &s) in trials.iter().zip(shifts) {
        let l = x.len();
        for t in 0..l.min(len) {
            sum[t] += x[(t + s) % l];
            n[t] += 1;
        }
    }
    sum.iter()
        .zip(&n)
        .map(|(s, &c)| if c > 0 { s / c as f64 } else { f64::NAN })
        .collect()
}

/// The finite prefix of a trial average (steps every analysed trial may lack at the end).
fn finite_prefix(m: &[f64]) -> Vec<f64> {
    m.iter().copied().take_while(|v| v.is_finite()).collect()
}

fn variance_stat(m: &[f64]) -> f64 {
    let mean = m.iter().sum::<f64>() / m.len().max(1) as f64;
    m.iter().map(|v| (v - mean).powi(2)).sum()
}

/// Lowest periodogram bin with at least `cycles` cycles in `len` steps.
fn min_bin(len: usize, cycles: f64) -> usize {
    (cycles.ceil() as usize).max(1).min(len / 2 + 1)
}

/// Width at half height (between the interpolated crossings of `min + (peak − min)/2`).
fn half_width(m: &[f64], peak: usize) -> f64 {
    let lo = m.iter().copied().fold(f64::INFINITY, f64::min);
    let half = lo + (m[peak] - lo) / 2.0;
    let cross = |range: &mut dyn Iterator<Item = usize>| {
        let mut prev = peak;
        for t in range {
            if m[t] <= half {
                let (a, b) = (m[t], m[prev]);
                let f = if b > a { (half - a) / (b - a) } else { 0.0 };
                return Some(t as f64 + (prev as f64 - t as f64) * f);
            }
            prev = t;
        }
        None
    };
    match (cross(&mut (0..peak).rev()), cross(&mut (peak + 1..m.len()))) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    }
}

/// The single-trial rhythm test on `trials` (each truncated to the shortest, `m` steps):
/// `(peak bin, p against the AR(1) null, the bin is above the one below it and the mean
/// autocorrelation repeats)`.
fn rhythm(trials: &[Vec<f64>], m: usize, bin0: usize) -> (usize, f64, bool) {
    let k = trials.len();
    let half = m / 2;
    let mut power = vec![0.0; half + 1];
    let mut acf = vec![0.0; half + 1];
    let (mut c0, mut c1) = (0.0, 0.0);
    for x in trials {
        let x = &x[..m];
        for (p, v) in power.iter_mut().zip(periodogram(x)) {
            *p += v / k as f64;
        }
        for (a, v) in acf.iter_mut().zip(autocorrelation(x, half)) {
            *a += v / k as f64;
        }
        let mean = x.iter().sum::<f64>() / m as f64;
        for t in 0..m {
            let d = x[t] - mean;
            c0 += d * d;
            if t + 1 < m {
                c1 += d * (x[t + 1] - mean);
            }
        }
    }
    // Tested bins: bin0 … half − 1 (the Nyquist bin has other statistics).
    let last = half.saturating_sub(1);
    if c0 <= 0.0 || bin0 > last {
        return (0, 1.0, false);
    }
    let rho = (c1 / c0).clamp(-0.99, 0.99);
    let shape: Vec<f64> = (0..=half)
        .map(|j| {
            let w = 2.0 * std::f64::consts::PI * j as f64 / m as f64;
            (1.0 - rho * rho) / (1.0 - 2.0 * rho * w.cos() + rho * rho)
        })
        .collect();
    // Scale the null to the observed mean power over bins 1 … half − 1.
    let bins = 1..=last;
    let scale = bins.clone().map(|j| power[j]).sum::<f64>()
        / bins.clone().map(|j| shape[j]).sum::<f64>().max(1e-300);
    let (peak, _) = spectral_peak(&power[..=last], bin0);
    if peak < bin0 || scale <= 0.0 {
        return (peak, 1.0, false);
    }
    let narrowband = power[peak] > power[peak - 1] && acf_repeats(&acf, -0.25, 0.25);
    let ratio = power[peak] / (scale * shape[peak]);
    let dof = 2.0 * k as f64;
    let tail = ChiSquared::new(dof).map_or(1.0, |d| d.sf(ratio * dof));
    let tested = (last + 1 - bin0) as f64;
    (peak, (tail * tested).min(1.0), narrowband)
}

/// Classifies every unit of `cube` (`[trials, W, units]`, NaN after a trial's end).
pub fn classify_units(cube: &Cube, cfg: &CategoryConfig) -> Result<Vec<UnitTests>, CategoryError> {
    if cube.time < cfg.min_window {
        return Err(CategoryError::WindowTooShort {
            window: cube.time,
            min: cfg.min_window,
        });
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(cfg.seed);
    let mut out = Vec::with_capacity(cube.units);
    for i in 0..cube.units {
        let trials: Vec<Vec<f64>> = unit_trials(cube, i)
            .into_iter()
            .filter(|x| !x.is_empty())
            .collect();
        if trials.len() < cfg.min_trials.max(2) {
            return Err(CategoryError::TooFewTrials {
                trials: trials.len(),
                min: cfg.min_trials.max(2),
            });
        }
        let zero = vec![0; trials.len()];
        let m = finite_prefix(&rotated_average(&trials, &zero, cube.time));
        if m.len() < cfg.min_window {
            return Err(CategoryError::WindowTooShort {
                window: m.len(),
                min: cfg.min_window,
            });
        }
        let len = m.len();
        let s = variance_stat(&m);
        let mut above = 0usize;
        let mut shifts = vec![0usize; trials.len()];
        for _ in 0..cfg.surrogates {
            for (sh, x) in shifts.iter_mut().zip(&trials) {
                *sh = rng.random_range(0..x.len());
            }
            let ms: Vec<f64> = rotated_average(&trials, &shifts, len)
                .into_iter()
                .map(|v| if v.is_finite() { v } else { 0.0 })
                .collect();
            if variance_stat(&ms) >= s {
                above += 1;
            }
        }
        // The rhythm test on the longest stretch `shortest` that at least `min_trials`
        // trials cover (those trials, truncated to it); undefined below `min_window`.
        let mut lens: Vec<usize> = trials.iter().map(Vec::len).collect();
        lens.sort_unstable_by(|a, b| b.cmp(a));
        let shortest = lens[cfg.min_trials.max(2).min(lens.len()) - 1];
        let long: Vec<Vec<f64>> = trials
            .iter()
            .filter(|x| x.len() >= shortest)
            .cloned()
            .collect();
        let bin0 = min_bin(shortest, cfg.min_cycles);
        let (k_peak, spectral_p, narrowband) = if shortest >= cfg.min_window {
            rhythm(&long, shortest, bin0)
        } else {
            (0, f64::NAN, false)
        };
        let tuning_p = (above + 1) as f64 / (cfg.surrogates + 1) as f64;
        let tuned = tuning_p <= cfg.alpha && s > 0.0;
        let (mono, _) = monotone_r2(&m);
        let uni = unimodal_r2(&m);
        let peak = argmax(&m);
        let (lo, hi) = crate::neural::finite_range(m.iter().copied());
        let falls = |side: &[f64]| {
            side.iter().copied().fold(f64::INFINITY, f64::min) <= hi - 0.5 * (hi - lo)
        };
        let ramp = tuned && mono >= cfg.monotone_r2;
        let time_field = tuned
            && uni >= cfg.unimodal_r2
            && peak > 0
            && peak + 1 < len
            && falls(&m[..peak])
            && falls(&m[peak + 1..]);
        let oscillating = tuned && k_peak >= bin0 && spectral_p <= cfg.alpha && narrowband;
        let shapes = [ramp, time_field, oscillating];
        let category = match (tuned, shapes.iter().filter(|&&b| b).count()) {
            (false, _) => Category::Untuned,
            (true, 1) if ramp => Category::Ramp,
            (true, 1) if time_field => Category::TimeField,
            (true, 1) => Category::Oscillating,
            _ => Category::Mixed,
        };
        out.push(UnitTests {
            unit: i,
            tuning_p,
            monotone_r2: mono,
            unimodal_r2: uni,
            peak_time: peak,
            peak_width: half_width(&m, peak),
            spectral_peak: if shortest > 0 {
                k_peak as f64 / shortest as f64
            } else {
                f64::NAN
            },
            spectral_p,
            narrowband,
            ramp,
            time_field,
            oscillating,
            category,
        });
    }
    Ok(out)
}

/// Counts per category (they sum to the units classified).
pub type CategoryCounts = PerCategory<usize>;

impl CategoryCounts {
    /// Counts of `units`' categories.
    pub fn of(units: &[UnitTests]) -> Self {
        let mut c = CategoryCounts::default();
        for u in units {
            *c.get_mut(u.category) += 1;
        }
        c
    }

    /// Units counted.
    pub fn total(&self) -> usize {
        CATEGORIES.iter().map(|&c| self.get(c)).sum()
    }
}

/// A value per category (fractions or interval bounds).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct PerCategory<T> {
    /// Ramps.
    pub ramp: T,
    /// Time fields.
    pub time_field: T,
    /// Oscillating units.
    pub oscillating: T,
    /// Mixed units.
    pub mixed: T,
    /// Untuned units.
    pub untuned: T,
}

impl<T: Copy> PerCategory<T> {
    /// From a function of the category.
    pub fn from_fn(f: impl Fn(Category) -> T) -> Self {
        PerCategory {
            ramp: f(Category::Ramp),
            time_field: f(Category::TimeField),
            oscillating: f(Category::Oscillating),
            mixed: f(Category::Mixed),
            untuned: f(Category::Untuned),
        }
    }

    /// The value of `cat`.
    pub fn get(&self, cat: Category) -> T {
        match cat {
            Category::Ramp => self.ramp,
            Category::TimeField => self.time_field,
            Category::Oscillating => self.oscillating,
            Category::Mixed => self.mixed,
            Category::Untuned => self.untuned,
        }
    }

    /// The value of `cat`, to change it.
    pub fn get_mut(&mut self, cat: Category) -> &mut T {
        match cat {
            Category::Ramp => &mut self.ramp,
            Category::TimeField => &mut self.time_field,
            Category::Oscillating => &mut self.oscillating,
            Category::Mixed => &mut self.mixed,
            Category::Untuned => &mut self.untuned,
        }
    }
}

/// Wilson score 95% interval `[lo, hi]` of a proportion `k / n` (`[0, 1]` for `n = 0`).
pub fn wilson_interval(k: usize, n: usize) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let z = 1.959_963_984_540_054;
    let (nf, p) = (n as f64, k as f64 / n as f64);
    let denom = 1.0 + z * z / nf;
    let centre = (p + z * z / (2.0 * nf)) / denom;
    let half = z / denom * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt();
    let lo = if k == 0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let hi = if k >= n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    [lo, hi]
}
