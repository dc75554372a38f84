//! Temporal reproduction (Ready–Set–Go): the analytic predictions of the Bayesian observers
//! (`chronocooked_models::bayes`, re-exported here: the generative model, the observers and
//! their simulation), the per-record likelihood, maximum-likelihood fits and the behavioural
//! summaries of Jazayeri & Shadlen (2010, *Nat Neurosci* 13:1020; J&S below).
//!
//! All times are in environment **steps**.
//!
//! # Numerics
//!
//! Integrals over `tm` (predictions and the likelihood of a record) use the trapezoid rule
//! on a uniform grid in `z = (tm − ts)/(wm·ts)`, `|z| ≤ 8.5` (tail mass 2e-17), with
//! Gaussian weights normalised to 1. For integrands that are smooth in `tm` (BLS and ML) the
//! trapezoid rule on the line converges geometrically, like Gauss–Hermite, but unlike a
//! fixed Gauss–Hermite rule it resolves sharp integrands: the spacing is chosen per `ts`
//! from the narrowest feature, `h_z = 0.6·wp·te_lo / (wm·ts·max f′)` clamped to
//! `[0.0025, 0.1]`, where `te_lo` is the smallest estimate within `|z| ≤ 3` (floored at
//! half the shortest prior value) and `max f′` the steepest slope of the estimator there
//! (exact derivative for BLS, `c` for ML). Halving the spacing changes a log-likelihood by
//! < 1e-7 relative (unit-tested over the corners and middle of the parameter box; the
//! exception is a grossly misfit corner such as `wm = wp = 0.01` on data with `wm ≈ 0.15`,
//! where records lie beyond the grid's ±8.5 SDs and their ~1e-20 likelihoods are accurate
//! to ~1e-3 relative — thousands of log-units below the maximum, so fits are unaffected).
//! Normal tail masses use statrs' `erfc` (≈ 1e-10 relative accuracy). MAP needs no quadrature: its estimate is piecewise
//! constant in `tm` with breakpoints that are roots of quadratics, so `P(te = sₖ | ts)` is a
//! sum of exact normal-interval masses.
//!
//! # Submodules
//!
//! [`predict`] (analytic `E[tp|ts]`, `Var[tp|ts]`), [`likelihood`] (the per-record
//! likelihood), [`fit`] (maximum-likelihood fits and model choice), [`summary`] (J&S's
//! behavioural summaries).

pub mod fit;
mod grid;
pub mod likelihood;
mod optimise;
pub mod predict;
pub mod summary;

pub use chronocooked_models::bayes::{
    Observer, ObserverAgent, ObserverError, Prior, Record, Rounding, W_MAX, W_MIN, agent,
    check_finite, check_interval, check_weber, error, ml_gain, normal, observer, prior, round_step,
    simulate,
};
pub use fit::{FitReport, ObserverFit, fit_observer, fit_observers};
pub use likelihood::log_likelihood;
pub use predict::{Prediction, predict, predict_at, predicted_summary};
pub use summary::{Summary, TsMoments, summarize, summary_from_moments};
