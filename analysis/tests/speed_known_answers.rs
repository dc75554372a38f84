//! Known answers for the KiNeT speed analysis (Remington et al. 2018) on synthetic
//! trajectories whose kinematics are known by construction. The curves are random smooth
//! curves drawn in this file (a ramp along a random direction plus sinusoids orthogonal to
//! it, in 3–7 dimensions, several seeds and several sets of intervals), not curves the
//! implementation was written against:
//!
//! * time-stretched copies `x_i(t) = g(t/ts_i)` → relative speed `ts_ref/ts_i`, scaling
//!   index 1;
//! * a fixed-speed clock `x_i(t) = g(t/S)` truncated at `ts_i` → speed 1, index 0;
//! * partial scaling, speed ∝ `ts^−½` → index ½;
//! * the same with noise added to every state;
//! * initial states and offsets ordered by `ts` → rank correlations ±1;
//! * bad input → typed errors.

use chronocooked_analysis::neural::speed::{
    ConditionTrajectory, ReferenceChoice, SpeedAnalysis, SpeedError, SpeedOptions, kinet_speed,
    spearman,
};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::f64::consts::PI;

/// A random smooth curve `g(u) = a·u·r + Σₘ bₘ sin(ωₘu + φₘ)·vₘ` with `r` a unit vector and
/// every `vₘ` a unit vector orthogonal to `r`, so that progress along `r` is strictly
/// monotone (no loops, a unique nearest point).
struct Curve {
    rate: f64,
    r: Vec<f64>,
    terms: Vec<(f64, f64, f64, Vec<f64>)>,
    /// A unit vector orthogonal to `r` and every `vₘ` (when `dims ≥ 5`).
    free: Option<Vec<f64>>,
}

fn unit(v: Vec<f64>) -> Vec<f64> {
    let n = v.iter().map(|a| a * a).sum::<f64>().sqrt();
    v.into_iter().map(|a| a / n).collect()
}

/// Removes from `v` its components along each of `basis` (orthonormal), then normalises.
fn orthogonalise(mut v: Vec<f64>, basis: &[Vec<f64>]) -> Vec<f64> {
    for b in basis {
        let d: f64 = v.iter().zip(b).map(|(p, q)| p * q).sum();
        v.iter_mut().zip(b).for_each(|(p, q)| *p -= d * q);
    }
    unit(v)
}

impl Curve {
    fn random(rng: &mut Xoshiro256PlusPlus, dims: usize) -> Self {
        let gauss = |rng: &mut Xoshiro256PlusPlus| -> Vec<f64> {
            (0..dims).map(|_| rng.sample(StandardNormal)).collect()
        };
        let r = unit(gauss(rng));
        let mut basis = vec![r.clone()];
        let mut terms = Vec::new();
        for _ in 0..3 {
            let v = orthogonalise(gauss(rng), &basis[..1]);
            if dims >= 5 {
                basis.push(orthogonalise(v.clone(), &basis));
            }
            terms.push((
                rng.random_range(0.2..0.6),
                rng.random_range(2.0..7.0),
                rng.random_range(0.0..2.0 * PI),
                v,
            ));
        }
        let free = (dims >= 5).then(|| orthogonalise(gauss(rng), &basis));
        Curve {
            rate: rng.random_range(1.5..2.5),
            r,
            terms,
            free,
        }
    }

    fn at(&self, u: f64) -> Vec<f64> {
        let mut x: Vec<f64> = self.r.iter().map(|a| self.rate * u * a).collect();
        for (b, w, phi, v) in &self.terms {
            let s = b * (w * u + phi).sin();
            x.iter_mut().zip(v).for_each(|(p, q)| *p += s * q);
        }
        x
    }
}

/// The condition with states `x(t) = position(t)` for `t = 0..=ts` (steps), plus noise.
fn condition(
    ts: f64,
    dims: usize,
    noise: f64,
    rng: &mut Xoshiro256PlusPlus,
    position: impl Fn(f64) -> Vec<f64>,
) -> ConditionTrajectory {
    let time = ts as usize + 1;
    let mut states = Vec::with_capacity(time * dims);
    for t in 0..time {
        for v in position(t as f64) {
            let e: f64 = rng.sample(StandardNormal);
            states.push(v + noise * e);
        }
    }
    ConditionTrajectory {
        ts,
        time,
        dims,
        states,
    }
}

