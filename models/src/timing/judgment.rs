//! Bisection judgments: at the end of the timed interval each timing model compares its
//! own timing state with its memories of the two anchors and says "short" or "long".
//!
//! The comparison is the model's, re-derived from its literature; in every case the
//! criterion sits at the geometric mean of the remembered anchors, the similarity rule
//! of scalar expectancy theory (Gibbon 1981; Allan & Gibbon 1991: respond "long" when
//! `t/S ≥ L/t`, i.e. `t ≥ √(S·L)`):
//!
//! * drift-diffusion — two accumulators run during the interval with the drifts learned for
//!   the short and the long anchor (`z/S`, `z/L`, each from its own rewarded trials); the
//!   ratios `t/S` and `t/L` are read as `x_S/z` and `x_L/z`, so "long" iff
//!   `ln(x_S/z) + ln(x_L/z) ≥ 0` (Simen et al. 2011's timer, two drifts). Diffusion noise
//!   in both accumulators gives the scalar variability of the judgment.
//! * striatal beat frequency — a criterion pattern is stored at `√(T_S·T_L)` from one
//!   sample of each anchor memory (memory noise, Matell & Meck 2004); "long" iff its
//!   coincidence has been passed during the interval (its detector envelope peaked).
//! * time cells — the population's elapsed-time estimate (centre of mass of the active
//!   cells' preferred times) is compared with the mean log estimate of each anchor's
//!   rewarded trials ([`CategoryMemory`]); clock-speed noise, when set, varies it.
//!
//! Probes far shorter than the short anchor are judged "short" by every rule (the
//! comparison is with a criterion, not a similarity to each anchor), so the psychometric
//! curves are monotone up to the judgment noise.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Rewarded durations kept per category.
pub const CATEGORY_MEMORY: usize = 20;

/// Choice slot of the short anchor (short counter).
pub const SHORT: u8 = 0;
/// Choice slot of the long anchor (long counter).
pub const LONG: u8 = 1;

/// The subjective log durations of the rewarded short and long trials (last
/// [`CATEGORY_MEMORY`] each).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct CategoryMemory {
    /// Stored `ln t̂` per slot ([`SHORT`], [`LONG`]).
    pub log_times: BTreeMap<u8, Vec<f64>>,
}

impl CategoryMemory {
    /// Stores `log_t` (a subjective `ln` duration) as a member of category `slot`.
    pub fn store(&mut self, slot: u8, log_t: f64) {
        if !log_t.is_finite() {
            return;
        }
        let m = self.log_times.entry(slot).or_default();
        if m.len() == CATEGORY_MEMORY {
            m.remove(0);
        }
        m.push(log_t);
    }

    /// The criterion: the midpoint of the two categories' mean log durations (their
    /// geometric mean); `None` until both are stored.
    pub fn criterion(&self) -> Option<f64> {
        let mean = |slot: u8| {
            let m = self.log_times.get(&slot).filter(|m| !m.is_empty())?;
            Some(m.iter().sum::<f64>() / m.len() as f64)
        };
        Some(0.5 * (mean(SHORT)? + mean(LONG)?))
    }

    /// "Long" (`true`) iff `log_t` reaches the criterion; `None` without a criterion.
    pub fn judge(&self, log_t: f64) -> Option<bool> {
        self.criterion().map(|c| log_t >= c)
    }
}

/// Drift-diffusion ratio rule: "long" iff `ln(x_S/z) + ln(x_L/z) ≥ 0` for the short- and
/// long-anchor accumulators' values `x_s`, `x_l` (a non-positive value is "short").
pub fn ddm_ratio_rule(x_s: f64, x_l: f64, z: f64) -> bool {
    x_s > 0.0 && x_l > 0.0 && (x_s / z).ln() + (x_l / z).ln() >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn criterion_is_the_geometric_mean() {
        let mut m = CategoryMemory::default();
        assert_eq!(m.judge(1.0), None);
        m.store(SHORT, 4f64.ln());
        assert_eq!(m.judge(1.0), None);
        m.store(LONG, 16f64.ln());
        assert!((m.criterion().unwrap() - 8f64.ln()).abs() < 1e-12);
        assert_eq!(m.judge(7.9f64.ln()), Some(false));
        assert_eq!(m.judge(8f64.ln()), Some(true));
        assert_eq!(m.judge(0.5f64.ln()), Some(false));
    }

    #[test]
    fn memory_keeps_the_last_entries() {
        let mut m = CategoryMemory::default();
        for i in 0..(CATEGORY_MEMORY + 5) {
            m.store(SHORT, i as f64);
        }
        let s = &m.log_times[&SHORT];
        assert_eq!(s.len(), CATEGORY_MEMORY);
        assert_eq!(s[0], 5.0);
        m.store(SHORT, f64::NAN);
        assert_eq!(m.log_times[&SHORT].len(), CATEGORY_MEMORY);
    }

    #[test]
    fn ratio_rule_switches_at_the_geometric_mean() {
        // Noise-free accumulators: x_S = z t/S, x_L = z t/L with S 6, L 8: switch at √48.
        let (s, l, z) = (6.0, 8.0, 1.0);
        for t in 1..12 {
            let t = t as f64;
            assert_eq!(
                ddm_ratio_rule(z * t / s, z * t / l, z),
                t >= (s * l).sqrt(),
                "t {t}"
            );
        }
        assert!(!ddm_ratio_rule(-0.1, 2.0, 1.0));
    }
}
