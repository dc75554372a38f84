//! KiNeT on recorded reproduction activity (`analysis/src/neural/production.rs`): synthetic
//! datasets shaped as `record` writes them — Ready, `ts` steps, Set, a production of `ts`
//! steps, the reproduction context on every trial — whose kinematics are known by
//! construction, with noise on every trial:
//!
//! * `stretched`: after Set the population runs `g(t / ts)` — time-stretched copies of one
//!   curve, relative speed `ts_ref / ts`, scaling index 1 (timing by speed);
//! * `clock`: `g(t / 12)` whatever `ts` — a clock of fixed speed, index 0;
//! * a unit that never varies is left out of the dimensions;
//! * each context (prior × gain) is analysed on its own, with its middle `ts` as reference;
//! * the neural summary aligns a reproduction dataset's windows to Set.

use chronocooked_analysis::neural::production::production_speed;
use chronocooked_analysis::neural::summary::{SummaryOptions, neural_summary};
use chronocooked_env::RsgState;
use chronocooked_models::activity::{Event, Population, Trial};
use chronocooked_models::{ActivityDataset, ActivityMeta, Marker};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use rand_xoshiro::Xoshiro256PlusPlus;

const READY: u32 = 3;
const TRIALS: usize = 10;
/// Priors (index, ts range) of the synthetic task.
const PRIORS: [(u8, std::ops::RangeInclusive<u32>); 2] = [(0, 8..=14), (1, 14..=20)];

/// A smooth curve with monotone progress along its first coordinate.
fn g(u: f64) -> [f64; 3] {
    [u, 0.5 * (std::f64::consts::PI * u).sin(), u * u]
}

/// One trial of `ts`: Ready at step READY, Set `ts` steps later, the pickup `ts` steps
/// after Set and the delivery 2 steps after that. Populations: `stretched` (3 units),
/// `clock` (3 units), `silent` (1 unit, constant).
fn trial(prior: u8, ts: u32, rng: &mut Xoshiro256PlusPlus) -> Trial {
    let noise = Normal::new(0.0, 0.02).unwrap();
    let set = READY + ts;
    let steps = (set + ts + 3) as usize;
    let mut activity = Vec::with_capacity(steps * 7);
    for s in 0..steps {
        let t = s as f64 - f64::from(set) - 1.0;
        let (a, b) = if t < 0.0 {
            ([0.0; 3], [0.0; 3])
        } else {
            (g(t / f64::from(ts)), g(t / 12.0))
        };
        for v in a.iter().chain(&b) {
            activity.push((v + noise.sample(rng)) as f32);
        }
        activity.push(0.25);
    }
    let event = |step: u32, marker: Marker| Event { step, marker };
    Trial {
        td: ts,
        start: (1, 1),
        steps,
        activity,
        events: vec![
            event(READY, Marker::Ready),
            event(set, Marker::Set),
            event(set + ts, Marker::Pickup),
            event(set + ts + 2, Marker::Delivery),
        ],
        reward: 1.0,
        success: true,
        oven_tds: Vec::new(),
        reproduction: Some(RsgState {
            prior,
            gain: 0,
            foreperiod: READY,
        }),
    }
}

fn dataset(seed: u64) -> ActivityDataset {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut trials = Vec::new();
    for (prior, range) in PRIORS {
        for ts in range {
            for _ in 0..TRIALS {
                trials.push(trial(prior, ts, &mut rng));
            }
        }
    }
    let population = |name: &str, size| Population {
        name: name.into(),
        size,
    };
    ActivityDataset {
        meta: ActivityMeta {
            model: "synthetic".into(),
            task: chronocooked_env::Task::parse("Reproduction-v0", &[] as &[&str]).unwrap(),
            seed,
            dt: 1.0,
            populations: vec![
                population("stretched", 3),
                population("clock", 3),
                population("silent", 1),
            ],
        },
        trials,
    }
}

#[test]
fn stretched_trajectories_time_by_speed_and_a_fixed_clock_does_not() {
    for seed in [1, 2, 3] {
        let ds = dataset(seed);
        let stretched = production_speed(&ds, Some("stretched"));
        let clock = production_speed(&ds, Some("clock"));
        assert_eq!(stretched.len(), 2, "one analysis per context");
        for (s, (prior, range)) in stretched.iter().zip(PRIORS) {
            assert_eq!((s.prior, s.gain, s.units), (prior, 0, 3));
            let ts: Vec<u32> = s.conditions.iter().map(|c| c.ts).collect();
            assert_eq!(ts, range.clone().collect::<Vec<_>>());
            // The middle ts of seven is the reference.
            let reference = range.start() + 3;
            assert_eq!(s.reference_ts, reference);
            for c in &s.conditions {
                assert_eq!((c.trials, c.steps), (TRIALS, c.ts as usize));
                let want = f64::from(reference) / f64::from(c.ts);
                let got = c.relative_speed.unwrap();
                assert!((got / want - 1.0).abs() < 0.05, "seed {seed}: {c:?}");
            }
            let index = s.scaling_index.unwrap();
            assert!((index - 1.0).abs() < 0.1, "seed {seed}: {index}");
        }
        for c in &clock {
            let index = c.scaling_index.unwrap();
            assert!(index.abs() < 0.1, "seed {seed}: {index}");
        }
        // The constant unit adds no dimension; alone it gives no analysis.
        assert!(production_speed(&ds, Some("silent")).is_empty());
        assert_eq!(production_speed(&ds, None)[0].units, 6);
        assert!(production_speed(&ds, Some("nonexistent")).is_empty());
    }
}

#[test]
fn the_summary_of_a_reproduction_dataset_is_aligned_to_set() {
    let ds = dataset(4);
    let s = neural_summary(&ds, Some("stretched"), &SummaryOptions::default()).unwrap();
    // Every ts of both priors, the longest (20) as the headline; windows of 2 × ts after Set.
    assert_eq!(s.by_td.len(), 13);
    assert_eq!((s.td, s.window), (20, 40));
    assert_eq!(s.trials, TRIALS);
    assert_eq!(s.production_speed.len(), 2);
    // The first unit rises linearly from Set over ts steps: a ramp at every ts.
    let ramp = s.categories.as_ref().unwrap().counts.ramp;
    assert!(ramp >= 1, "{s:?}");
}
