//! Seeded simulation of the observer models (J&S Fig. 3).

use super::observer::{Estimator, Observer};
use super::{ObserverError, Prior, Record, Rounding, check_weber, round_step};
use rand::Rng;
use rand_distr::StandardNormal;

/// Simulates `trials_per_ts` trials at every prior value (a balanced design; records
/// grouped by `ts` in ascending order): `tm = ts + wm·ts·ε₁`, `te = f(tm)`,
/// `tp = te + wp·|te|·ε₂` with independent standard normals `ε₁, ε₂` drawn from `rng`
/// (in that order, trial by trial), then `tp` rounded to `⌊tp + ½⌋` under
/// [`Rounding::WholeSteps`]. Times in steps; `wm, wp ∈ [0.01, 1]`; `trials_per_ts ≥ 1`.
/// Returns `K × trials_per_ts` records.
pub fn simulate<R: Rng + ?Sized>(
    observer: Observer,
    wm: f64,
    wp: f64,
    prior: &Prior,
    trials_per_ts: usize,
    rounding: Rounding,
    rng: &mut R,
) -> Result<Vec<Record>, ObserverError> {
    check_weber("wm", wm)?;
    check_weber("wp", wp)?;
    if trials_per_ts == 0 {
        return Err(ObserverError::TooFew {
            field: "trials_per_ts",
            got: 0,
            min: 1,
        });
    }
    let est = Estimator::new(observer, wm, prior.values());
    let mut out = Vec::with_capacity(prior.values().len() * trials_per_ts);
    for &ts in prior.values() {
        for _ in 0..trials_per_ts {
            let e1: f64 = rng.sample(StandardNormal);
            let te = est.estimate(ts + wm * ts * e1);
            let e2: f64 = rng.sample(StandardNormal);
            let tp = te + wp * te.abs() * e2;
            let tp = match rounding {
                Rounding::None => tp,
                Rounding::WholeSteps => round_step(tp),
            };
            out.push(Record { ts, tp });
        }
    }
    Ok(out)
}
