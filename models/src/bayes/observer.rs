//! The three observers' estimators `te = f(tm)` (J&S Fig. 4) and the exact distribution of
//! the MAP estimate.
//!
//! All use the scalar likelihood `λ(s | tm) ∝ exp(−(tm − s)² / (2 wm² s²)) / s` (the
//! `1/(wm·s)` normalisation kept; the constant `1/(√(2π) wm)` cancels in every ratio and
//! argmax). See the module [`super`] for the definitions and their sources.

use super::normal::interval_mass;
use super::{ObserverError, Prior, check_finite, check_weber};

/// An observer model: how a measurement `tm` (steps) becomes an estimate `te` (steps).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Observer {
    /// Bayes least squares: the posterior mean over the prior's values.
    Bls,
    /// Maximum a posteriori: the prior value of largest likelihood (uniform prior).
    Map,
    /// Maximum likelihood over the continuous positive line, ignoring the prior:
    /// `te = c·tm` with `c =` [`ml_gain`]`(wm)`.
    Ml,
}

impl Observer {
    /// The three observers, in the order fits report them: BLS, MAP, ML.
    pub const ALL: [Observer; 3] = [Observer::Bls, Observer::Map, Observer::Ml];

    /// Short name: `"BLS"`, `"MAP"` or `"ML"`.
    pub fn name(self) -> &'static str {
        match self {
            Observer::Bls => "BLS",
            Observer::Map => "MAP",
            Observer::Ml => "ML",
        }
    }

    /// The estimate `te = f(tm)` (steps) of a measurement `tm` (steps, any finite value)
    /// by an observer with measurement Weber fraction `wm ∈ [0.01, 1]` and the given prior.
    pub fn estimate(self, tm: f64, wm: f64, prior: &Prior) -> Result<f64, ObserverError> {
        check_finite("tm", tm)?;
        check_weber("wm", wm)?;
        Ok(Estimator::new(self, wm, prior.values()).estimate(tm))
    }
}

/// The ML gain `c = (−1 + √(1 + 4wm²)) / (2wm²)`: the unconstrained maximiser of the
/// scalar likelihood is `te = c·tm` (dimensionless, `c < 1`; `c ≈ 1 − wm²` for small
/// `wm`). Computed in the cancellation-free form `2 / (1 + √(1 + 4wm²))`.
pub fn ml_gain(wm: f64) -> Result<f64, ObserverError> {
    check_weber("wm", wm)?;
    Ok(gain(wm))
}

/// [`ml_gain`] without the range check.
pub fn gain(wm: f64) -> f64 {
    2.0 / (1.0 + (1.0 + 4.0 * wm * wm).sqrt())
}

/// An observer's estimator with its per-`wm` constants precomputed.
pub struct Estimator<'a> {
    observer: Observer,
    wm: f64,
    values: &'a [f64],
    ln_s: Vec<f64>,
}

impl<'a> Estimator<'a> {
    /// The estimator of `observer` at `wm` over the prior's values (unchecked).
    pub fn new(observer: Observer, wm: f64, values: &'a [f64]) -> Self {
        Estimator {
            observer,
            wm,
            values,
            ln_s: values.iter().map(|s| s.ln()).collect(),
        }
    }

    /// `ln λ(sₖ | tm)` up to a constant.
    fn log_lik(&self, k: usize, tm: f64) -> f64 {
        let s = self.values[k];
        let z = (tm - s) / (self.wm * s);
        -self.ln_s[k] - 0.5 * z * z
    }

    /// `te = f(tm)` (steps).
    pub fn estimate(&self, tm: f64) -> f64 {
        match self.observer {
            Observer::Bls => self.bls(tm).0,
            Observer::Map => self.values[self.map_index(tm)],
            Observer::Ml => gain(self.wm) * tm,
        }
    }

    /// The BLS estimate and its exact derivative `(f(tm), f′(tm))`:
    /// `f′ = Cov_post(s, ∂ ln λ/∂tm)` with `∂ ln λ(s|tm)/∂tm = (s − tm)/(wm² s²)`.
    pub fn bls(&self, tm: f64) -> (f64, f64) {
        let k_max = (0..self.values.len())
            .map(|k| self.log_lik(k, tm))
            .fold(f64::NEG_INFINITY, f64::max);
        let (mut w_sum, mut s_sum, mut g_sum, mut sg_sum) = (0.0, 0.0, 0.0, 0.0);
        for (k, &s) in self.values.iter().enumerate() {
            let w = (self.log_lik(k, tm) - k_max).exp();
            let g = (s - tm) / (self.wm * self.wm * s * s);
            w_sum += w;
            s_sum += w * s;
            g_sum += w * g;
            sg_sum += w * s * g;
        }
        let f = s_sum / w_sum;
        (f, sg_sum / w_sum - f * g_sum / w_sum)
    }

