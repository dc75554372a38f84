//! `eval`: play the evaluation protocol of a task with any agent and write per-episode
//! records and the metrics; `eval --from DIR` recomputes the metrics from saved records.

use anyhow::{Result, bail};
use chronocooked_analysis::Mode;
use chronocooked_env::Task;
use chronocooked_pipeline::stages::{self, EvalOutcome, EvalRequest, EvalSubject};
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Run folder of a trained agent (PPO or timing model), or a zoo agent
    /// (`zoo:<model>/<task>`, see `zoo list`).
    #[arg(long, conflicts_with_all = ["agent", "from"])]
    pub run: Option<PathBuf>,
    /// A reference agent instead of a run: oracle or random; on the reproduction task also a
    /// Bayesian observer `bls`, `map` or `ml`, with its noise as `bls:WM,WP` (default 0.1,0.06).
    #[arg(long, conflicts_with = "from")]
    pub agent: Option<String>,
    /// Task the agent was trained on (default: the run's; FixedInterval-v0 for --agent).
    #[arg(long)]
    pub task: Option<String>,
    /// Task parameters `key=value`: of --task, else of the run's own task (or of
    /// FixedInterval-v0 for --agent).
    #[arg(long = "env", value_name = "KEY=VALUE")]
    pub task_params: Vec<String>,
    /// Stochastic protocol: N episodes per condition (sampled actions) instead of greedy
    /// episodes from every start cell (1–10,000: the paper's protocol plays 100; every
    /// episode's steps are kept in memory for the metrics).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=chronocooked_analysis::evaluation::protocol::MAX_STOCHASTIC_EPISODES as u64))]
    pub stochastic: Option<u64>,
    /// Seed of the evaluation (its noise draws and stochastic start cells). Default: the
    /// run's training seed, so replicate runs are evaluated with independent draws and a
    /// rerun gives the same result; 0 for `--agent` and `--human`.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Metrics of recorded human play (`env play --record FILE`, JSON lines).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["run", "agent", "from"])]
    pub human: Option<PathBuf>,
    /// Recompute metrics.json from the records of an earlier `eval` output folder.
    #[arg(long, value_name = "DIR")]
    pub from: Option<PathBuf>,
    /// Output folder (records.jsonl, eval.json, metrics.json).
    #[arg(long, default_value = "eval")]
    pub out: PathBuf,
    /// Also record the model's activity during the protocol: `activity.json` and its NPZ
    /// export `activity/` in the output folder, one trial per evaluated episode (what
    /// `export --format nwb` pairs with the episodes).
    #[arg(long)]
    pub activity: bool,
    /// Evaluate a run whose training did not finish (stopped, killed, out of disk) from its
    /// newest checkpoint; `eval.json` records the step (`unfinished_at_step`). Without it,
    /// such a run is refused.
    #[arg(long, requires = "run")]
    pub unfinished: bool,
}

fn report(out: &Path, outcome: &EvalOutcome) {
    use chronocooked_analysis::columns::{COLUMNS, Value};
    let m = &outcome.metrics;
    println!(
        "{}: {} episodes → {} ({} figure files)",
        m.model,
        m.episodes,
        out.join(chronocooked_present::eval_folder::METRICS)
            .display(),
        outcome.figures.len()
    );
    // The task's own measures: the leaderboard's columns this evaluation has.
    for c in &COLUMNS {
        if let Value::Run(f) = c.value
            && let Some(v) = f(m)
        {
            println!("  {}, {}: {v:.3}  ({})", c.group, c.title, c.doc);
        }
    }
    println!(
        "  rewarded episodes: {:.1}% of all {} (every condition of the protocol pooled, \
         probes included; the lines above are the task's measures)",
        m.success_rate * 100.0,
        m.episodes
    );
    if let Some((trials, units, file)) = &outcome.activity {
        println!(
            "activity: {trials} trials × {units} units → {}",
            file.display()
        );
    }
}

/// Runs `eval`.
pub fn run(args: EvalArgs) -> Result<()> {
    let outcome = if let Some(dir) = &args.from {
        stages::rescore_eval_folder(dir, &args.out)?
    } else if let Some(file) = &args.human {
        stages::evaluate_human(file, args.seed.unwrap_or(0), &args.out)?
    } else {
        let subject = match (&args.run, &args.agent) {
            (Some(run), _) => EvalSubject::Run(crate::cmd::zoo_agents::resolve_run(run)?),
            (None, Some(name)) => EvalSubject::Reference(name.clone()),
            (None, None) => {
                bail!("say what to evaluate: --run DIR, --agent oracle|random, or --from DIR")
            }
        };
        let seed = args.seed.unwrap_or_else(|| match &subject {
            EvalSubject::Run(dir) => chronocooked_training::RunFolder::open(dir)
                .ok()
                .and_then(|r| r.seed)
                .unwrap_or(0),
            EvalSubject::Reference(_) => 0,
        });
        let task = match (&args.task, &subject) {
            (Some(id), _) => Some(Task::parse(id, &args.task_params)?),
            (None, _) if args.task_params.is_empty() => None,
            (None, EvalSubject::Run(dir)) => Some(
                chronocooked_training::RunFolder::open(dir)?
                    .task
                    .with(&args.task_params)?,
            ),
            (None, EvalSubject::Reference(_)) => {
                Some(Task::parse("FixedInterval-v0", &args.task_params)?)
            }
        };
        stages::evaluate(&EvalRequest {
            subject,
            task,
            mode: match args.stochastic {
                Some(n) => Mode::Stochastic {
                    episodes: n as usize,
                },
                None => Mode::Reference,
            },
            seed,
            out: args.out.clone(),
            activity: args.activity,
            unfinished: args.unfinished,
        })?
    };
    report(&args.out, &outcome);
    Ok(())
}
