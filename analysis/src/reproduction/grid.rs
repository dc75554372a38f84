//! The distribution of the estimate `te` given a sample interval `ts`, as weighted points:
//! exact support masses for MAP, a trapezoid grid over the measurement for BLS and ML.
//!
//! The grid is uniform in `z = (tm − ts)/(wm·ts)` over `|z| ≤ Z_MAX` with weights
//! `h·φ(z)` normalised to 1; its spacing is chosen per `ts` from the narrowest feature of
//! the integrand (see the module [`super`] "Numerics").

use super::normal::pdf;
use super::observer::{Estimator, Observer, gain};

/// Half-width of the measurement grid in standard deviations (tail mass 2e-17).
pub(crate) const Z_MAX: f64 = 8.5;
/// Smallest grid spacing in `z` (at most 6 801 nodes).
pub(crate) const H_MIN: f64 = 0.0025;
/// Largest grid spacing in `z` (171 nodes).
pub(crate) const H_MAX: f64 = 0.1;
/// Spacing as a fraction of the narrowest feature's width (in `z`).
const FEATURE_FRACTION: f64 = 0.6;
/// The narrowest feature is searched within `|z| ≤ CORE_Z` (the rest carries < 0.3 % of
/// the mass, where a coarser resolution costs < 1e-6 relative).
const CORE_Z: f64 = 3.0;
/// Pilot spacing for locating the BLS estimator's steepest slope.
const PILOT_H: f64 = 0.05;
/// Smallest estimate used for the feature width, as a fraction of the shortest prior value
/// (productions far below every prior value only occur in the measurement's far tail).
const TE_FLOOR_FRACTION: f64 = 0.5;

/// The distribution of `te` given `ts`: points `te` (steps) with probabilities `weight`
/// (summing to 1).
pub(crate) struct TeDistribution {
    /// Estimates (steps).
    pub te: Vec<f64>,
    /// Their probabilities.
    pub weight: Vec<f64>,
}

/// The distribution of `te | ts` for `observer` at `(wm, wp)` over the prior's `values`;
/// `refine` divides the automatic spacing (1 in use; 2 in the accuracy test).
pub(crate) fn te_distribution(
    observer: Observer,
    ts: f64,
    wm: f64,
    wp: f64,
    values: &[f64],
    refine: f64,
) -> TeDistribution {
    let est = Estimator::new(observer, wm, values);
    if observer == Observer::Map {
        return TeDistribution {
            te: values.to_vec(),
            weight: est.map_masses(ts),
        };
    }
    let h0 = spacing(&est, observer, ts, wm, wp, values) / refine;
    let n_half = (Z_MAX / h0).ceil() as usize;
    let h = Z_MAX / n_half as f64;
    let n = 2 * n_half + 1;
    let (mut te, mut weight) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let z = -Z_MAX + i as f64 * h;
        te.push(est.estimate(ts * (1.0 + wm * z)));
        weight.push(pdf(z));
    }
    let total: f64 = weight.iter().sum();
    weight.iter_mut().for_each(|w| *w /= total);
    TeDistribution { te, weight }
}

/// Grid spacing in `z`: `0.6·wp·te_lo / (wm·ts·max f′)`, clamped to `[H_MIN, H_MAX]`.
fn spacing(est: &Estimator, observer: Observer, ts: f64, wm: f64, wp: f64, values: &[f64]) -> f64 {
    let sigma = wm * ts;
    let (slope_max, te_lo) = match observer {
        Observer::Ml => {
            let c = gain(wm);
            (c, c * ts * (1.0 - CORE_Z * wm))
        }
        Observer::Bls | Observer::Map => {
            let n = (2.0 * CORE_Z / PILOT_H).round() as usize;
            let (mut slope_max, mut te_lo) = (0.0f64, f64::INFINITY);
            for i in 0..=n {
                let z = -CORE_Z + i as f64 * PILOT_H;
                let (f, d) = est.bls(ts * (1.0 + wm * z));
                slope_max = slope_max.max(d.abs());
                te_lo = te_lo.min(f);
            }
            (slope_max, te_lo)
        }
    };
    let te_lo = te_lo.max(TE_FLOOR_FRACTION * values[0]);
    let width = wp * te_lo / (sigma * slope_max.max(1e-12));
    (FEATURE_FRACTION * width).clamp(H_MIN, H_MAX)
}
