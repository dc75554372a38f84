//! The neural summary (the leaderboard's neural columns) on synthetic populations whose
//! answers are known: pure ramps, sinusoids at known frequencies, a tiling sequence of
//! Gaussian bumps, identical bumps and pure noise, recorded as an activity dataset with the
//! oven turning on at step 0.

use chronocooked_analysis::neural::oscillation::welch;
use chronocooked_analysis::neural::summary::{NeuralSummary, neural_summary};
use chronocooked_models::activity::{Event, Population, Trial};
use chronocooked_models::{ActivityDataset, ActivityMeta, Marker};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::PI;

const WINDOW: usize = 40;
const TRIALS: usize = 30;
const UNITS: usize = 8;
/// The sequence tiles the window with one unit per step (N = M: sequentiality 1 for a
/// one-hot sequence).
const SEQUENCE: usize = WINDOW;
const PERIODS: [f64; UNITS] = [4.0, 5.0, 6.0, 8.0, 10.0, 13.0, 16.0, 20.0];

fn gauss(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0
}

/// Population `p` (0 ramps, 1 oscillators, 2 tiling sequence, 3 identical bumps, 4 noise),
/// unit `i`, time `t` after oven-on (steps), plus noise of SD `noise`.
fn signal(p: usize, i: usize, t: f64) -> f64 {
    match p {
        0 => (t + 1.0) * (0.2 + 0.1 * i as f64) * if i.is_multiple_of(2) { 1.0 } else { -1.0 },
        1 => (2.0 * PI * t / PERIODS[i] + i as f64).sin(),
        2 => (-(t - i as f64).powi(2) / 2.0).exp(),
        3 => (-(t - 20.0).powi(2) / (2.0 * 3.0f64.powi(2))).exp(),
        _ => 0.0,
    }
}

const NAMES: [&str; 5] = ["ramps", "oscillators", "sequence", "identical", "noise"];

fn size(p: usize) -> usize {
    if p == 2 { SEQUENCE } else { UNITS }
}

fn dataset(seed: u64) -> ActivityDataset {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let populations: Vec<Population> = NAMES
        .iter()
        .enumerate()
        .map(|(p, n)| Population {
            name: n.to_string(),
            size: size(p),
        })
        .collect();
    let n: usize = (0..NAMES.len()).map(size).sum();
    let trials = (0..TRIALS)
        .map(|_| {
            // Step 0: the onion goes in; steps 1 … WINDOW are oven times 0 … WINDOW−1.
            let steps = WINDOW + 1;
            let mut activity = Vec::with_capacity(steps * n);
            for s in 0..steps {
                let t = s as f64 - 1.0;
                for p in 0..NAMES.len() {
                    for i in 0..size(p) {
                        let sd = if p == 4 { 1.0 } else { 0.05 };
                        let v = if s == 0 { 0.0 } else { signal(p, i, t) };
                        activity.push((v + sd * gauss(&mut rng)) as f32);
                    }
                }
            }
            Trial {
                td: WINDOW as u32,
                start: (0, 0),
                steps,
                activity,
                events: vec![Event {
                    step: 0,
                    marker: Marker::OvenOn,
                }],
                reward: 1.0,
                success: true,
            }
        })
        .collect();
    ActivityDataset {
        meta: ActivityMeta {
            model: "synthetic".into(),
            task: "FixedInterval-v0".into(),
            env: vec![],
            seed,
            dt: 1.0,
            populations,
        },
        trials,
    }
}

fn summary(ds: &ActivityDataset, population: &str) -> NeuralSummary {
    neural_summary(ds, Some(population), Some(WINDOW), 7).expect("population has varying units")
}

#[test]
fn ramps_are_ramping_and_nothing_else() {
    let s = summary(&dataset(1), "ramps");
    assert_eq!((s.units, s.trials, s.window), (UNITS, TRIALS, WINDOW));
    assert_eq!(s.frac_ramping, 1.0, "{s:?}");
    assert_eq!(s.frac_oscillating, 0.0, "{s:?}");
    // Ramps carry elapsed time: a linear read-out decodes it to within a step.
    assert!(s.decode_ridge < 1.0, "{s:?}");
}

#[test]
fn sinusoids_oscillate_at_their_own_frequencies() {
    let ds = dataset(2);
    let s = summary(&ds, "oscillators");
    assert_eq!(s.frac_oscillating, 1.0, "{s:?}");
    assert_eq!(s.frac_ramping, 0.0, "{s:?}");
    // Spectral peak of each unit's trial average within one frequency bin (1/WINDOW).
    let base = UNITS; // the oscillators' first column
    let n: usize = (0..NAMES.len()).map(size).sum();
    for (i, period) in PERIODS.iter().enumerate() {
        let avg: Vec<f64> = (1..=WINDOW)
            .map(|s| {
                ds.trials
                    .iter()
                    .map(|t| f64::from(t.activity[s * n + base + i]))
                    .sum::<f64>()
                    / TRIALS as f64
            })
            .collect();
        let spectrum = welch(&avg, WINDOW, 1.0);
        assert!(
            (spectrum.peak - 1.0 / period).abs() <= 1.0 / WINDOW as f64 + 1e-9,
            "unit {i}: peak {} vs {}",
            spectrum.peak,
            1.0 / period
        );
    }
}

#[test]
fn a_tiling_sequence_is_made_of_time_cells_with_high_sequentiality() {
    let s = summary(&dataset(3), "sequence");
    assert_eq!(s.units, SEQUENCE);
    assert!(s.frac_time_cells >= 0.9, "{s:?}");
    // Noiseless Gaussian bumps (σ = 1 step) give PE = 1 and TS ≈ 1 − H(1, .61, .61, .14, .14)/ln 40
    // ≈ 0.63, so SqI ≈ 0.79; the noisy baseline of the other 37 units lowers TS further.
    assert!(s.sequentiality > 0.55, "{s:?}");
    assert_eq!(s.frac_oscillating, 0.0, "{s:?}");
    assert!(s.decode_bayes < 2.0 && s.decode_ridge < 4.0, "{s:?}");
    // Identical bumps: every unit peaks at step 20 (PE = 0).
    let identical = summary(&dataset(3), "identical");
    assert!(identical.sequentiality < 0.2, "{identical:?}");
    assert!(identical.sequentiality < s.sequentiality - 0.4);
}

#[test]
fn pure_noise_has_no_structure_and_decodes_at_chance() {
    let s = summary(&dataset(4), "noise");
    assert_eq!(s.frac_ramping, 0.0, "{s:?}");
    assert!(s.frac_time_cells <= 1.0 / UNITS as f64, "{s:?}");
    assert!(s.frac_oscillating <= 2.0 / UNITS as f64, "{s:?}");
    // Chance: guessing the middle of a uniform window errs by WINDOW/4 on average.
    let chance = WINDOW as f64 / 4.0;
    assert!(s.decode_ridge > 0.7 * chance, "{s:?}");
    assert!(s.decode_bayes > 0.7 * chance, "{s:?}");
}
