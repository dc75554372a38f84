//! Does the fingerprint recognise a mechanism it has not seen? Leave one seed out: each
//! mechanism's signature of one training seed is held out, the fingerprints are rebuilt
//! from every other mechanism signature (seed means; each feature standardised by its
//! pooled within-mechanism SD over those signatures), and the held-out signature is named
//! by its nearest fingerprint.
//!
//! * The **confusion matrix** counts, per true mechanism, the mechanisms its held-out seeds
//!   were named as.
//! * The **self-distance range** of a mechanism is the range of its held-out seeds'
//!   distances to its own (rebuilt) fingerprint: how far an unseen seed of that mechanism
//!   lies from it. It is the scale of "near".
//! * The **identification limit** of a mechanism is the upper 99% prediction limit for the
//!   self-distance of one new seed: the held-out self-distances are taken as log-normal,
//!   `exp(m̄ + t₀.₉₉,ν · s · √(1 + 1/k))` (one-sided) with `m̄` the mean log self-distance of the
//!   mechanism's `k` seeds, `s` the SD of the log self-distances pooled over the
//!   mechanisms (`ν` degrees of freedom: every mechanism's seeds less one) — one
//!   scale for all, as the distances are in seed SDs of every mechanism alike. A new seed of
//!   the mechanism lies beyond it once in a hundred; the largest of 8 held-out seeds would
//!   be exceeded once in nine.
//! * An **agent** is *identified* with its nearest mechanism only when its distance (on the
//!   same scale: fingerprints and SDs from all mechanism signatures) lies within that
//!   mechanism's identification limit; otherwise it is "not identified", however near it is
//!   relative to the other mechanisms.

use super::{MECHANISMS, Scale, Signature, View, distance, mean_features};
use std::collections::BTreeMap;

/// One held-out signature of a mechanism and what it was named.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct HeldOut {
    /// The mechanism it belongs to.
    pub mechanism: String,
    /// Its training seed.
    pub seed: u64,
    /// The mechanism whose fingerprint is nearest (`None`: no distance defined).
    pub named: Option<String>,
    /// Distance to its own mechanism's fingerprint (standardised RMS).
    pub self_distance: f64,
    /// Distance to the nearest other mechanism's fingerprint.
    pub other_distance: f64,
}

/// An agent against the mechanisms' self-distance ranges.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AgentVerdict {
    /// The agent.
    pub agent: String,
    /// Its nearest mechanism.
    pub nearest: String,
    /// Its distance to that mechanism's fingerprint (same scale as the self-distances).
    pub distance: f64,
    /// Whether it lies within that mechanism's self-distance range.
    pub identified: bool,
}

/// Coverage of the identification limit: the share of new seeds of a mechanism within it
/// (one-sided).
pub const LIMIT_COVERAGE: f64 = 0.99;

/// Leave-one-seed-out identification of every mechanism, and the agents' verdicts, in one
/// view.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Identification {
    /// The view whose features were compared.
    pub view: View,
    /// Every held-out mechanism signature, in mechanism then seed order.
    pub held_out: Vec<HeldOut>,
    /// Agents (models not among the mechanisms), in name order.
    pub agents: Vec<AgentVerdict>,
}

impl Identification {
    /// Held-out seeds of `truth` named as `named`.
    pub fn count(&self, truth: &str, named: &str) -> usize {
        self.held_out
            .iter()
            .filter(|h| h.mechanism == truth && h.named.as_deref() == Some(named))
            .count()
    }

    /// Share of `mechanism`'s held-out seeds named as itself (NaN without seeds).
    pub fn accuracy(&self, mechanism: &str) -> f64 {
        let n = self
            .held_out
            .iter()
            .filter(|h| h.mechanism == mechanism)
            .count();
        self.count(mechanism, mechanism) as f64 / n as f64
    }

    /// The identification limit of `mechanism` (see the module docs): `None` without two
    /// held-out seeds of some mechanism to pool a spread from, or without a seed of it.
    pub fn limit(&self, mechanism: &str) -> Option<f64> {
        use statrs::distribution::{ContinuousCDF, StudentsT};
        let logs = |m: &str| -> Vec<f64> {
            self.held_out
                .iter()
                .filter(|h| {
                    h.mechanism == m && h.self_distance.is_finite() && h.self_distance > 0.0
                })
                .map(|h| h.self_distance.ln())
                .collect()
        };
        let mut mechanisms: Vec<&str> =
            self.held_out.iter().map(|h| h.mechanism.as_str()).collect();
        mechanisms.sort_unstable();
        mechanisms.dedup();
        let (mut ss, mut dof) = (0.0, 0usize);
        for m in mechanisms {
            let x = logs(m);
            if x.len() >= 2 {
                let mean = x.iter().sum::<f64>() / x.len() as f64;
                ss += x.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
                dof += x.len() - 1;
            }
        }
        let own = logs(mechanism);
        if dof == 0 || own.is_empty() {
            return None;
        }
        let s = (ss / dof as f64).sqrt();
        let k = own.len() as f64;
        let mean = own.iter().sum::<f64>() / k;
        let t = StudentsT::new(0.0, 1.0, dof as f64)
            .ok()?
            .inverse_cdf(LIMIT_COVERAGE);
        Some((mean + t * s * (1.0 + 1.0 / k).sqrt()).exp())
    }

