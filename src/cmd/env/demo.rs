//! `env demo`: oracle vs random policy on every registered task from every free start cell
//! (and every trained TD), a GIF of one oracle episode per task and a summary table
//! (text + JSON).

use super::{RenderPolicy, play_episode};
use anyhow::Result;
use chronocooked_env::{ChronoEnv, ResetOptions, TaskFamily, all_tasks, render};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `env demo`.
#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Output folder for GIFs and the summary.
    #[arg(long, default_value = "lab-out/env-demo")]
    pub out: PathBuf,
    /// Base seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

/// TDs (and never-ready flags) a task is evaluated at in the demo, as its family declares
/// them.
fn conditions(env: &ChronoEnv) -> Vec<(u32, Option<bool>)> {
    env.config().demo_conditions()
}

/// Runs the demo.
pub fn run(args: DemoArgs) -> Result<()> {
    std::fs::create_dir_all(&args.out)?;
    println!("Chronocooked Lab demo: oracle vs random policy on every task, every start cell\n");
    println!(
        "{:<18} {:>9} {:>12} {:>12} {:>12} {:>12}",
        "task", "episodes", "oracle ret", "oracle len", "random ret", "random len"
    );
    let mut summary = Vec::new();
    let mut fi_ascii = String::new();
    for spec in all_tasks() {
        let mut env = ChronoEnv::new(&spec.default_config())?;
        let starts: Vec<(usize, usize)> = env.layout().free_coords();
        let mut stats = [(0.0f64, 0u64), (0.0f64, 0u64)];
        let mut episodes = 0u64;
        for (i, &(td, never_ready)) in conditions(&env).iter().enumerate() {
            for (j, &start) in starts.iter().enumerate() {
                let options = ResetOptions {
                    start: Some(start),
                    td: Some(td),
                    never_ready,
                    ..ResetOptions::default()
                };
                let seed = args.seed + (i * 1000 + j) as u64;
                for (k, policy) in [RenderPolicy::Oracle, RenderPolicy::Random]
                    .into_iter()
                    .enumerate()
                {
                    let (_, ret, len) = play_episode(&mut env, seed, &options, policy)?;
                    stats[k].0 += ret;
                    stats[k].1 += len as u64;
                }
                episodes += 1;
            }
        }
        let n = episodes as f64;
        println!(
            "{:<18} {:>9} {:>12.3} {:>12.1} {:>12.3} {:>12.1}",
            spec.id,
            episodes,
            stats[0].0 / n,
            stats[0].1 as f64 / n,
            stats[1].0 / n,
            stats[1].1 as f64 / n
        );
        // One oracle episode per task as a GIF (first condition, first start cell).
        let (td, never_ready) = conditions(&env)[0];
        let options = ResetOptions {
            start: Some(starts[starts.len() - 1]),
            td: Some(td),
            never_ready,
            ..ResetOptions::default()
        };
        let (frames, _, _) = play_episode(&mut env, args.seed, &options, RenderPolicy::Oracle)?;
        let images: Vec<_> = frames
            .iter()
            .map(|f| render::frame(env.layout(), env.family(), f))
            .collect();
        let gif = args.out.join(format!("{}.gif", spec.id));
        chronocooked_env::fs::write_atomic(&gif, &render::gif_bytes(&images, 25)?)?;
        summary.push(serde_json::json!({
            "task": spec.id,
            "episodes": episodes,
            "oracle_mean_return": stats[0].0 / n,
            "oracle_mean_length": stats[0].1 as f64 / n,
            "random_mean_return": stats[1].0 / n,
            "random_mean_length": stats[1].1 as f64 / n,
            "gif": gif,
        }));
        if spec.family == TaskFamily::FixedInterval {
            fi_ascii = format!(
                "\nLast frame of the FixedInterval-v0 oracle episode (@ agent, V oven, O onion, D delivery):\n{}",
                render::ascii(
                    env.layout(),
                    env.family(),
                    frames.last().expect("non-empty")
                )
                .lines()
                .map(|l| format!("    {l}"))
                .collect::<Vec<_>>()
                .join("\n")
            );
        }
    }
    println!("{fi_ascii}");
    let path = args.out.join("summary.json");
    chronocooked_env::fs::write_atomic(&path, serde_json::to_string_pretty(&summary)?.as_bytes())?;
    println!("\nGIFs and summary.json written to {}", args.out.display());
    Ok(())
}
