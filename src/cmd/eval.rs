//! `eval`: play the evaluation protocol of a task with any agent and write per-episode
//! records and the metrics; `eval --from DIR` recomputes the metrics from saved records.

use anyhow::{Context, Result, bail};
use chronocooked_analysis::evaluation::folder::{self as eval_folder, EvalInfo};
use chronocooked_analysis::{EvalRecord, Mode, reference_conditions, run_protocol_recorded};
use chronocooked_env::ChronoEnv;
use chronocooked_models::Agent;
use chronocooked_models::activity::{ActivityMeta, TrialRecorder};
use chronocooked_models::agent::{OracleAgent, RandomAgent};
use chronocooked_training::timing_run::load_agent;
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `eval`.
#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Run folder of a trained agent (PPO or timing model).
    #[arg(long, conflicts_with_all = ["agent", "from"])]
    pub run: Option<PathBuf>,
    /// A reference agent instead of a run: oracle or random.
    #[arg(long, conflicts_with = "from")]
    pub agent: Option<String>,
    /// Task the agent was trained on (default: the run's; FixedInterval-v0 for --agent).
    #[arg(long)]
    pub task: Option<String>,
    /// Task overrides `key=value` (with --task).
    #[arg(long = "env", value_name = "KEY=VALUE")]
    pub env: Vec<String>,
    /// Stochastic protocol: N episodes per condition (sampled actions) instead of greedy
    /// episodes from every start cell.
    #[arg(long)]
    pub stochastic: Option<usize>,
    /// Seed of the evaluation.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
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
}

fn write_metrics(out: &Path, info: &EvalInfo, records: &[EvalRecord]) -> Result<()> {
    let (metrics, figures) =
        eval_folder::write_metrics(out, info, records).map_err(anyhow::Error::msg)?;
    report(out, &metrics, figures.len());
    Ok(())
}

fn report(out: &Path, metrics: &chronocooked_analysis::Metrics, figures: usize) {
    println!(
        "{}: {} episodes, success {:.1}% → {} ({} figure files)",
        metrics.model,
        metrics.episodes,
        metrics.success_rate * 100.0,
        out.join("metrics.json").display(),
        figures
    );
}

/// Runs `eval`.
pub fn run(args: EvalArgs) -> Result<()> {
    if let Some(dir) = &args.from {
        let info = eval_folder::read_eval_info(dir).map_err(anyhow::Error::msg)?;
        let records = chronocooked_analysis::evaluation::protocol::read_records(dir)
            .map_err(|e| anyhow::anyhow!("{e} (not an eval folder)"))?;
        return write_metrics(&args.out, &info, &records);
    }
    if let Some(file) = &args.human {
        let text =
            std::fs::read_to_string(file).with_context(|| format!("reading {}", file.display()))?;
        let records = chronocooked_analysis::behaviour::human::records_from_trace(&text)
            .map_err(|e| anyhow::anyhow!("{}: {e}", file.display()))?;
        if records.is_empty() {
            bail!(
                "{} holds no episodes (record some with `env play --record`)",
                file.display()
            );
        }
        let first = &records[0].condition;
        let info = EvalInfo {
            model: "human".into(),
            task: first.task.clone(),
            env: first.env.clone(),
            mode: Mode::Stochastic {
                episodes: records.len(),
            },
            seed: args.seed,
        };
        return write_outputs(&args.out, &info, &records);
    }
    let (task, env) = match (&args.task, &args.run) {
        (Some(t), _) => (t.clone(), args.env.clone()),
        (None, Some(run)) => chronocooked_training::timing_run::run_task(run)?,
        (None, None) => ("FixedInterval-v0".to_string(), args.env.clone()),
    };
    let config = chronocooked_env::make_config(&task, &env)?;
    let mut agent: Box<dyn Agent> = match (&args.run, args.agent.as_deref()) {
        (Some(run), _) => load_agent(run, Some(&config))?,
        (None, Some("oracle")) => Box::new(OracleAgent::new(&ChronoEnv::new(&config)?)),
        (None, Some("random")) => Box::new(RandomAgent::default()),
        (None, Some(other)) => bail!(
            "unknown --agent `{other}` (allowed: oracle, random; trained models via --run DIR)"
        ),
        (None, None) => {
            bail!("say what to evaluate: --run DIR, --agent oracle|random, or --from DIR")
        }
    };
    let mode = match args.stochastic {
        Some(0) => bail!("--stochastic needs a positive number of episodes per condition"),
        Some(n) => Mode::Stochastic { episodes: n },
        None => Mode::Reference,
    };
    let conditions = reference_conditions(&task, &env)?;
    let meta = ActivityMeta::new(&agent.name(), &task, &env, args.seed);
    let mut recorder = TrialRecorder::new(meta);
    let records = run_protocol_recorded(
        agent.as_mut(),
        &conditions,
        mode,
        args.seed,
        args.activity.then_some(&mut recorder),
    )?;
    let info = EvalInfo {
        model: agent.name(),
        task,
        env,
        mode,
        seed: args.seed,
    };
    write_outputs(&args.out, &info, &records)?;
    if args.activity {
        let dataset = recorder.finish();
        if dataset.meta.n_units() == 0 {
            bail!(
                "{} records no activity (reference agents have no units); drop --activity",
                info.model
            );
        }
        let files = eval_folder::write_activity(&args.out, &dataset).map_err(anyhow::Error::msg)?;
        println!(
            "activity: {} trials × {} units → {}",
            dataset.trials.len(),
            dataset.meta.n_units(),
            files[0].display()
        );
    }
    Ok(())
}

fn write_outputs(out: &Path, info: &EvalInfo, records: &[EvalRecord]) -> Result<()> {
    let (metrics, figures) =
        eval_folder::write_eval_folder(out, info, records).map_err(anyhow::Error::msg)?;
    report(out, &metrics, figures.len());
    Ok(())
}
