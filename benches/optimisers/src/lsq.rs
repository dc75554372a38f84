//! Study 1: the paper's logistic least squares (`chronocooked_paper::lsq`) against the
//! `levenberg-marquardt` crate, on synthetic bisection curves and on the curves of the
//! committed paper analyses.

use crate::report::{Outcome, Solver, TableSpec, Trial, interleaved, print_table};
use chronocooked_paper::lsq::{LsqFit, LsqHow, fit_paper, fit_paper_with, levenberg_marquardt};
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DVector, Dyn, OMatrix, Owned, U2, Vector2};
use rand::{Rng, SeedableRng};
use rand_distr::{Binomial, Distribution};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::cell::{Cell, RefCell};

/// RNG seed of the synthetic curves.
const SEED: u64 = 20_261_203;
/// Long anchors `L` (short anchor `S = L/2`, probes `1 … L+4`).
const LONGS: [u32; 4] = [8, 12, 16, 24];
/// Row groups: noise (`None` = the exact logistic, `Some(n)` = the mean of `n` Bernoulli
/// draws) and the range of the slope scale `k` (drawn log-uniformly). The last group,
/// steeper than the brief's realistic range, holds the step-like curves on which solvers
/// differ in the committed analyses.
const GROUPS: [(Option<u64>, (f64, f64)); 4] = [
    (None, (0.5, 4.0)),
    (Some(100), (0.5, 4.0)),
    (Some(20), (0.5, 4.0)),
    (Some(20), (0.1, 0.5)),
];
/// Curves per (long anchor, group).
const PER_CELL: usize = 25;
/// Timing repeats per fit.
const REPEATS: usize = 15;
/// scipy's `ftol = xtol` for `curve_fit`.
const SCIPY_TOL: f64 = 1.49012e-8;
/// MINPACK's evaluation budget is `patience · (n + 1)`: 600 for two parameters, as the
/// lab's solver (and scipy's forward-difference `lmdif`).
const PATIENCE: usize = 200;

/// Table names of the solvers (the lab's first).
const SOLVERS: [&str; 3] = [
    "lab `lsq::levenberg_marquardt`",
    "crate LM, analytic Jacobian",
    "crate LM, forward differences",
];

/// One synthetic curve.
struct Curve {
    d: Vec<f64>,
    p: Vec<f64>,
    short: f64,
    long: f64,
}

/// The logistic function.
fn sigmoid(z: f64) -> f64 {
    1.0 / (1.0 + (-z).exp())
}

/// The common objective: the sum of squared residuals at `(x0, k)`.
fn ssr(d: &[f64], p: &[f64], x0: f64, k: f64) -> f64 {
    d.iter()
        .zip(p)
        .map(|(&t, &y)| (sigmoid((t - x0) / k) - y).powi(2))
        .sum()
}

/// The logistic curve as a `levenberg-marquardt` problem; counts residual evaluations
/// (including those of the finite-difference Jacobian).
struct Logistic<'a> {
    d: &'a [f64],
    p: &'a [f64],
    x: Vector2<f64>,
    forward_differences: bool,
    evaluations: Cell<usize>,
    /// The last residuals computed and their parameters (the difference Jacobian reuses
    /// them, as MINPACK's `lmdif` reuses the residuals at the current point).
    last: RefCell<Option<(Vector2<f64>, DVector<f64>)>>,
}

impl Logistic<'_> {
    fn residuals_at(&self, x: &Vector2<f64>) -> DVector<f64> {
        self.evaluations.set(self.evaluations.get() + 1);
        DVector::from_iterator(
            self.d.len(),
            self.d
                .iter()
                .zip(self.p)
                .map(|(&t, &y)| sigmoid((t - x[0]) / x[1]) - y),
        )
    }
}

