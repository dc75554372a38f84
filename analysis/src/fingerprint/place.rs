//! Placing one agent's signature among the mechanism signatures: distances on the
//! identification's scale, self-distance ranges, bootstrap shares and the verdict.

use crate::mechanisms::{
    ALL_FEATURES, MECHANISMS, Scale, Signature, View, distance, identify, mean_features,
};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::BTreeMap;

/// The committed mechanism signatures the fingerprint compares with: the timing models of
/// the mechanisms study on the reference preset (`results/mechanisms-reference/
/// signatures.csv`, 8 seeds per mechanism, unit categories of rules version 2), compiled
/// in so an installed package needs no repository.
const REFERENCE_CSV: &str = include_str!("../../data/mechanism-signatures.csv");

/// Where [`reference_signatures`] come from (printed beside every placement).
pub const REFERENCE_SOURCE: &str =
    "results/mechanisms-reference (timing models, 8 seeds each; unit categories rules 2)";

/// Parses a `signatures.csv` (`model,seed,<features…>`, written by `chronocooked
/// mechanisms`): one signature per line, empty cells missing. Columns other than
/// [`ALL_FEATURES`] are refused; a feature missing from the header is missing everywhere.
pub fn signatures_from_csv(text: &str) -> Result<Vec<Signature>, String> {
    let mut reader = csv::ReaderBuilder::new().from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| format!("header: {e}"))?
        .iter()
        .map(str::to_string)
        .collect();
    if header.len() < 2 || header[0] != "model" || header[1] != "seed" {
        return Err(format!(
            "header {header:?}: expected `model,seed,` then feature names"
        ));
    }
    for f in &header[2..] {
        if !ALL_FEATURES.contains(&f.as_str()) {
            return Err(format!(
                "unknown feature column `{f}` (allowed: {})",
                ALL_FEATURES.join(", ")
            ));
        }
    }
    let mut out = Vec::new();
    for (line, row) in reader.records().enumerate() {
        let row = row.map_err(|e| format!("line {}: {e}", line + 2))?;
        let seed = row[1]
            .parse::<u64>()
            .map_err(|_| format!("line {}: seed `{}` is not an integer", line + 2, &row[1]))?;
        let mut features = BTreeMap::new();
        for (name, cell) in header[2..].iter().zip(row.iter().skip(2)) {
            if cell.is_empty() {
                continue;
            }
            let v: f64 = cell
                .parse()
                .map_err(|_| format!("line {}: {name} `{cell}` is not a number", line + 2))?;
            if v.is_finite() {
                features.insert(name.clone(), v);
            }
        }
        out.push(Signature {
            model: row[0].to_string(),
            seed,
            features,
        });
    }
    Ok(out)
}

/// The committed signatures of the [`MECHANISMS`] (see [`REFERENCE_SOURCE`]).
pub fn reference_signatures() -> Vec<Signature> {
    signatures_from_csv(REFERENCE_CSV)
        .expect("the compiled-in mechanism signatures parse (tested)")
        .into_iter()
        .filter(|s| MECHANISMS.contains(&s.model.as_str()))
        .collect()
}

/// The agent against one mechanism.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MechanismDistance {
    /// The mechanism.
    pub mechanism: String,
    /// Distance of the agent's signature to the mechanism's fingerprint (seed mean): the
    /// RMS over shared features of the differences in units of each feature's pooled
    /// within-mechanism SD (see [`crate::mechanisms`]).
    pub distance: f64,
    /// The distances of the mechanism's own held-out seeds to its fingerprint (leave one
    /// seed out, `(min, max)`): how far an unseen seed of it lies.
    pub self_range: Option<(f64, f64)>,
    /// The mechanism's identification limit: the upper 99% prediction limit for a new seed's
    /// distance (see [`crate::mechanisms::identify`]); the agent is identified with its
    /// nearest mechanism only within it.
    pub limit: Option<f64>,
    /// Share of bootstrap resamples (every mechanism's seeds resampled with replacement)
    /// in which this mechanism is the nearest.
    pub bootstrap_share: f64,
}

