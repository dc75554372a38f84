//! Temporal scaling of a population's *geometry*: does the trajectory at a long TD trace the
//! same shape as at a short TD, stretched in time?
//!
//! Per-unit scaling ([`crate::neural::scaling_factor_from`]) needs unit `j` to be the same
//! unit at both TDs — one agent timing two intervals, or timing models of one model and
//! seed. Two separately trained networks share no units, but they can share a geometry: the
//! matrix of distances between the population's states at every pair of times,
//! `D(t₁, t₂) = ‖x(t₁) − x(t₂)‖` (trial-averaged states, every unit), is unchanged by a
//! permutation, rotation or common gain of the units. This module compares the short TD's
//! matrix `Dₛ(τ₁, τ₂)` with the long TD's read at stretched times, `Dₗ(s·τ₁, s·τ₂)`
//! (τ = steps since oven-on, bilinear interpolation), for factors `s = 1.01ᵏ` in
//! `[1/4, 4]`, fitting `Dₗ ≈ b·Dₛ` (a gain, no offset: both vanish on the diagonal) and
//! scoring the fit by R². The best `s` is the geometry's scaling factor: ≈ `TD_long /
//! TD_short` when the dynamics stretch with the interval (Wang, Narain, Hosseini & Jazayeri
//! 2018; Mello, Soares & Paton 2015), ≈ 1 for a clock that runs at a fixed speed
//! (oscillators, a fixed delay line).
//!
//! Some geometries cannot tell the two apart: a straight-line trajectory at constant speed
//! (a linear ramp) has `D ∝ |τ₁ − τ₂|` at every speed, so every `s` fits equally. The
//! factor is therefore reported only when the fits at `s = 1` and `s = TD_long / TD_short`
//! differ by at least [`MIN_CONTRAST`] in R²; otherwise it is undefined.

/// Smallest difference in R² between the fixed-clock (`s = 1`) and the stretched
/// (`s = TD ratio`) readings for the factor to be defined.
pub const MIN_CONTRAST: f64 = 0.05;

/// The geometry's scaling between two TDs' windows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeometryScaling {
    /// Best factor `s` (`Dₗ(s·τ₁, s·τ₂) ≈ b·Dₛ(τ₁, τ₂)`).
    pub factor: f64,
    /// R² of the fit at `factor`.
    pub r2: f64,
    /// R² at `s = 1` (a fixed clock).
    pub r2_fixed: f64,
    /// R² at `s = td_ratio` (perfect scaling).
    pub r2_scaled: f64,
    /// `ln(factor) / ln(td_ratio)`: 1 for dynamics that stretch with the interval, 0 for a
    /// fixed clock.
    pub index: f64,
}

/// Distance matrix `[T, T]` of a `[T, units]` trajectory (row-major), rows up to the first
/// with a non-finite value.
fn distances(traj: &[f64], units: usize) -> (Vec<f64>, usize) {
    let rows: Vec<&[f64]> = traj
        .chunks_exact(units.max(1))
        .take_while(|r| r.iter().all(|v| v.is_finite()))
        .collect();
    let t = rows.len();
    let mut d = vec![0.0; t * t];
    for i in 0..t {
        for j in i + 1..t {
            let v = rows[i]
                .iter()
                .zip(rows[j])
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            d[i * t + j] = v;
            d[j * t + i] = v;
        }
    }
    (d, t)
}

/// Bilinear interpolation of a `[t, t]` matrix at real indices (both in `[0, t − 1]`).
fn at(d: &[f64], t: usize, x: f64, y: f64) -> f64 {
    let (i, j) = (x.floor() as usize, y.floor() as usize);
    let (fx, fy) = (x - i as f64, y - j as f64);
    let (i1, j1) = ((i + 1).min(t - 1), (j + 1).min(t - 1));
    let v = |a: usize, b: usize| d[a * t + b];
    (1.0 - fx) * ((1.0 - fy) * v(i, j) + fy * v(i, j1))
        + fx * ((1.0 - fy) * v(i1, j) + fy * v(i1, j1))
}

