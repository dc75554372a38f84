//! The fingerprint tables and figure of a study (`chronocooked mechanisms RESULTS`).

use chronocooked_analysis::mechanisms::{
    ALL_FEATURES, Comparison, DYNAMICS_NEURAL, FEATURES, MECHANISMS, MechanismError, Scale,
    Signature, View, compare, feature_sds, mean_features, signatures,
};
use chronocooked_env::markdown::Table;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What [`write_tables`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// `signatures.csv`, `mechanisms.csv`, `mechanisms.md`, `pairwise.csv`,
    /// `fingerprints.svg`/`.png`.
    pub files: Vec<PathBuf>,
    /// Signatures (model × seed).
    pub signatures: usize,
    /// Agents compared.
    pub agents: usize,
    /// The leave-one-seed-out identification in each view compared, unit view first (also
    /// in `mechanisms.md`).
    pub identifications: Vec<chronocooked_analysis::mechanisms::Identification>,
    /// Views asked for but not compared: no signature holds any of their own features
    /// (the study's activity was recorded before the view existed).
    pub unrecorded: Vec<View>,
}

fn fmt(x: f64, digits: usize) -> String {
    if x.is_finite() {
        format!("{x:.digits$}")
    } else {
        "–".into()
    }
}

/// Reads the compact results under `results`, compares every agent with the
/// [`MECHANISMS`] in `views` (bootstrap of `resamples`, seeded) and writes into `out`:
/// `signatures.csv` (model, seed, every feature of both views), `mechanisms.csv` (view,
/// agent, mechanism, distance, nearest fraction, seeds), `pairwise.csv` (view, every
/// pair of model × seed signatures and their distance on the mechanisms' scale) and
/// `mechanisms.md` (the
/// fingerprints with seed spreads, then per view the agents' distances and nearest
/// mechanism, the leave-one-seed-out identification and every agent seed's verdict).
pub fn write_tables(
    results: &Path,
    out: &Path,
    resamples: usize,
    seed: u64,
    views: &[View],
) -> Result<Written, MechanismError> {
    let _lock =
        chronocooked_env::fs::FolderLock::acquire(out).map_err(|e| MechanismError::File {
            path: out.to_path_buf(),
            message: e.to_string(),
        })?;
    let sigs = signatures(results)?;
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
    let mut csv = format!("model,seed,{}\n", ALL_FEATURES.join(","));
    for s in &sigs {
        let row: Vec<String> = ALL_FEATURES
            .iter()
            .map(|f| s.features.get(*f).map_or(String::new(), |v| v.to_string()))
            .collect();
        csv.push_str(&format!("{},{},{}\n", s.model, s.seed, row.join(",")));
    }
    let mut mcsv = String::from(
        "view,agent,mechanism,distance,nearest_fraction,agent_seeds,mechanism_seeds\n",
    );
    // Markdown: fingerprints (mean ± SD over seeds), then the comparison per view.
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.dedup();
    let mut md = String::from("# Mechanism fingerprints\n\n");
    md.push_str(
        "Mean ± SD over training seeds (n). Unit view (basis-dependent): the behaviour and \
         the single-unit features; dynamics view (basis-free): the behaviour and the \
         population trajectory's features (`dyn_*`, the same in any orthogonal basis of \
         the units).\n\n",
    );
    for (title, features) in [
        ("Behaviour and unit features", &FEATURES[..]),
        (
            "Dynamics features (`dyn_scaling` recorded, not compared)",
            &DYNAMICS_TABLE[..],
        ),
    ] {
        md.push_str(&format!("### {title}\n\n"));
        md.push_str(&spread_table(&sigs, &models, features));
        md.push('\n');
    }
    let mut identifications = Vec::new();
    let mut agents_compared = 0;
    let (views, unrecorded): (Vec<View>, Vec<View>) =
        views.iter().partition(|v| v.recorded_in(&sigs));
    for &view in &unrecorded {
        md.push_str(&format!(
            "\n# {}\n\nNot compared: no signature of this study holds any of its own \
             features ({}); its activity was recorded before this view existed, and a \
             comparison would be one of the behaviour alone. Rerunning the study's record \
             stage (`chronocooked sweep FILE`) adds them.\n",
            view.title(),
            view.own_features().join(", ")
        ));
    }
    for &view in &views {
        let comparisons = compare(&sigs, &MECHANISMS, resamples, seed, view);
        for c in &comparisons {
            mcsv.push_str(&format!(
                "{},{},{},{},{},{},{}\n",
                view.key(),
                c.agent,
                c.mechanism,
                c.distance,
                c.nearest_fraction,
                c.seeds.0,
                c.seeds.1
            ));
        }
        md.push_str(&format!("\n# {}\n", view.title()));
        md.push_str(&format!(
            "\n## Nearest mechanism\n\nFeatures: {}. Distance: RMS of feature differences \
             in units of each feature's seed-to-seed SD within a mechanism (pooled over the \
             mechanisms; 1 = one seed SD on every feature); nearest: the share of \
             {resamples} bootstrap resamples of the seeds in which the mechanism is the \
             nearest.\n\n",
            view.features().join(", ")
        ));
        let mut table = Table::new(
            ["agent"]
                .into_iter()
                .chain(MECHANISMS)
                .chain(["nearest (bootstrap share)"]),
        );
        let mut agents: Vec<&str> = comparisons.iter().map(|c| c.agent.as_str()).collect();
        agents.dedup();
        agents_compared = agents.len();
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
            let nearest = chronocooked_analysis::mechanisms::nearest_label(&mine);
            table.row(std::iter::once(a.to_string()).chain(cells).chain([nearest]));
        }
        md.push_str(&table.render());
        let identification = chronocooked_analysis::mechanisms::identify(&sigs, view);
        md.push_str(&identification_markdown(&identification));
        md.push_str(&seed_verdicts_markdown(&sigs, &identification));
        identifications.push(identification);
    }
    let mut pairs = String::from("view,model_a,seed_a,model_b,seed_b,distance\n");
    for &view in &views {
        for p in chronocooked_analysis::mechanisms::pairwise(&sigs, view) {
            pairs.push_str(&format!(
                "{},{},{},{},{},{}\n",
                view.key(),
                p.a.0,
                p.a.1,
                p.b.0,
                p.b.1,
                p.distance
            ));
        }
    }
    let mut files = vec![
        write("signatures.csv", &csv)?,
        write("mechanisms.csv", &mcsv)?,
        write("mechanisms.md", &md)?,
        write("pairwise.csv", &pairs)?,
    ];
    files.extend(fingerprint_figure(&sigs, &out.join("fingerprints"))?);
    Ok(Written {
        files,
        signatures: sigs.len(),
        agents: agents_compared,
        identifications,
        unrecorded,
    })
}