impl LeastSquaresProblem<f64, Dyn, U2> for Logistic<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, U2>;
    type ParameterStorage = Owned<f64, U2>;

    fn set_params(&mut self, x: &Vector2<f64>) {
        self.x = *x;
    }

    fn params(&self) -> Vector2<f64> {
        self.x
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let r = self.residuals_at(&self.x);
        *self.last.borrow_mut() = Some((self.x, r.clone()));
        Some(r)
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U2>> {
        let (x0, k) = (self.x[0], self.x[1]);
        if !self.forward_differences {
            let mut j = OMatrix::<f64, Dyn, U2>::zeros(self.d.len());
            for (i, &t) in self.d.iter().enumerate() {
                let s = sigmoid((t - x0) / k);
                let ds = s * (1.0 - s);
                j[(i, 0)] = -ds / k;
                j[(i, 1)] = -ds * (t - x0) / (k * k);
            }
            return Some(j);
        }
        // MINPACK `fdjac2` with scipy's default `epsfcn`: h = √ε·|x_j| (√ε when x_j = 0).
        let base = match &*self.last.borrow() {
            Some((x, r)) if *x == self.x => r.clone(),
            _ => self.residuals_at(&self.x),
        };
        let eps = f64::EPSILON.sqrt();
        let mut j = OMatrix::<f64, Dyn, U2>::zeros(self.d.len());
        for c in 0..2 {
            let h = if self.x[c] == 0.0 {
                eps
            } else {
                eps * self.x[c].abs()
            };
            let mut xh = self.x;
            xh[c] += h;
            let rh = self.residuals_at(&xh);
            j.set_column(c, &((rh - &base) / h));
        }
        Some(j)
    }
}

/// The crate's LM with scipy's `curve_fit` settings (`ftol = xtol = 1.49012e-8`,
/// `gtol = 0`, step bound 100, at most 600 residual evaluations); `None` unless MINPACK
/// reports convergence (scipy raises otherwise), plus the evaluations used.
pub fn crate_lm(
    d: &[f64],
    p: &[f64],
    start: (f64, f64),
    forward_differences: bool,
) -> (Option<(f64, f64)>, usize) {
    let problem = Logistic {
        d,
        p,
        x: Vector2::new(start.0, start.1),
        forward_differences,
        evaluations: Cell::new(0),
        last: RefCell::new(None),
    };
    let (problem, report) = LevenbergMarquardt::new()
        .with_ftol(SCIPY_TOL)
        .with_xtol(SCIPY_TOL)
        .with_gtol(0.0)
        .with_stepbound(100.0)
        .with_patience(PATIENCE)
        .minimize(problem);
    let x = problem.x;
    let ok = report.termination.was_successful() && x.iter().all(|v| v.is_finite());
    (ok.then_some((x[0], x[1])), problem.evaluations.get())
}

/// A fit as an [`Outcome`] (objective: [`ssr`] on the curve).
fn outcome(c: &Curve, fit: Option<(f64, f64)>, evaluations: Option<usize>) -> Outcome {
    match fit {
        Some((x0, k)) => Outcome {
            params: Some(vec![x0, k]),
            objective: ssr(&c.d, &c.p, x0, k),
            evaluations,
        },
        None => Outcome::failed(evaluations),
    }
}

/// The start `fit_paper` uses: the arithmetic mean of the anchors, `k = 1`.
fn start(c: &Curve) -> (f64, f64) {
    (0.5 * (c.short + c.long), 1.0)
}

/// The lab's solver.
fn lab(c: &Curve) -> Outcome {
    outcome(c, levenberg_marquardt(&c.d, &c.p, start(c)), None)
}

/// The crate with the analytic Jacobian.
fn crate_analytic(c: &Curve) -> Outcome {
    let (fit, n) = crate_lm(&c.d, &c.p, start(c), false);
    outcome(c, fit, Some(n))
}

/// The crate with the forward-difference Jacobian.
fn crate_differences(c: &Curve) -> Outcome {
    let (fit, n) = crate_lm(&c.d, &c.p, start(c), true);
    outcome(c, fit, Some(n))
}

