//! The basis-free dynamics signature (`neural::dynamics`) on synthetic populations whose
//! answers are known in closed form, at every TD of the paper (3 … 24 steps), several seeds
//! and unit counts from 8 to 1,000; and its invariance: each population mixed by a random
//! orthogonal matrix gives the same signature, and the features stated to survive an
//! invertible map of condition number ≤ 10 do.
//!
//! Populations (rows = steps 1 … 2 × window after the onset, as the summary aligns them):
//! * ramps: `x_i(t) = g_i t + b_i` (a line attractor driven at constant speed);
//! * a ring attractor: one oscillator `(cos ωt, sin ωt)` embedded in `N` units;
//! * an oscillator bank: `K` phase-reset cosines (SBF-like);
//! * a delay line: one-hot units, unit `i` active at step `i`;
//! * scale-invariant time cells: Gaussian fields at log-spaced delays with widths in
//!   proportion (a log-time code: speed ∝ 1/t in the continuum limit);
//! * decaying traces (Laplace): `e^{−s t}` for log-spaced rates (speed ∝ 1/t as well);
//! * a slow-point chain against a limit cycle: the same circle inside the window; after it
//!   the cycle goes on and the chain settles on its last point.

use chronocooked_analysis::neural::dynamics::{Dynamics, dynamics};
use nalgebra::DMatrix;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::TAU;

/// The TDs of the paper's tasks (FI 4 … 24, the TD-cue task 3 … 15).
const TDS: [u32; 8] = [3, 4, 6, 9, 12, 15, 18, 24];

