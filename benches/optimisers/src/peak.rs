//! Study 2: the peak-interval Gaussian fit (`chronocooked_analysis::behaviour::peak`)
//! against the `levenberg-marquardt` crate on synthetic rate curves.

use crate::report::{Outcome, Solver, TableSpec, Trial, interleaved, print_table};
use chronocooked_analysis::behaviour::peak::fit_gaussian;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DVector, Dyn, OMatrix, Owned, U4, Vector4};
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, Normal};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::cell::Cell;

/// RNG seed of the synthetic curves.
const SEED: u64 = 20_261_204;
/// Target durations `TD` (curves over `t = 0 … 2·TD`).
const TDS: [u32; 4] = [6, 12, 18, 24];
/// Gaussian noise standard deviations added to every point.
const NOISE: [f64; 4] = [0.0, 0.02, 0.05, 0.1];
/// Curves per (TD, noise level).
const PER_CELL: usize = 16;
/// Timing repeats per fit.
const REPEATS: usize = 15;

/// Table names of the solvers (the lab's first).
const SOLVERS: [&str; 2] = ["lab `peak::fit_gaussian`", "crate LM (defaults)"];

/// `a·exp(−(t − μ)²/(2σ²)) + b` with `p = [a, μ, σ, b]`.
fn model(p: &[f64], t: f64) -> f64 {
    let z = (t - p[1]) / p[2];
    p[0] * (-0.5 * z * z).exp() + p[3]
}

/// The common objective: the residual sum of squares over the finite points.
fn rss(rate: &[f64], p: &[f64]) -> f64 {
    rate.iter()
        .enumerate()
        .filter(|(_, y)| y.is_finite())
        .map(|(t, &y)| (y - model(p, t as f64)).powi(2))
        .sum()
}

/// The rate curve as a `levenberg-marquardt` problem; counts residual evaluations.
struct Gaussian<'a> {
    pts: &'a [(f64, f64)],
    x: Vector4<f64>,
    evaluations: Cell<usize>,
}

impl LeastSquaresProblem<f64, Dyn, U4> for Gaussian<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, U4>;
    type ParameterStorage = Owned<f64, U4>;

    fn set_params(&mut self, x: &Vector4<f64>) {
        self.x = *x;
    }

    fn params(&self) -> Vector4<f64> {
        self.x
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.evaluations.set(self.evaluations.get() + 1);
        let p = self.x.as_slice();
        Some(DVector::from_iterator(
            self.pts.len(),
            self.pts.iter().map(|&(t, y)| model(p, t) - y),
        ))
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U4>> {
        let [a, mu, s, _] = [self.x[0], self.x[1], self.x[2], self.x[3]];
        let mut j = OMatrix::<f64, Dyn, U4>::zeros(self.pts.len());
        for (i, &(t, _)) in self.pts.iter().enumerate() {
            let z = (t - mu) / s;
            let e = (-0.5 * z * z).exp();
            j[(i, 0)] = e;
            j[(i, 1)] = a * e * z / s;
            j[(i, 2)] = a * e * z * z / s;
            j[(i, 3)] = 1.0;
        }
        Some(j)
    }
}

/// The crate's fit from the lab's start (`[max − min, argmax, max(span/6, 1), min]`),
/// with the lab's acceptance rules (`a > 0`, peak inside the observed times, spread at
/// most the span; the model depends on `σ²`, so `|σ|` is taken). Default crate settings.
fn crate_fit(rate: &[f64]) -> Outcome {
    let pts: Vec<(f64, f64)> = rate
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .map(|(t, &v)| (t as f64, v))
        .collect();
    if pts.len() < 5 {
        return Outcome::failed(None);
    }
    let (tmax, ymax) =
        pts.iter().copied().fold(
            (0.0, f64::NEG_INFINITY),
            |b, p| if p.1 > b.1 { p } else { b },
        );
    let ymin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    if ymax <= ymin {
        return Outcome::failed(None);
    }
    let (t0, t1) = (pts[0].0, pts[pts.len() - 1].0);
    let span = t1 - t0;
    let problem = Gaussian {
        pts: &pts,
        x: Vector4::new(ymax - ymin, tmax, (span / 6.0).max(1.0), ymin),
        evaluations: Cell::new(0),
    };
    let (problem, report) = LevenbergMarquardt::new().minimize(problem);
    let evaluations = Some(problem.evaluations.get());
    let x = problem.x;
    let p = vec![x[0], x[1], x[2].abs(), x[3]];
    let accepted = report.termination.was_successful()
        && p.iter().all(|v| v.is_finite())
        && p[0] > 0.0
        && p[2] > 0.0
        && p[2] <= span
        && (t0..=t1).contains(&p[1]);
    if !accepted {
        return Outcome::failed(evaluations);
    }
    Outcome {
        objective: rss(rate, &p),
        params: Some(p),
        evaluations,
    }
}

