//! Bisection judgments: at the end of the timed interval each timing model compares its
//! own timing state with its memories of the two anchors and says "short" or "long".
//!
//! The comparison is the model's, re-derived from its literature. Where the criterion lies
//! between the remembered anchors `S*`, `L*` is the [`DecisionRule`] (a setting,
//! `--set decision_rule=…`): by default scalar expectancy theory's ratio rule (Gibbon 1981;
//! Allan & Gibbon 1991: respond "long" when `t/S ≥ L/t`), which puts the criterion — and so
//! the bisection point — at the geometric mean **by construction**; the difference rule
//! puts it at the arithmetic mean, the likelihood rule at (about) the harmonic mean, and the
//! learned rule moves it by feedback until errors on the two anchors balance, so where the
//! bisection point falls is then a measured result (Kopec & Brody 2010 review how human
//! bisection points move between these means). Per model:
//!
//! * drift-diffusion — two accumulators run during the interval with the drifts learned for
//!   the short and the long anchor (`z/S`, `z/L`, each from its own rewarded trials); the
//!   ratios `t/S` and `t/L` are read as `x_S/z` and `x_L/z`, so "long" iff
//!   `ln(x_S/z) + ln(x_L/z) ≥ 0` (Simen et al. 2011's timer, two drifts). Diffusion noise
//!   in both accumulators gives the scalar variability of the judgment, and puts its 50%
//!   point ≈ 0.5% above the rule's criterion ([`ddm_judgment_boundary`]: the median of the
//!   product of two independent Gaussian accumulators lies below the product of their means).
//! * striatal beat frequency — a criterion pattern is stored at `√(T_S·T_L)` from one
//!   sample of each anchor memory (memory noise, Matell & Meck 2004); "long" iff its
//!   coincidence has been passed during the interval (its detector envelope peaked).
//! * time cells — the population's elapsed-time estimate (centre of mass of the active
//!   cells' preferred times) is compared with the criterion between one remembered
//!   estimate of each anchor, drawn per trial from its rewarded trials
//!   ([`CategoryMemory::sample`]); clock-speed noise varies both the estimate and the
//!   memories.
//!
//! Probes far shorter than the short anchor are judged "short" by every rule (the
//! comparison is with a criterion, not a similarity to each anchor), so the psychometric
//! curves are monotone up to the judgment noise.
//!
//! **More than two categories** (multi-anchor categorization): the same comparison is made
//! at every boundary between two neighbouring remembered anchors, and the judgment is the
//! category of the interval between the boundaries passed ([`Categories`]). Each boundary
//! is the rule's criterion for its own pair — a chain of bisections, each one the
//! comparison above (Church & Deluty 1977 and Gibbon 1981 derive the rules for one pair; a
//! category scale built from them is the "partition" reading of Allan 2002) — so with the
//! default ratio rule every boundary lies at the **geometric mean of its two neighbouring
//! anchors**, with the difference rule at their arithmetic mean. A scalar memory sample per
//! anchor makes every boundary's spread proportional to its location: the predicted Weber
//! fraction is the same at every boundary. The learned rule needs to be told the true
//! category after an error; with more than two counters an unpaid choice says only "not
//! this one", so the learned rule is for two categories only (refused with more).

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Rewarded durations kept per category (per anchor): the time cells' and SBF's reference
/// memory of the anchors. In scalar expectancy theory the reference memory is the
/// distribution of all reinforced durations, sampled anew on every trial (Gibbon, Church &
/// Meck 1984); a finite store only bounds its size, and it must be large enough that the
/// store's own mean does not wander from run to run. Each stored duration carries the
/// clock's and the memory's noise (log SD ≈ 0.21 at 0.15 each), so the store's mean sits
/// ≈ 0.21/√N from the anchor: 4.7% at N = 20 (the value until 2026-11-28), which moved one
/// run's category boundaries 3.5–3.9% (SD over runs), and 1.5% at N = 200, which moved
/// them 1.5–2.0% (SBF and the three time cells, anchor sets 5,9,16,28 and 4,7,12, seeds
/// 1–8 each; the nominal geometric mean inside the fit's 95% interval in 67 of 155
/// boundaries at 20, 117 of 156 at 200; RESULTS "Anchor memory size"). The trial-to-trial
/// sample, the memory's share of each judgment's variance, is the same at either size.
pub const CATEGORY_MEMORY: usize = 200;

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

    /// The remembered anchors `(S*, L*)`: `exp` of each category's mean log duration.
    pub fn anchors(&self) -> Option<(f64, f64)> {
        let mean = |slot: u8| {
            let m = self.log_times.get(&slot).filter(|m| !m.is_empty())?;
            Some((m.iter().sum::<f64>() / m.len() as f64).exp())
        };
        Some((mean(SHORT)?, mean(LONG)?))
    }

    /// One remembered duration of each category `(S*, L*)`, drawn at random from its
    /// stored ones: scalar expectancy theory's reference-memory sample, drawn anew on every
    /// trial (Gibbon, Church & Meck 1984) — the memory's share of the judgment's variance.
    pub fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> Option<(f64, f64)> {
        let s = self.draw(SHORT, rng)?;
        Some((s, self.draw(LONG, rng)?))
    }

    /// One remembered duration of category `slot` drawn at random from its stored ones
    /// (`None`, drawing nothing, while it has none).
    pub fn draw<R: rand::Rng + ?Sized>(&self, slot: u8, rng: &mut R) -> Option<f64> {
        let m = self.log_times.get(&slot).filter(|m| !m.is_empty())?;
        Some(m[rng.random_range(0..m.len())].exp())
    }
}