fn gauss(rng: &mut Xoshiro256PlusPlus) -> f64 {
    // Box–Muller.
    let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
    (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
}

/// A trajectory `[rows, units]` row-major from `f(t, i)`, `t` = 1 … rows (steps since the
/// onset).
fn traj(rows: usize, units: usize, f: impl Fn(f64, usize) -> f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(rows * units);
    for r in 0..rows {
        for i in 0..units {
            out.push(f(r as f64 + 1.0, i));
        }
    }
    out
}

/// A random orthogonal `[n, n]` matrix: QR of a Gaussian matrix, signs fixed so that it is
/// Haar-distributed (Mezzadri 2007).
fn orthogonal(n: usize, rng: &mut Xoshiro256PlusPlus) -> DMatrix<f64> {
    let g = DMatrix::from_fn(n, n, |_, _| gauss(rng));
    let qr = g.qr();
    let (mut q, r) = (qr.q(), qr.r());
    for j in 0..n {
        if r[(j, j)] < 0.0 {
            q.column_mut(j).neg_mut();
        }
    }
    q
}

/// A random invertible `[n, n]` matrix of condition number `cond`: `U diag(s) Vᵀ` with
/// singular values from 1 to `cond` (both ends present).
fn invertible(n: usize, cond: f64, rng: &mut Xoshiro256PlusPlus) -> DMatrix<f64> {
    let (u, v) = (orthogonal(n, rng), orthogonal(n, rng));
    let s = DMatrix::from_fn(n, n, |i, j| {
        if i != j {
            0.0
        } else if i == 0 {
            1.0
        } else if i == n - 1 {
            cond
        } else {
            cond.powf(rng.random::<f64>())
        }
    });
    u * s * v.transpose()
}

/// `x M`: every state `x(t)` mapped to `Mᵀ x(t)` (a change of basis of the units).
fn mix(x: &[f64], units: usize, m: &DMatrix<f64>) -> Vec<f64> {
    let rows = x.len() / units;
    let a = DMatrix::from_row_slice(rows, units, x) * m;
    (0..rows)
        .flat_map(|r| (0..units).map(move |c| (r, c)))
        .map(|(r, c)| a[(r, c)])
        .collect()
}

fn close(a: Option<f64>, b: f64, tol: f64) -> bool {
    a.is_some_and(|a| (a - b).abs() <= tol)
}

/// Ramps of random gains and offsets.
fn ramps(rows: usize, units: usize, rng: &mut Xoshiro256PlusPlus) -> Vec<f64> {
    let (g, b): (Vec<f64>, Vec<f64>) = (0..units).map(|_| (gauss(rng), gauss(rng))).unzip();
    traj(rows, units, |t, i| g[i] * t + b[i])
}

/// One oscillator of `omega` rad/step embedded by random orthonormal columns.
fn ring(rows: usize, units: usize, omega: f64, rng: &mut Xoshiro256PlusPlus) -> Vec<f64> {
    let q = orthogonal(units, rng);
    traj(rows, units, |t, i| {
        q[(i, 0)] * (omega * t).cos() + q[(i, 1)] * (omega * t).sin()
    })
}

/// `k` phase-reset cosines (frequencies `omegas`) read by `units` units with random
/// weights.
fn bank(rows: usize, units: usize, omegas: &[f64], rng: &mut Xoshiro256PlusPlus) -> Vec<f64> {
    let w: Vec<Vec<f64>> = (0..units)
        .map(|_| omegas.iter().map(|_| gauss(rng)).collect())
        .collect();
    traj(rows, units, |t, i| {
        omegas
            .iter()
            .zip(&w[i])
            .map(|(o, a)| a * (o * t).cos())
            .sum()
    })
}

/// A one-hot delay line: unit `i` is active at step `i + 1` (`units` steps long).
fn delay_line(rows: usize, units: usize) -> Vec<f64> {
    traj(rows, units, |t, i| f64::from(t as usize == i + 1))
}

#[test]
fn ramps_are_one_dimensional_straight_and_at_constant_speed() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    for &td in &TDS {
        let w = 2 * td as usize;
        for &units in &[8, 100, 1000] {
            for _ in 0..3 {
                let d = dynamics(&ramps(2 * w, units, &mut rng), units, w, td);
                assert_eq!(d.steps, w);
                assert!(close(d.dimension, 0.0, 1e-9), "td {td} n {units}: {d:?}");
                assert!(close(d.straightness, 1.0, 1e-9), "{d:?}");
                assert!(close(d.turning, 1.0, 1e-9), "{d:?}");
                assert!(close(d.speed_trend, 0.0, 1e-9), "{d:?}");
                assert!(close(d.continuation, 1.0, 1e-9), "{d:?}");
                // An accumulator: eigenvalue 1, no rotation.
                assert!(close(d.spectral_radius, 1.0, 1e-3), "{d:?}");
                assert!(close(d.rotation, 0.0, 1e-3), "{d:?}");
            }
        }
    }
}

#[test]
fn a_ring_attractor_rotates_at_its_frequency_and_a_line_attractor_does_not() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(12);
    for &td in &TDS {
        let w = 2 * td as usize;
        for &units in &[8, 100] {
            // Periods from 3 steps to two windows.
            for &period in &[3.0, 5.0, 2.0 * w as f64] {
                let omega = TAU / period;
                let d = dynamics(&ring(2 * w, units, omega, &mut rng), units, w, td);
                let m = format!("td {td} n {units} period {period}: {d:?}");
                assert!(close(d.turning, omega.cos(), 1e-9), "{m}");
                assert!(close(d.speed_trend, 0.0, 1e-9), "{m}");
                assert!(close(d.continuation, 1.0, 1e-9), "{m}");
                // Chord over arc.
                let chord = 2.0 * (omega * (w - 1) as f64 / 2.0).sin().abs();
                let arc = (w - 1) as f64 * 2.0 * (omega / 2.0).sin();
                assert!(close(d.straightness, chord / arc, 1e-6), "{m}");
                assert!(close(d.spectral_radius, 1.0, 1e-3), "{m}");
                assert!(
                    close(d.rotation, omega * f64::from(td) / TAU, 1e-3),
                    "{m}: expected {}",
                    omega * f64::from(td) / TAU
                );
            }
            let line = dynamics(&ramps(2 * w, units, &mut rng), units, w, td);
            assert!(close(line.rotation, 0.0, 1e-3), "{line:?}");
        }
    }
}

