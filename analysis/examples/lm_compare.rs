//! Fit-by-fit comparison of the paper's psychometric least-squares fit
//! (`paper::lsq::fit_paper`, hand-written Levenberg–Marquardt) with the
//! `levenberg-marquardt` crate (MINPACK with scipy's tolerances), once with the analytic
//! Jacobian (`lmder`) and once with `lmdif`'s forward differences (what scipy's
//! `curve_fit` runs), on every curve a paper analysis fits: each bisection run's P(long)
//! and each cell's run-averaged curve in `analysis.json`. With a scipy reference
//! (`scripts/lsq-scipy-reference.py`, same order) it also counts agreement with scipy.
//! The measured outcome is in `paper/lsq.rs`'s module doc.
//!
//! `cargo run --release -p chronocooked-analysis --example lm_compare -- \
//!   results/paper-core/analysis.json [scipy.json]`

use chronocooked_analysis::paper::lsq::{LsqFit, LsqHow, fit_paper, fit_paper_with};
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DVector, Dyn, OMatrix, Owned, U2, Vector2};
use serde_json::Value;

/// One fitted curve: label, anchors and P(long) per probe 1 … L+4 (NaN: no value).
struct Case {
    label: String,
    short: u32,
    long: u32,
    p: Vec<f64>,
}

/// Every curve the paper's bisection analysis fits, in `analysis.json` order (per model
/// and cell: each run, then the averaged curve).
fn cases(analysis: &Value) -> Vec<Case> {
    let num = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
    let mut out = Vec::new();
    for m in analysis["bisection"].as_array().into_iter().flatten() {
        for c in m["cells"].as_array().into_iter().flatten() {
            let (short, long) = (num(&c["short"]) as u32, num(&c["long"]) as u32);
            let curves = c["runs"]
                .as_array()
                .into_iter()
                .flatten()
                .map(|r| (format!("seed{}", r["seed"]), &r["p_long"]))
                .chain([("averaged".to_string(), &c["curve"])]);
            for (what, p) in curves {
                out.push(Case {
                    label: format!(
                        "{} {short}-{long} {what}",
                        m["model"].as_str().unwrap_or("?")
                    ),
                    short,
                    long,
                    p: p.as_array().into_iter().flatten().map(num).collect(),
                });
            }
        }
    }
    out
}

/// `P(d) = 1 / (1 + e^{−(d − x0)/k})` fitted to `(d, y)`; parameters `(x0, k)`. With
/// `forward_differences`, the Jacobian is MINPACK `lmdif`'s (scipy's default: forward
/// differences, step `√ε·|x_j|`) and every evaluation, the Jacobian's included, counts
/// towards the 600 of `maxfev` (past them the residuals are `None`: scipy's `ier` 5).
struct Logistic {
    d: Vec<f64>,
    y: Vec<f64>,
    x: Vector2<f64>,
    forward_differences: bool,
    evaluations: std::cell::Cell<usize>,
}

impl Logistic {
    fn r(&self, x0: f64, k: f64) -> DVector<f64> {
        self.evaluations.set(self.evaluations.get() + 1);
        DVector::from_iterator(
            self.d.len(),
            self.d
                .iter()
                .zip(&self.y)
                .map(|(&t, &y)| sigmoid((t - x0) / k) - y),
        )
    }
}

fn sigmoid(z: f64) -> f64 {
    1.0 / (1.0 + (-z).exp())
}

impl LeastSquaresProblem<f64, Dyn, U2> for Logistic {
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
        if self.forward_differences && self.evaluations.get() >= 600 {
            return None;
        }
        Some(self.r(self.x[0], self.x[1]))
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U2>> {
        let (x0, k) = (self.x[0], self.x[1]);
        let mut j = OMatrix::<f64, Dyn, U2>::zeros(self.d.len());
        if self.forward_differences {
            let eps = f64::EPSILON.sqrt();
            // lmdif reuses the residuals at x (not counted again).
            let base = self.r(x0, k);
            self.evaluations.set(self.evaluations.get() - 1);
            for c in 0..2 {
                let mut h = eps * self.x[c].abs();
                if h == 0.0 {
                    h = eps;
                }
                let mut x = self.x;
                x[c] += h;
                let col = (self.r(x[0], x[1]) - &base) / h;
                j.set_column(c, &col);
            }
            return Some(j);
        }
        for (i, &t) in self.d.iter().enumerate() {
            let s = sigmoid((t - x0) / k);
            let ds = s * (1.0 - s);
            j[(i, 0)] = -ds / k;
            j[(i, 1)] = -ds * (t - x0) / (k * k);
        }
        Some(j)
    }
}

