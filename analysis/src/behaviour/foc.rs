//! First oven check (FOC), the paper's fixed-interval timing measure.
//!
//! Both conventions find the pickup (the successful interact at the oven) and walk back
//! over the unbroken run of interacts that ends in it; FOC is the oven timer (steps since
//! the onion went in) at the first interact of that run. Episodes without a pickup have no
//! FOC.
//!
//! * [`FocConvention::Paper`] (the default, as the paper's code computes it): the run is
//!   any consecutive interact actions; a run that starts with the onion put itself (timer
//!   −1: the agent interacted without a break from the put to the pickup) gives FOC 0.
//! * [`FocConvention::Checks`] (the lab's earlier choice): only interacts that check the
//!   running oven extend the run, so the put is never part of it and the same agent gets
//!   FOC 1.

use chronocooked_env::{Events, Info};
use chronocooked_models::EpisodeRecord;
use serde::{Deserialize, Serialize};

/// How the run of interacts before the pickup is delimited.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FocConvention {
    /// The paper's code: any consecutive interacts; a run from the put gives FOC 0.
    #[default]
    Paper,
    /// Only oven checks (interacts at the running oven) extend the run.
    Checks,
}

/// FOC of one episode (paper convention) from its actions (codes) and per-step `info`;
/// `None` without pickup.
pub fn first_oven_check(actions: &[u8], infos: &[Info]) -> Option<i32> {
    first_oven_check_with(actions, infos, FocConvention::Paper)
}

/// FOC of one episode under `convention`; `None` without pickup.
pub fn first_oven_check_with(
    actions: &[u8],
    infos: &[Info],
    convention: FocConvention,
) -> Option<i32> {
    let pickup = infos.iter().position(|i| i.events.has(Events::PICKUP))?;
    let mut first = pickup;
    while first > 0 {
        let j = first - 1;
        let extends = match convention {
            FocConvention::Paper => actions[j] == 5,
            FocConvention::Checks => actions[j] == 5 && infos[j].events.has(Events::OVEN_CHECK),
        };
        if !extends {
            break;
        }
        first = j;
    }
    Some(infos[first].timer_at_action.max(0))
}

/// FOC of a recorded episode (paper convention).
pub fn episode_foc(record: &EpisodeRecord) -> Option<i32> {
    first_oven_check(&record.actions, &record.infos)
}

/// FOC summary at one TD.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FocStats {
    /// Target duration (steps).
    pub td: u32,
    /// Episodes with a FOC.
    pub n: usize,
    /// Mean FOC (NaN without data).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub mean: f64,
    /// Sample SD (n − 1; NaN below 2 episodes).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub sd: f64,
    /// `sd / mean`.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub cv: f64,
}

/// Ordinary least squares `y = slope·x + intercept`; returns `(slope, intercept, R²)`
/// (all NaN when fewer than two points or no spread in `x`; R² NaN — undefined — when `y`
/// has no spread, e.g. all-zero SDs: there is no variance to explain, and a "perfect" R²
/// of 1 would report a degenerate fit as the scalar property).
pub fn linear_fit(x: &[f64], y: &[f64]) -> (f64, f64, f64) {
    let n = x.len().min(y.len());
    if n < 2 {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let mx = x[..n].iter().sum::<f64>() / n as f64;
    let my = y[..n].iter().sum::<f64>() / n as f64;
    let sxx: f64 = x[..n].iter().map(|v| (v - mx).powi(2)).sum();
    let syy: f64 = y[..n].iter().map(|v| (v - my).powi(2)).sum();
    let sxy: f64 = x[..n]
        .iter()
        .zip(&y[..n])
        .map(|(a, b)| (a - mx) * (b - my))
        .sum();
    if sxx <= 0.0 {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    let slope = sxy / sxx;
    let r2 = if syy > 0.0 {
        sxy * sxy / (sxx * syy)
    } else {
        f64::NAN
    };
    (slope, my - slope * mx, r2)
}

/// Per-TD FOC statistics from `(td, focs)` groups.
pub fn foc_stats(groups: &[(u32, Vec<f64>)]) -> Vec<FocStats> {
    groups
        .iter()
        .map(|(td, v)| {
            let s = crate::stats::Spread::of(v.iter().copied());
            FocStats {
                td: *td,
                n: v.len(),
                mean: s.mean,
                sd: s.sd,
                cv: s.sd / s.mean,
            }
        })
        .collect()
}

/// Scalar-property summary across TDs.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ScalarProperty {
    /// Slope of mean FOC vs TD.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub mean_slope: f64,
    /// R² of mean FOC vs TD (timing: close to 1 with slope ≈ 1).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub r2_mean_vs_td: f64,
    /// Slope of SD vs mean FOC (≈ the constant CV under the scalar property).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub sd_slope: f64,
    /// R² of SD vs mean FOC (scalar property: close to 1).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub r2_sd_vs_mean: f64,
}

/// Pools per-TD statistics of several runs into one [`FocStats`] per TD (exact pooled mean
/// and sample SD from each run's n, mean and SD), sorted by TD.
pub fn pool_foc_stats(stats: &[FocStats]) -> Vec<FocStats> {
    let mut tds: Vec<u32> = stats.iter().map(|s| s.td).collect();
    tds.sort_unstable();
    tds.dedup();
    tds.into_iter()
        .map(|td| {
            let g: Vec<&FocStats> = stats
                .iter()
                .filter(|s| s.td == td && s.n > 0 && s.mean.is_finite())
                .collect();
            let n: usize = g.iter().map(|s| s.n).sum();
            let mean = if n > 0 {
                g.iter().map(|s| s.n as f64 * s.mean).sum::<f64>() / n as f64
            } else {
                f64::NAN
            };
            let ss: f64 = g
                .iter()
                .map(|s| {
                    let within = if s.n > 1 && s.sd.is_finite() {
                        (s.n - 1) as f64 * s.sd * s.sd
                    } else {
                        0.0
                    };
                    within + s.n as f64 * (s.mean - mean).powi(2)
                })
                .sum();
            let sd = if n > 1 {
                (ss / (n - 1) as f64).sqrt()
            } else {
                f64::NAN
            };
            FocStats {
                td,
                n,
                mean,
                sd,
                cv: sd / mean,
            }
        })
        .collect()
}

/// Regressions of mean FOC on TD and of SD on mean over the TDs with data.
pub fn scalar_property(stats: &[FocStats]) -> ScalarProperty {
    let ok: Vec<&FocStats> = stats.iter().filter(|s| s.mean.is_finite()).collect();
    let td: Vec<f64> = ok.iter().map(|s| f64::from(s.td)).collect();
    let mean: Vec<f64> = ok.iter().map(|s| s.mean).collect();
    let (mean_slope, _, r2_mean_vs_td) = linear_fit(&td, &mean);
    let with_sd: Vec<&&FocStats> = ok.iter().filter(|s| s.sd.is_finite()).collect();
    let m: Vec<f64> = with_sd.iter().map(|s| s.mean).collect();
    let sd: Vec<f64> = with_sd.iter().map(|s| s.sd).collect();
    let (sd_slope, _, r2_sd_vs_mean) = linear_fit(&m, &sd);
    ScalarProperty {
        mean_slope,
        r2_mean_vs_td,
        sd_slope,
        r2_sd_vs_mean,
    }
}