#[test]
fn an_oscillator_bank_has_its_eigenvalues_on_the_unit_circle_at_its_frequencies() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(13);
    for &td in &[6u32, 9, 12, 15, 18, 24] {
        let w = 2 * td as usize;
        // As many frequencies as a determined fit allows (2K + 1 parameters, w − 1 samples).
        let k = ((w - 3) / 2).min(6);
        for &units in &[8, 100, 1000] {
            for seed in 0..2 {
                let omegas: Vec<f64> = (0..k)
                    .map(|j| 0.25 + 2.5 * (j as f64 + 0.5 * f64::from(seed)) / k as f64)
                    .collect();
                if 2 * k > units {
                    continue;
                }
                let d = dynamics(&bank(2 * w, units, &omegas, &mut rng), units, w, td);
                let m = format!("td {td} n {units} k {k}: {d:?}");
                assert!(close(d.spectral_radius, 1.0, 1e-3), "{m}");
                let mean = omegas.iter().sum::<f64>() / k as f64;
                assert!(close(d.rotation, mean * f64::from(td) / TAU, 1e-2), "{m}");
                // Undamped: it goes on after the window as fast as in it (the phases
                // drift apart, so only roughly 1).
                assert!(
                    d.continuation.is_some_and(|c| (0.6..1.6).contains(&c)),
                    "{m}"
                );
                // More than one dimension, far from a delay line's every-step-new.
                assert!(d.dimension.is_some_and(|x| x > 0.02 && x < 0.9), "{m}");
            }
        }
    }
}

#[test]
fn a_delay_line_turns_every_step_into_a_new_orthogonal_direction() {
    for &td in &TDS {
        let w = 2 * td as usize;
        // Long enough to run through the window and the window after it.
        for &units in &[2 * w, 1000] {
            let d = dynamics(&delay_line(2 * w, units), units, w, td);
            let m = format!("td {td} n {units}: {d:?}");
            assert!(close(d.dimension, 1.0, 1e-9), "{m}");
            assert!(close(d.turning, -0.5, 1e-9), "{m}");
            assert!(close(d.speed_trend, 0.0, 1e-9), "{m}");
            // √2 from the first to the last state over w − 1 steps of √2.
            assert!(close(d.straightness, 1.0 / (w - 1) as f64, 1e-9), "{m}");
            assert!(close(d.continuation, 1.0, 1e-9), "{m}");
            // A shift fitted on a finite window: its eigenvalues spread round the circle
            // (the roots of a companion matrix), about a quarter cycle per step on average,
            // inside the circle by O(1/T).
            let per_step = d.rotation.unwrap() / f64::from(td);
            assert!((0.24..=0.36).contains(&per_step), "{m}");
            assert!(
                d.spectral_radius.is_some_and(|r| (0.6..1.0).contains(&r)),
                "{m}"
            );
        }
        // A chain that ends with the window: nothing moves after its last unit leaves.
        let d = dynamics(&delay_line(2 * w, w), w, w, td);
        // One step of √2 … then one of 1 (the last unit falls silent), then stillness.
        let expected = 1.0 / (w as f64 * 2f64.sqrt());
        assert!(close(d.continuation, expected, 1e-9), "td {td}: {d:?}");
    }
}

/// Gaussian fields at `units` log-spaced delays from 1 to `4 × w` steps, widths `cv ×`
/// their delay.
fn log_time_cells(rows: usize, units: usize, w: usize, cv: f64) -> Vec<f64> {
    let top = (4 * w) as f64;
    let centre = |i: usize| top.powf(i as f64 / (units - 1) as f64);
    traj(rows, units, |t, i| {
        let c = centre(i);
        (-(t - c).powi(2) / (2.0 * (cv * c).powi(2))).exp()
    })
}

