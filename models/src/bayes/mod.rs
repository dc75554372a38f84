//! The Bayesian observers of temporal reproduction (Ready–Set–Go; Jazayeri & Shadlen 2010,
//! *Nat Neurosci* 13:1020, "Temporal context calibrates interval timing"; J&S below): the
//! generative model, the observers, their seeded simulation and the agent that plays the
//! reproduction task with them ([`ObserverAgent`]). Their analytic predictions, likelihood,
//! fits and the behavioural summaries are `chronocooked_analysis::reproduction`.
//!
//! All times are in environment **steps**.
//!
//! # The generative model (J&S Fig. 3)
//!
//! * A sample interval `ts` is drawn from a **discrete uniform prior** over the
//!   [`Prior`]'s values (≥ 2 distinct positive values, steps).
//! * The measurement is `tm ~ N(ts, (wm·ts)²)` — scalar (Weber) measurement noise, `wm` the
//!   Weber fraction of measurement.
//! * The observer maps the measurement to an estimate `te = f(tm)` ([`Observer`]).
//! * The production is `tp ~ N(te, (wp·|te|)²)` — scalar production noise, `wp` its Weber
//!   fraction. Optionally `tp` is rounded to whole steps ([`Rounding::WholeSteps`],
//!   `round(x) = ⌊x + ½⌋`, i.e. the bin `[n − ½, n + ½)` maps to `n`), as a stepped task
//!   produces.
//!
//! `wm` and `wp` are restricted to `[W_MIN, W_MAX] = [0.01, 1]` everywhere (simulation,
//! predictions and fits); values outside give [`ObserverError::OutOfRange`].
//!
//! # The observers (J&S Methods, Fig. 4)
//!
//! The likelihood of an interval given a measurement is the full scalar density
//! `λ(ts | tm) = p(tm | ts) = exp(−(tm − ts)² / (2 wm² ts²)) / (√(2π) wm ts)`, **including
//! its `1/(wm·ts)` normalisation**, which depends on `ts` and therefore tilts the posterior
//! towards shorter intervals (dropping it, as some public fitting code does, is not J&S's
//! model and biases the estimates up).
//!
//! * **BLS** (Bayes least squares): the posterior mean, `f(tm) = Σₖ sₖ λ(sₖ|tm) / Σₖ
//!   λ(sₖ|tm)` over the prior's values `sₖ` — the estimator minimising the expected squared
//!   error, J&S's model of their subjects.
//! * **MAP**: the posterior mode, `f(tm) = argmaxₖ λ(sₖ|tm)` (the prior is uniform, so the
//!   mode is the support value of largest likelihood; ties go to the shorter value). It always
//!   lies in the prior's support.
//! * **ML**: J&S define the MLE as the `ts` that maximises `λ(ts|tm)` *ignoring the prior*;
//!   their Fig. 4 draws it as a straight line through the origin with slope below 1, not
//!   confined to the prior's range. We therefore maximise over the **continuous positive
//!   line**, not over the prior's support (that would be our MAP). Setting
//!   `∂ ln λ / ∂ts = 0` gives `wm² ts² + tm ts − tm² = 0`, whose root that is positive for
//!   `tm > 0` is `te = c·tm`, `c = (−1 + √(1 + 4wm²)) / (2wm²) = 2 / (1 + √(1 + 4wm²))`
//!   ([`ml_gain`]). The Gaussian measurement model puts probability `Φ(−1/wm)` on `tm ≤ 0`
//!   (< 1e-6 for `wm ≤ 0.2`, 4e-4 at 0.3, 0.16 at 1); there the likelihood on the positive
//!   line has no estimate that continues the line, and we keep the same linear rule
//!   `te = c·tm` (so `E[te|ts] = c·ts` exactly, and a negative estimate produces a negative
//!   `tp` with SD `wp·|te|`). Nothing is clipped, so simulation and likelihood agree.
//!
//! Two documented departures from J&S: (1) J&S's model observers use a *continuous* uniform
//! prior over `[min, max]` (their 11 values were dense relative to `wm·ts`); ours use the
//! task's discrete prior, which is the ideal observer of a task with a few whole-step
//! intervals and converges to J&S's when the spacing is ≪ `wm·ts`. As a consequence our MAP
//! is the ML restricted to the support (a step function), where J&S's MAP is the ML clipped
//! to `[min, max]`. (2) J&S fitted an additive offset in some analyses; we have none.
//!
//! # Submodules
//!
//! [`prior`] (the prior's support), [`observer`] (estimators), [`simulate`] (seeded
//! simulation), [`agent`] (the observer playing the task), [`normal`] (normal densities and
//! interval masses), [`error`] (the typed errors).

pub mod agent;
pub mod error;
pub mod normal;
pub mod observer;
pub mod prior;
pub mod simulate;

pub use agent::ObserverAgent;
pub use error::ObserverError;
pub use observer::{Observer, ml_gain};
pub use prior::Prior;
pub use simulate::simulate;

/// Smallest allowed Weber fraction `wm` or `wp` (dimensionless).
pub const W_MIN: f64 = 0.01;
/// Largest allowed Weber fraction `wm` or `wp` (dimensionless).
pub const W_MAX: f64 = 1.0;

/// One trial: the sample interval `ts` and the produced interval `tp`, both in steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record {
    /// Sample interval (steps, > 0).
    pub ts: f64,
    /// Produced interval (steps; a whole number under [`Rounding::WholeSteps`]).
    pub tp: f64,
}

/// Whether productions are continuous or rounded to whole steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Rounding {
    /// `tp` is the continuous production (density likelihood).
    #[default]
    None,
    /// `tp` is `⌊tp + ½⌋` of the continuous production (likelihood = probability mass of
    /// the bin `[tp − ½, tp + ½)`; predicted variance includes the rounding).
    WholeSteps,
}

/// Rounds a production to whole steps: `⌊x + ½⌋` (the bin `[n − ½, n + ½)` maps to `n`).
pub fn round_step(x: f64) -> f64 {
    (x + 0.5).floor()
}

/// `value` must be finite.
pub fn check_finite(field: &'static str, value: f64) -> Result<f64, ObserverError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ObserverError::NotFinite { field, value })
    }
}

/// `value` must be a finite interval > 0 steps.
pub fn check_interval(field: &'static str, value: f64) -> Result<f64, ObserverError> {
    check_finite(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(ObserverError::NotPositive { field, value })
    }
}

/// `value` must be a Weber fraction in `[W_MIN, W_MAX]`.
pub fn check_weber(field: &'static str, value: f64) -> Result<f64, ObserverError> {
    check_finite(field, value)?;
    if (W_MIN..=W_MAX).contains(&value) {
        Ok(value)
    } else {
        Err(ObserverError::OutOfRange {
            field,
            value,
            min: W_MIN,
            max: W_MAX,
        })
    }
}