/// R² of the gain-only fit `long(s·τ) ≈ b·short(τ)` over the short window's time pairs
/// that fall inside the long window (`None` when fewer than 4 time points do).
fn fit(ds: &[f64], ts: usize, dl: &[f64], tl: usize, s: f64, origin: f64) -> Option<f64> {
    let mapped: Vec<(usize, f64)> = (0..ts)
        .map(|i| (i, (i as f64 + origin) * s - origin))
        .filter(|&(_, x)| x >= 0.0 && x <= (tl - 1) as f64)
        .collect();
    if mapped.len() < 4.max(ts / 2) {
        return None;
    }
    let mut pairs = Vec::with_capacity(mapped.len() * mapped.len() / 2);
    for (a, &(i, xi)) in mapped.iter().enumerate() {
        for &(j, xj) in &mapped[a + 1..] {
            pairs.push((ds[i * ts + j], at(dl, tl, xi, xj)));
        }
    }
    let sxx: f64 = pairs.iter().map(|p| p.0 * p.0).sum();
    if sxx <= 0.0 {
        return None;
    }
    let b = pairs.iter().map(|p| p.0 * p.1).sum::<f64>() / sxx;
    let my = pairs.iter().map(|p| p.1).sum::<f64>() / pairs.len() as f64;
    let ss: f64 = pairs.iter().map(|p| (p.1 - my).powi(2)).sum();
    let sse: f64 = pairs.iter().map(|p| (p.1 - b * p.0).powi(2)).sum();
    (ss > 0.0).then(|| 1.0 - sse / ss)
}

/// The fit R² of every factor `s = 1.01ᵏ` in `[1/4, 4]` whose stretched times fall inside
/// the long window: `(s, R²)` ascending in `s` (the curve whose peak is
/// [`GeometryScaling::factor`]; empty when a window has fewer than 4 finite rows).
pub fn geometry_profile(
    short: &[f64],
    units_short: usize,
    long: &[f64],
    units_long: usize,
    origin: f64,
) -> Vec<(f64, f64)> {
    if units_short == 0 || units_long == 0 {
        return Vec::new();
    }
    let (ds, ts) = distances(short, units_short);
    let (dl, tl) = distances(long, units_long);
    if ts < 4 || tl < 4 {
        return Vec::new();
    }
    let steps = (4f64.ln() / 0.01f64.ln_1p()).floor() as i32;
    (-steps..=steps)
        .filter_map(|k| {
            let s = 1.01f64.powi(k);
            fit(&ds, ts, &dl, tl, s, origin).map(|r2| (s, r2))
        })
        .collect()
}

