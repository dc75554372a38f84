//! The log-likelihood of `(ts, tp)` records under an observer model.
//!
//! `p(tp | ts) = ∫ p(tp | f(tm)) p(tm | ts) dtm`, integrated numerically over the
//! measurement (trapezoid grid, see the module [`super`] "Numerics"; exact support masses
//! for MAP). For continuous productions `p(tp | te)` is the density of `N(te, (wp·te)²)`;
//! for whole-step productions it is the mass of the rounding bin `[tp − ½, tp + ½)`. Each
//! record's likelihood is floored at `1e-300` (log ≈ −690.8) so that a single impossible
//! record makes a model very unlikely without making the log-likelihood `−∞`.

use super::grid::te_distribution;
use super::normal::{interval_mass, pdf};
use super::observer::Observer;
use super::{
    ObserverError, Prior, Record, Rounding, check_finite, check_interval, check_weber, round_step,
};

/// Floor on one record's likelihood.
const LIKELIHOOD_FLOOR: f64 = 1e-300;

/// The total log-likelihood (natural log; densities in 1/steps for continuous `tp`,
/// probabilities for whole-step `tp`) of `records` under `observer` with Weber fractions
/// `wm, wp ∈ [0.01, 1]` and the observer's `prior`. Records need `ts > 0`, finite `tp`
/// (whole steps under [`Rounding::WholeSteps`]); at least one record.
pub fn log_likelihood(
    observer: Observer,
    wm: f64,
    wp: f64,
    records: &[Record],
    prior: &Prior,
    rounding: Rounding,
) -> Result<f64, ObserverError> {
    check_weber("wm", wm)?;
    check_weber("wp", wp)?;
    let data = Prepared::new(records, rounding)?;
    Ok(data.log_likelihood(observer, wm, wp, prior.values(), 1.0))
}

/// Records grouped by `ts`, identical productions merged with a count.
pub(crate) struct Prepared {
    groups: Vec<(f64, Vec<(f64, f64)>)>,
    rounding: Rounding,
    n: usize,
}

impl Prepared {
    /// Validates and groups the records.
    pub(crate) fn new(records: &[Record], rounding: Rounding) -> Result<Self, ObserverError> {
        if records.is_empty() {
            return Err(ObserverError::TooFew {
                field: "records",
                got: 0,
                min: 1,
            });
        }
        let mut sorted = Vec::with_capacity(records.len());
        for r in records {
            check_interval("ts", r.ts)?;
            check_finite("tp", r.tp)?;
            if rounding == Rounding::WholeSteps && round_step(r.tp) != r.tp {
                return Err(ObserverError::NotWholeSteps { value: r.tp });
            }
            sorted.push(*r);
        }
        sorted.sort_by(|a, b| a.ts.total_cmp(&b.ts).then(a.tp.total_cmp(&b.tp)));
        let groups = sorted
            .chunk_by(|a, b| a.ts == b.ts)
            .map(|g| {
                let tps = g
                    .chunk_by(|a, b| a.tp == b.tp)
                    .map(|same| (same[0].tp, same.len() as f64))
                    .collect();
                (g[0].ts, tps)
            })
            .collect();
        Ok(Prepared {
            groups,
            rounding,
            n: records.len(),
        })
    }

    /// Number of records.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// The log-likelihood (unchecked parameters); `refine` divides the grid spacing.
    pub(crate) fn log_likelihood(
        &self,
        observer: Observer,
        wm: f64,
        wp: f64,
        values: &[f64],
        refine: f64,
    ) -> f64 {
        let mut ll = 0.0;
        for (ts, tps) in &self.groups {
            let dist = te_distribution(observer, *ts, wm, wp, values, refine);
            // Drop points that cannot matter, keep (te, weight, production SD).
            let pts: Vec<(f64, f64, f64)> = dist
                .te
                .iter()
                .zip(&dist.weight)
                .filter(|(_, w)| **w > 1e-18)
                .map(|(&t, &w)| (t, w, wp * t.abs()))
                .collect();
            for &(tp, count) in tps {
                let p: f64 = match self.rounding {
                    Rounding::None => pts
                        .iter()
                        .filter(|(_, _, sd)| *sd > 0.0)
                        .map(|&(t, w, sd)| {
                            let z = (tp - t) / sd;
                            if z.abs() < 40.0 { w * pdf(z) / sd } else { 0.0 }
                        })
                        .sum(),
                    Rounding::WholeSteps => pts
                        .iter()
                        .map(|&(t, w, sd)| {
                            if sd > 0.0 {
                                w * interval_mass((tp - 0.5 - t) / sd, (tp + 0.5 - t) / sd)
                            } else if round_step(t) == tp {
                                w
                            } else {
                                0.0
                            }
                        })
                        .sum(),
                };
                ll += count * p.max(LIKELIHOOD_FLOOR).ln();
            }
        }
        ll
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduction::simulate;
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// Halving the grid spacing changes the log-likelihood by < 1e-7 relative at the
    /// corners of the parameter box and in its middle, for both kinds of production; the
    /// exception is the corner (0.01, 0.01), where most records lie beyond the grid's
    /// ±8.5 measurement SDs and their (~1e-20) likelihoods are accurate only to ~1e-3
    /// relative — there the log-likelihood is > 5 000 below the good fits', so a fit is
    /// unaffected.
    #[test]
    fn quadrature_is_converged() {
        let prior = Prior::new(&[18.0, 22.0, 26.0, 30.0, 34.0, 38.0]).unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        for rounding in [Rounding::None, Rounding::WholeSteps] {
            let recs = simulate(Observer::Bls, 0.15, 0.08, &prior, 40, rounding, &mut rng).unwrap();
            let data = Prepared::new(&recs, rounding).unwrap();
            for obs in [Observer::Bls, Observer::Ml] {
                let good = data.log_likelihood(obs, 0.15, 0.08, prior.values(), 1.0);
                let corner = data.log_likelihood(obs, 0.01, 0.01, prior.values(), 1.0);
                assert!(corner < good - 5000.0, "{obs:?}: {corner} vs {good}");
                for (wm, wp) in [
                    (0.01, 1.0),
                    (1.0, 0.01),
                    (1.0, 1.0),
                    (0.15, 0.08),
                    (0.3, 0.02),
                    (0.05, 0.03),
                ] {
                    let a = data.log_likelihood(obs, wm, wp, prior.values(), 1.0);
                    let b = data.log_likelihood(obs, wm, wp, prior.values(), 2.0);
                    assert!(
                        (a - b).abs() <= 1e-7 * a.abs(),
                        "{obs:?} {rounding:?} wm {wm} wp {wp}: {a} vs {b}"
                    );
                }
            }
        }
    }
}
