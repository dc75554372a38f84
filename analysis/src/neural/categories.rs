//! Mutually exclusive unit categories — `ramp`, `time_field`, `oscillating`, `mixed`,
//! `untuned`, `beyond_window` — on a window of `W` steps after an event (`[trials, W,
//! units]`, usually `W = 2 × TD` on peak-interval probe trials; the rhythm and
//! beyond-window tests also read the steps recorded after it), each decided by a test with
//! a stated false-positive rate.
//!
//! 1. **Tuned** (time-locked to the event): the variance over time of the unit's trial
//!    average, `S = Σ_t (m(t) − m̄)²`, against `surrogates` per-trial circular time shifts
//!    (each trial rotated by its own uniform random offset within its recorded steps: every
//!    trial keeps its values and its autocorrelation, the alignment to the event is
//!    destroyed). `p = (1 + #{S* ≥ S}) / (1 + surrogates)`; tuned when `p ≤ alpha`. Under
//!    the null (activity not locked to the event) this is a permutation test: its
//!    false-positive rate is `alpha` (5%; measured on white and AR(1) noise in
//!    `analysis/tests/neural_categories.rs`).
//! 2. Shape tests on the trial average of a tuned unit, each scored as the fraction of the
//!    average's *explainable* variance its fit explains — the sampling noise of a trial
//!    average of few trials discounted ([`crate::neural::shape::AverageNoise`]), so that a
//!    delay-line unit whose average is a jagged histogram of a dozen trials' spikes is
//!    judged by its shape, not by the number of trials:
//!    * **ramp**: its best monotone (isotonic) fit explains ≥ `monotone_r2` (90%) —
//!      rising or falling through the window, extreme at an edge;
//!    * **time field**: its best unimodal (rise-then-fall) fit explains ≥ `unimodal_r2`
//!      (90%), the maximum is interior (not the first or last step) and the activity falls
//!      by at least half its range on both sides of the maximum. A ramp's maximum is at an
//!      edge, so a unit cannot pass both tests with the same maximum; one that passes both
//!      (possible only with noise) is `mixed`;
//!    * **oscillating** — tested on every unit, tuned or not: a rhythm in the single
//!      trials, *induced* as well as evoked (a rhythm whose phase drifts from trial to trial
//!      with clock noise flattens the trial average and fails the tuning test, but
//!      oscillates on every trial). On `max(W, rhythm_window)` steps (32: enough cycles at
//!      TD 4, whose 8-step window holds one), by three conditions: (a) the trial-averaged
//!      single-trial periodogram's largest bin with at least `min_cycles` (2) cycles in the
//!      stretch is significantly above a red-noise (AR(1)) null fitted to the same trials
//!      (the bin's power over the null's is `χ²₂ₖ/2K`-distributed for K trials; Bonferroni
//!      over the tested bins, level `alpha` — the test of Torrence & Compo 1998; a circular
//!      shift keeps every trial's spectrum, so it cannot serve here); (b) that bin is a
//!      spectral peak (above the bin just below it: the spectra of ramps and bumps fall
//!      from the lowest frequencies on); (c) the mean single-trial autocorrelation repeats
//!      itself within half the stretch — a trough ≤ −0.25, then a peak ≥ 0.25
//!      ([`crate::neural::oscillation::acf_repeats`]), which a single bump, however narrow,
//!      never shows;
//!    * **beyond the window**: a tuned unit that is neither a time field nor oscillating,
//!      whose trial average over the window and one more window after it passes the
//!      time-field test with its maximum at or after the window's last step — a field that
//!      peaks after the window (a delay line's late units). Counted in a category of its
//!      own, `beyond_window`, rather than as a ramp or as mixed; without recorded steps
//!      after the window the test cannot see it and such a unit stays a ramp or mixed.
//! 3. Category, in this order: oscillating → `oscillating` (the trial average of a rhythm
//!    reset by the event is a damped copy of it — a bump, then a decaying or rising edge —
//!    which the shape tests cannot tell from a shape of its own, so the rhythm decides);
//!    beyond the window → `beyond_window`; neither tuned nor oscillating → `untuned`; a
//!    ramp → `ramp`; a time field → `time_field` (a noisy average can fit both within its
//!    noise: then the field only if its fall or rise is real,
//!    [`crate::neural::shape::unimodal_gain_p`] ≤ `alpha`); tuned with none of them
//!    (time-locked but complex: e.g. a transient with less than two cycles, a
//!    rise-fall-rise) → `mixed`.
//!
//! Undefined tests are reported as errors, never as "false": fewer than `min_trials`
//! trials (a circular shift of one trial leaves its average's variance unchanged) or a
//! window shorter than `min_window` steps. The rhythm test of a unit is run on the longest
//! stretch after the event that `min_trials` trials cover; when that is shorter than
//! `min_window` (trials that end early, off probe trials) it is undefined for the unit
//! (`spectral_p` NaN) and the summaries count those units (`rhythm_undefined`).