/// Decaying traces `e^{−s t}` at `units` log-spaced rates from `1/(4w)` to 2 per step.
fn laplace(rows: usize, units: usize, w: usize) -> Vec<f64> {
    let (lo, hi) = (1.0 / (4 * w) as f64, 2.0f64);
    traj(rows, units, |t, i| {
        let s = lo * (hi / lo).powf(i as f64 / (units - 1) as f64);
        (-s * t).exp()
    })
}

#[test]
fn log_time_codes_slow_down_as_one_over_elapsed_time() {
    for &td in &[6u32, 9, 12, 15, 18, 24] {
        let w = 2 * td as usize;
        for &units in &[64, 200, 1000] {
            let cells = dynamics(&log_time_cells(2 * w, units, w, 0.3), units, w, td);
            let traces = dynamics(&laplace(2 * w, units, w), units, w, td);
            for (name, d) in [("time cells", cells), ("laplace", traces)] {
                let m = format!("{name} td {td} n {units}: {d:?}");
                // The continuum answer is −1; a finite window and bank bend it a little.
                assert!(
                    d.speed_trend.is_some_and(|s| (-1.25..=-0.75).contains(&s)),
                    "{m}"
                );
                // Slower after the window than in it.
                assert!(d.continuation.is_some_and(|c| c < 0.6), "{m}");
            }
            // Decays: eigenvalues inside the circle, on the real line.
            assert!(traces.rotation.is_some_and(|r| r < 0.05), "{traces:?}");
        }
    }
}

#[test]
fn a_slow_point_chain_and_a_limit_cycle_differ_only_after_the_trial() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(14);
    for &td in &TDS {
        let w = 2 * td as usize;
        let omega = TAU / (2.0 * w as f64);
        let units = 50;
        let q = orthogonal(units, &mut rng);
        let point =
            |t: f64, i: usize| q[(i, 0)] * (omega * t).cos() + q[(i, 1)] * (omega * t).sin();
        let cycle = traj(2 * w, units, point);
        // The chain follows the same path to the end of the window, then holds its last
        // point (a slow point reached).
        let end = w as f64;
        let chain = traj(2 * w, units, |t, i| point(t.min(end), i));
        let (c, s) = (
            dynamics(&cycle, units, w, td),
            dynamics(&chain, units, w, td),
        );
        // Inside the trial they are the same trajectory.
        for (a, b) in [
            (c.dimension, s.dimension),
            (c.turning, s.turning),
            (c.straightness, s.straightness),
            (c.rotation, s.rotation),
        ] {
            assert!((a.unwrap() - b.unwrap()).abs() < 1e-9, "{c:?} {s:?}");
        }
        // After it, one goes on and the other stands still.
        assert!(close(c.continuation, 1.0, 1e-9), "{c:?}");
        assert!(close(s.continuation, 0.0, 1e-9), "{s:?}");
    }
}

/// Every population of this file at TD `td`, `units` units.
fn populations(
    td: u32,
    units: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> Vec<(&'static str, Vec<f64>)> {
    let w = 2 * td as usize;
    let rows = 2 * w;
    vec![
        ("ramps", ramps(rows, units, rng)),
        ("ring", ring(rows, units, TAU / 7.0, rng)),
        ("bank", bank(rows, units, &[0.3, 0.9, 1.7, 2.4], rng)),
        ("delay line", delay_line(rows, units)),
        ("time cells", log_time_cells(rows, units, w, 0.3)),
        ("laplace", laplace(rows, units, w)),
    ]
}

fn values(d: &Dynamics) -> Vec<(&'static str, Option<f64>)> {
    chronocooked_analysis::neural::dynamics::features(d).to_vec()
}

#[test]
fn every_feature_is_the_same_in_any_orthogonal_basis() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(15);
    for &td in &TDS {
        let w = 2 * td as usize;
        for &units in &[8usize, 64, 300] {
            let q = orthogonal(units, &mut rng);
            for (name, x) in populations(td, units, &mut rng) {
                let (a, b) = (
                    dynamics(&x, units, w, td),
                    dynamics(&mix(&x, units, &q), units, w, td),
                );
                for ((f, u), (_, v)) in values(&a).into_iter().zip(values(&b)) {
                    match (u, v) {
                        (Some(u), Some(v)) => assert!(
                            (u - v).abs() <= 1e-6 * (1.0 + u.abs()),
                            "{name} td {td} n {units} {f}: {u} vs {v}"
                        ),
                        (None, None) => {}
                        _ => panic!("{name} td {td} n {units} {f}: {u:?} vs {v:?}"),
                    }
                }
            }
        }
    }
}

