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
    #[arg(long, required_unless_present = "sweep", num_args = 1..)]
    pub run: Vec<PathBuf>,
    /// Instead of `--run`: every agent (model × seed) of a sweep's output folder, from its
    /// finished jobs of the protocol's conditions (as `sweeps/mechanisms-heldout.toml`
    /// trains them), each into `OUT/<model>-<seed>/` with the default seed, and one line per
    /// agent in `OUT/fingerprints.txt`. Rerunning places finished agents again from their
    /// recorded signatures.
    #[arg(long, value_name = "SWEEP_OUT", conflicts_with_all = ["run", "name", "seed"])]
    pub sweep: Option<PathBuf>,
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
    if let Some(sweep) = &args.sweep {
        return run_sweep(sweep, &args);
    }
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
            let distance = if d.distance.is_finite() {
                format!("{:5.2}", d.distance)
            } else {
                "    –".to_string()
            };
            println!(
                "    {:<18} distance {distance}  its own seeds {}  limit {}  bootstrap share {:.2}",
                d.mechanism,
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

/// `fingerprint --sweep`: every agent of a sweep's output, one line each.
fn run_sweep(sweep: &std::path::Path, args: &FingerprintArgs) -> Result<()> {
    use chronocooked_pipeline::stages::{fingerprint_sweep, sweep_line};
    let agents = fingerprint_sweep(sweep, &args.out, args.resamples as usize)?;
    let mut text = String::new();
    for a in &agents {
        let line = sweep_line(a);
        println!("{line}");
        text.push_str(&line);
        text.push('\n');
    }
    let file = args.out.join("fingerprints.txt");
    chronocooked_env::fs::write_atomic(&file, text.as_bytes())?;
    let reused = agents.iter().filter(|a| a.reused).count();
    println!(
        "{} agents ({} played now, {reused} placed again from their folders) → {}",
        agents.len(),
        agents.len() - reused,
        file.display()
    );
    Ok(())
}