/// One agent placed among the mechanisms in one view.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Placement {
    /// The view whose features were compared.
    pub view: View,
    /// The agent's name.
    pub model: String,
    /// Its signature: feature → value (every feature it has, of both views).
    pub signature: BTreeMap<String, f64>,
    /// Features of the view it lacks (e.g. the neural ones of an agent without activity),
    /// in the view's order.
    pub missing: Vec<String>,
    /// Every mechanism, nearest first.
    pub distances: Vec<MechanismDistance>,
    /// The nearest mechanism (`None`: no feature shared with any).
    pub nearest: Option<String>,
    /// Whether its distance lies within the nearest mechanism's identification limit.
    pub identified: bool,
    /// Held-out mechanism seeds named as their own mechanism, of all held out (the
    /// reference's own check).
    pub reference_identification: (usize, usize),
    /// Bootstrap resamples behind the shares.
    pub resamples: usize,
}

/// Places `agent` among the `mechanisms`' signatures (models of [`MECHANISMS`]; others are
/// ignored) in `view`: distances on the leave-one-seed-out identification's scale
/// ([`identify`]), the self-distance ranges, `resamples` bootstrap resamples of the
/// mechanisms' seeds (seeded by `seed`) and the verdict.
pub fn place(
    agent: &Signature,
    mechanisms: &[Signature],
    resamples: usize,
    seed: u64,
    view: View,
) -> Placement {
    let mechs: Vec<&Signature> = mechanisms
        .iter()
        .filter(|s| MECHANISMS.contains(&s.model.as_str()))
        .collect();
    let mut all: Vec<Signature> = mechs.iter().map(|s| (*s).clone()).collect();
    // The agent under a name no mechanism has, so `identify` treats it as an agent.
    let probe_name = format!("agent:{}", agent.model);
    all.push(Signature {
        model: probe_name.clone(),
        ..agent.clone()
    });
    let id = identify(&all, view);
    let verdict = id.agents.iter().find(|a| a.agent == probe_name);
    let scale = Scale::of(&mechs, &MECHANISMS, view);
    let x = mean_features(&[agent]);
    let mut by_model: BTreeMap<&str, Vec<&Signature>> = BTreeMap::new();
    for s in &mechs {
        by_model.entry(s.model.as_str()).or_default().push(s);
    }
    let mut wins: BTreeMap<&str, usize> = BTreeMap::new();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    for _ in 0..resamples {
        let mut best: Option<(&str, f64)> = None;
        for (m, seeds) in &by_model {
            let pick: Vec<&Signature> = (0..seeds.len())
                .map(|_| seeds[rng.random_range(0..seeds.len())])
                .collect();
            let d = distance(&x, &mean_features(&pick), &scale);
            if d.is_finite() && best.is_none_or(|b| d < b.1) {
                best = Some((m, d));
            }
        }
        if let Some((m, _)) = best {
            *wins.entry(m).or_default() += 1;
        }
    }
    let mut distances: Vec<MechanismDistance> = by_model
        .iter()
        .map(|(m, seeds)| MechanismDistance {
            mechanism: m.to_string(),
            distance: distance(&x, &mean_features(seeds), &scale),
            self_range: id.self_range(m),
            limit: id.limit(m),
            bootstrap_share: wins.get(m).copied().unwrap_or(0) as f64 / resamples.max(1) as f64,
        })
        .collect();
    distances.sort_by(|a, b| {
        let key = |d: f64| if d.is_finite() { d } else { f64::INFINITY };
        key(a.distance).total_cmp(&key(b.distance))
    });
    let correct = id
        .held_out
        .iter()
        .filter(|h| h.named.as_deref() == Some(h.mechanism.as_str()))
        .count();
    Placement {
        view,
        model: agent.model.clone(),
        signature: agent.features.clone(),
        missing: view
            .features()
            .iter()
            .filter(|f| !agent.features.contains_key(**f))
            .map(|f| f.to_string())
            .collect(),
        distances,
        nearest: verdict.map(|v| v.nearest.clone()),
        identified: verdict.is_some_and(|v| v.identified),
        reference_identification: (correct, id.held_out.len()),
        resamples,
    }
}