/// Synthetic bisection curves: `x0 = √(S·L)·(1 ± 15 %)`, `k` log-uniform in each group's range.
pub fn run() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(SEED);
    let solvers: [Solver<Curve>; 3] = [&lab, &crate_analytic, &crate_differences];
    let mut trials = Vec::new();
    for (noise, (k_lo, k_hi)) in GROUPS {
        for long in LONGS {
            for _ in 0..PER_CELL {
                let short = f64::from(long / 2);
                let long = f64::from(long);
                let x0 = (short * long).sqrt() * (1.0 + rng.random_range(-0.15..0.15));
                let k = (rng.random_range(k_lo.ln()..k_hi.ln())).exp();
                let d: Vec<f64> = (1..=long as u32 + 4).map(f64::from).collect();
                let p = d
                    .iter()
                    .map(|&t| {
                        let q = sigmoid((t - x0) / k);
                        match noise {
                            None => q,
                            Some(n) => {
                                let draws = Binomial::new(n, q).expect("probability in [0, 1]");
                                draws.sample(&mut rng) as f64 / n as f64
                            }
                        }
                    })
                    .collect();
                let curve = Curve { d, p, short, long };
                let (outcomes, seconds) = interleaved(REPEATS, &solvers, &curve);
                trials.push(Trial {
                    group: match noise {
                        None => format!("exact, k {k_lo}–{k_hi}"),
                        Some(n) => format!("n = {n}, k {k_lo}–{k_hi}"),
                    },
                    truth: vec![x0, k],
                    outcomes,
                    seconds,
                });
            }
        }
    }
    println!("## 1. Paper psychometric fit (`paper/src/lsq.rs`) vs `levenberg-marquardt` 0.15.0\n");
    println!(
        "{} synthetic curves (seed {SEED}): L ∈ {LONGS:?}, S = L/2, probes 1…L+4, \
         x0 = √(S·L)·(1 ± 15 %), k log-uniform in the row's range; P = the exact logistic or \
         the mean of n Bernoulli draws. Start (AM, 1) as `fit_paper`; crate: ftol = xtol = \
         1.49012e-8, gtol = 0, step bound 100, ≤ 600 residual evaluations (the evaluations column \
         counts residual evaluations, including the forward-difference Jacobian's; \
         analytic Jacobians are not counted). The k 0.1–0.5 rows are steeper than the \
         realistic range on purpose: step-like curves are where the solvers differ on the \
         committed data (1b). \
         Objective: sum of squared residuals (lower/higher: by more than 1e-12 + 1e-6 × the \
         lab's). Within tol: exact data |Δx0|, |Δk| ≤ 1e-4; \
         noisy data |Δx0| ≤ 0.5 steps and |Δk| ≤ 0.5·k. Time: median of {REPEATS} \
         interleaved repeats.\n",
        trials.len()
    );
    let within = |t: &Trial, p: &[f64]| {
        let (dx, dk) = ((p[0] - t.truth[0]).abs(), (p[1] - t.truth[1]).abs());
        if t.group.starts_with("exact") {
            dx <= 1e-4 && dk <= 1e-4
        } else {
            dx <= 0.5 && dk <= 0.5 * t.truth[1]
        }
    };
    print_table(
        &trials,
        &TableSpec {
            solvers: &SOLVERS,
            shown: &[("x0", 0), ("k", 1)],
            within: &within,
            time_unit: ("µs", 1e-6),
            objective_gap: (1e-12, 1e-6),
        },
    );
}

/// A curve of a committed analysis: its anchors, P(long) per probe (NaN = missing) and
/// the committed fit.
struct Committed {
    short: f64,
    long: f64,
    p: Vec<f64>,
    fit: Option<(LsqHow, f64, f64)>,
}

/// The bisection curves (runs and cell averages) of an `analysis.json`.
fn committed_curves(path: &std::path::Path) -> Result<Vec<Committed>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let as_curve = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .map(|a| a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
            .unwrap_or_default()
    };
    let as_fit = |v: &serde_json::Value| -> Option<(LsqHow, f64, f64)> {
        let fit: LsqFit = serde_json::from_value(v.clone()).ok()?;
        Some((fit.how, fit.bp, fit.k))
    };
    let mut out = Vec::new();
    for model in json["bisection"].as_array().into_iter().flatten() {
        for cell in model["cells"].as_array().into_iter().flatten() {
            let short = cell["short"].as_f64().ok_or("cell without short")?;
            let long = cell["long"].as_f64().ok_or("cell without long")?;
            let runs = cell["runs"].as_array().into_iter().flatten();
            for (p, fit) in runs
                .map(|r| (&r["p_long"], &r["fit"]))
                .chain([(&cell["curve"], &cell["fit"])])
            {
                out.push(Committed {
                    short,
                    long,
                    p: as_curve(p),
                    fit: as_fit(fit),
                });
            }
        }
    }
    Ok(out)
}

/// The decision and numbers of a `fit_paper` outcome.
fn decision(f: &Option<LsqFit>) -> Option<(LsqHow, f64, f64)> {
    f.map(|f| (f.how, f.bp, f.k))
}

