//! The neural summary on synthetic populations whose answers are known: pure ramps,
//! sinusoids at known frequencies, a tiling sequence of Gaussian bumps, identical bumps and
//! pure noise, recorded as an activity dataset with the oven turning on at step 0 and
//! analysed over the summary's window of 2 × TD steps; plus populations recorded at two
//! TDs that stretch with the interval (scaling = TD ratio) or do not (scaling = 1).

use chronocooked_analysis::neural::categories::Category;
use chronocooked_analysis::neural::summary::{
    NeuralSummary, SummaryOptions, classify_td, neural_summary,
};
use chronocooked_models::activity::{Event, Population, Trial};
use chronocooked_models::{ActivityDataset, ActivityMeta, Marker};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::PI;

/// The TD of the synthetic trials; the summary's window is 2 × TD = 40 steps.
const TD: u32 = 20;
const WINDOW: usize = 2 * TD as usize;
const TRIALS: usize = 30;
const UNITS: usize = 8;
/// The sequence tiles the window with one unit per step.
const SEQUENCE: usize = WINDOW;
/// Periods (steps): every one gives ≥ 2 cycles in the 40-step window.
const PERIODS: [f64; UNITS] = [4.0, 5.0, 6.0, 8.0, 10.0, 13.0, 16.0, 20.0];

fn gauss(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0
}

/// Population `p` (0 ramps, 1 oscillators, 2 tiling sequence, 3 identical bumps, 4 noise),
/// unit `i`, time `t` after oven-on (steps).
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

fn meta(populations: Vec<Population>, seed: u64) -> ActivityMeta {
    ActivityMeta {
        model: "synthetic".into(),
        task: chronocooked_env::Task::parse("PeakInterval-v0", &[] as &[&str]).unwrap(),
        seed,
        dt: 1.0,
        populations,
    }
}

/// A trial of `steps` steps with the oven turned on at step 0 and activity `f(step)`.
fn trial(td: u32, steps: usize, activity: Vec<f32>) -> Trial {
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
            trial(TD, steps, activity)
        })
        .collect();
    ActivityDataset {
        meta: meta(populations, seed),
        trials,
    }
}

fn opts() -> SummaryOptions {
    let mut o = SummaryOptions::default();
    o.categories.seed = 7;
    o
}

fn summary(ds: &ActivityDataset, population: &str) -> NeuralSummary {
    neural_summary(ds, Some(population), &opts()).expect("population exists")
}

fn counts(s: &NeuralSummary) -> chronocooked_analysis::neural::categories::CategoryCounts {
    s.categories.as_ref().expect("categories defined").counts
}

#[test]
fn ramps_are_ramps_and_nothing_else() {
    let s = summary(&dataset(1), "ramps");
    assert_eq!((s.units, s.trials, s.window), (UNITS, TRIALS, WINDOW));
    assert_eq!(counts(&s).ramp, UNITS, "{s:?}");
    // 8 units: counts and intervals, no fractions.
    let c = s.categories.as_ref().unwrap();
    assert!(c.fractions.is_none());
    // Wilson 95% interval of 8/8: [0.676, 1].
    assert!(
        (c.ci.ramp[0] - 0.6756).abs() < 1e-3 && c.ci.ramp[1] == 1.0,
        "{c:?}"
    );
    // Ramps carry elapsed time: a linear read-out decodes it to within a step.
    assert!(s.decode_ridge.unwrap() < 1.0, "{s:?}");
    // One TD recorded: no scaling.
    assert!(s.scaling.is_none());
}

#[test]
fn sinusoids_oscillate_at_their_own_frequencies() {
    let ds = dataset(2);
    let s = summary(&ds, "oscillators");
    assert_eq!(counts(&s).oscillating, UNITS, "{s:?}");
    let c = classify_td(&ds, Some("oscillators"), TD, &opts()).unwrap();
    for (u, period) in c.tests.unwrap().iter().zip(PERIODS) {
        // Spectral peak within one frequency bin (1/WINDOW) of the unit's own frequency.
        assert!(
            (u.spectral_peak - 1.0 / period).abs() <= 1.0 / WINDOW as f64 + 1e-9,
            "{u:?}: period {period}"
        );
        assert!(!u.ramp && !u.time_field, "{u:?}");
    }
}