/// Where a bisection judgment puts its criterion between the remembered anchors `S*` and
/// `L*` (serialised `ratio`, `difference`, `likelihood`, `learned`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecisionRule {
    /// Scalar expectancy theory's ratio rule, "long" iff `t/S* ≥ L*/t`: criterion at the
    /// geometric mean `√(S*·L*)` (Gibbon 1981; Allan & Gibbon 1991).
    #[default]
    Ratio,
    /// Difference rule, "long" iff `t − S* ≥ L* − t`: criterion at the arithmetic mean
    /// `(S* + L*)/2` (the rule Church & Deluty 1977 tested against the geometric mean).
    Difference,
    /// Likelihood rule: "long" iff `t` is likelier under the long anchor's memory than
    /// under the short one's, both Gaussian with the same CV (scalar memories). Equal
    /// likelihoods at `(t/S* − 1)² = (t/L* − 1)²` to first order in the CV: the harmonic mean
    /// `2 S* L*/(S* + L*)` (Gibbon 1981's likelihood-ratio rule, below the geometric mean).
    Likelihood,
    /// A criterion learned from feedback: it starts at the arithmetic mean and moves by
    /// [`CRITERION_STEP`] (log units) after every error — up after a wrong "long", down
    /// after a wrong "short" — so it settles where errors on the two anchors balance.
    Learned,
}

/// Step (in `ln` time) of the learned criterion after each bisection error.
pub const CRITERION_STEP: f64 = 0.02;

impl DecisionRule {
    /// Every rule, in display order.
    pub const ALL: [DecisionRule; 4] = [
        DecisionRule::Ratio,
        DecisionRule::Difference,
        DecisionRule::Likelihood,
        DecisionRule::Learned,
    ];

    /// The setting's value (`ratio`, `difference`, `likelihood`, `learned`).
    pub fn name(self) -> &'static str {
        match self {
            DecisionRule::Ratio => "ratio",
            DecisionRule::Difference => "difference",
            DecisionRule::Likelihood => "likelihood",
            DecisionRule::Learned => "learned",
        }
    }

    /// Parses a setting's value; the error lists the allowed ones.
    pub fn from_name(value: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == value)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|r| r.name()).collect();
                format!("one of {}", names.join(", "))
            })
    }

    /// The fixed criterion of the rule for remembered anchors `s`, `l` (> 0, any time
    /// unit); the learned rule's starting point (the arithmetic mean).
    pub fn criterion(self, s: f64, l: f64) -> f64 {
        match self {
            DecisionRule::Ratio => (s * l).sqrt(),
            DecisionRule::Difference | DecisionRule::Learned => 0.5 * (s + l),
            DecisionRule::Likelihood => 2.0 * s * l / (s + l),
        }
    }
}

/// A decision rule with its learned state (the learned criterion, when it has one).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Decision {
    /// The rule.
    pub rule: DecisionRule,
    /// The learned rule's criterion (`ln` of the timer's time unit), once learning began.
    #[serde(default)]
    pub learned_log_criterion: Option<f64>,
}

impl Decision {
    /// The criterion (the timer's time unit) for remembered anchors `s`, `l`.
    pub fn criterion(&self, s: f64, l: f64) -> f64 {
        match (self.rule, self.learned_log_criterion) {
            (DecisionRule::Learned, Some(c)) => c.exp(),
            (rule, _) => rule.criterion(s, l),
        }
    }

