//! The fingerprint tables and figure of a study (`chronocooked mechanisms RESULTS`).

use super::{
    Comparison, FEATURES, MECHANISMS, MechanismError, Signature, compare, feature_sds,
    mean_features, read::signatures,
};
use chronocooked_env::markdown::Table;
use std::path::{Path, PathBuf};

/// What [`write_tables`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// `signatures.csv`, `mechanisms.csv`, `mechanisms.md`, `fingerprints.svg`/`.png`.
    pub files: Vec<PathBuf>,
    /// Signatures (model × seed).
    pub signatures: usize,
    /// Agents compared.
    pub agents: usize,
    /// The leave-one-seed-out identification (also in `mechanisms.md`).
    pub identification: super::Identification,
}

fn fmt(x: f64, digits: usize) -> String {
    if x.is_finite() {
        format!("{x:.digits$}")
    } else {
        "–".into()
    }
}

/// Reads the compact results under `results`, compares every agent with the
/// [`MECHANISMS`] (bootstrap of `resamples`, seeded) and writes into `out`:
/// `signatures.csv` (model, seed, every feature), `mechanisms.csv` (agent, mechanism,
/// distance, nearest fraction, seeds) and `mechanisms.md` (the fingerprints with seed
/// spreads, then per agent its distances and nearest mechanism).
pub fn write_tables(
    results: &Path,
    out: &Path,
    resamples: usize,
    seed: u64,
) -> Result<Written, MechanismError> {
    let _lock =
        chronocooked_env::fs::FolderLock::acquire(out).map_err(|e| MechanismError::File {
            path: out.to_path_buf(),
            message: e.to_string(),
        })?;
    let sigs = signatures(results)?;
    let comparisons = compare(&sigs, &MECHANISMS, resamples, seed);
    let write = |name: &str, text: &str| {
        let p = out.join(name);
        chronocooked_env::fs::write_atomic(&p, text.as_bytes()).map_err(|e| {
            MechanismError::File {
                path: p.clone(),
                message: e.error.to_string(),
            }
        })?;
        Ok::<PathBuf, MechanismError>(p)
    };
    let mut csv = format!("model,seed,{}\n", FEATURES.join(","));
    for s in &sigs {
        let row: Vec<String> = FEATURES
            .iter()
            .map(|f| s.features.get(*f).map_or(String::new(), |v| v.to_string()))
            .collect();
        csv.push_str(&format!("{},{},{}\n", s.model, s.seed, row.join(",")));
    }
    let mut mcsv =
        String::from("agent,mechanism,distance,nearest_fraction,agent_seeds,mechanism_seeds\n");
    for c in &comparisons {
        mcsv.push_str(&format!(
            "{},{},{},{},{},{}\n",
            c.agent, c.mechanism, c.distance, c.nearest_fraction, c.seeds.0, c.seeds.1
        ));
    }
    // Markdown: fingerprints (mean ± SD over seeds), then the comparison.
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.dedup();
    let mut md = String::from("# Mechanism fingerprints\n\n");
    md.push_str(&format!(
        "Mean ± SD over training seeds (n). Features: {}.\n\n",
        FEATURES.join(", ")
    ));
    let mut table = Table::new(["model", "n"].into_iter().chain(FEATURES));
    for m in &models {
        let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == *m).collect();
        let cells: Vec<String> = FEATURES
            .iter()
            .map(|f| {
                let sp = crate::stats::Spread::of(
                    mine.iter().filter_map(|s| s.features.get(*f).copied()),
                );
                if sp.n == 0 {
                    "–".into()
                } else {
                    format!("{} ± {}", fmt(sp.mean, 3), fmt(sp.sd, 3))
                }
            })
            .collect();
        table.row(
            [m.to_string(), mine.len().to_string()]
                .into_iter()
                .chain(cells),
        );
    }
    md.push_str(&table.render());
    md.push_str(&format!(
        "\n## Nearest mechanism\n\nDistance: RMS of feature differences in units of each \
         feature's seed-to-seed SD within a mechanism (pooled over the mechanisms; 1 = one \
         seed SD on every feature); nearest: the share of {resamples} bootstrap \
         resamples of the seeds in which the mechanism is the nearest.\n\n"
    ));
    let mut table = Table::new(
        ["agent"]
            .into_iter()
            .chain(MECHANISMS)
            .chain(["nearest (bootstrap share)"]),
    );
    let mut agents: Vec<&str> = comparisons.iter().map(|c| c.agent.as_str()).collect();
    agents.dedup();
    for a in &agents {
        let mine: Vec<&Comparison> = comparisons.iter().filter(|c| c.agent == *a).collect();
        let cells: Vec<String> = MECHANISMS
            .iter()
            .map(|m| {
                mine.iter()
                    .find(|c| c.mechanism == *m)
                    .map_or("–".into(), |c| fmt(c.distance, 2))
            })
            .collect();
        let nearest = crate::mechanisms::nearest_label(&mine);
        table.row(std::iter::once(a.to_string()).chain(cells).chain([nearest]));
    }
    md.push_str(&table.render());
    let identification = super::identify(&sigs);
    md.push_str(&identification_markdown(&identification));
    let mut files = vec![
        write("signatures.csv", &csv)?,
        write("mechanisms.csv", &mcsv)?,
        write("mechanisms.md", &md)?,
    ];
    files.extend(fingerprint_figure(&sigs, &out.join("fingerprints"))?);
    Ok(Written {
        files,
        signatures: sigs.len(),
        agents: agents.len(),
        identification,
    })
}

