//! Maximum-likelihood fits of `(wm, wp)` for each observer and the choice between them.
//!
//! Each fit maximises [`log_likelihood`](super::log_likelihood) over
//! `(ln wm, ln wp) ∈ [ln 0.01, ln 1]²`: a 9 × 9 log-spaced grid, then Nelder–Mead from the
//! best grid point (projected onto the box), restarted once from its result with a
//! simplex a tenth the size (see `optimise`). The chosen observer is the one of largest
//! maximised log-likelihood; all three have the same two free parameters, so AIC
//! (`2k − 2 ln L`) and BIC (`k ln n − 2 ln L`) rank them identically — both are reported.
//! Ties go to the earlier observer in [`Observer::ALL`] (BLS, MAP, ML).

use super::likelihood::Prepared;
use super::observer::Observer;
use super::optimise::minimise_box;
use super::{ObserverError, Prior, Record, Rounding, W_MAX, W_MIN};

/// Free parameters of every observer model (`wm`, `wp`).
pub const N_PARAMS: usize = 2;

/// One observer's maximum-likelihood fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObserverFit {
    /// The observer.
    pub observer: Observer,
    /// Fitted measurement Weber fraction (in `[0.01, 1]`).
    pub wm: f64,
    /// Fitted production Weber fraction (in `[0.01, 1]`).
    pub wp: f64,
    /// Maximised log-likelihood (natural log).
    pub log_likelihood: f64,
    /// Number of records fitted.
    pub n_trials: usize,
    /// `AIC = 2k − 2 ln L` with `k = 2`.
    pub aic: f64,
    /// `BIC = k ln n − 2 ln L` with `k = 2`.
    pub bic: f64,
    /// Log-likelihood evaluations used by the optimiser.
    pub evaluations: usize,
}

/// The fits of all three observers and the chosen one.
#[derive(Debug, Clone, PartialEq)]
pub struct FitReport {
    /// One fit per observer, in the order of [`Observer::ALL`] (BLS, MAP, ML).
    pub fits: Vec<ObserverFit>,
    /// The observer of largest log-likelihood (= smallest AIC = smallest BIC).
    pub best: Observer,
}

impl FitReport {
    /// The fit of `observer`.
    pub fn fit_of(&self, observer: Observer) -> &ObserverFit {
        let i = Observer::ALL
            .iter()
            .position(|o| *o == observer)
            .unwrap_or(0);
        &self.fits[i]
    }

    /// The chosen observer's fit.
    pub fn best_fit(&self) -> &ObserverFit {
        self.fit_of(self.best)
    }
}

/// Fits `(wm, wp)` of one observer (with the given prior) to `records` by maximum
/// likelihood. Records need `ts > 0` and finite `tp` (whole steps under
/// [`Rounding::WholeSteps`]).
pub fn fit_observer(
    observer: Observer,
    records: &[Record],
    prior: &Prior,
    rounding: Rounding,
) -> Result<ObserverFit, ObserverError> {
    let data = Prepared::new(records, rounding)?;
    Ok(fit_prepared(observer, &data, prior))
}

/// Fits all three observers and chooses the one of largest log-likelihood.
pub fn fit_observers(
    records: &[Record],
    prior: &Prior,
    rounding: Rounding,
) -> Result<FitReport, ObserverError> {
    let data = Prepared::new(records, rounding)?;
    let fits: Vec<ObserverFit> = Observer::ALL
        .iter()
        .map(|&o| fit_prepared(o, &data, prior))
        .collect();
    let mut best = 0;
    for (i, fit) in fits.iter().enumerate() {
        if fit.log_likelihood > fits[best].log_likelihood {
            best = i;
        }
    }
    Ok(FitReport {
        best: fits[best].observer,
        fits,
    })
}

fn fit_prepared(observer: Observer, data: &Prepared, prior: &Prior) -> ObserverFit {
    let (lo, hi) = (W_MIN.ln(), W_MAX.ln());
    let values = prior.values();
    let opt = minimise_box(
        |x| -data.log_likelihood(observer, x[0].exp(), x[1].exp(), values, 1.0),
        [lo, lo],
        [hi, hi],
    );
    let wm = opt.x[0].exp().clamp(W_MIN, W_MAX);
    let wp = opt.x[1].exp().clamp(W_MIN, W_MAX);
    let ll = -opt.value;
    let k = N_PARAMS as f64;
    let n = data.len();
    ObserverFit {
        observer,
        wm,
        wp,
        log_likelihood: ll,
        n_trials: n,
        aic: 2.0 * k - 2.0 * ll,
        bic: k * (n as f64).ln() - 2.0 * ll,
        evaluations: opt.evaluations,
    }
}