    /// Feedback on one judgment: `judged_long` was the answer, `was_long` the truth, `s` and
    /// `l` the remembered anchors. Only the learned rule changes (after an error).
    pub fn feedback(&mut self, s: f64, l: f64, judged_long: bool, was_long: bool) {
        if self.rule != DecisionRule::Learned || judged_long == was_long {
            return;
        }
        let c = self
            .learned_log_criterion
            .unwrap_or_else(|| self.rule.criterion(s, l).ln());
        let step = if judged_long {
            CRITERION_STEP
        } else {
            -CRITERION_STEP
        };
        if (c + step).is_finite() {
            self.learned_log_criterion = Some(c + step);
        }
    }
}

/// Drift-diffusion ratio rule: "long" iff `ln(x_S/z) + ln(x_L/z) ≥ 0` for the short- and
/// long-anchor accumulators' values `x_s`, `x_l` (a non-positive value is "short").
pub fn ddm_ratio_rule(x_s: f64, x_l: f64, z: f64) -> bool {
    x_s > 0.0 && x_l > 0.0 && (x_s / z).ln() + (x_l / z).ln() >= 0.0
}

/// Probability that drift-diffusion's judgment says "long" after `t` steps of
/// accumulation, for remembered anchors `s` < `l` (steps: drifts `z/s`, `z/l`), threshold
/// `z`, noise coefficient `m` (diffusion `c = m √A`, as
/// [`crate::timing::ddm::DriftDiffusion`]), memory noise `kappa` (each trial's drift of an
/// anchor is its learned drift times `exp(κ ε)`, `ε ~ N(0, 1)`, drawn per anchor) and the
/// rule's `criterion` between the anchors (steps; [`DecisionRule::criterion`]).
///
/// The judgment compares the accumulators' geometric reading `τ = √(x_S/A_S · x_L/A_L)`
/// (`A` the learned drifts) with the criterion — for the ratio rule, whose criterion is
/// `√(s·l)`, that is exactly [`ddm_ratio_rule`]'s `x_S·x_L ≥ z²`. Given the trial's drifts
/// `a_S`, `a_L`, each accumulator's value after `t` steps is Gaussian, `x ~ N(a t, m² a t)`
/// (the sum of `t` Gaussian increments), the two independent, so with
/// `k = criterion² z² / (s l)`
/// `P(long | a_S, a_L) = ∫₀^∞ φ_S(x) · (1 − Φ((k/x − μ_L)/σ_L)) dx`
/// (a non-positive value is "short"; Simpson, 400 intervals over `μ_S ± 10 σ_S`), averaged
/// over the two memory factors (midpoint rule, 40 points per factor over ±5 SD). Without
/// noise it is the step at the criterion.
pub fn ddm_judgment_p_long(
    t: f64,
    s: f64,
    l: f64,
    criterion: f64,
    noise: (f64, f64),
    z: f64,
) -> f64 {
    let (m, kappa) = noise;
    let k = criterion * criterion * z * z / (s * l);
    // Memory factors: (value, weight) pairs of exp(κ ε).
    let factors: Vec<(f64, f64)> = if kappa > 0.0 {
        const POINTS: usize = 40;
        let width = 10.0 / POINTS as f64;
        let raw: Vec<(f64, f64)> = (0..POINTS)
            .map(|i| {
                let e = -5.0 + (i as f64 + 0.5) * width;
                ((kappa * e).exp(), (-0.5 * e * e).exp())
            })
            .collect();
        let total: f64 = raw.iter().map(|(_, w)| w).sum();
        raw.into_iter().map(|(f, w)| (f, w / total)).collect()
    } else {
        vec![(1.0, 1.0)]
    };
    let mut p = 0.0;
    for &(f_s, w_s) in &factors {
        for &(f_l, w_l) in &factors {
            let (a_s, a_l) = (f_s * z / s, f_l * z / l);
            p += w_s
                * w_l
                * product_at_least(
                    a_s * t,
                    m * (a_s * t).sqrt(),
                    a_l * t,
                    m * (a_l * t).sqrt(),
                    k,
                );
        }
    }
    p.clamp(0.0, 1.0)
}