    /// Index of the MAP estimate: the prior value of largest likelihood (first on ties).
    pub fn map_index(&self, tm: f64) -> usize {
        let mut best = 0;
        let mut best_l = self.log_lik(0, tm);
        for k in 1..self.values.len() {
            let l = self.log_lik(k, tm);
            if l > best_l {
                best = k;
                best_l = l;
            }
        }
        best
    }

    /// `P(te = sₖ | ts)` for the MAP observer, exactly: the winner changes only where two
    /// log-likelihoods cross; `ln λ(s_k|tm) − ln λ(s_j|tm)` (`s_j < s_k`) is the quadratic
    /// `A tm² + B tm + C` with `A = (1/s_j² − 1/s_k²)/(2wm²) > 0`,
    /// `B = −(1/s_j − 1/s_k)/wm²`, `C = −ln(s_k/s_j) < 0`, so it has one negative and one
    /// positive root. Between consecutive roots the winner is constant; each interval
    /// contributes its normal mass under `tm ~ N(ts, (wm·ts)²)`.
    pub fn map_masses(&self, ts: f64) -> Vec<f64> {
        let (v, wm2) = (self.values, self.wm * self.wm);
        let mut roots = Vec::with_capacity(v.len() * v.len());
        for j in 0..v.len() {
            for k in j + 1..v.len() {
                let a = (1.0 / (v[j] * v[j]) - 1.0 / (v[k] * v[k])) / (2.0 * wm2);
                let b = -(1.0 / v[j] - 1.0 / v[k]) / wm2;
                let c = -(v[k] / v[j]).ln();
                let disc = b * b - 4.0 * a * c;
                // b < 0, so q = (|b| + √disc)/2 > 0 without cancellation.
                let q = -0.5 * (b - disc.sqrt());
                roots.push(q / a);
                roots.push(c / q);
            }
        }
        roots.retain(|r| r.is_finite());
        roots.sort_by(f64::total_cmp);
        roots.dedup();
        let sigma = self.wm * ts;
        let mut masses = vec![0.0; v.len()];
        let mut lo = f64::NEG_INFINITY;
        for i in 0..=roots.len() {
            let hi = roots.get(i).copied().unwrap_or(f64::INFINITY);
            let rep = match (lo.is_finite(), hi.is_finite()) {
                (true, true) => 0.5 * (lo + hi),
                (false, true) => hi - 1.0 - hi.abs(),
                (true, false) => lo + 1.0 + lo.abs(),
                (false, false) => ts,
            };
            let mass = interval_mass((lo - ts) / sigma, (hi - ts) / sigma);
            masses[self.map_index(rep)] += mass;
            lo = hi;
        }
        masses
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bls_derivative_matches_finite_difference() {
        let values = [10.0, 12.0, 15.0, 19.0];
        let e = Estimator::new(Observer::Bls, 0.12, &values);
        for tm in [6.0, 11.0, 13.7, 18.0, 25.0] {
            let h = 1e-5;
            let fd = (e.bls(tm + h).0 - e.bls(tm - h).0) / (2.0 * h);
            assert!(
                (e.bls(tm).1 - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                "tm {tm}"
            );
        }
    }

    #[test]
    fn map_masses_sum_to_one_and_match_brute_force() {
        let values = [8.0, 11.0, 13.0, 20.0, 21.0];
        let (wm, ts) = (0.2, 13.0);
        let e = Estimator::new(Observer::Map, wm, &values);
        let m = e.map_masses(ts);
        assert!((m.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        // Brute force: midpoint rule over tm on a fine grid (error ≲ dz·φ per breakpoint).
        let mut brute = [0.0; 5];
        let (n, span) = (1_000_000, 12.0);
        let dz = 2.0 * span / n as f64;
        for i in 0..n {
            let z = -span + (i as f64 + 0.5) * dz;
            brute[e.map_index(ts + wm * ts * z)] += dz * super::super::normal::pdf(z);
        }
        for k in 0..5 {
            assert!(
                (m[k] - brute[k]).abs() < 2e-5,
                "k {k}: {} vs {}",
                m[k],
                brute[k]
            );
        }
    }
}
