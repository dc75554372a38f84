//! The two views of `chronocooked fingerprint` on the lab's own mechanisms, trained as the
//! reference study trains them with a seed no study uses (50), then seen in another basis:
//!
//! * each timing population mixed by one random orthogonal matrix (the same at TD 6 and
//!   TD 12; read-outs left as they are) — the same dynamics: the dynamics view names every
//!   mechanism as itself and identifies it, its distance moving by at most 5% of the
//!   mechanism's identification limit; the unit view of the mixed oscillator bank (SBF)
//!   changes, a documented fact of single-unit categories, not a failure;
//! * the same activity with its time steps shuffled within each trial (the same states in
//!   another order: no dynamics) — a negative control: not identified in the dynamics view.

use crate::common::{self, run_ok};
use crate::mechanisms::copy_tree;
use chronocooked_analysis::neural::probe::summarize_file;
use chronocooked_models::ActivityDataset;
use chronocooked_present::fingerprint::{Fingerprint, agent_signature, reference_signatures};
use nalgebra::DMatrix;
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::path::{Path, PathBuf};

/// The fixed-interval conditions of the protocol (their recordings carry the neural
/// features).
const RECORDED: [&str; 2] = ["fi-td6", "fi-td12"];

/// Populations that read the timing out (left unmixed, as the fingerprint leaves them out).
const READOUTS: [&str; 3] = ["value", "rpe", "drift"];