/// The leave-one-seed-out identification as Markdown: the confusion matrix, each
/// mechanism's self-distance range, and each agent's verdict on that scale.
pub fn identification_markdown(id: &super::Identification) -> String {
    let mut md = String::from(
        "\n## Identification (leave one seed out)\n\nEach mechanism seed held out in turn, the \
         fingerprints rebuilt from the other mechanism signatures (features in units of their \
         seed-to-seed SD within a mechanism, pooled over those), the held-out seed named by \
         its nearest fingerprint. Rows: true \
         mechanism; columns: named as. Self-distance: the held-out seeds' distances to their \
         own fingerprint (min–max); limit: the upper 99% prediction limit for a new seed's \
         self-distance (log-normal, spread pooled over the mechanisms); nearest other: their \
         smallest distance to another.\n\n",
    );
    let mut table = Table::new(["mechanism"].into_iter().chain(MECHANISMS).chain([
        "correct",
        "self-distance",
        "limit",
        "nearest other",
    ]));
    for m in MECHANISMS {
        let mine: Vec<&super::HeldOut> = id.held_out.iter().filter(|h| h.mechanism == m).collect();
        if mine.is_empty() {
            continue;
        }
        let cells: Vec<String> = MECHANISMS
            .iter()
            .map(|n| id.count(m, n).to_string())
            .collect();
        let range = id.self_range(m).map_or("–".into(), |(lo, hi)| {
            format!("{}–{}", fmt(lo, 2), fmt(hi, 2))
        });
        let other = mine
            .iter()
            .map(|h| h.other_distance)
            .fold(f64::INFINITY, f64::min);
        table.row(std::iter::once(m.to_string()).chain(cells).chain([
            format!("{}/{}", id.count(m, m), mine.len()),
            range,
            id.limit(m).map_or("–".into(), |l| fmt(l, 2)),
            fmt(other, 2),
        ]));
    }
    md.push_str(&table.render());
    md.push_str(
        "\nAgents on the same scale (fingerprints and SDs from every mechanism signature): \
         identified only when the distance to the nearest mechanism lies within that \
         mechanism's limit.\n\n",
    );
    let mut table = Table::new([
        "agent",
        "nearest",
        "distance",
        "its self-distance",
        "its limit",
        "verdict",
    ]);
    for a in &id.agents {
        let range = id.self_range(&a.nearest).map_or("–".into(), |(lo, hi)| {
            format!("{}–{}", fmt(lo, 2), fmt(hi, 2))
        });
        table.row([
            a.agent.clone(),
            a.nearest.clone(),
            fmt(a.distance, 2),
            range,
            id.limit(&a.nearest).map_or("–".into(), |l| fmt(l, 2)),
            if a.identified {
                "identified"
            } else {
                "not identified"
            }
            .to_string(),
        ]);
    }
    md.push_str(&table.render());
    md
}

/// The fingerprints as a heat map: one row per model (seed mean), one column per named
/// feature, each cell the feature's value in SDs from its mean over all signatures
/// (diverging colours, full at ±2 SD, the value printed); SVG and PNG at `stem`.
pub fn fingerprint_figure(sigs: &[Signature], stem: &Path) -> Result<Vec<PathBuf>, MechanismError> {
    use crate::figures::{LabelledMatrix, write_matrix};
    let sds = feature_sds(sigs.iter());
    let all: Vec<&Signature> = sigs.iter().collect();
    let centre = mean_features(&all);
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.dedup();
    let values = models
        .iter()
        .map(|m| {
            let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == *m).collect();
            let mean = mean_features(&mine);
            FEATURES
                .iter()
                .map(|f| {
                    let z = (|| Some((mean.get(f)? - centre.get(f)?) / sds.get(f)?))();
                    z.unwrap_or(f64::NAN)
                })
                .collect()
        })
        .collect();
    let matrix = LabelledMatrix {
        title: "Mechanism fingerprints: seed means in SDs from the mean of all signatures".into(),
        rows: models.iter().map(|m| m.to_string()).collect(),
        columns: FEATURES.iter().map(|f| f.to_string()).collect(),
        values,
        scale: 2.0,
    };
    write_matrix(stem, &matrix, (1300, 620)).map_err(|e| MechanismError::File {
        path: stem.to_path_buf(),
        message: e.to_string(),
    })
}