#[test]
fn a_tiling_sequence_is_made_of_time_fields_with_high_sequentiality() {
    let ds = dataset(3);
    let s = summary(&ds, "sequence");
    assert_eq!(s.units, SEQUENCE);
    let c = counts(&s);
    // Units 0 and 39 peak at an edge, and unit 38 falls by only 1 − e^(−1/2) = 39% of its
    // range after its peak (less than half): inside the window they are monotone (ramps),
    // never time fields. Unit 1 rises by that 39% before its peak — more than the quarter a
    // field cut by the event must show (`MIN_FIELD_RISE`) — so it is a field.
    assert!(c.time_field >= SEQUENCE - 3, "{c:?}");
    assert_eq!(c.oscillating, 0, "{c:?}");
    assert_eq!(c.untuned, 0, "{c:?}");
    let f = s.categories.as_ref().unwrap().fractions.unwrap();
    assert!(f.time_field >= 0.9, "{f:?}");
    // Every time field peaks at its own step: the fields tile the window.
    let tests = classify_td(&ds, Some("sequence"), TD, &opts())
        .unwrap()
        .tests
        .unwrap();
    for u in tests.iter().filter(|u| u.category == Category::TimeField) {
        assert_eq!(u.peak_time, u.unit, "{u:?}");
        // σ = 1 step: full width at half maximum 2·√(2 ln 2) ≈ 2.35 steps (undefined for
        // a field whose rise the event cuts before it reaches half height: unit 1).
        assert!(
            (u.peak_width - 2.35).abs() < 0.6 || (u.unit == 1 && u.peak_width.is_nan()),
            "{u:?}"
        );
    }
    // Noiseless Gaussian bumps (σ = 1 step) give PE = 1 and TS ≈ 0.63, so SqI ≈ 0.79.
    assert!(s.sequentiality.unwrap() > 0.55, "{s:?}");
    assert!(
        s.decode_bayes.unwrap() < 2.0 && s.decode_ridge.unwrap() < 4.0,
        "{s:?}"
    );
    // Identical bumps: every unit is the same time field at step 20 (PE = 0).
    let identical = summary(&ds, "identical");
    assert_eq!(counts(&identical).time_field, UNITS, "{identical:?}");
    assert!(identical.sequentiality.unwrap() < 0.2, "{identical:?}");
}

#[test]
fn pure_noise_is_untuned_and_decodes_at_chance() {
    let s = summary(&dataset(4), "noise");
    let c = counts(&s);
    // Each unit is a false positive with probability alpha = 0.05 (measured on 600 units
    // in analysis/tests/neural_categories.rs); 8 units: at most one.
    assert!(c.untuned >= UNITS - 1, "{c:?}");
    assert_eq!(c.total(), UNITS);
    // Chance: guessing the middle of a uniform window errs by WINDOW/4 on average.
    let chance = WINDOW as f64 / 4.0;
    assert!(s.decode_ridge.unwrap() > 0.7 * chance, "{s:?}");
    assert!(s.decode_bayes.unwrap() > 0.7 * chance, "{s:?}");
}

/// Two TDs of a population of 12 bumps at fractions `(i + 1)/13` of the window: `stretch`
/// = peaks and widths scale with TD; otherwise the same bumps at both TDs (a fixed clock).
fn two_td_dataset(stretch: bool) -> ActivityDataset {
    let units = 12;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    let mut trials = Vec::new();
    for td in [10u32, 20] {
        let scale = if stretch { f64::from(td) / 10.0 } else { 1.0 };
        for _ in 0..20 {
            let steps = 2 * td as usize + 1;
            let mut activity = Vec::with_capacity(steps * units);
            for s in 0..steps {
                // τ = steps since oven-on (the first window step is τ = 1).
                let tau = s as f64;
                for i in 0..units {
                    let centre0 = 20.0 * (i + 1) as f64 / 13.0;
                    let (centre, width) = (centre0 * scale, (1.0 + 0.1 * centre0) * scale);
                    let v = if s == 0 {
                        0.0
                    } else {
                        (-(tau - centre).powi(2) / (2.0 * width * width)).exp()
                    };
                    activity.push((v + 0.02 * gauss(&mut rng)) as f32);
                }
            }
            trials.push(trial(td, steps, activity));
        }
    }
    ActivityDataset {
        meta: meta(
            vec![Population {
                name: "cells".into(),
                size: units,
            }],
            0,
        ),
        trials,
    }
}

#[test]
fn scaling_is_the_td_ratio_for_stretching_activity_and_one_for_a_fixed_clock() {
    let s = summary(&two_td_dataset(true), "cells");
    let sc = s.scaling.as_ref().expect("two TDs");
    assert_eq!((sc.td_short, sc.td_long, sc.td_ratio), (10, 20, 2.0));
    let m = sc.median.unwrap();
    assert!((m - 2.0).abs() < 0.15, "{sc:?}");
    assert!(sc.units >= 10, "{sc:?}");
    // Stretched dynamics run at half the speed at twice the TD.
    assert!((sc.speed_ratio.unwrap() - 0.5).abs() < 0.1, "{sc:?}");
    assert_eq!(s.by_td.len(), 2);
    assert_eq!((s.by_td[0].window, s.by_td[1].window), (20, 40));
    let fixed = summary(&two_td_dataset(false), "cells");
    let sc = fixed.scaling.as_ref().unwrap();
    assert!((sc.median.unwrap() - 1.0).abs() < 0.1, "{sc:?}");
    // The same trajectory at the same speed (compared over the shorter window).
    assert!((sc.speed_ratio.unwrap() - 1.0).abs() < 0.1, "{sc:?}");
}