/// One agent placed in both views, side by side.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Fingerprint {
    /// The unit view (basis-dependent).
    pub units: Placement,
    /// The dynamics view (basis-free).
    pub dynamics: Placement,
}

impl Fingerprint {
    /// Places `agent` in both views (see [`place`]).
    pub fn place(agent: &Signature, mechanisms: &[Signature], resamples: usize, seed: u64) -> Self {
        Fingerprint {
            units: place(agent, mechanisms, resamples, seed, View::Units),
            dynamics: place(agent, mechanisms, resamples, seed, View::Dynamics),
        }
    }

    /// Both placements, unit view first.
    pub fn views(&self) -> [&Placement; 2] {
        [&self.units, &self.dynamics]
    }

    /// The agent's name.
    pub fn model(&self) -> &str {
        &self.units.model
    }

    /// Whether the two views give the same verdict: the same nearest mechanism, and
    /// identified in both or in neither.
    pub fn views_agree(&self) -> bool {
        self.units.nearest == self.dynamics.nearest
            && self.units.identified == self.dynamics.identified
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compiled_in_signatures_hold_every_mechanism_with_eight_seeds() {
        let sigs = reference_signatures();
        for m in MECHANISMS {
            let n = sigs.iter().filter(|s| s.model == m).count();
            assert_eq!(n, 8, "{m}");
        }
    }

    #[test]
    fn a_csv_with_an_unknown_column_or_a_bad_number_is_refused_naming_it() {
        let e = signatures_from_csv("model,seed,wf,speed\nddm,0,0.1,2\n").unwrap_err();
        assert!(e.contains("`speed`") && e.contains("foc_cv"), "{e}");
        let e = signatures_from_csv("model,seed,wf\nddm,0,abc\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("wf `abc`"), "{e}");
        let e = signatures_from_csv("name,seed\n").unwrap_err();
        assert!(e.contains("model,seed"), "{e}");
        let ok = signatures_from_csv("model,seed,wf,pi_cv\nddm,3,0.1,\n").unwrap();
        assert_eq!(ok[0].seed, 3);
        assert_eq!(ok[0].features.len(), 1);
    }

    /// A copy of a mechanism's seed is nearest to it, within its self range, with every
    /// resample agreeing; a signature far from everything is not identified.
    #[test]
    fn a_seed_of_a_mechanism_is_placed_with_it_and_an_outlier_is_not_identified() {
        let mechs = reference_signatures();
        for m in MECHANISMS {
            let own: Vec<&Signature> = mechs.iter().filter(|s| s.model == m).collect();
            // The seed mean of the mechanism itself: distance 0 to its fingerprint.
            let mean = mean_features(&own);
            let agent = Signature {
                model: "copy".into(),
                seed: 0,
                features: mean.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
            };
            let p = place(&agent, &mechs, 200, 1, View::Units);
            assert_eq!(p.nearest.as_deref(), Some(m), "{p:?}");
            assert!(p.identified, "{p:?}");
            assert!(p.distances[0].distance < 1e-9);
            assert_eq!(p.distances[0].mechanism, m);
            assert!(p.distances[0].bootstrap_share > 0.9, "{p:?}");
            assert!(
                p.missing.is_empty()
                    || own
                        .iter()
                        .any(|s| s.features.len() < crate::mechanisms::FEATURES.len())
            );
        }
        let far = Signature {
            model: "far".into(),
            seed: 0,
            features: ALL_FEATURES
                .iter()
                .map(|f| (f.to_string(), 100.0))
                .collect(),
        };
        let p = place(&far, &mechs, 100, 1, View::Units);
        assert!(!p.identified && p.nearest.is_some(), "{p:?}");
        let (correct, all) = p.reference_identification;
        assert_eq!(all, 40);
        assert!(correct >= 38, "{correct}/{all}");
    }
}