/// Interval sets (steps) the cases cycle through.
const TS_SETS: [&[f64]; 4] = [
    &[24.0, 30.0, 36.0, 44.0, 52.0],
    &[20.0, 26.0, 31.0, 37.0, 45.0, 55.0],
    &[30.0, 34.0, 40.0, 47.0],
    &[18.0, 25.0, 33.0, 41.0, 50.0],
];

/// The expected speed (relative to the reference's) for every condition and the analysis.
fn run(
    seed: u64,
    noise: f64,
    speed_exponent: f64,
    stretched: bool,
) -> (SpeedAnalysis, Vec<f64>, Vec<f64>) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let dims = 3 + (seed as usize % 5);
    let curve = Curve::random(&mut rng, dims);
    let ts_set = TS_SETS[seed as usize % TS_SETS.len()];
    let ts_ref = ts_set[ts_set.len() / 2];
    // Common clock scale for the fixed/partial cases (steps per unit of u).
    let scale = 40.0;
    let mut conds = Vec::new();
    let mut expected = Vec::new();
    for &ts in ts_set {
        let c = if stretched {
            expected.push(ts_ref / ts);
            condition(ts, dims, noise, &mut rng, |t| curve.at(t / ts))
        } else {
            // Speed ∝ ts^−α relative to the reference: u = t·(ts/ts_ref)^−α / scale.
            let v = (ts / ts_ref).powf(-speed_exponent);
            expected.push(v);
            condition(ts, dims, noise, &mut rng, |t| curve.at(t * v / scale))
        };
        conds.push(c);
    }
    let analysis = kinet_speed(&conds, SpeedOptions::default()).unwrap();
    (analysis, expected, ts_set.to_vec())
}

fn check(
    label: &str,
    a: &SpeedAnalysis,
    expected: &[f64],
    speed_tol: f64,
    index: f64,
    index_tol: f64,
) {
    for (k, e) in a.conditions.iter().zip(expected) {
        let s = k.relative_speed.unwrap_or(f64::NAN);
        assert!(
            (s / e - 1.0).abs() < speed_tol,
            "{label}: ts {} speed {s} expected {e} ({} interior points)",
            k.ts,
            k.n_used
        );
    }
    let got = a.scaling_index.unwrap();
    eprintln!("{label}: scaling index {got:.4} (expected {index})");
    assert!(
        (got - index).abs() < index_tol,
        "{label}: index {got} expected {index}"
    );
}

#[test]
fn time_stretched_trajectories_scale_fully() {
    for seed in 0..6 {
        let (a, expected, ts) = run(seed, 0.0, 1.0, true);
        check(
            &format!("stretched seed {seed}"),
            &a,
            &expected,
            0.02,
            1.0,
            0.05,
        );
        // The reference is the middle interval; its own matches are exact.
        let r = &a.conditions[a.reference];
        assert_eq!(r.ts, ts[ts.len() / 2]);
        assert!(
            r.matches
                .iter()
                .all(|m| m.time == m.t_ref && m.distance == 0.0)
        );
        // Identical initial states: the initial-condition order is undefined.
        assert_eq!(a.initial_order, None);
    }
}

#[test]
fn fixed_speed_clock_does_not_scale() {
    for seed in 10..16 {
        let (a, expected, _) = run(seed, 0.0, 0.0, false);
        check(
            &format!("fixed seed {seed}"),
            &a,
            &expected,
            0.02,
            0.0,
            0.05,
        );
        // Shorter conditions than the reference run out of states: late reference times
        // hit their boundary and are excluded.
        let shortest = &a.conditions[0];
        assert!(shortest.n_used < a.conditions[a.reference].matches.len() - 2);
    }
}

#[test]
fn partial_scaling_gives_half() {
    for seed in 20..26 {
        let (a, expected, _) = run(seed, 0.0, 0.5, false);
        check(
            &format!("partial seed {seed}"),
            &a,
            &expected,
            0.03,
            0.5,
            0.05,
        );
    }
}