/// The dynamics features of the fingerprint table: the compared ones and `dyn_scaling`.
const DYNAMICS_TABLE: [&str; 8] = [
    DYNAMICS_NEURAL[0],
    DYNAMICS_NEURAL[1],
    DYNAMICS_NEURAL[2],
    DYNAMICS_NEURAL[3],
    DYNAMICS_NEURAL[4],
    DYNAMICS_NEURAL[5],
    DYNAMICS_NEURAL[6],
    "dyn_scaling",
];

/// Mean ± SD over seeds of `features` per model, as a Markdown table. A feature no
/// signature holds gets no column; the line under the table names it (a study recorded
/// before the feature existed, or read without its scaling runs).
fn spread_table(sigs: &[Signature], models: &[&str], features: &[&str]) -> String {
    let (features, missing): (Vec<&str>, Vec<&str>) = features
        .iter()
        .partition(|f| sigs.iter().any(|s| s.features.contains_key(**f)));
    let mut table = Table::new(["model", "n"].into_iter().chain(features.iter().copied()));
    for m in models {
        let mine: Vec<&Signature> = sigs.iter().filter(|s| s.model == *m).collect();
        let cells: Vec<String> = features
            .iter()
            .map(|f| {
                let sp = chronocooked_analysis::stats::Spread::of(
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
    let mut md = table.render();
    if !missing.is_empty() {
        md.push_str(&format!(
            "\nNot recorded in this study: {} (no signature holds them: the activity was \
             recorded before these features existed, or, for the scaling features, the \
             study was read without `--scaling-from`).\n",
            missing
                .iter()
                .map(|f| format!("`{f}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    md
}

/// Every agent seed's own verdict (a verdict per model hides seeds that differ: Eissa et
/// al. 2025): its nearest mechanism, distance and that mechanism's limit, then per agent
/// how many seeds are nearest which mechanism and how many are identified.
pub fn seed_verdicts_markdown(
    sigs: &[Signature],
    id: &chronocooked_analysis::mechanisms::Identification,
) -> String {
    let verdicts = chronocooked_analysis::mechanisms::seed_verdicts(sigs, id);
    if verdicts.is_empty() {
        return String::new();
    }
    let mut md = String::from(
        "\nEvery agent seed on its own (its signature against the mechanisms' fingerprints, \
         same scale and limits):\n\n",
    );
    let mut table = Table::new([
        "agent",
        "seed",
        "nearest",
        "distance",
        "its limit",
        "verdict",
    ]);
    for v in &verdicts {
        table.row([
            v.agent.clone(),
            v.seed.to_string(),
            v.nearest.clone(),
            fmt(v.distance, 2),
            id.limit(&v.nearest).map_or("–".into(), |l| fmt(l, 2)),
            if v.identified {
                "identified"
            } else {
                "not identified"
            }
            .to_string(),
        ]);
    }
    md.push_str(&table.render());
    let mut agents: Vec<&str> = verdicts.iter().map(|v| v.agent.as_str()).collect();
    agents.dedup();
    let mut summary = Table::new([
        "agent",
        "seeds",
        "nearest (seeds)",
        "identified",
        "distance / limit (min–max)",
    ]);
    for a in agents {
        let mine: Vec<_> = verdicts.iter().filter(|v| v.agent == a).collect();
        let mut nearest: Vec<(String, usize)> = Vec::new();
        for v in &mine {
            match nearest.iter_mut().find(|(m, _)| *m == v.nearest) {
                Some(slot) => slot.1 += 1,
                None => nearest.push((v.nearest.clone(), 1)),
            }
        }
        nearest.sort_by(|x, y| y.1.cmp(&x.1).then(x.0.cmp(&y.0)));
        let ratios: Vec<f64> = mine
            .iter()
            .filter_map(|v| id.limit(&v.nearest).map(|l| v.distance / l))
            .collect();
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
                (lo.min(*r), hi.max(*r))
            });
        summary.row([
            a.to_string(),
            mine.len().to_string(),
            nearest
                .iter()
                .map(|(m, n)| format!("{m} {n}"))
                .collect::<Vec<_>>()
                .join(", "),
            format!(
                "{}/{}",
                mine.iter().filter(|v| v.identified).count(),
                mine.len()
            ),
            if ratios.is_empty() {
                "–".into()
            } else {
                format!("{}–{}", fmt(lo, 2), fmt(hi, 2))
            },
        ]);
    }
    md.push('\n');
    md.push_str(&summary.render());
    md
}

/// The leave-one-seed-out identification as Markdown: the confusion matrix, each
/// mechanism's self-distance range, and each agent's verdict on that scale.
pub fn identification_markdown(id: &chronocooked_analysis::mechanisms::Identification) -> String {
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
        let mine: Vec<&chronocooked_analysis::mechanisms::HeldOut> =
            id.held_out.iter().filter(|h| h.mechanism == m).collect();
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

/// Caption of [`placed_fingerprint_figure`].
pub const PLACED_FINGERPRINT_CAPTION: &str = "Each model of this report (bottom rows, seed means) beside the committed timing mechanisms (top rows: seed means of results/mechanisms-reference, 8 seeds each): every feature of both views, in within-mechanism seed SDs from the mechanisms' mean, the units the distances are measured in (colour full at ±2; – a feature the model lacks). The table below gives each model's nearest mechanism, its distance and that mechanism's identification limit, in each view.";

/// The report's fingerprint figure: the committed mechanisms' seed means (`reference`, one
/// row each, labelled with their seed counts) above the report's models (`sigs`, seed
/// means), one column per feature of the unit view then the dynamics view's own, each cell
/// the feature in within-mechanism seed SDs (pooled over the [`MECHANISMS`],
/// as the distances are) from the mechanisms' mean. SVG and PNG at `stem`, drawn at the
/// width the report shows it (1300 px), so its text is read at its own size.
pub fn placed_fingerprint_figure(
    sigs: &[Signature],
    reference: &[Signature],
    stem: &Path,
) -> Result<Vec<PathBuf>, MechanismError> {
    use crate::figures::{LabelledMatrix, write_matrix};
    let refs: Vec<&Signature> = reference.iter().collect();
    let mut columns: Vec<&'static str> = View::Units.features().to_vec();
    for f in View::Dynamics.features() {
        if !columns.contains(f) {
            columns.push(f);
        }
    }
    let mut sds: BTreeMap<&'static str, f64> = BTreeMap::new();
    for view in View::ALL {
        sds.extend(Scale::of(&refs, &MECHANISMS, view).sds().clone());
    }
    let group_mean = |model: &str, pool: &[&Signature]| {
        let mine: Vec<&Signature> = pool.iter().copied().filter(|s| s.model == model).collect();
        (mine.len(), mean_features(&mine))
    };
    let mechanism_means: Vec<(&str, usize, BTreeMap<&'static str, f64>)> = MECHANISMS
        .iter()
        .map(|m| {
            let (n, mean) = group_mean(m, &refs);
            (*m, n, mean)
        })
        .filter(|(_, n, _)| *n > 0)
        .collect();
    let centre: BTreeMap<&'static str, f64> = columns
        .iter()
        .filter_map(|f| {
            let v: Vec<f64> = mechanism_means
                .iter()
                .filter_map(|m| m.2.get(f).copied())
                .collect();
            (!v.is_empty()).then(|| (*f, v.iter().sum::<f64>() / v.len() as f64))
        })
        .collect();
    let z = |mean: &BTreeMap<&'static str, f64>| -> Vec<f64> {
        columns
            .iter()
            .map(|f| {
                (|| Some((mean.get(f)? - centre.get(f)?) / sds.get(f).filter(|s| **s > 0.0)?))()
                    .unwrap_or(f64::NAN)
            })
            .collect()
    };
    let mut rows = Vec::new();
    let mut values = Vec::new();
    for (m, n, mean) in &mechanism_means {
        rows.push(format!("{m} (study, {n} seeds)"));
        values.push(z(mean));
    }
    let own: Vec<&Signature> = sigs.iter().collect();
    let mut models: Vec<&str> = sigs.iter().map(|s| s.model.as_str()).collect();
    models.sort_unstable();
    models.dedup();
    for m in models {
        let (n, mean) = group_mean(m, &own);
        let seeds = if n == 1 {
            "1 seed".to_string()
        } else {
            format!("{n} seeds")
        };
        rows.push(format!("{m} (this report, {seeds})"));
        values.push(z(&mean));
    }
    let height = 70 + 34 * rows.len() as u32 + 210;
    let matrix = LabelledMatrix {
        title:
            "Fingerprints beside the committed mechanisms: features in within-mechanism seed SDs"
                .into(),
        rows,
        columns: columns.iter().map(|f| f.to_string()).collect(),
        values,
        scale: 2.0,
    };
    write_matrix(stem, &matrix, (1300, height)).map_err(|e| MechanismError::File {
        path: stem.to_path_buf(),
        message: e.to_string(),
    })
}

/// The fingerprints as a heat map: one row per model (seed mean), one column per feature of
/// the unit view then the dynamics view's own that any signature holds (a study recorded
/// before the dynamics view draws the unit view alone), each cell the feature's value in
/// SDs from its mean over all signatures (diverging colours, full at ±2 SD, the value
/// printed); SVG and PNG at `stem`.
pub fn fingerprint_figure(sigs: &[Signature], stem: &Path) -> Result<Vec<PathBuf>, MechanismError> {
    use crate::figures::{LabelledMatrix, write_matrix};
    let mut columns: Vec<&'static str> = View::Units.features().to_vec();
    for f in View::Dynamics.features() {
        if !columns.contains(f) && sigs.iter().any(|s| s.features.contains_key(*f)) {
            columns.push(f);
        }
    }
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
            columns
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
        columns: columns.iter().map(|f| f.to_string()).collect(),
        values,
        scale: 2.0,
    };
    write_matrix(stem, &matrix, (1300, 620)).map_err(|e| MechanismError::File {
        path: stem.to_path_buf(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::{fingerprint_figure, placed_fingerprint_figure, spread_table};
    use chronocooked_analysis::mechanisms::*;

    /// A report model whose seed mean is a mechanism's seed mean is drawn with that
    /// mechanism's values: the figure places it on the committed study's scale, and the
    /// mechanisms' rows come first, each with its seed count.
    #[test]
    fn the_placed_figure_draws_a_model_on_the_mechanisms_scale() {
        let reference = crate::fingerprint::reference_signatures();
        let ddm: Vec<&Signature> = reference.iter().filter(|s| s.model == "ddm").collect();
        let mean = mean_features(&ddm);
        let copy = Signature {
            model: "my-agent".into(),
            seed: 0,
            features: mean.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        };
        let dir = tempfile::tempdir().unwrap();
        let files = placed_fingerprint_figure(&[copy], &reference, &dir.path().join("fp")).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        let at = |text: &str| svg.find(text).unwrap_or_else(|| panic!("{text} missing"));
        assert!(at("ddm (study, 8 seeds)") < at("timecells-laplace (study, 8 seeds)"));
        assert!(at("timecells-laplace (study, 8 seeds)") < at("my-agent (this report, 1 seed)"));
        for f in View::Units
            .features()
            .iter()
            .chain(View::Dynamics.features())
        {
            at(&format!(">\n{f}\n<"));
        }
        // The copy's row repeats the ddm row's printed values, cell for cell.
        let texts: Vec<&str> = svg
            .split("</text>")
            .filter_map(|t| t.rsplit('>').next())
            .collect();
        let mut columns: Vec<&str> = View::Units.features().to_vec();
        columns.extend(
            View::Dynamics
                .features()
                .iter()
                .filter(|f| !View::Units.features().contains(f)),
        );
        let row = |name: &str| {
            let i = texts.iter().position(|t| t.contains(name)).unwrap();
            texts[i + 1..i + 1 + columns.len()].to_vec()
        };
        assert_eq!(row("ddm (study"), row("my-agent"));
    }

    /// A feature no signature holds gets no column and is named under the table; a feature
    /// one model lacks keeps its column with "–" in that model's row; mean ± SD by hand.
    #[test]
    fn the_spread_table_drops_unrecorded_features_and_names_them() {
        let sig = |model: &str, seed: u64, feats: &[(&str, f64)]| Signature {
            model: model.into(),
            seed,
            features: feats.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        };
        let sigs = [
            sig("a", 0, &[("x", 1.0), ("y", 2.0)]),
            sig("a", 1, &[("x", 3.0), ("y", 2.0)]),
            sig("b", 0, &[("x", 5.0)]),
        ];
        let md = spread_table(&sigs, &["a", "b"], &["x", "y", "z", "w"]);
        let lines: Vec<&str> = md.lines().collect();
        assert_eq!(lines[0], "| model | n | x | y |");
        // x over seeds 1 and 3: mean 2, sample SD √2 = 1.414.
        assert_eq!(lines[2], "| a | 2 | 2.000 ± 1.414 | 2.000 ± 0.000 |");
        assert_eq!(lines[3], "| b | 1 | 5.000 ± – | – |");
        assert!(md.contains("Not recorded in this study: `z`, `w`"), "{md}");
        let full = spread_table(&sigs[..2], &["a"], &["x", "y"]);
        assert!(!full.contains("Not recorded"), "{full}");
    }

    /// The study figure draws a dynamics column only when a signature holds the feature: the
    /// unit view's columns always, `dyn_dimension` when recorded, never an empty one.
    #[test]
    fn the_study_figure_draws_the_dynamics_features_a_study_recorded() {
        let dir = tempfile::tempdir().unwrap();
        let draw = |with_dynamics: bool, name: &str| {
            let sigs: Vec<Signature> = (0..2)
                .map(|seed| {
                    let mut features: std::collections::BTreeMap<String, f64> = FEATURES
                        .iter()
                        .map(|f| (f.to_string(), seed as f64))
                        .collect();
                    if with_dynamics {
                        features.insert("dyn_dimension".into(), 2.0 + seed as f64);
                    }
                    Signature {
                        model: format!("m{seed}"),
                        seed,
                        features,
                    }
                })
                .collect();
            let files = fingerprint_figure(&sigs, &dir.path().join(name)).unwrap();
            std::fs::read_to_string(&files[0]).unwrap()
        };
        let label = |f: &str| format!(">\n{f}\n<");
        let with = draw(true, "with");
        let without = draw(false, "without");
        for f in FEATURES {
            assert!(
                with.contains(&label(f)) && without.contains(&label(f)),
                "{f}"
            );
        }
        assert!(with.contains(&label("dyn_dimension")));
        assert!(!without.contains(&label("dyn_dimension")));
        assert!(!with.contains(&label("dyn_rotation")));
    }
}