#[test]
fn a_thousand_unit_population_mixes_without_changing_its_signature() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(16);
    let (td, units) = (12u32, 1000usize);
    let w = 2 * td as usize;
    let q = orthogonal(units, &mut rng);
    let omegas: Vec<f64> = (0..100).map(|j| 0.05 + 0.03 * j as f64).collect();
    let x = bank(2 * w, units, &omegas, &mut rng);
    let (a, b) = (
        dynamics(&x, units, w, td),
        dynamics(&mix(&x, units, &q), units, w, td),
    );
    for ((f, u), (_, v)) in values(&a).into_iter().zip(values(&b)) {
        let (u, v) = (u.unwrap(), v.unwrap());
        assert!((u - v).abs() <= 1e-6 * (1.0 + u.abs()), "{f}: {u} vs {v}");
    }
}

/// The linear-dynamics spectrum of a low-dimensional trajectory (a determined fit) is that
/// of any invertible change of basis; the features built on Euclidean lengths are not
/// (stated in the module doc), and this shows that they do change.
#[test]
fn the_spectrum_survives_an_invertible_map_and_the_lengths_do_not() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(17);
    let mut length_changed = false;
    for &td in &TDS {
        let w = 2 * td as usize;
        for &units in &[8usize, 64] {
            let m = invertible(units, 10.0, &mut rng);
            let omegas: &[f64] = if w >= 8 { &[0.4, 1.3] } else { &[0.9] };
            for (name, x) in [
                ("ramps", ramps(2 * w, units, &mut rng)),
                ("ring", ring(2 * w, units, TAU / 5.0, &mut rng)),
                ("bank", bank(2 * w, units, omegas, &mut rng)),
            ] {
                let (a, b) = (
                    dynamics(&x, units, w, td),
                    dynamics(&mix(&x, units, &m), units, w, td),
                );
                let msg = format!("{name} td {td} n {units}: {a:?} vs {b:?}");
                assert!(
                    (a.spectral_radius.unwrap() - b.spectral_radius.unwrap()).abs() < 2e-3,
                    "{msg}"
                );
                assert!(
                    (a.rotation.unwrap() - b.rotation.unwrap()).abs() < 2e-3,
                    "{msg}"
                );
                if name != "ramps" {
                    length_changed |= (a.turning.unwrap() - b.turning.unwrap()).abs() > 1e-3;
                }
            }
        }
    }
    assert!(
        length_changed,
        "an invertible map should bend the lengths and angles"
    );
}

#[test]
fn too_short_or_still_trajectories_have_no_signature() {
    let still = vec![1.0; 40 * 5];
    let d = dynamics(&still, 5, 20, 10);
    assert_eq!(d.dimension, None);
    assert_eq!(d.rotation, None);
    let mut short = ramps(3, 4, &mut Xoshiro256PlusPlus::seed_from_u64(1));
    short.extend(vec![f64::NAN; 4 * 10]);
    let d = dynamics(&short, 4, 12, 6);
    assert_eq!((d.steps, d.turning), (3, None));
}