#[test]
fn noisy_variants_keep_their_index() {
    // Independent noise of SD 0.01 on every state entry (the curves move ≈ 0.04–0.12 per
    // step). Over 40 random curves per kind the index error has SD ≤ 0.012 at this noise
    // (≈ 0.015–0.026 at SD 0.02), so ±0.05 is a ≥ 4 SD margin.
    for seed in 30..36 {
        let (a, e, _) = run(seed, 0.01, 1.0, true);
        check(
            &format!("noisy stretched seed {seed}"),
            &a,
            &e,
            0.05,
            1.0,
            0.05,
        );
        let (a, e, _) = run(seed + 10, 0.01, 0.0, false);
        check(
            &format!("noisy fixed seed {}", seed + 10),
            &a,
            &e,
            0.05,
            0.0,
            0.05,
        );
        let (a, e, _) = run(seed + 20, 0.01, 0.5, false);
        check(
            &format!("noisy partial seed {}", seed + 20),
            &a,
            &e,
            0.05,
            0.5,
            0.05,
        );
    }
}

/// Conditions `x_i(t) = g(t/ts_i) + δ_i·e` with `e` orthogonal to the whole curve, so the
/// matched phase is exact, the distance is `|δ_i|` and the initial states differ by `δ_i`.
fn offset_conditions(seed: u64, ts_set: &[f64], deltas: &[f64]) -> Vec<ConditionTrajectory> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let dims = 6;
    let curve = Curve::random(&mut rng, dims);
    let e = curve.free.clone().unwrap();
    ts_set
        .iter()
        .zip(deltas)
        .map(|(&ts, &delta)| {
            condition(ts, dims, 0.0, &mut rng, |t| {
                let mut x = curve.at(t / ts);
                x.iter_mut().zip(&e).for_each(|(p, q)| *p += delta * q);
                x
            })
        })
        .collect()
}

#[test]
fn initial_states_and_offsets_ordered_by_ts() {
    // Unsorted input; the middle ts (31) is at index 2.
    let ts_set = [40.0, 22.0, 31.0, 55.0, 27.0];
    // Both orders are oriented by the extremes (the axis runs from the shortest to the
    // longest condition; the signed distance is negative on the shortest's side), so
    // offsets growing or shrinking with ts are both perfectly ordered (+1); a permuted
    // assignment is not. Offsets by ts (22, 27, 31, 40, 55):
    //   increasing  −0.3, −0.2, 0, 0.1, 0.4
    //   decreasing   0.3,  0.2, 0, −0.1, −0.4
    //   permuted    −0.3,  0.2, 0, −0.1, 0.4 → projections (δ − δ_S)/(δ_L − δ_S) have ranks
    //   1, 4, 3, 2, 5 against ts ranks 1…5: Σd² = 8, ρ = 1 − 6·8/(5·24) = 0.6; the signed
    //   distances are ±|δ| by side, i.e. δ itself here, with the same ranks: ρ = 0.6.
    let by_ts = |v: [f64; 5]| -> Vec<f64> {
        // ts_set order → value for that ts.
        let order = [22.0, 27.0, 31.0, 40.0, 55.0];
        ts_set
            .iter()
            .map(|t| v[order.iter().position(|o| o == t).unwrap()])
            .collect()
    };
    let cases = [
        (50u64, by_ts([-0.3, -0.2, 0.0, 0.1, 0.4]), 1.0),
        (51, by_ts([0.3, 0.2, 0.0, -0.1, -0.4]), 1.0),
        (52, by_ts([-0.3, 0.2, 0.0, -0.1, 0.4]), 0.6),
    ];
    for (seed, deltas, rho) in cases {
        let conds = offset_conditions(seed, &ts_set, &deltas);
        let a = kinet_speed(&conds, SpeedOptions::default()).unwrap();
        assert_eq!(a.reference, 2, "middle ts is 31 at input index 2");
        let io = a.initial_order.unwrap();
        let dor = a.distance_order.unwrap();
        assert!(
            (io - rho).abs() < 1e-12 && (dor - rho).abs() < 1e-12,
            "seed {seed}: {io} {dor}"
        );
        let (d_short, d_long) = (deltas[1], deltas[3]);
        for ((k, &ts), &delta) in a.conditions.iter().zip(&ts_set).zip(&deltas) {
            // Offsets orthogonal to the curve: |distance| = |δ|, sign by the nearer extreme
            // direction (direction of x_ref − x_i is −sign(δ)·e), speed unchanged.
            let side = if delta == 0.0 {
                0.0
            } else if (delta > 0.0) == (d_short > 0.0) {
                -1.0
            } else {
                1.0
            };
            let d = k.mean_signed_distance.unwrap();
            assert!(
                (d - side * delta.abs()).abs() < 1e-3,
                "seed {seed} ts {ts}: {d} vs {delta}"
            );
            let s = k.relative_speed.unwrap();
            assert!((s * ts / 31.0 - 1.0).abs() < 0.02, "ts {ts}: speed {s}");
        }
        // Projection on the shortest→longest axis: 0 and 1 at the extremes.
        let p: Vec<f64> = a
            .conditions
            .iter()
            .map(|k| k.initial_projection.unwrap())
            .collect();
        assert!(p[1].abs() < 1e-9 && (p[3] - 1.0).abs() < 1e-9, "{p:?}");
        let expect_mid = (deltas[2] - d_short) / (d_long - d_short);
        assert!((p[2] - expect_mid).abs() < 1e-9);
    }
    // An explicit reference is honoured.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(60);
    let curve = Curve::random(&mut rng, 4);
    let conds: Vec<_> = [20.0, 30.0, 40.0]
        .iter()
        .map(|&ts| condition(ts, 4, 0.0, &mut rng, |t| curve.at(t / ts)))
        .collect();
    let a = kinet_speed(
        &conds,
        SpeedOptions {
            reference: ReferenceChoice::Condition(0),
            ..SpeedOptions::default()
        },
    )
    .unwrap();
    assert_eq!(a.reference, 0);
    let s = a.conditions[2].relative_speed.unwrap();
    assert!((s - 0.5).abs() < 0.01, "{s}");
}

