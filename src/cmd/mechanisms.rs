//! `mechanisms`: which timing mechanism each trained agent resembles — the fingerprints of a
//! study's compact results (`paper collect` output) and the nearest mechanism per agent.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `mechanisms`.
#[derive(Args, Debug)]
pub struct MechanismsArgs {
    /// Compact results of a study (e.g. results/mechanisms, written by `paper collect`).
    pub results: PathBuf,
    /// Output folder (signatures.csv, mechanisms.csv, mechanisms.md; default: the results
    /// folder).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Bootstrap resamples of the seeds (1–100,000: the default 1,000 gives a share to
    /// ±0.02; 100,000 already takes minutes).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub resamples: u64,
    /// Seed of the bootstrap.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// A sweep's output folder (e.g. lab-out/mechanisms) whose fixed-interval runs of each
    /// model and seed at two or more TDs are first recorded together on probe trials, for
    /// the temporal-scaling feature; the compact summaries go to `<results>/scaling/`
    /// (groups already there are skipped).
    #[arg(long, value_name = "SWEEP_OUT")]
    pub scaling_from: Option<PathBuf>,
    /// Which views to compare in: `units` (single-unit categories, basis-dependent),
    /// `dynamics` (the population trajectory, basis-free) or `both`.
    #[arg(long, value_enum, default_value_t = ViewArg::Both)]
    pub view: ViewArg,
}

/// The views `mechanisms` compares in.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ViewArg {
    /// The unit view only.
    Units,
    /// The dynamics view only.
    Dynamics,
    /// Both, side by side.
    Both,
}

impl ViewArg {
    fn views(self) -> Vec<chronocooked_analysis::mechanisms::View> {
        use chronocooked_analysis::mechanisms::View;
        match self {
            ViewArg::Units => vec![View::Units],
            ViewArg::Dynamics => vec![View::Dynamics],
            ViewArg::Both => View::ALL.to_vec(),
        }
    }
}

/// Runs `mechanisms`.
pub fn run(args: MechanismsArgs) -> Result<()> {
    let out = args.out.clone().unwrap_or_else(|| args.results.clone());
    if let Some(study) = &args.scaling_from {
        let s = chronocooked_pipeline::stages::record_scaling(study, &args.results)?;
        println!(
            "scaling: {} model x seed groups recorded, {} already there",
            s.recorded.len(),
            s.skipped
        );
    }
    let w = chronocooked_present::mechanisms::write_tables(
        &args.results,
        &out,
        args.resamples as usize,
        args.seed,
        &args.view.views(),
    )?;
    println!(
        "{} signatures (model x seed), {} agents compared with the timing mechanisms; wrote {}",
        w.signatures,
        w.agents,
        w.files
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    for view in &w.unrecorded {
        println!(
            "{}: not compared (no signature holds any of its own features: {}; the study was \
             recorded before this view existed)",
            view.title(),
            view.own_features().join(", ")
        );
    }
    for id in &w.identifications {
        println!("{}:", id.view.title());
        print_identification(id);
        let unplaced = w.agents.saturating_sub(id.agents.len());
        if unplaced > 0 {
            println!(
                "  {unplaced} of {} agents: no verdict: they share no feature with the \
                 mechanisms (every feature is measured on timed responses, which an agent \
                 trained on a short budget does not make yet)",
                w.agents
            );
        }
    }
    let mut mechanisms: Vec<&str> = w
        .identifications
        .first()
        .map(|id| id.held_out.iter().map(|h| h.mechanism.as_str()).collect())
        .unwrap_or_default();
    mechanisms.sort_unstable();
    mechanisms.dedup();
    if mechanisms.len() < 2 {
        println!(
            "note: this study has {} timing mechanism(s) ({}): naming a held-out seed needs \
             two or more, with several seeds each. To place an agent among the committed \
             mechanisms ({}), fingerprint its run: chronocooked fingerprint --run DIR",
            mechanisms.len(),
            if mechanisms.is_empty() {
                "none".to_string()
            } else {
                mechanisms.join(", ")
            },
            chronocooked_present::fingerprint::REFERENCE_SOURCE
        );
    }
    Ok(())
}

/// The leave-one-seed-out identification and the agents' verdicts of one view.
fn print_identification(id: &chronocooked_analysis::mechanisms::Identification) {
    let mut mechs: Vec<&str> = id.held_out.iter().map(|h| h.mechanism.as_str()).collect();
    mechs.dedup();
    let held: Vec<String> = mechs
        .iter()
        .map(|m| {
            let n = id.held_out.iter().filter(|h| h.mechanism == *m).count();
            let range = id
                .self_range(m)
                .map_or(String::new(), |(lo, hi)| format!(", self {lo:.2}–{hi:.2}"));
            let limit = id
                .limit(m)
                .map_or(String::new(), |l| format!(", limit {l:.2}"));
            format!("{m} {}/{n}{range}{limit}", id.count(m, m))
        })
        .collect();
    println!(
        "  identification, leave one seed out (held-out seeds named as their own mechanism): {}",
        held.join("; ")
    );
    for a in &id.agents {
        let range = id
            .self_range(&a.nearest)
            .map_or(String::new(), |(lo, hi)| format!("{lo:.2}–{hi:.2}"));
        let limit = id
            .limit(&a.nearest)
            .map_or("–".into(), |l| format!("{l:.2}"));
        println!(
            "  {}: {} (nearest {}, distance {:.2}; its limit {limit}, its seeds lie {range} \
             from it)",
            a.agent,
            if a.identified {
                "identified"
            } else {
                "not identified"
            },
            a.nearest,
            a.distance
        );
    }
}