use crate::neural::locking::{locking_p, rotated_average, variance_stat};
use crate::neural::oscillation::{acf_repeats, autocorrelation};
use crate::neural::shape::{
    AverageNoise, monotone_r2_noisy, periodogram, spectral_peak, unimodal_gain_p, unimodal_r2_noisy,
};
use crate::neural::{Cube, argmax};
use rand::SeedableRng;
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
    /// Neither time-locked to the event (surrogate test not significant) nor rhythmic on
    /// single trials.
    Untuned,
    /// A time field whose peak lies at or after the window's last step: rising inside the
    /// window, peaking and falling by half its range on the steps recorded after it (a
    /// delay line's late units).
    BeyondWindow,
}

/// Every category, in report order.
pub const CATEGORIES: [Category; 6] = [
    Category::Ramp,
    Category::TimeField,
    Category::Oscillating,
    Category::Mixed,
    Category::Untuned,
    Category::BeyondWindow,
];

impl Category {
    /// The JSON / column name (`ramp`, `time_field`, `oscillating`, `mixed`, `untuned`,
    /// `beyond_window`).
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
    /// Shortest stretch (steps after the event) the rhythm test runs on where the trials
    /// are recorded that long, default 32: a 2 × TD window at TD 4 (8 steps) holds at most
    /// one cycle of a rhythm with an 8-step period, and the test needs `min_cycles` (2) in
    /// its lowest bin plus the bin below it to tell a peak; 32 steps hold 4 cycles of an
    /// 8-step period (5 Hz at the SBF clock's 40 steps/s) and resolve frequencies to 1/32
    /// cycle/step. Longer windows are used whole.
    #[serde(default = "default_rhythm_window")]
    pub rhythm_window: usize,
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
            rhythm_window: default_rhythm_window(),
            seed: 0,
        }
    }
}

fn default_rhythm_window() -> usize {
    32
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
    /// Explainable variance of the trial average explained by the best monotone fit (its
    /// sampling noise discounted: [`crate::neural::shape::AverageNoise`]).
    pub monotone_r2: f64,
    /// Explainable variance explained by the best unimodal fit.
    pub unimodal_r2: f64,
    /// Step of the trial average's maximum (steps after the event).
    pub peak_time: usize,
    /// Width (steps) of the peak at half its height above the window's minimum (NaN when
    /// it does not fall to half on both sides); for a time field whose fall lies after the
    /// window, measured on the steps recorded after it.
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
    /// A ramp (after the category rules of the module docs).
    pub ramp: bool,
    /// A time field inside the window (after the category rules).
    pub time_field: bool,
    /// Passed the rhythm test.
    pub oscillating: bool,
    /// Step of the maximum of the trial average over the window and the steps recorded
    /// after it (up to one more window), when that maximum lies at or after the window's
    /// last step and the unit falls by half its range after it: a field beyond the window.
    #[serde(default)]
    pub late_peak: Option<usize>,
    /// The category.
    pub category: Category,
}

/// One unit's recorded steps per trial (finite prefix: NaN marks the end of a trial).
fn unit_trials(cube: &Cube, i: usize) -> Vec<Vec<f64>> {
    (0..cube.trials())
        .map(|k| {
            (0..cube.time())
                .map(|t| cube.at(k, t, i))
                .take_while(|v| v.is_finite())
                .collect()
        })
        .collect()
}

/// The finite prefix of a trial average (steps every analysed trial may lack at the end).
fn finite_prefix(m: &[f64]) -> Vec<f64> {
    m.iter().copied().take_while(|v| v.is_finite()).collect()
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

/// Sampling noise of the trial average of `trials` over its first `len` steps: at each
/// step with two or more trials, their unbiased variance over their count.
fn average_noise(trials: &[Vec<f64>], len: usize) -> AverageNoise {
    let mut sum_sq = 0.0;
    for t in 0..len {
        let at: Vec<f64> = trials.iter().filter_map(|x| x.get(t).copied()).collect();
        let k = at.len();
        if k >= 2 {
            let mean = at.iter().sum::<f64>() / k as f64;
            let var = at.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1) as f64;
            sum_sq += var / k as f64;
        }
    }
    AverageNoise { sum_sq }
}

/// The beyond-window test reads up to this many windows after the event (where recorded).
pub const EXTENDED_WINDOWS: usize = 4;

/// The beyond-window test bins the recorded stretch into `window / BINS_PER_WINDOW`-step
/// bins (at least 1 step: none below a 16-step window).
pub const BINS_PER_WINDOW: usize = 8;