    /// `(min, max)` of `mechanism`'s held-out distances to its own fingerprint.
    pub fn self_range(&self, mechanism: &str) -> Option<(f64, f64)> {
        let d: Vec<f64> = self
            .held_out
            .iter()
            .filter(|h| h.mechanism == mechanism && h.self_distance.is_finite())
            .map(|h| h.self_distance)
            .collect();
        (!d.is_empty()).then(|| {
            (
                d.iter().copied().fold(f64::INFINITY, f64::min),
                d.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        })
    }
}

/// Fingerprints (seed means) of the mechanisms among `sigs`.
fn fingerprints<'a>(sigs: &[&'a Signature]) -> BTreeMap<&'a str, BTreeMap<&'static str, f64>> {
    let mut by_model: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in sigs {
        by_model.entry(s.model.as_str()).or_default().push(s);
    }
    by_model
        .into_iter()
        .map(|(m, v)| (m, mean_features(&v)))
        .collect()
}

/// The nearest fingerprint to `x` and its distance, and the distance to `own` (NaN when
/// absent) and to the nearest fingerprint other than `own`.
fn nearest(
    x: &BTreeMap<&'static str, f64>,
    prints: &BTreeMap<&str, BTreeMap<&'static str, f64>>,
    scale: &Scale,
    own: &str,
) -> (Option<(String, f64)>, f64, f64) {
    let d: Vec<(&str, f64)> = prints
        .iter()
        .map(|(m, p)| (*m, distance(x, p, scale)))
        .filter(|(_, d)| d.is_finite())
        .collect();
    let best = d
        .iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(m, v)| (m.to_string(), *v));
    let own_d = d.iter().find(|(m, _)| *m == own).map_or(f64::NAN, |x| x.1);
    let other = d
        .iter()
        .filter(|(m, _)| *m != own)
        .map(|x| x.1)
        .fold(f64::INFINITY, f64::min);
    (best, own_d, other)
}

/// Leave-one-seed-out identification of the [`MECHANISMS`] among `sigs` and the verdict on
/// every other model (see the module docs), on `view`'s features.
pub fn identify(sigs: &[Signature], view: View) -> Identification {
    let mechs: Vec<&Signature> = sigs
        .iter()
        .filter(|s| MECHANISMS.contains(&s.model.as_str()))
        .collect();
    let mut held_out = Vec::new();
    for (i, h) in mechs.iter().enumerate() {
        let rest: Vec<&Signature> = mechs
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .map(|(_, s)| *s)
            .collect();
        // A mechanism with no other seed has no fingerprint to be named by.
        if !rest.iter().any(|s| s.model == h.model) {
            continue;
        }
        let scale = Scale::of(&rest, &MECHANISMS, view);
        let x = mean_features(&[*h]);
        let (best, own, other) = nearest(&x, &fingerprints(&rest), &scale, &h.model);
        held_out.push(HeldOut {
            mechanism: h.model.clone(),
            seed: h.seed,
            named: best.map(|b| b.0),
            self_distance: own,
            other_distance: other,
        });
    }
    held_out.sort_by(|a, b| {
        let pos = |m: &str| MECHANISMS.iter().position(|x| *x == m);
        pos(&a.mechanism)
            .cmp(&pos(&b.mechanism))
            .then(a.seed.cmp(&b.seed))
    });
    let mut id = Identification {
        view,
        held_out,
        agents: Vec::new(),
    };
    let scale = Scale::of(&mechs, &MECHANISMS, view);
    let prints = fingerprints(&mechs);
    let mut agents: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in sigs
        .iter()
        .filter(|s| !MECHANISMS.contains(&s.model.as_str()))
    {
        agents.entry(s.model.as_str()).or_default().push(s);
    }
    for (a, seeds) in agents {
        let (best, _, _) = nearest(&mean_features(&seeds), &prints, &scale, "");
        if let Some((m, d)) = best {
            let identified = id.limit(&m).is_some_and(|limit| d <= limit);
            id.agents.push(AgentVerdict {
                agent: a.to_string(),
                nearest: m,
                distance: d,
                identified,
            });
        }
    }
    id
}

/// One agent seed's own verdict.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SeedVerdict {
    /// The agent.
    pub agent: String,
    /// Its training seed.
    pub seed: u64,
    /// The mechanism whose fingerprint is nearest to this seed's signature.
    pub nearest: String,
    /// Its distance (same scale as the identification's).
    pub distance: f64,
    /// Whether it lies within that mechanism's identification limit.
    pub identified: bool,
}

