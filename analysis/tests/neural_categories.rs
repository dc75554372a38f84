//! The unit categories' false-positive rates on pure noise (white and autocorrelated), their
//! exclusivity on clean shapes, and degenerate inputs: constant units, too few trials, too
//! short windows, small populations (counts and Wilson intervals, no fractions).

use crate::synthetic;

use chronocooked_analysis::neural::Cube;
use chronocooked_analysis::neural::categories::{
    Category, CategoryConfig, CategoryError, classify_units, wilson_interval,
};
use chronocooked_analysis::neural::summary::{SummaryOptions, neural_summary};
use chronocooked_models::activity::{Event, Population, Trial};
use chronocooked_models::{ActivityDataset, ActivityMeta, Marker};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use synthetic::{cube, gauss};

/// Fraction of `units` in each category, then the fraction that is tuned, then the
/// fraction whose spectral test alone (ungated by tuning) is significant.
fn rates(c: &Cube, seed: u64) -> [f64; 6] {
    let cfg = CategoryConfig {
        seed,
        ..CategoryConfig::default()
    };
    let tests = classify_units(c, c.time(), &cfg).unwrap();
    let n = tests.len() as f64;
    let frac = |cat| tests.iter().filter(|u| u.category == cat).count() as f64 / n;
    [
        frac(Category::Ramp),
        frac(Category::TimeField),
        frac(Category::Oscillating),
        frac(Category::Mixed),
        1.0 - frac(Category::Untuned),
        tests.iter().filter(|u| u.spectral_p <= 0.05).count() as f64 / n,
    ]
}

/// False-positive rates on 600 units of noise (20 trials × 24 steps, the window of TD 12).
/// Any category other than `untuned` is a false positive; the tuning test has level 0.05,
/// so the total is 0.05 ± 0.009 (binomial SD over 600 units): asserted ≤ 0.08. A false
/// positive has no shape as a rule and lands in `mixed`; each shape test's own rate is
/// asserted ≤ 0.05 (measured: white noise 0.063 tuned — ramp 0, time field 0, oscillating
/// 0.002, mixed 0.062; AR(1) ρ = 0.8: 0.062 — ramp 0.020, time field 0.008, oscillating 0,
/// mixed 0.033).
fn assert_false_positive_rates(name: &str, r: [f64; 6]) {
    let [ramp, field, osc, mixed, tuned, spectral] = r;
    println!(
        "{name}: tuned {tuned:.3} (ramp {ramp:.3}, time field {field:.3}, oscillating {osc:.3}, mixed {mixed:.3}); spectral test alone {spectral:.3}"
    );
    assert!(tuned <= 0.08, "{name}: {r:?}");
    // The AR(1)-null spectral test (Bonferroni over bins) on its own, ungated.
    assert!(spectral <= 0.06, "{name}: {r:?}");
    for v in [ramp, field, osc] {
        assert!(v <= 0.05, "{name}: {r:?}");
    }
    assert!(mixed <= tuned + 1e-12);
}

#[test]
fn white_noise_units_are_untuned_at_the_stated_rate() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let c = cube(20, 24, 600, |_, _, _| gauss(&mut rng));
    assert_false_positive_rates("white noise", rates(&c, 2));
}

#[test]
fn autocorrelated_noise_units_are_untuned_at_the_stated_rate() {
    // AR(1), ρ = 0.8 per step (slow fluctuations like a recurrent network's), each trial
    // starting from the stationary distribution: not locked to the event.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let rho: f64 = 0.8;
    let mut prev = 0.0;
    let c = cube(20, 24, 600, |_, t, _| {
        let e = gauss(&mut rng);
        prev = if t == 0 {
            e
        } else {
            rho * prev + (1.0 - rho * rho).sqrt() * e
        };
        prev
    });
    assert_false_positive_rates("AR(1) noise", rates(&c, 4));
}

#[test]
fn clean_shapes_land_in_exactly_their_category() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let w = 24;
    // Unit 0 rising ramp, 1 falling exponential decay, 2 interior bump, 3 a 3-cycle rhythm,
    // 4 a saturating rise, 5 a bump at the window's last step (a ramp inside the window).
    let shapes = |t: f64, i: usize| match i {
        0 => t / 23.0,
        1 => (-t / 6.0).exp(),
        2 => (-(t - 12.0).powi(2) / 8.0).exp(),
        3 => (2.0 * std::f64::consts::PI * 3.0 * t / 24.0).cos(),
        4 => 1.0 - (-t / 5.0).exp(),
        _ => (-(t - 23.0).powi(2) / 8.0).exp(),
    };
    let c = cube(16, w, 6, |_, t, i| {
        shapes(t as f64, i) + 0.05 * gauss(&mut rng)
    });
    let tests = classify_units(&c, c.time(), &CategoryConfig::default()).unwrap();
    let want = [
        Category::Ramp,
        Category::Ramp,
        Category::TimeField,
        Category::Oscillating,
        Category::Ramp,
        Category::Ramp,
    ];
    for (u, w) in tests.iter().zip(want) {
        assert_eq!(u.category, w, "{u:?}");
        // A ramp is never a time field and a time field never a ramp.
        assert!(!(u.ramp && u.time_field), "{u:?}");
    }
    assert_eq!(tests[2].peak_time, 12);
}

