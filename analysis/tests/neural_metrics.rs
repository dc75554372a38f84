//! Neural metrics with known answers on synthetic populations.

use chronocooked_analysis::neural::correlation_p;
use chronocooked_analysis::{
    Cube, Decoder, classify_ramps, decode_time, sequentiality_index, temporal_information,
    time_cells,
};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn gauss(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0
}

/// `trials × time × units` from `f(trial, t, unit)`.
fn cube(
    trials: usize,
    time: usize,
    units: usize,
    mut f: impl FnMut(usize, usize, usize) -> f64,
) -> Cube {
    let mut data = Vec::with_capacity(trials * time * units);
    for k in 0..trials {
        for t in 0..time {
            for i in 0..units {
                data.push(f(k, t, i));
            }
        }
    }
    Cube::new(trials, time, units, data).expect("trials × time × units values")
}

#[test]
fn correlation_p_matches_known_values() {
    // r = 0.5, n = 12: t = 1.826, df 10 → two-sided p = 0.0978.
    assert!(
        (correlation_p(0.5, 12) - 0.0978).abs() < 5e-4,
        "{}",
        correlation_p(0.5, 12)
    );
    // r = 0.9, n = 5: t = 3.576, df 3 → p = 0.0374.
    assert!((correlation_p(0.9, 5) - 0.0374).abs() < 5e-4);
    assert!(correlation_p(0.0, 30) > 0.999);
}

#[test]
fn ramp_classifier_separates_ramps_from_noise() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    // Units 0–4 ramp (up or down) with noise; 5–9 are noise; trial average over 30 trials.
    let c = cube(30, 20, 10, |_, t, i| {
        let noise = 0.3 * gauss(&mut rng);
        if i < 5 {
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            sign * 0.1 * t as f64 + noise
        } else {
            noise
        }
    });
    let ramps = classify_ramps(&c.average(), 10, 0.9, 0.05);
    for r in &ramps {
        assert_eq!(r.ramping, r.unit < 5, "{r:?}");
    }
    assert!(ramps[1].slope < 0.0 && ramps[0].slope > 0.0);
}

#[test]
fn sequentiality_is_one_for_a_tiling_sequence_and_zero_for_identical_ramps() {
    let n = 12;
    let seq = cube(1, n, n, |_, t, i| if t == i { 1.0 } else { 0.0 });
    assert!((sequentiality_index(&seq.average(), n) - 1.0).abs() < 1e-12);
    let ramps = cube(1, n, n, |_, t, _| t as f64);
    assert!(sequentiality_index(&ramps.average(), n) < 1e-9);
    // Temporal information: a sharp bump carries more than a ramp.
    let info_seq = temporal_information(&seq.average(), n);
    let info_ramp = temporal_information(&ramps.average(), n);
    assert!(info_seq[3] > 2.0 * info_ramp[3]);
}

#[test]
fn time_cells_are_found_and_decoders_recover_time() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(4);
    // 16 time cells tiling 24 steps (Gaussian fields, width 1.5, trial jitter) + 4 noise units.
    let (trials, time, units) = (40, 24, 20);
    let c = cube(trials, time, units, |_, t, i| {
        let noise = 0.1 * gauss(&mut rng);
        if i < 16 {
            let centre = 1.0 + i as f64 * 1.4;
            (-(t as f64 - centre).powi(2) / (2.0 * 1.5 * 1.5)).exp() + noise
        } else {
            noise
        }
    });
    let cells = time_cells(&c, 1, 200, 7);
    for u in &cells {
        assert_eq!(u.time_cell, u.unit < 16, "{u:?}");
        if u.unit < 16 {
            let centre = 1.0 + u.unit as f64 * 1.4;
            assert!((u.peak_time as f64 - centre).abs() <= 1.0, "{u:?}");
        }
    }
    for decoder in [Decoder::Ridge, Decoder::Bayes] {
        let r = decode_time(&c, decoder, 5, 1.0);
        let limit = if decoder == Decoder::Bayes { 0.5 } else { 2.0 };
        assert!(
            r.mean_abs_error < limit,
            "{decoder:?}: {}",
            r.mean_abs_error
        );
        assert_eq!(r.error_by_time.len(), time);
    }
    // Noise alone cannot be decoded: error near that of guessing the middle (~6 steps).
    let noise = cube(trials, time, 6, |_, _, _| gauss(&mut rng));
    assert!(decode_time(&noise, Decoder::Ridge, 5, 1.0).mean_abs_error > 4.0);
}

/// A unit silent on every trial but one (a delay-line cell that fires on a single trial):
/// in the fold that tests that trial it is constant on the training trials, and must not
/// turn the read-out of a perfect ramp into nonsense. With a second perfect ramp the error
/// stays near 0; the read-out also never leaves the window.
#[test]
fn a_unit_constant_on_the_training_trials_does_not_break_the_ridge_read_out() {
    let (trials, time) = (12, 12);
    let c = cube(trials, time, 3, |k, t, i| match i {
        0 => t as f64,
        1 => 0.5 * t as f64 + 3.0,
        _ => {
            if k == 7 && t == 4 {
                250.0
            } else {
                0.0
            }
        }
    });
    let r = decode_time(&c, Decoder::Ridge, 12, 1e-3);
    // Exact ramps: the only error is trial 7, step 4, where the odd unit is 250 — with the
    // unit weightless there, the error is that of the ramps alone (≈ 0).
    assert!(r.mean_abs_error < 0.05, "{}", r.mean_abs_error);
    // Read-outs are clipped: no bin's error can exceed the window.
    let bad = cube(
        trials,
        time,
        1,
        |k, t, _| if k == 3 { 1e6 } else { t as f64 },
    );
    let r = decode_time(&bad, Decoder::Ridge, 12, 1e-3);
    for e in r.error_by_time.iter().filter(|e| e.is_finite()) {
        assert!(*e <= (time - 1) as f64 + 1e-9, "{e}");
    }
}

#[test]
fn scaling_factor_recovers_a_known_stretch() {
    use chronocooked_analysis::neural::scaling_factor;
    // A time field at 5 of a 12-step interval, and the same field stretched for 24 steps.
    let bump = |t: f64, c: f64, w: f64| (-(t - c).powi(2) / (2.0 * w * w)).exp();
    let a: Vec<f64> = (0..14).map(|t| bump(t as f64, 5.0, 1.5)).collect();
    let b: Vec<f64> = (0..28).map(|t| bump(t as f64, 10.0, 3.0)).collect();
    let (s, r2) = scaling_factor(&a, &b);
    assert!((s - 2.0).abs() < 0.05 && r2 > 0.99, "s {s}, R² {r2}");
    // A non-scaling (fixed-latency) response: best factor near 1.
    let c: Vec<f64> = (0..28).map(|t| bump(t as f64, 5.0, 1.5)).collect();
    assert!((scaling_factor(&a, &c).0 - 1.0).abs() < 0.05);
}