/// The lab's fit (objective: [`rss`]).
fn lab_fit(rate: &[f64]) -> Outcome {
    match fit_gaussian(rate) {
        Some(f) => {
            let p = vec![f.amplitude, f.peak, f.spread, f.baseline];
            Outcome {
                objective: rss(rate, &p),
                params: Some(p),
                evaluations: None,
            }
        }
        None => Outcome::failed(None),
    }
}

/// Synthetic peak-interval curves: `μ = TD·(1 ± 10 %)`, `σ ∈ [0.15, 0.5]·TD`,
/// `a ∈ [0.3, 1]`, `b ∈ [0, 0.2]`, plus Gaussian noise.
pub fn run() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
    let lab = |r: &Vec<f64>| lab_fit(r);
    let krate = |r: &Vec<f64>| crate_fit(r);
    let solvers: [Solver<Vec<f64>>; 2] = [&lab, &krate];
    let mut trials = Vec::new();
    for noise in NOISE {
        for td in TDS {
            for _ in 0..PER_CELL {
                let td = f64::from(td);
                let truth = vec![
                    rng.random_range(0.3..1.0),
                    td * (1.0 + rng.random_range(-0.1..0.1)),
                    td * rng.random_range(0.15..0.5),
                    rng.random_range(0.0..0.2),
                ];
                let normal = Normal::new(0.0, noise).expect("finite noise level");
                let rate: Vec<f64> = (0..=2 * td as u32)
                    .map(|t| model(&truth, f64::from(t)) + normal.sample(&mut rng))
                    .collect();
                let (outcomes, seconds) = interleaved(REPEATS, &solvers, &rate);
                trials.push(Trial {
                    group: format!("noise sd {noise}"),
                    truth,
                    outcomes,
                    seconds,
                });
            }
        }
    }
    println!(
        "## 2. Peak-interval Gaussian fit (`analysis/src/behaviour/peak.rs`) vs `levenberg-marquardt` 0.15.0\n"
    );
    println!(
        "{} synthetic rate curves (seed {SEED}) over t = 0…2·TD, TD ∈ {TDS:?}: \
         r(t) = a·exp(−(t−μ)²/(2σ²)) + b, μ = TD·(1 ± 10 %), σ ∈ [0.15, 0.5]·TD, \
         a ∈ [0.3, 1], b ∈ [0, 0.2], plus N(0, sd²) noise per point. Both solvers start at \
         the lab's start and apply the lab's acceptance rules (a > 0, μ inside the window, \
         σ ≤ span); the crate runs with its defaults (tolerances 30·ε, ≤ 500 residual \
         evaluations + Jacobians). Objective: residual sum of squares (lower/higher: by more than 1e-12 + 1e-6 × the \
         lab's). Within tol: exact \
         data all four parameters within 1e-4; noisy data |Δμ| ≤ 0.1·μ and |Δσ| ≤ 0.25·σ. \
         Time: median of {REPEATS} interleaved repeats.\n",
        trials.len()
    );
    let within = |t: &Trial, p: &[f64]| {
        let err = |i: usize| (p[i] - t.truth[i]).abs();
        if t.group == "noise sd 0" {
            (0..4).all(|i| err(i) <= 1e-4)
        } else {
            err(1) <= 0.1 * t.truth[1] && err(2) <= 0.25 * t.truth[2]
        }
    };
    print_table(
        &trials,
        &TableSpec {
            solvers: &SOLVERS,
            shown: &[("μ", 1), ("σ", 2), ("a", 0), ("b", 3)],
            within: &within,
            time_unit: ("µs", 1e-6),
            objective_gap: (1e-12, 1e-6),
        },
    );
}
