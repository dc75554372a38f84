//! Known-answer comparison of the lab's three hand-written optimisers with well-kept crates.
//!
//! 1. `chronocooked_paper::lsq::levenberg_marquardt` (the paper's logistic least squares)
//!    against the `levenberg-marquardt` crate (MINPACK port) with an analytic Jacobian and
//!    with scipy's forward-difference Jacobian.
//! 2. `chronocooked_analysis::behaviour::peak::fit_gaussian` (Gaussian + baseline fit of a
//!    peak-interval rate curve) against the `levenberg-marquardt` crate.
//! 3. `chronocooked_analysis::reproduction::fit_observer` (9 × 9 grid then Nelder–Mead,
//!    restarted once, in a box) against `argmin`'s Nelder–Mead on the same objective.
//!
//! Every problem is synthetic with a known generating truth (fixed seeds), every solver
//! gets the identical objective and start, and timings are interleaved in one run. See
//! `README.md` for the command and the measured tables.

mod lsq;
mod observer;
mod peak;
mod report;

fn main() {
    println!("# Hand-written optimisers vs well-kept crates (known-answer problems)\n");
    lsq::run();
    lsq::run_project_inputs();
    peak::run();
    observer::run();
}