/// Trial average over the steps that at least `min_k` trials reach (stops at the first
/// step fewer reach; at most `len` steps).
fn covered_average(trials: &[Vec<f64>], len: usize, min_k: usize) -> Vec<f64> {
    (0..len)
        .map_while(|t| {
            let at: Vec<f64> = trials.iter().filter_map(|x| x.get(t).copied()).collect();
            (at.len() >= min_k).then(|| at.iter().sum::<f64>() / at.len() as f64)
        })
        .collect()
}

/// The time-field shape test on a trial average `m` with sampling noise `noise`: the
/// unimodal fit explains ≥ `min_r2` of its explainable variance, the maximum is interior,
/// the average falls by half its range after it and rises by [`MIN_FIELD_RISE`] of its
/// range before it. Returns the maximum's step when it passes.
fn field_peak(m: &[f64], noise: AverageNoise, min_r2: f64) -> Option<usize> {
    let len = m.len();
    // `NaN` (nothing to explain beyond the noise) fails the test.
    let r2 = unimodal_r2_noisy(m, noise);
    if len < 3 || r2.is_nan() || r2 < min_r2 {
        return None;
    }
    let peak = argmax(m);
    let (lo, hi) = crate::neural::finite_range(m.iter().copied());
    let drop = |side: &[f64], share: f64| {
        side.iter().copied().fold(f64::INFINITY, f64::min) <= hi - share * (hi - lo)
    };
    (peak > 0 && peak + 1 < len && drop(&m[..peak], MIN_FIELD_RISE) && drop(&m[peak + 1..], 0.5))
        .then_some(peak)
}

/// Share of its range a time field must rise by before its maximum: a quarter, where it must
/// fall by half after it. The window starts at the event, so a field that peaks in its
/// first steps shows only the end of its rise (microstimuli peaking 2 steps after the
/// event rise by about half); a decaying unit with a bump of noise at its start rises by
/// a few percent.
pub const MIN_FIELD_RISE: f64 = 0.25;

/// Centre of a field (`m` passed the time-field test): the centroid of its activity above
/// the window's minimum over the steps at or above half its range. Unlike the maximum, it
/// does not jump across a jagged plateau (a wide field averaged over a dozen trials).
fn field_centre(m: &[f64]) -> f64 {
    let (lo, hi) = crate::neural::finite_range(m.iter().copied());
    let half = lo + 0.5 * (hi - lo);
    let (mut w, mut wt) = (0.0, 0.0);
    for (t, &v) in m.iter().enumerate().filter(|(_, v)| **v >= half) {
        w += v - lo;
        wt += t as f64 * (v - lo);
    }
    if w > 0.0 { wt / w } else { argmax(m) as f64 }
}