/// The geometry scaling between a short TD's trial-averaged trajectory `short`
/// (`[T_s, units_short]`, row-major) and a long TD's `long` (`[T_l, units_long]`); the
/// units need not correspond. `td_ratio = TD_long / TD_short`; `origin` = steps since
/// oven-on at row 0. `None` when a window has fewer than 4 finite rows, a trajectory does
/// not move, or the fits at `s = 1` and `s = td_ratio` differ by less than
/// [`MIN_CONTRAST`].
pub fn geometry_scaling(
    short: &[f64],
    units_short: usize,
    long: &[f64],
    units_long: usize,
    td_ratio: f64,
    origin: f64,
) -> Option<GeometryScaling> {
    if units_short == 0 || units_long == 0 || td_ratio.is_nan() || td_ratio <= 1.0 {
        return None;
    }
    let (ds, ts) = distances(short, units_short);
    let (dl, tl) = distances(long, units_long);
    if ts < 4 || tl < 4 {
        return None;
    }
    let r2_fixed = fit(&ds, ts, &dl, tl, 1.0, origin)?;
    let r2_scaled = fit(&ds, ts, &dl, tl, td_ratio, origin)?;
    if (r2_fixed - r2_scaled).abs() < MIN_CONTRAST {
        return None;
    }
    let best = geometry_profile(short, units_short, long, units_long, origin)
        .into_iter()
        .fold(
            (f64::NAN, f64::NEG_INFINITY),
            |b, p| if p.1 > b.1 { p } else { b },
        );
    best.0.is_finite().then(|| GeometryScaling {
        factor: best.0,
        r2: best.1,
        r2_fixed,
        r2_scaled,
        index: best.0.ln() / td_ratio.ln(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `[T, units]` of Gaussian time fields with peaks `peaks` (steps) and width `width`.
    fn fields(t: usize, peaks: &[f64], width: impl Fn(f64) -> f64) -> Vec<f64> {
        let mut out = Vec::new();
        for step in 0..t {
            let tau = step as f64 + 1.0;
            for &p in peaks {
                out.push((-(tau - p).powi(2) / (2.0 * width(p).powi(2))).exp());
            }
        }
        out
    }

    #[test]
    fn time_fields_that_stretch_with_the_interval_scale_by_the_td_ratio() {
        // TD 6 (window 12) and TD 12 (window 24): fields at the same fractions of TD.
        let frac = [0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75];
        let short = fields(12, &frac.map(|f| 6.0 * f), |_| 1.5);
        let long = fields(24, &frac.map(|f| 12.0 * f), |_| 3.0);
        let g = geometry_scaling(&short, 7, &long, 7, 2.0, 1.0).unwrap();
        assert!((g.factor - 2.0).abs() < 0.06, "{g:?}");
        assert!((g.index - 1.0).abs() < 0.05, "{g:?}");
        assert!(g.r2_scaled > 0.99 && g.r2_fixed < 0.9, "{g:?}");
    }

    #[test]
    fn the_profile_peaks_at_the_factor() {
        let frac = [0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75];
        let short = fields(12, &frac.map(|f| 6.0 * f), |_| 1.5);
        let long = fields(24, &frac.map(|f| 12.0 * f), |_| 3.0);
        let p = geometry_profile(&short, 7, &long, 7, 1.0);
        let g = geometry_scaling(&short, 7, &long, 7, 2.0, 1.0).unwrap();
        let top = p.iter().fold(p[0], |b, x| if x.1 > b.1 { *x } else { b });
        assert_eq!(top, (g.factor, g.r2));
        assert!(p.windows(2).all(|w| w[0].0 < w[1].0));
        // Factors that stretch the short window beyond the long one are left out.
        assert!(p.iter().all(|x| x.0 <= 4.0 && x.0 >= 0.25));
    }

    #[test]
    fn a_fixed_delay_line_does_not_scale() {
        // The same absolute fields at both TDs (the long window sees more of them).
        let peaks: Vec<f64> = (1..=24).map(f64::from).collect();
        let short = fields(12, &peaks, |_| 1.5);
        let long = fields(24, &peaks, |_| 1.5);
        let g = geometry_scaling(&short, 24, &long, 24, 2.0, 1.0).unwrap();
        assert!((g.factor - 1.0).abs() < 0.03, "{g:?}");
        assert!(g.index.abs() < 0.05, "{g:?}");
    }

    #[test]
    fn oscillators_at_fixed_frequencies_do_not_scale() {
        let freqs = [0.05, 0.11, 0.17, 0.23, 0.31];
        let osc = |t: usize| -> Vec<f64> {
            (0..t)
                .flat_map(|s| {
                    freqs.iter().flat_map(move |f| {
                        let ph = 2.0 * std::f64::consts::PI * f * (s as f64 + 1.0);
                        [ph.cos(), ph.sin()]
                    })
                })
                .collect()
        };
        let g = geometry_scaling(&osc(12), 10, &osc(24), 10, 2.0, 1.0).unwrap();
        assert!((g.factor - 1.0).abs() < 0.03, "{g:?}");
    }

    #[test]
    fn a_different_network_with_the_same_stretched_geometry_still_scales() {
        // The long population is a rotated, gain-changed, padded copy of stretched fields:
        // no unit corresponds, the geometry does.
        let frac = [0.3, 0.6, 0.9, 1.2, 1.5];
        let short = fields(16, &frac.map(|f| 8.0 * f), |p| 0.25 * p);
        let base = fields(32, &frac.map(|f| 16.0 * f), |p| 0.25 * p);
        let (c, s) = (0.6f64, 0.8f64);
        let long: Vec<f64> = base
            .chunks(5)
            .flat_map(|r| {
                [
                    3.0 * (c * r[0] - s * r[1]),
                    3.0 * (s * r[0] + c * r[1]),
                    3.0 * r[4],
                    3.0 * r[2],
                    3.0 * r[3],
                    0.7,
                ]
            })
            .collect();
        let g = geometry_scaling(&short, 5, &long, 6, 2.0, 1.0).unwrap();
        assert!((g.factor - 2.0).abs() < 0.06, "{g:?}");
    }

    #[test]
    fn a_linear_ramp_cannot_tell_scaling_from_a_fixed_clock() {
        let short: Vec<f64> = (0..12).map(|t| t as f64 / 6.0).collect();
        let long: Vec<f64> = (0..24).map(|t| t as f64 / 12.0).collect();
        assert_eq!(geometry_scaling(&short, 1, &long, 1, 2.0, 1.0), None);
    }

    #[test]
    fn a_ramp_that_reaches_a_bound_at_the_remembered_time_scales() {
        // A drift-diffusion accumulator tuned to each TD: rises to 1 at TD, then holds.
        let ramp = |td: f64, t: usize| -> Vec<f64> {
            (0..t).map(|s| ((s as f64 + 1.0) / td).min(1.0)).collect()
        };
        let g = geometry_scaling(&ramp(6.0, 12), 1, &ramp(12.0, 24), 1, 2.0, 1.0).unwrap();
        assert!((g.factor - 2.0).abs() < 0.06, "{g:?}");
    }

    #[test]
    fn too_short_or_still_windows_are_undefined() {
        assert_eq!(
            geometry_scaling(&[0.0, 1.0, 2.0], 1, &[0.0; 8], 1, 2.0, 1.0),
            None
        );
        assert_eq!(
            geometry_scaling(&[1.0; 12], 1, &[1.0; 24], 1, 2.0, 1.0),
            None
        );
        let nan_rows = [f64::NAN; 12];
        assert_eq!(
            geometry_scaling(&nan_rows, 1, &[1.0; 24], 1, 2.0, 1.0),
            None
        );
    }
}
