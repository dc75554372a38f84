//! `train`: a PPO agent (run folder with config, curves, checkpoints, model) or a timing
//! model ([`timing`]).

mod timing;

use anyhow::{Context, Result, bail};
use chronocooked_models::Architecture;
use chronocooked_training::{Progress, UpdateLog, resolve, run_training};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;

/// Arguments of `train`.
#[derive(Args, Debug)]
pub struct TrainArgs {
    /// Task id (see `chronocooked env list`).
    #[arg(long, default_value = "FixedInterval-v0")]
    pub task: String,
    /// Model: cnn-mlp, or lstm|gru|rnn|ctrnn + hidden size (lstm125, ctrnn8, …).
    #[arg(long, default_value = "lstm125")]
    pub model: String,
    /// Hyperparameter preset: reference (the paper's) or fast (quickest wall-clock).
    #[arg(long, default_value = "reference")]
    pub preset: String,
    /// Seed of everything random in the run.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Env-step budget (overrides the preset's).
    #[arg(long)]
    pub steps: Option<u64>,
    /// Override a setting: `--set key=value` (repeatable; `env.<param>=v` for task parameters).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Run folder (default: runs/<task>/<model>/seed<N>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Continue the run in this folder from its newest checkpoint.
    #[arg(long, value_name = "RUN_DIR", conflicts_with_all = ["out"])]
    pub resume: Option<PathBuf>,
    /// No progress bar (one line per update on stderr instead is not printed either).
    #[arg(long)]
    pub quiet: bool,
}

struct Bar {
    bar: Option<ProgressBar>,
}

impl Progress for Bar {
    fn update(&mut self, row: &UpdateLog, total: u64) {
        if let Some(b) = &self.bar {
            b.set_length(total);
            b.set_position(row.env_steps.min(total));
            let eval = row
                .eval_success
                .map(|s| format!(" eval {:.0}%", s * 100.0))
                .unwrap_or_default();
            b.set_message(format!(
                "{:>6.0} steps/s  success {:>5.1}%  return {:.3}{eval}",
                row.steps_per_s,
                row.success_rate * 100.0,
                row.ep_return_mean
            ));
        }
    }
}

/// Runs `train`.
pub fn run(args: TrainArgs) -> Result<()> {
    let timing_resume = args
        .resume
        .as_deref()
        .is_some_and(chronocooked_training::is_timing_run_config);
    if timing_resume || chronocooked_models::timing::zoo::is_timing_model(&args.model) {
        if args.steps.is_some() {
            bail!("timing models train by episodes: use --set episodes=N instead of --steps");
        }
        return timing::train(
            &args.task,
            &args.model,
            args.seed,
            &args.sets,
            args.out,
            args.resume.as_deref(),
            args.quiet,
        );
    }
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let bar = (!args.quiet).then(|| {
        let b = ProgressBar::new(1);
        b.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {msg}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        b
    });
    let mut progress = Bar { bar: bar.clone() };
    let summary = if let Some(dir) = &args.resume {
        if args.steps.is_some() || !args.sets.is_empty() {
            bail!(
                "--resume continues a run with its saved config; --steps/--set cannot be combined with it"
            );
        }
        run_training(None, dir, &command, &mut progress)
            .with_context(|| format!("resuming {}", dir.display()))?
    } else {
        let model: Architecture = args.model.parse().map_err(anyhow::Error::msg)?;
        let mut sets = args.sets.clone();
        if let Some(s) = args.steps {
            sets.push(format!("total_steps={s}"));
        }
        let cfg = resolve(&args.task, model, &args.preset, args.seed, &sets)?;
        let dir = args.out.clone().unwrap_or_else(|| {
            PathBuf::from(format!(
                "runs/{}/{}/seed{}",
                cfg.task,
                model.name(),
                args.seed
            ))
        });
        run_training(Some(cfg), &dir, &command, &mut progress)?
    };
    if let Some(b) = bar {
        b.finish();
    }
    if let Err(e) = chronocooked_analysis::report::figures::learning_curve(&summary.dir) {
        eprintln!("warning: learning-curve figure not written: {e}");
    }
    println!("{}", serde_json::to_string_pretty(&summary)?);
    Ok(())
}