/// Classifies every unit of `cube` (`[trials, T, units]`, NaN after a trial's end) on a
/// window of its first `window` steps (`window ≤ T`). The tuning and shape tests use the
/// window; the rhythm test uses up to `max(window, cfg.rhythm_window)` steps and the
/// beyond-window test up to `EXTENDED_WINDOWS × window`, where the cube has them.
pub fn classify_units(
    cube: &Cube,
    window: usize,
    cfg: &CategoryConfig,
) -> Result<Vec<UnitTests>, CategoryError> {
    let window = window.min(cube.time());
    if window < cfg.min_window {
        return Err(CategoryError::WindowTooShort {
            window,
            min: cfg.min_window,
        });
    }
    let min_k = cfg.min_trials.max(2);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(cfg.seed);
    let mut out = Vec::with_capacity(cube.units());
    for i in 0..cube.units() {
        let recorded: Vec<Vec<f64>> = unit_trials(cube, i)
            .into_iter()
            .filter(|x| !x.is_empty())
            .collect();
        if recorded.len() < min_k {
            return Err(CategoryError::TooFewTrials {
                trials: recorded.len(),
                min: min_k,
            });
        }
        let cut = |x: &Vec<f64>, n: usize| x[..x.len().min(n)].to_vec();
        let trials: Vec<Vec<f64>> = recorded.iter().map(|x| cut(x, window)).collect();
        let zero = vec![0; trials.len()];
        let m = finite_prefix(&rotated_average(&trials, &zero, window));
        if m.len() < cfg.min_window {
            return Err(CategoryError::WindowTooShort {
                window: m.len(),
                min: cfg.min_window,
            });
        }
        let len = m.len();
        let s = variance_stat(&m);
        let tuning_p = locking_p(&trials, len, cfg.surrogates, &mut rng);
        // The rhythm test on single trials (induced as well as evoked: no time-locking
        // needed), on the longest stretch up to max(window, rhythm_window) steps that at
        // least `min_trials` trials cover (those trials, truncated to it); undefined below
        // `min_window`.
        let rhythm_len = window.max(cfg.rhythm_window);
        let mut lens: Vec<usize> = recorded.iter().map(|x| x.len().min(rhythm_len)).collect();
        lens.sort_unstable_by(|a, b| b.cmp(a));
        let shortest = lens[min_k.min(lens.len()) - 1];
        let long: Vec<Vec<f64>> = recorded
            .iter()
            .filter(|x| x.len() >= shortest)
            .map(|x| cut(x, shortest))
            .collect();
        let bin0 = min_bin(shortest, cfg.min_cycles);
        let (k_peak, spectral_p, narrowband) = if shortest >= cfg.min_window {
            rhythm(&long, shortest, bin0)
        } else {
            (0, f64::NAN, false)
        };
        let tuned = tuning_p <= cfg.alpha && s > 0.0;
        let noise = average_noise(&trials, len);
        let (mono, _) = monotone_r2_noisy(&m, noise);
        let uni = unimodal_r2_noisy(&m, noise);
        let peak = argmax(&m);
        let mut ramp = tuned && mono >= cfg.monotone_r2;
        let mut time_field = tuned && field_peak(&m, noise, cfg.unimodal_r2).is_some();
        if ramp && time_field {
            // Both fit within the noise: the field only if its fall (or rise) is real.
            let field = unimodal_gain_p(&m, noise) <= cfg.alpha;
            (ramp, time_field) = (!field, field);
        }
        let oscillating = k_peak >= bin0 && spectral_p <= cfg.alpha && narrowband;
        // Where steps after the window are recorded, the same field test on the window
        // and up to `EXTENDED_WINDOWS` − 1 more windows, in bins of `window / 8` steps,
        // sees the fall after a late peak, and where the peak of a sparse unit lies: a
        // unit that fires once per trial after the window leaves a few early spikes in it,
        // which can pass for a field inside, and a dozen trials' spikes spread over a wide
        // late field average to noise step by step, but not bin by bin. A field found
        // there decides: its peak bin centred inside the window makes a time field, at or
        // after the window's end a field beyond it.
        let mut late_peak = None;
        let mut width = half_width(&m, peak);
        if !oscillating {
            let ext_raw = covered_average(&recorded, EXTENDED_WINDOWS * window, min_k);
            let ext_len = ext_raw.len();
            if ext_len > len {
                let b = (window / BINS_PER_WINDOW).max(1);
                let binned: Vec<Vec<f64>> = recorded
                    .iter()
                    .map(|x| {
                        x[..x.len().min(ext_len)]
                            .chunks_exact(b)
                            .map(|c| c.iter().sum::<f64>() / b as f64)
                            .collect::<Vec<f64>>()
                    })
                    // A trial shorter than one bin has none (nothing to shift).
                    .filter(|x| !x.is_empty())
                    .collect();
                let bins = ext_len / b;
                let ext = covered_average(&binned, bins, min_k);
                let ext_noise = average_noise(&binned, ext.len());
                // A unit not locked within the window (a late field's few early spikes)
                // must be locked on the longer stretch.
                let locked =
                    tuned || locking_p(&binned, ext.len(), cfg.surrogates, &mut rng) <= cfg.alpha;
                if field_peak(&ext, ext_noise, cfg.unimodal_r2).is_some()
                    && locked
                    && unimodal_gain_p(&ext, ext_noise) <= cfg.alpha
                {
                    ramp = false;
                    // The field's centre in steps after the event (a bin's centre is
                    // `b·bin + (b − 1)/2`).
                    let centre = b as f64 * field_centre(&ext) + (b as f64 - 1.0) / 2.0;
                    if centre + 1.0 >= window as f64 {
                        (late_peak, time_field) = (Some(centre.round() as usize), false);
                    } else {
                        time_field = true;
                        // Its fall may lie after the window: the width on the longer stretch.
                        if width.is_nan() {
                            width = half_width(&ext_raw, argmax(&ext_raw));
                        }
                    }
                }
            }
        }
        // A rhythm on single trials decides: the trial average of a rhythm reset by the
        // event is a damped copy of it (its first cycle a bump, then a decaying or rising
        // edge as phases drift apart), which the shape tests cannot tell from a ramp or a
        // field of its own.
        if oscillating {
            (ramp, time_field) = (false, false);
        }
        let shapes = [ramp, time_field, oscillating];
        let category = match (tuned || oscillating, shapes.iter().filter(|&&b| b).count()) {
            _ if late_peak.is_some() => Category::BeyondWindow,
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
            peak_width: width,
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
            late_peak,
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
    /// Fields beyond the window (absent from files written before the category existed).
    #[serde(default)]
    pub beyond_window: T,
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
            beyond_window: f(Category::BeyondWindow),
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
            Category::BeyondWindow => self.beyond_window,
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
            Category::BeyondWindow => &mut self.beyond_window,
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