/// The curves the committed paper analyses fit (`results/paper-core`,
/// `results/paper-switches`), through `fit_paper` with each solver: whether the
/// notebook's decision (fit / step fallback / failed) and the fitted numbers change.
pub fn run_project_inputs() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../results");
    println!("### 1b. The committed paper analyses' curves through `fit_paper_with`\n");
    println!(
        "Every run curve and run-averaged cell curve of `bisection` in the analysis files \
         (curves with ≥ 2 finite points), refitted with the lab's solver (`fit_paper`) and \
         with the crate inside `fit_paper_with` (the notebook's rules unchanged). \
         \"Committed\" = the fit stored in the file.\n"
    );
    println!(
        "| analysis | curves | lab = committed (decision; BP, k within 1e-9) | solver | decision = lab | both fit: BP and k within 1e-4 rel. | both fit: max rel. ΔBP | both fit: max rel. Δk | fits / fallbacks / failed |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for name in ["paper-core", "paper-switches"] {
        let path = root.join(name).join("analysis.json");
        let curves = match committed_curves(&path) {
            Ok(c) => c,
            Err(e) => {
                println!("| {name} | not read: {e} | | | | | | | |");
                continue;
            }
        };
        let curves: Vec<Committed> = curves
            .into_iter()
            .filter(|c| c.p.iter().filter(|v| v.is_finite()).count() >= 2)
            .collect();
        let probes = |c: &Committed| -> Vec<f64> {
            (1..=c.p.len() as u32).map(f64::from).collect::<Vec<f64>>()
        };
        let lab: Vec<Option<(LsqHow, f64, f64)>> = curves
            .iter()
            .map(|c| decision(&fit_paper(&probes(c), &c.p, c.short, c.long)))
            .collect();
        let same =
            |a: &Option<(LsqHow, f64, f64)>, b: &Option<(LsqHow, f64, f64)>, tol: f64| match (a, b)
            {
                (None, None) => true,
                (Some(a), Some(b)) => {
                    a.0 == b.0 && (a.1 - b.1).abs() <= tol && (a.2 - b.2).abs() <= tol
                }
                _ => false,
            };
        let as_committed = curves
            .iter()
            .zip(&lab)
            .filter(|(c, l)| same(&c.fit, l, 1e-9))
            .count();
        let count = |fits: &[Option<(LsqHow, f64, f64)>]| {
            let of = |h: LsqHow| fits.iter().flatten().filter(|f| f.0 == h).count();
            let failed = fits.iter().filter(|f| f.is_none()).count();
            format!(
                "{} / {} / {failed}",
                of(LsqHow::Fit),
                of(LsqHow::StepFallback)
            )
        };
        println!(
            "| {name} | {} | {as_committed} of {} | {} | – | – | – | – | {} |",
            curves.len(),
            curves.len(),
            SOLVERS[0],
            count(&lab)
        );
        for (s, fd) in [(1, false), (2, true)] {
            let other: Vec<Option<(LsqHow, f64, f64)>> = curves
                .iter()
                .map(|c| {
                    let solve = |d: &[f64], y: &[f64], st: (f64, f64)| crate_lm(d, y, st, fd).0;
                    decision(&fit_paper_with(&probes(c), &c.p, c.short, c.long, solve))
                })
                .collect();
            let agree = lab
                .iter()
                .zip(&other)
                .filter(|(a, b)| a.map(|f| f.0) == b.map(|f| f.0))
                .count();
            let (mut dbp, mut dk, mut n_both, mut n_close) = (0.0f64, 0.0f64, 0, 0);
            for (a, b) in lab.iter().zip(&other) {
                if let (Some(a), Some(b)) = (a, b)
                    && a.0 == LsqHow::Fit
                    && b.0 == LsqHow::Fit
                {
                    let (rbp, rk) = (((b.1 - a.1) / a.1).abs(), ((b.2 - a.2) / a.2).abs());
                    dbp = dbp.max(rbp);
                    dk = dk.max(rk);
                    n_both += 1;
                    n_close += usize::from(rbp <= 1e-4 && rk <= 1e-4);
                }
            }
            println!(
                "| {name} | {} | | {} | {agree} of {} | {n_close} of {n_both} | {dbp:.1e} | {dk:.1e} | {} |",
                curves.len(),
                SOLVERS[s],
                curves.len(),
                count(&other)
            );
        }
    }
    println!();
}