#[test]
fn rhythms_whose_speed_varies_from_trial_to_trial_still_oscillate() {
    // Oscillators at 5–15 Hz sampled every 25 ms (0.125–0.375 cycles per step), all starting
    // in phase at oven-on, each trial's frequencies scaled by one log-normal factor
    // (SD 0.15, like the SBF's clock noise): the trial average decays after a cycle or two,
    // the single trials keep their rhythm.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(21);
    let (td, units) = (12u32, 20usize);
    let freqs: Vec<f64> = (0..units)
        .map(|i| (5.0 + 10.0 * i as f64 / (units - 1) as f64) * 0.025)
        .collect();
    let trials = (0..36)
        .map(|_| {
            let r = (0.15 * gauss(&mut rng)).exp();
            let steps = 2 * td as usize + 1;
            let mut activity = Vec::with_capacity(steps * units);
            for s in 0..steps {
                for f in &freqs {
                    activity.push((2.0 * PI * f * r * s as f64).cos() as f32);
                }
            }
            trial(td, steps, activity)
        })
        .collect();
    let ds = ActivityDataset {
        meta: meta(
            vec![Population {
                name: "osc".into(),
                size: units,
            }],
            0,
        ),
        trials,
    };
    let c = classify_td(&ds, Some("osc"), td, &opts()).unwrap();
    let bin = 1.0 / c.window as f64;
    for (u, f) in c.tests.unwrap().iter().zip(&freqs) {
        assert_eq!(u.category, Category::Oscillating, "{f}: {u:?}");
        assert!((u.spectral_peak - f).abs() <= bin + 1e-9, "{f}: {u:?}");
    }
}

/// A multi-oven agent's second clock: oven 1 (TD 10) turns on at step 0 and oven 2 (TD 16)
/// at step 7, as in an asynchronous episode. Population `bump` peaks 10 steps after oven 1's
/// onset and `bump_oven2` 16 steps after oven 2's: each is classified at its own oven's
/// duration and aligned to its own oven's onset, so both are time fields peaking at their
/// TD (aligned to oven 1, `bump_oven2` would peak at 23 and be summarised at TD 10).
#[test]
fn a_second_ovens_population_is_aligned_to_its_own_onset_and_duration() {
    const TD1: u32 = 10;
    const TD2: u32 = 16;
    const ON2: usize = 7;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    let bump = |t: f64, at: u32| (-(t - f64::from(at)).powi(2) / (2.0 * 3.0f64.powi(2))).exp();
    let populations = vec![
        Population {
            name: "bump".into(),
            size: UNITS,
        },
        Population {
            name: "bump_oven2".into(),
            size: UNITS,
        },
    ];
    let steps = ON2 + 1 + 2 * TD2 as usize;
    let trials = (0..TRIALS)
        .map(|_| {
            let mut activity = Vec::with_capacity(steps * 2 * UNITS);
            for s in 0..steps {
                // Oven k's time 0 is the step after its onset.
                let t1 = s as f64 - 1.0;
                let t2 = s as f64 - (ON2 as f64 + 1.0);
                for (t, td) in [(t1, TD1), (t2, TD2)] {
                    for _ in 0..UNITS {
                        let v = if t < 0.0 { 0.0 } else { bump(t, td) };
                        activity.push((v + 0.05 * gauss(&mut rng)) as f32);
                    }
                }
            }
            let mut trial = trial(TD1, steps, activity);
            trial.events.push(Event {
                step: ON2 as u32,
                marker: Marker::OvenOn2,
            });
            trial.oven_tds = vec![TD1, TD2];
            trial
        })
        .collect();
    let ds = ActivityDataset {
        meta: meta(populations, 11),
        trials,
    };
    for (population, td) in [("bump", TD1), ("bump_oven2", TD2)] {
        let tests = classify_td(&ds, Some(population), td, &opts())
            .unwrap()
            .tests
            .unwrap();
        for u in &tests {
            assert_eq!(u.category, Category::TimeField, "{population}: {u:?}");
            assert_eq!(u.peak_time, td as usize, "{population}: {u:?}");
        }
        let s = summary(&ds, population);
        assert_eq!((s.td, s.window), (td, 2 * td as usize), "{population}");
        assert_eq!(s.by_td.len(), 1, "{population}: one duration per oven");
    }
    // No trial's second oven lasted TD 10.
    assert!(classify_td(&ds, Some("bump_oven2"), TD1, &opts()).is_err());
}