/// `P(x_S · x_L ≥ k)` for independent `x_S ~ N(μ_S, σ_S²)`, `x_L ~ N(μ_L, σ_L²)`, both
/// positive (a non-positive value fails).
fn product_at_least(mu_s: f64, sd_s: f64, mu_l: f64, sd_l: f64, k: f64) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal};
    if sd_s == 0.0 || sd_l == 0.0 {
        return if mu_s > 0.0 && mu_l > 0.0 && mu_s * mu_l >= k {
            1.0
        } else {
            0.0
        };
    }
    let unit = Normal::standard();
    let (lo, hi) = ((mu_s - 10.0 * sd_s).max(0.0), mu_s + 10.0 * sd_s);
    const N: usize = 400;
    let h = (hi - lo) / N as f64;
    let f = |x: f64| {
        if x <= 0.0 {
            return 0.0;
        }
        let density = (-0.5 * ((x - mu_s) / sd_s).powi(2)).exp()
            / (sd_s * (2.0 * std::f64::consts::PI).sqrt());
        density * (1.0 - unit.cdf((k / x - mu_l) / sd_l))
    };
    let mut sum = f(lo) + f(hi);
    for i in 1..N {
        sum += f(lo + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// Where drift-diffusion's category boundary between anchors `s` < `l` lies on noisy
/// accumulators and memories (`noise` = (diffusion `m`, memory `κ`)): the `t` (steps) at
/// which [`ddm_judgment_p_long`] is one half. The diffusion noise puts it above the rule's
/// criterion — the median of the product `x_S x_L` of two independent Gaussians lies below
/// the product of their means — by ≈ 0.5% at the default m 0.15 for any anchor pair (the
/// accumulators' relative spreads there are `m/√(t/s)` and `m/√(t/l)`, which depend on the
/// pair only through its ratio); the log-symmetric memory factors widen the curve without
/// moving its midpoint much.
pub fn ddm_judgment_boundary(s: f64, l: f64, criterion: f64, noise: (f64, f64), z: f64) -> f64 {
    let (mut lo, mut hi) = (s, l);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if ddm_judgment_p_long(mid, s, l, criterion, noise, z) < 0.5 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Boundaries between neighbouring remembered anchors, and the category of a duration:
/// the rule of a k-category judgment (k ≥ 2; k = 2 is bisection).
#[derive(Debug, Clone, PartialEq)]
pub struct Categories {
    /// Choice slots of the remembered anchors, in slot order (the task's counters, whose
    /// anchors increase).
    pub slots: Vec<u8>,
    /// The boundary between `slots[i]` and `slots[i + 1]` (same unit as the anchors).
    pub boundaries: Vec<f64>,
}

impl Categories {
    /// The categories of remembered anchors `(slot, duration)` in slot order under
    /// `decision`; `None` with fewer than two anchors or a non-positive or non-finite one.
    /// With two anchors the boundary is [`Decision::criterion`] (the learned criterion
    /// included); with more, each boundary is the rule's fixed criterion for its pair.
    pub fn new(anchors: &[(u8, f64)], decision: &Decision) -> Option<Self> {
        if anchors.len() < 2 || anchors.iter().any(|&(_, a)| !(a.is_finite() && a > 0.0)) {
            return None;
        }
        let boundaries = if anchors.len() == 2 {
            vec![decision.criterion(anchors[0].1, anchors[1].1)]
        } else {
            anchors
                .windows(2)
                .map(|w| decision.rule.criterion(w[0].1, w[1].1))
                .collect()
        };
        Some(Categories {
            slots: anchors.iter().map(|&(slot, _)| slot).collect(),
            boundaries,
        })
    }

    /// The slot whose category holds duration `t`: the one after the boundaries `t`
    /// reaches (a boundary itself belongs to the category above it, as an anchor does in
    /// the reference's category error rate).
    pub fn category(&self, t: f64) -> u8 {
        self.slot_after(self.boundaries.iter().filter(|&&b| t >= b).count())
    }

    /// The slot after `passed` boundaries (the last one beyond them all).
    pub fn slot_after(&self, passed: usize) -> u8 {
        self.slots[passed.min(self.slots.len() - 1)]
    }
}

/// The remembered anchors `(slot, duration)` a judgment among `k` categories uses, from
/// `remembered(slot)` (which may draw a memory sample), in slot order:
/// * `k ≤ 2` (bisection): slots 0 and 1, asked in order up to the first without a memory
///   — both are needed, and nothing is asked after a gap;
/// * `k > 2` (multi-anchor): every slot `0 … k−1` that has a memory. The judgment is made
///   among the anchors learned so far, so a counter that has paid is used before every
///   counter has (each is learned only when it pays: an unpaid choice among more than two
///   counters does not say which one was right).
pub fn remembered_slots(k: usize, mut remembered: impl FnMut(u8) -> Option<f64>) -> Vec<(u8, f64)> {
    let mut out = Vec::new();
    for slot in 0..k.max(2).min(usize::from(u8::MAX)) as u8 {
        match remembered(slot) {
            Some(a) => out.push((slot, a)),
            None if k <= 2 => break,
            None => {}
        }
    }
    out
}

/// Whether the remembered anchors suffice for a judgment among `k` categories: both in
/// bisection, any two with more categories.
pub fn can_judge(k: usize, remembered: usize) -> bool {
    remembered >= 2 && (k > 2 || remembered == k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn k_categories_put_each_boundary_at_its_pairs_mean() {
        // Anchors 3, 10, 20, 25: ratio boundaries at √30, √200, √500.
        let anchors = [(0, 3.0), (1, 10.0), (2, 20.0), (3, 25.0)];
        let c = Categories::new(&anchors, &Decision::default()).unwrap();
        for (b, want) in c.boundaries.iter().zip([30f64, 200.0, 500.0]) {
            assert!((b - want.sqrt()).abs() < 1e-12, "{b} vs √{want}");
        }
        assert_eq!(c.category(1.0), 0);
        assert_eq!(c.category(5.4), 0); // √30 ≈ 5.48
        assert_eq!(c.category(5.5), 1);
        assert_eq!(
            c.category(30f64.sqrt()),
            1,
            "a boundary belongs to the category above"
        );
        assert_eq!(c.category(14.0), 1); // √200 ≈ 14.14
        assert_eq!(c.category(22.0), 2); // √500 ≈ 22.36
        assert_eq!(c.category(1e9), 3);
        // The difference rule: arithmetic means 6.5, 15, 22.5; likelihood: harmonic means.
        let rule = |rule| Decision {
            rule,
            learned_log_criterion: None,
        };
        let c = Categories::new(&anchors, &rule(DecisionRule::Difference)).unwrap();
        assert_eq!(c.boundaries, vec![6.5, 15.0, 22.5]);
        let c = Categories::new(&anchors, &rule(DecisionRule::Likelihood)).unwrap();
        assert!((c.boundaries[1] - 2.0 * 200.0 / 30.0).abs() < 1e-12);
        // A slot not yet learned: the judgment is among the others (3 | 20 at √60).
        let c = Categories::new(&[(0, 3.0), (2, 20.0)], &Decision::default()).unwrap();
        assert_eq!(c.category(7.0), 0);
        assert_eq!(c.category(8.0), 2);
        // Two anchors: the bisection criterion (a learned one included).
        let learned = Decision {
            rule: DecisionRule::Learned,
            learned_log_criterion: Some(7f64.ln()),
        };
        let c = Categories::new(&[(0, 4.0), (1, 16.0)], &learned).unwrap();
        assert!((c.boundaries[0] - 7.0).abs() < 1e-12);
        assert_eq!(c.category(6.9), 0);
        assert_eq!(c.category(7.0), 1);
        let d = Decision::default();
        assert_eq!(Categories::new(&[(0, 4.0)], &d), None);
        assert_eq!(Categories::new(&[(0, 4.0), (1, f64::NAN)], &d), None);
        assert_eq!(Categories::new(&[(0, 4.0), (1, 0.0)], &d), None);
    }

    #[test]
    fn bisection_needs_both_anchors_and_more_categories_any_two() {
        let mut asked = Vec::new();
        let known = |slot: u8| (slot != 1).then_some(f64::from(slot) + 1.0);
        let got = remembered_slots(2, |slot| {
            asked.push(slot);
            known(slot)
        });
        assert_eq!(got, vec![(0, 1.0)]);
        assert_eq!(asked, vec![0, 1], "nothing is asked after the gap");
        assert!(!can_judge(2, got.len()));
        let got = remembered_slots(4, known);
        assert_eq!(got, vec![(0, 1.0), (2, 3.0), (3, 4.0)]);
        assert!(can_judge(4, got.len()));
        assert!(!can_judge(4, 1));
        assert!(can_judge(2, 2));
    }

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
    fn each_rule_puts_its_criterion_at_its_mean() {
        let (s, l) = (4.0, 16.0);
        assert!((DecisionRule::Ratio.criterion(s, l) - 8.0).abs() < 1e-12);
        assert!((DecisionRule::Difference.criterion(s, l) - 10.0).abs() < 1e-12);
        assert!((DecisionRule::Likelihood.criterion(s, l) - 6.4).abs() < 1e-12);
        for r in DecisionRule::ALL {
            assert_eq!(DecisionRule::from_name(r.name()), Ok(r));
        }
        assert!(
            DecisionRule::from_name("geometric")
                .unwrap_err()
                .contains("ratio")
        );
    }

    #[test]
    fn the_learned_criterion_settles_where_errors_balance() {
        // A noise-free observer of t in {4, 16}: every error moves the criterion toward
        // the interval between the anchors; starting at the AM (10), no error ever occurs.
        let mut d = Decision {
            rule: DecisionRule::Learned,
            learned_log_criterion: None,
        };
        assert!((d.criterion(4.0, 16.0) - 10.0).abs() < 1e-12);
        // A wrong "long" on a short trial raises it by one step.
        d.feedback(4.0, 16.0, true, false);
        let c = d.learned_log_criterion.unwrap();
        assert!((c - (10f64.ln() + CRITERION_STEP)).abs() < 1e-12);
        // A wrong "short" lowers it back; a right answer leaves it.
        d.feedback(4.0, 16.0, false, true);
        d.feedback(4.0, 16.0, true, true);
        assert!((d.learned_log_criterion.unwrap() - 10f64.ln()).abs() < 1e-12);
        // Fixed rules never learn.
        let mut fixed = Decision::default();
        fixed.feedback(4.0, 16.0, true, false);
        assert_eq!(fixed.learned_log_criterion, None);
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

    #[test]
    fn the_ratio_rules_probability_is_what_two_simulated_accumulators_give() {
        use crate::timing::ddm::DriftDiffusion;
        use rand::{Rng, SeedableRng};
        // Anchors 7 and 13 (no doc uses them), the default noises (diffusion 0.15, memory
        // 0.2), z 1: the two accumulators stepped as the agent steps them, judged by the
        // rule, against the integral.
        let (s, l, m, kappa, z) = (7.0, 13.0, 0.15, 0.2, 1.0);
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(11);
        let trials = 40_000;
        for t in [7u32, 9, 10, 13] {
            let mut long = 0;
            for _ in 0..trials {
                // This trial's memory samples of the two drifts, then the accumulators.
                let e_s: f64 = rng.sample(rand_distr::StandardNormal);
                let e_l: f64 = rng.sample(rand_distr::StandardNormal);
                let mut a = DriftDiffusion::new((kappa * e_s).exp() * z / s, z, m);
                let mut b = DriftDiffusion::new((kappa * e_l).exp() * z / l, z, m);
                for _ in 0..t {
                    a.step(1.0, &mut rng);
                    b.step(1.0, &mut rng);
                }
                long += usize::from(ddm_ratio_rule(a.x, b.x, z));
            }
            let measured = long as f64 / trials as f64;
            let p = ddm_judgment_p_long(f64::from(t), s, l, (s * l).sqrt(), (m, kappa), z);
            let se = (p * (1.0 - p) / trials as f64).sqrt().max(1e-4);
            assert!(
                (measured - p).abs() < 4.0 * se,
                "t {t}: simulated {measured:.4}, integral {p:.4}"
            );
        }
    }

    #[test]
    fn the_noisy_ratio_rules_boundary_lies_just_above_the_geometric_mean() {
        // Without noise the geometric mean exactly; with the default diffusion noise ≈ 0.5%
        // above it for any pair, growing with the noise.
        for (s, l) in [(7.0, 13.0), (4.0, 8.0), (16.0, 28.0)] {
            let gm = f64::sqrt(s * l);
            assert!((ddm_judgment_boundary(s, l, gm, (0.0, 0.0), 1.0) - gm).abs() < 1e-9);
            // Memory noise alone (log-symmetric factors, exact accumulators): the GM.
            let memory = ddm_judgment_boundary(s, l, gm, (0.0, 0.2), 1.0) / gm - 1.0;
            assert!(memory.abs() < 1e-3, "{s}-{l}: {memory}");
            let b = ddm_judgment_boundary(s, l, gm, (0.15, 0.0), 1.0) / gm - 1.0;
            assert!((0.002..0.01).contains(&b), "{s}-{l}: {b}");
            let wider = ddm_judgment_boundary(s, l, gm, (0.3, 0.0), 1.0) / gm - 1.0;
            assert!(wider > 2.0 * b, "{s}-{l}: {wider} vs {b}");
        }
    }
}
