//! `fingerprint`: which timing mechanism do trained runs of one agent resemble? The runs
//! (fixed interval TD 6 / TD 12, bisection 4-12; any subset) play the mechanisms protocol
//! and the agent's signature is placed among the committed timing mechanisms. They are
//! compared with mechanisms trained as `sweeps/mechanisms-reference.toml` trains them
//! (fixed interval with `stop_at_success=none`, bisection stopping at 0.95): train the
//! runs the same way for a like-for-like comparison (a timing model stopped at its first
//! solution behaves differently).

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `fingerprint`.
#[derive(Args, Debug)]
pub struct FingerprintArgs {
    /// Run folders (or `zoo:<model>/<task>`) of one agent, one per protocol condition it
    /// has: fixed interval TD 6, fixed interval TD 12, bisection 4-12 (matched by each
    /// run's task and settings; missing conditions leave their features out).
    #[arg(long, required = true, num_args = 1..)]
    pub run: Vec<PathBuf>,
    /// Output folder (condition folders, fingerprint.{md,html,png,json}).
    #[arg(long)]
    pub out: PathBuf,
    /// The agent's name in the outputs (default: the runs' model).
    #[arg(long)]
    pub name: Option<String>,
    /// Seed of the protocol's episodes, the category tests and the bootstrap.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Bootstrap resamples of the mechanisms' seeds (1–100,000).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub resamples: u64,
}

/// Runs `fingerprint`.
pub fn run(args: FingerprintArgs) -> Result<()> {
    let runs = args
        .run
        .iter()
        .map(|r| crate::cmd::zoo_agents::resolve_run(r))
        .collect::<Result<Vec<_>>>()?;
    let r = chronocooked_pipeline::stages::fingerprint(
        &chronocooked_pipeline::stages::FingerprintRequest {
            runs,
            name: args.name.clone(),
            seed: args.seed,
            resamples: args.resamples as usize,
            out: args.out.clone(),
        },
    )?;
    let f = &r.placement;
    println!("{} ({})", f.model(), r.conditions.join(", "));
    for p in f.views() {
        println!("  {}", chronocooked_present::fingerprint::verdict(p));
        for d in &p.distances {
            println!(
                "    {:<18} distance {:5.2}  its own seeds {}  limit {}  bootstrap share {:.2}",
                d.mechanism,
                d.distance,
                d.self_range
                    .map_or("–".into(), |(lo, hi)| format!("{lo:.2}–{hi:.2}")),
                d.limit.map_or("–".into(), |l| format!("{l:.2}")),
                d.bootstrap_share
            );
        }
        if !p.missing.is_empty() {
            println!("    missing features: {}", p.missing.join(", "));
        }
    }
    println!("  {}.", chronocooked_present::fingerprint::agreement(f));
    println!("wrote {}", args.out.join("fingerprint.html").display());
    Ok(())
}