#[test]
fn wilson_intervals_match_their_formula() {
    // 0 of 1: [0, z²/(1+z²)] = [0, 0.7935]; 5 of 10: 0.5 ± 0.2634.
    let [lo, hi] = wilson_interval(0, 1);
    assert!(lo == 0.0 && (hi - 0.7935).abs() < 1e-4);
    let [lo, hi] = wilson_interval(5, 10);
    assert!((lo - 0.2366).abs() < 1e-4 && (hi - 0.7634).abs() < 1e-4);
    assert_eq!(wilson_interval(0, 0), [0.0, 1.0]);
}

#[test]
fn too_few_trials_or_too_short_windows_leave_the_tests_undefined() {
    let one = cube(1, 24, 2, |_, t, _| t as f64);
    assert!(matches!(
        classify_units(&one, one.time(), &CategoryConfig::default()),
        Err(CategoryError::TooFewTrials { trials: 1, .. })
    ));
    let short = cube(10, 6, 2, |_, t, _| t as f64);
    assert!(matches!(
        classify_units(&short, short.time(), &CategoryConfig::default()),
        Err(CategoryError::WindowTooShort { window: 6, .. })
    ));
}

/// A dataset of one population: units `0..varying` ramp, the rest are constant; `trials`
/// trials of TD `td`.
fn ramp_dataset(td: u32, trials: usize, varying: usize, constant: usize) -> ActivityDataset {
    let n = varying + constant;
    let steps = 2 * td as usize + 1;
    let trials = (0..trials)
        .map(|k| {
            let mut activity = Vec::with_capacity(steps * n);
            for s in 0..steps {
                for i in 0..n {
                    let v = if i < varying {
                        s as f64 * (1.0 + i as f64) + 0.01 * ((k * 7 + s * 3) % 5) as f64
                    } else {
                        0.5
                    };
                    activity.push(v as f32);
                }
            }
            Trial {
                td,
                start: (0, 0),
                steps,
                activity,
                events: vec![Event {
                    step: 0,
                    marker: Marker::OvenOn,
                }],
                reward: 0.0,
                success: false,
                oven_tds: Vec::new(),
                reproduction: None,
            }
        })
        .collect();
    ActivityDataset {
        meta: ActivityMeta {
            model: "synthetic".into(),
            task: chronocooked_env::Task::parse("PeakInterval-v0", &[] as &[&str]).unwrap(),
            seed: 0,
            dt: 1.0,
            populations: vec![Population {
                name: "p".into(),
                size: n,
            }],
        },
        trials,
    }
}

#[test]
fn constant_units_are_excluded_and_small_populations_get_no_fractions() {
    let s = neural_summary(
        &ramp_dataset(8, 12, 1, 3),
        Some("p"),
        &SummaryOptions::default(),
    )
    .unwrap();
    assert_eq!((s.units, s.constant_units), (1, 3));
    let c = s.categories.unwrap();
    assert_eq!(c.counts.ramp, 1);
    assert_eq!(c.counts.total(), 1);
    assert!(c.fractions.is_none(), "one unit: no fraction");
    // Twelve varying units: fractions, summing to 1.
    let s = neural_summary(
        &ramp_dataset(8, 12, 12, 0),
        Some("p"),
        &SummaryOptions::default(),
    )
    .unwrap();
    let f = s.categories.unwrap().fractions.unwrap();
    assert_eq!(f.ramp, 1.0);
    assert_eq!(
        f.ramp + f.time_field + f.oscillating + f.mixed + f.untuned,
        1.0
    );
    // Only constant units: nothing to classify, zero counts (never NaN fractions).
    let s = neural_summary(
        &ramp_dataset(8, 12, 0, 2),
        Some("p"),
        &SummaryOptions::default(),
    )
    .unwrap();
    assert_eq!((s.units, s.constant_units), (0, 2));
    assert_eq!(s.categories.unwrap().counts.total(), 0);
    // TD 3: a 6-step window is too short: categories undefined, with the reason.
    let s = neural_summary(
        &ramp_dataset(3, 12, 2, 0),
        Some("p"),
        &SummaryOptions::default(),
    )
    .unwrap();
    assert!(s.categories.is_none());
    assert!(s.undefined.unwrap().contains("window of 6 steps"));
    // Trials that end early (as on fixed-interval trials): 3 of 12 cover the window, too
    // few for the rhythm test, which is then undefined for every unit and counted.
    let mut ds = ramp_dataset(8, 12, 2, 0);
    for t in ds.trials.iter_mut().skip(3) {
        t.steps = 6;
        t.activity.truncate(6 * 2);
    }
    let s = neural_summary(&ds, Some("p"), &SummaryOptions::default()).unwrap();
    let c = s.categories.unwrap();
    assert_eq!((c.rhythm_undefined, c.counts.oscillating), (2, 0), "{c:?}");
    // An unknown population is a typed error.
    assert!(
        neural_summary(
            &ramp_dataset(8, 12, 1, 0),
            Some("q"),
            &SummaryOptions::default()
        )
        .is_err()
    );
}