/// Trains `model` on the protocol's three conditions (seed 50) and fingerprints it into
/// `<dir>/fp-<model>`.
fn fingerprint(model: &str, dir: &Path) -> PathBuf {
    let d = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let runs = [
        (
            "fi6",
            "FixedInterval-v0",
            vec!["env.td=6", "stop_at_success=none"],
        ),
        (
            "fi12",
            "FixedInterval-v0",
            vec!["env.td=12", "stop_at_success=none"],
        ),
        (
            "bis",
            "Bisection-v0",
            vec!["env.short=4", "env.long=12", "stop_at_success=0.95"],
        ),
    ];
    let mut args = vec!["fingerprint".to_string()];
    for (name, task, sets) in &runs {
        let out = d(&format!("{model}-{name}"));
        let mut train = vec!["train", "--model", model, "--task", task, "--seed", "50"];
        for s in sets {
            train.extend(["--set", s]);
        }
        train.extend(["--out", &out]);
        run_ok(&train);
        args.extend(["--run".to_string(), out]);
    }
    let fp = dir.join(format!("fp-{model}"));
    args.extend([
        "--out".into(),
        fp.to_str().unwrap().into(),
        "--resamples".into(),
        "100".into(),
    ]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    run_ok(&args);
    fp
}

/// A Haar-random orthogonal `[n, n]` matrix (QR of a Gaussian matrix, signs fixed).
fn orthogonal(n: usize, rng: &mut Xoshiro256PlusPlus) -> DMatrix<f64> {
    let g = DMatrix::from_fn(n, n, |_, _| {
        let (u, v): (f64, f64) = (rng.random::<f64>().max(1e-300), rng.random());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    });
    let qr = g.qr();
    let (mut q, r) = (qr.q(), qr.r());
    for j in 0..n {
        if r[(j, j)] < 0.0 {
            q.column_mut(j).neg_mut();
        }
    }
    q
}

/// Copies the fingerprint folder `fp` to `to`, applies `change` to the activity of each
/// recorded condition (the same `change` at both TDs), re-summarises it as the fingerprint
/// did (units correspond, seed 0) and places the changed agent in both views.
fn changed(fp: &Path, to: &Path, change: &mut dyn FnMut(&mut ActivityDataset)) -> Fingerprint {
    copy_tree(fp, to);
    for c in RECORDED {
        let path = to.join(c).join("activity.json");
        let bytes = chronocooked_env::integrity::read_checked(&path).unwrap();
        let mut ds = ActivityDataset::from_json(&bytes).unwrap();
        change(&mut ds);
        let json = serde_json::to_vec(&ds).unwrap();
        chronocooked_env::integrity::write_recorded(&path, &json).unwrap();
        summarize_file(&path, true, 0).unwrap();
    }
    place(to)
}

fn place(fp: &Path) -> Fingerprint {
    let sig = agent_signature(fp, "agent", true, 0).unwrap();
    Fingerprint::place(&sig, &reference_signatures(), 100, 1)
}

/// Mixes every timing population of `ds` by its own matrix from `mixes` (made on first
/// use from `rng`, then reused: the same basis at both TDs).
fn mix(
    ds: &mut ActivityDataset,
    mixes: &mut Vec<(String, DMatrix<f64>)>,
    rng: &mut Xoshiro256PlusPlus,
) {
    let n = ds.meta.n_units();
    for p in ds.meta.populations.clone() {
        if READOUTS.contains(&p.name.as_str()) || p.size < 2 {
            continue;
        }
        let range = ds.meta.range(&p.name).unwrap();
        if !mixes.iter().any(|(name, _)| *name == p.name) {
            mixes.push((p.name.clone(), orthogonal(p.size, rng)));
        }
        let q = &mixes.iter().find(|(name, _)| *name == p.name).unwrap().1;
        for t in &mut ds.trials {
            for row in t.activity.chunks_exact_mut(n) {
                let x: Vec<f64> = row[range.clone()].iter().map(|&v| f64::from(v)).collect();
                for (i, out) in row[range.clone()].iter_mut().enumerate() {
                    *out = (0..x.len()).map(|j| q[(i, j)] * x[j]).sum::<f64>() as f32;
                }
            }
        }
    }
}

/// Shuffles the time steps of every trial of `ds` (whole population vectors; the events
/// stay where they were).
fn shuffle_time(ds: &mut ActivityDataset, rng: &mut Xoshiro256PlusPlus) {
    let n = ds.meta.n_units();
    for t in &mut ds.trials {
        let mut rows: Vec<Vec<f32>> = t.activity.chunks_exact(n).map(<[f32]>::to_vec).collect();
        rows.shuffle(rng);
        t.activity = rows.concat();
    }
}

fn frac(f: &Fingerprint, feature: &str) -> f64 {
    f.units.signature.get(feature).copied().unwrap_or(f64::NAN)
}

#[test]
fn every_mechanism_mixed_by_an_orthogonal_matrix_keeps_its_dynamics_view_verdict() {
    let dir = common::temp_dir("dynamics-view");
    for (k, m) in chronocooked_analysis::mechanisms::MECHANISMS
        .iter()
        .enumerate()
    {
        let fp = fingerprint(m, &dir);
        let plain = place(&fp);
        let dyn_plain = &plain.dynamics;
        assert_eq!(dyn_plain.nearest.as_deref(), Some(*m), "{m}: {dyn_plain:?}");
        assert!(dyn_plain.identified, "{m}: {dyn_plain:?}");
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(k as u64);
        let mut mixes = Vec::new();
        let mixed = changed(&fp, &dir.join(format!("mixed-{m}")), &mut |ds| {
            mix(ds, &mut mixes, &mut rng)
        });
        let dm = &mixed.dynamics;
        assert_eq!(dm.nearest.as_deref(), Some(*m), "{m} mixed: {dm:?}");
        assert!(dm.identified, "{m} mixed: {dm:?}");
        let own = |p: &chronocooked_present::fingerprint::Placement| {
            p.distances
                .iter()
                .find(|d| d.mechanism == *m)
                .unwrap()
                .clone()
        };
        let (a, b) = (own(dyn_plain), own(dm));
        let limit = a.limit.unwrap();
        assert!(
            (a.distance - b.distance).abs() <= 0.05 * limit,
            "{m}: distance {} unmixed, {} mixed, limit {limit}",
            a.distance,
            b.distance
        );
        if *m == "sbf" {
            // The documented fact: an oscillator bank's units are oscillators in its own
            // basis only; mixed, they are mostly "mixed" units.
            let (before, after) = (
                frac(&plain, "frac_oscillating"),
                frac(&mixed, "frac_oscillating"),
            );
            assert!(before > 0.9 && after < before - 0.3, "{before} → {after}");
        }
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(100 + k as u64);
        let shuffled = changed(&fp, &dir.join(format!("shuffled-{m}")), &mut |ds| {
            shuffle_time(ds, &mut rng)
        });
        assert!(
            !shuffled.dynamics.identified,
            "{m} with its time steps shuffled: {:?}",
            shuffled.dynamics
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