/// Every seed of every agent (model not among the [`MECHANISMS`]) of `sigs` placed on its
/// own, in `id`'s view, against the fingerprints and limits of all mechanism signatures.
pub fn seed_verdicts(sigs: &[Signature], id: &Identification) -> Vec<SeedVerdict> {
    let mechs: Vec<&Signature> = sigs
        .iter()
        .filter(|s| MECHANISMS.contains(&s.model.as_str()))
        .collect();
    let scale = Scale::of(&mechs, &MECHANISMS, id.view);
    let prints = fingerprints(&mechs);
    let mut out: Vec<SeedVerdict> = sigs
        .iter()
        .filter(|s| !MECHANISMS.contains(&s.model.as_str()))
        .filter_map(|s| {
            let (best, _, _) = nearest(&mean_features(&[s]), &prints, &scale, "");
            let (m, d) = best?;
            Some(SeedVerdict {
                agent: s.model.clone(),
                seed: s.seed,
                identified: id.limit(&m).is_some_and(|l| d <= l),
                nearest: m,
                distance: d,
            })
        })
        .collect();
    out.sort_by(|a, b| a.agent.cmp(&b.agent).then(a.seed.cmp(&b.seed)));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanisms::tests::sig;

    /// Two mechanisms about 10 seed-SDs apart in two features, 8 seeds each (as the
    /// studies have): every held-out seed is named as itself, its self-distance is below
    /// its distance to the other; an agent among the first mechanism's seeds is
    /// identified, one halfway between is not.
    #[test]
    fn held_out_seeds_are_named_as_their_mechanism_and_a_halfway_agent_is_not_identified() {
        let mut s = Vec::new();
        let jitter = [
            -0.0175, -0.0125, -0.0075, -0.0025, 0.0025, 0.0075, 0.0125, 0.0175,
        ];
        for (k, e) in jitter.iter().enumerate() {
            s.push(sig(
                "ddm",
                k as u64,
                &[("wf", 0.1 + e), ("foc_cv", 0.2 - e)],
            ));
            s.push(sig(
                "sbf",
                k as u64,
                &[("wf", 0.3 + e), ("foc_cv", 0.4 + e)],
            ));
            s.push(sig(
                "like-ddm",
                k as u64,
                &[("wf", 0.1 - e), ("foc_cv", 0.2 + e)],
            ));
            s.push(sig(
                "halfway",
                k as u64,
                &[("wf", 0.2 + e), ("foc_cv", 0.3 - e)],
            ));
        }
        let id = identify(&s, View::Units);
        assert_eq!(id.held_out.len(), 16);
        assert_eq!((id.accuracy("ddm"), id.accuracy("sbf")), (1.0, 1.0));
        assert_eq!(id.count("ddm", "sbf"), 0);
        for h in &id.held_out {
            assert!(h.self_distance < h.other_distance, "{h:?}");
        }
        let (lo, hi) = id.self_range("ddm").unwrap();
        assert!(lo <= hi && hi.is_finite());
        let verdict = |a: &str| id.agents.iter().find(|v| v.agent == a).unwrap().clone();
        assert_eq!(verdict("like-ddm").nearest, "ddm");
        assert!(verdict("like-ddm").identified, "{:?}", verdict("like-ddm"));
        assert!(!verdict("halfway").identified, "{:?}", verdict("halfway"));
    }

    fn held(mechanism: &str, self_distance: f64) -> HeldOut {
        HeldOut {
            mechanism: mechanism.into(),
            seed: 0,
            named: Some(mechanism.into()),
            self_distance,
            other_distance: 10.0,
        }
    }

    /// The limit by hand: log self-distances −0.1, 0.1 (mechanism a) and 0.2, 0.4 (b):
    /// pooled SD √((0.02 + 0.02) / 2) = 0.1414 on 2 degrees of freedom, t₀.₉₉,₂ = 6.965
    /// (printed t tables): a's limit exp(0 + 6.965 · 0.1414 · √1.5) = 3.341, b's
    /// exp(0.3 + …) = 4.510. Without two seeds of any mechanism there is no limit.
    #[test]
    fn the_limit_is_the_log_normal_prediction_limit_with_a_pooled_spread() {
        let id = Identification {
            view: View::Units,
            held_out: vec![
                held("a", (-0.1f64).exp()),
                held("a", 0.1f64.exp()),
                held("b", 0.2f64.exp()),
                held("b", 0.4f64.exp()),
            ],
            agents: vec![],
        };
        assert!(
            (id.limit("a").unwrap() - 3.341).abs() < 2e-3,
            "{:?}",
            id.limit("a")
        );
        assert!(
            (id.limit("b").unwrap() - 4.510).abs() < 2e-3,
            "{:?}",
            id.limit("b")
        );
        assert_eq!(id.limit("c"), None);
        let single = Identification {
            view: View::Units,
            held_out: vec![held("a", 1.0), held("b", 2.0)],
            agents: vec![],
        };
        assert_eq!(single.limit("a"), None);
    }
}