#[test]
fn spearman_by_hand() {
    assert_eq!(
        spearman(&[1.0, 2.0, 3.0, 4.0], &[10.0, 20.0, 15.0, 40.0]),
        Some(0.8)
    );
    assert_eq!(spearman(&[1.0, 2.0], &[2.0, 1.0]), Some(-1.0));
    assert_eq!(spearman(&[1.0], &[2.0]), None);
}

#[test]
fn bad_input_gives_typed_errors() {
    let good = |ts: f64| ConditionTrajectory {
        ts,
        time: 6,
        dims: 2,
        states: (0..12).map(|i| i as f64 * ts).collect(),
    };
    let e = |c: Vec<ConditionTrajectory>| kinet_speed(&c, SpeedOptions::default()).unwrap_err();
    assert_eq!(
        e(vec![good(1.0)]),
        SpeedError::TooFewConditions { got: 1, min: 2 }
    );
    let mut bad = good(2.0);
    bad.dims = 3;
    bad.states = vec![0.0; 18];
    assert_eq!(
        e(vec![good(1.0), bad]),
        SpeedError::Dims {
            index: 1,
            dims: 3,
            expected: 2
        }
    );
    let mut bad = good(2.0);
    bad.states.pop();
    assert_eq!(
        e(vec![good(1.0), bad]),
        SpeedError::Shape {
            index: 1,
            len: 11,
            expected: 12
        }
    );
    // The default edge margin (1) needs 2·1 + 3 = 5 steps.
    let mut bad = good(2.0);
    bad.time = 4;
    bad.states.truncate(8);
    assert_eq!(
        e(vec![good(1.0), bad]),
        SpeedError::TooShort {
            index: 1,
            time: 4,
            min: 5
        }
    );
    let mut bad = good(2.0);
    bad.states[5] = f64::NAN;
    assert_eq!(
        e(vec![good(1.0), bad]),
        SpeedError::NotFinite {
            index: 1,
            time: 2,
            dim: 1
        }
    );
    assert!(matches!(
        e(vec![good(1.0), good(0.0)]),
        SpeedError::BadTs { index: 1, .. }
    ));
    assert!(matches!(
        e(vec![good(1.0), good(f64::NAN)]),
        SpeedError::BadTs { index: 1, .. }
    ));
    let err = kinet_speed(
        &[good(1.0), good(2.0)],
        SpeedOptions {
            reference: ReferenceChoice::Condition(5),
            ..SpeedOptions::default()
        },
    )
    .unwrap_err();
    assert_eq!(err, SpeedError::ReferenceOutOfRange { index: 5, n: 2 });
}