/// The crate's solve from `start`: `(x0, k)` when it terminated successfully (scipy's
/// `ier` 1–4) with finite parameters; also the termination and evaluation count.
fn crate_solve(
    d: &[f64],
    y: &[f64],
    start: (f64, f64),
    forward_differences: bool,
) -> (Option<(f64, f64)>, String) {
    let problem = Logistic {
        d: d.to_vec(),
        y: y.to_vec(),
        x: Vector2::new(start.0, start.1),
        forward_differences,
        evaluations: std::cell::Cell::new(0),
    };
    let lm = LevenbergMarquardt::new()
        .with_ftol(1.49012e-8)
        .with_xtol(1.49012e-8)
        .with_gtol(0.0)
        .with_stepbound(100.0)
        .with_patience(if forward_differences { 1000 } else { 200 });
    let (fitted, report) = lm.minimize(problem);
    let ok = report.termination.was_successful() && fitted.x.iter().all(|v| v.is_finite());
    (
        ok.then_some((fitted.x[0], fitted.x[1])),
        format!(
            "{:?} after {} evaluations",
            report.termination,
            fitted.evaluations.get()
        ),
    )
}

fn how(f: &Option<LsqFit>) -> &'static str {
    match f {
        Some(f) if f.how == LsqHow::Fit => "fit",
        Some(_) => "step fallback",
        None => "failed",
    }
}

/// Agreement of one solver with a reference: same decision, and the largest relative
/// difference of BP and k where both converged.
#[derive(Default)]
struct Tally {
    same: usize,
    worst_bp: f64,
    worst_k: f64,
}

impl Tally {
    fn add(&mut self, a: &Option<LsqFit>, reference: &Option<LsqFit>) {
        if how(a) != how(reference) {
            return;
        }
        self.same += 1;
        if let (Some(a), Some(r)) = (a, reference) {
            self.worst_bp = self.worst_bp.max(((a.bp - r.bp) / r.bp).abs());
            self.worst_k = self.worst_k.max(((a.k - r.k) / r.k).abs());
        }
    }
}

/// scipy's outcome of one curve (from `scripts/lsq-scipy-reference.py`).
fn scipy_fit(v: &Value) -> Option<LsqFit> {
    let how = match v["how"].as_str()? {
        "fit" => LsqHow::Fit,
        "step_fallback" => LsqHow::StepFallback,
        _ => return None,
    };
    let (bp, k) = (v["bp"].as_f64()?, v["k"].as_f64()?);
    let dl = k * 3f64.ln();
    Some(LsqFit {
        bp,
        k,
        dl,
        wf: dl / bp,
        how,
    })
}

fn main() {
    let mut args = std::env::args().skip(1);
    let read = |p: String| -> Value {
        serde_json::from_str(&std::fs::read_to_string(&p).expect("read")).expect("JSON")
    };
    let cases = cases(&read(args.next().expect("ANALYSIS.json")));
    let scipy: Option<Vec<Option<LsqFit>>> = args.next().map(|p| {
        let v = read(p);
        v.as_array()
            .expect("a list")
            .iter()
            .map(scipy_fit)
            .collect()
    });
    let names = ["lsq.rs", "crate lmder", "crate lmdif"];
    let mut vs_lsq: [Tally; 3] = Default::default();
    let mut vs_scipy: [Tally; 3] = Default::default();
    for (i, c) in cases.iter().enumerate() {
        let probes: Vec<f64> = (1..=c.long + 4).map(f64::from).collect();
        let (short, long) = (f64::from(c.short), f64::from(c.long));
        let mut fits = vec![fit_paper(&probes, &c.p, short, long)];
        let mut notes = vec![String::new()];
        for fd in [false, true] {
            let mut note = String::from("not called");
            fits.push(fit_paper_with(&probes, &c.p, short, long, |d, y, start| {
                let (r, n) = crate_solve(d, y, start, fd);
                note = n;
                r
            }));
            notes.push(note);
        }
        let mut line = c.label.clone();
        for (s, (f, note)) in fits.iter().zip(&notes).enumerate() {
            vs_lsq[s].add(f, &fits[0]);
            let shown = f.map_or(String::new(), |f| format!(" bp={:.9} k={:.9}", f.bp, f.k));
            line += &format!("\t{}: {}{shown} {note}", names[s], how(f));
        }
        if let Some(reference) = scipy.as_ref().map(|r| &r[i]) {
            for (s, f) in fits.iter().enumerate() {
                vs_scipy[s].add(f, reference);
            }
            line += &format!("\tscipy: {}", how(reference));
        }
        println!("{line}");
    }
    for (s, name) in names.iter().enumerate() {
        let t = &vs_lsq[s];
        print!(
            "{name}: {} of {} decisions as lsq.rs (converged: BP within {:.1e}, k within {:.1e})",
            t.same,
            cases.len(),
            t.worst_bp,
            t.worst_k
        );
        if scipy.is_some() {
            let t = &vs_scipy[s];
            print!(
                "; {} as scipy (BP within {:.1e}, k within {:.1e})",
                t.same, t.worst_bp, t.worst_k
            );
        }
        println!();
    }
}
