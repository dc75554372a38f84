//! Per-model neural summary of an activity dataset: the fractions of ramping, time-cell and
//! oscillating units, the sequentiality index and the elapsed-time decoding error — the
//! neural columns of the leaderboard.

use crate::neural::decode::{Decoder, decode_time};
use crate::neural::oscillation::is_oscillating;
use crate::neural::{Cube, classify_ramps, sequentiality_index, time_cells};
use chronocooked_models::{ActivityDataset, Marker};
use serde::{Deserialize, Serialize};

/// Neural summary of one model (one population or all units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NeuralSummary {
    /// Model.
    pub model: String,
    /// Population analysed (`all` for every unit).
    pub population: String,
    /// Units analysed (constant units excluded).
    pub units: usize,
    /// Trials aligned to oven-on.
    pub trials: usize,
    /// Steps after oven-on analysed.
    pub window: usize,
    /// Fraction of ramping units (|r| ≥ 0.9, p ≤ 0.05).
    #[serde(deserialize_with = "f64_or_nan")]
    pub frac_ramping: f64,
    /// Fraction of time cells (shuffle p < 0.05, odd/even reliability > 0.5).
    #[serde(deserialize_with = "f64_or_nan")]
    pub frac_time_cells: f64,
    /// Fraction of oscillating units (the trial average repeats itself: an autocorrelation
    /// trough ≤ −0.25 followed by a peak ≥ 0.4 within half the window,
    /// [`crate::neural::oscillation::is_oscillating`]; needs windows of ≥ 8 steps).
    #[serde(deserialize_with = "f64_or_nan")]
    pub frac_oscillating: f64,
    /// Sequentiality index of the trial average.
    #[serde(deserialize_with = "f64_or_nan")]
    pub sequentiality: f64,
    /// Cross-validated ridge decoding error (steps).
    #[serde(deserialize_with = "f64_or_nan")]
    pub decode_ridge: f64,
    /// Cross-validated Bayesian decoding error (steps).
    #[serde(deserialize_with = "f64_or_nan")]
    pub decode_bayes: f64,
}

/// Reads a number written by serde_json, where NaN is written as `null`.
pub fn f64_or_nan<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// Summarises `dataset` (population `population`, or all units when `None`), aligned to
/// oven-on over `window` steps (the trials' median length after oven-on when `None`).
pub fn neural_summary(
    dataset: &ActivityDataset,
    population: Option<&str>,
    window: Option<usize>,
    seed: u64,
) -> Option<NeuralSummary> {
    let n = dataset.meta.n_units();
    let cols = match population {
        Some(p) => dataset.meta.range(p)?,
        None => 0..n,
    };
    let mut lens: Vec<usize> = dataset
        .trials
        .iter()
        .filter_map(|t| {
            t.first(Marker::OvenOn)
                .map(|on| t.steps.saturating_sub(on as usize + 1))
        })
        .collect();
    if lens.is_empty() {
        return None;
    }
    lens.sort_unstable();
    let window = window.unwrap_or(lens[lens.len() / 2]).max(2);
    let (aligned, used) = dataset.aligned(Marker::OvenOn, window - 1);
    // Keep the chosen columns, and only units that vary.
    let full = Cube::from_f32(&aligned, used.len(), window, n);
    let varying: Vec<usize> = cols
        .filter(|&i| {
            let (lo, hi) = crate::neural::finite_range(
                (0..full.trials)
                    .flat_map(|k| (0..window).map(move |t| (k, t)))
                    .map(|(k, t)| full.at(k, t, i)),
            );
            hi - lo > 1e-9
        })
        .collect();
    let u = varying.len();
    if u == 0 {
        return None;
    }
    let mut data = Vec::with_capacity(full.trials * window * u);
    for k in 0..full.trials {
        for t in 0..window {
            data.extend(varying.iter().map(|&i| full.at(k, t, i)));
        }
    }
    let cube = Cube {
        trials: full.trials,
        time: window,
        units: u,
        data,
    };
    let avg = cube.average();
    let ramps = classify_ramps(&avg, u, 0.9, 0.05);
    let cells = time_cells(&cube, 1, 100, seed);
    let oscillating = (0..u)
        .filter(|&i| {
            let series: Vec<f64> = (0..window)
                .map(|t| avg[t * u + i])
                .filter(|v| v.is_finite())
                .collect();
            is_oscillating(&series)
        })
        .count();
    let frac = |c: usize| c as f64 / u as f64;
    Some(NeuralSummary {
        model: dataset.meta.model.clone(),
        population: population.unwrap_or("all").to_string(),
        units: u,
        trials: cube.trials,
        window,
        frac_ramping: frac(ramps.iter().filter(|r| r.ramping).count()),
        frac_time_cells: frac(cells.iter().filter(|c| c.time_cell).count()),
        frac_oscillating: frac(oscillating),
        sequentiality: sequentiality_index(&avg, u),
        decode_ridge: decode_time(&cube, Decoder::Ridge, 5, 1.0).mean_abs_error,
        decode_bayes: decode_time(&cube, Decoder::Bayes, 5, 1.0).mean_abs_error,
    })
}
