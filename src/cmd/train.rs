//! `train`: a PPO agent (run folder with config, curves, checkpoints, model) or a timing
//! model, through the pipeline's train stage, with a progress bar.

use anyhow::{Context, Result};
use chronocooked_models::TimingCurvePoint;
use chronocooked_pipeline::stages::{TrainObserver, TrainRequest};
use chronocooked_training::UpdateLog;
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
    /// Env-step budget (overrides the preset's); with --resume, raises the run's budget to N
    /// (the way to train a run on: `config.json` is rewritten with its SHA-256 record).
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

/// Progress bars of a PPO run (env steps) or a timing-model run (episodes).
struct Bars {
    bar: Option<ProgressBar>,
}

impl Bars {
    fn new(quiet: bool) -> Self {
        Bars {
            bar: (!quiet).then(|| ProgressBar::new(1)),
        }
    }

    fn show(&self, unit: &str, position: u64, total: u64, message: String) {
        if let Some(b) = &self.bar {
            if b.length() != Some(total) {
                b.set_style(
                    ProgressStyle::with_template(&format!(
                        "{{elapsed_precise}} [{{bar:30}}] {{pos}}/{{len}}{unit} {{msg}}"
                    ))
                    .expect("valid template")
                    .progress_chars("=> "),
                );
                b.set_length(total);
            }
            b.set_position(position.min(total));
            b.set_message(message);
        }
    }
}

impl TrainObserver for Bars {
    fn ppo_update(&mut self, row: &UpdateLog, total: u64) {
        let eval = row
            .eval_success
            .map(|s| format!(" eval {:.0}%", s * 100.0))
            .unwrap_or_default();
        self.show(
            "",
            row.env_steps,
            total,
            format!(
                "{:>6.0} steps/s  success {:>5.1}%  return {:.3}{eval}",
                row.steps_per_s,
                row.success_rate * 100.0,
                row.ep_return_mean
            ),
        );
    }

    fn timing_point(&mut self, p: &TimingCurvePoint, total: usize) {
        self.show(
            " episodes",
            p.episode as u64,
            total as u64,
            format!(
                "success {:.0}%  eval {:.0}%",
                p.train_success * 100.0,
                p.eval_success.unwrap_or(f64::NAN) * 100.0
            ),
        );
    }
}

/// Runs `train`.
pub fn run(args: TrainArgs) -> Result<()> {
    let req = TrainRequest {
        task: args.task.clone(),
        model: args.model.clone(),
        preset: args.preset.clone(),
        seed: args.seed,
        steps: args.steps,
        sets: args.sets.clone(),
        out: args.out.clone(),
        resume: args.resume.clone(),
        command: std::env::args().collect::<Vec<_>>().join(" "),
    };
    let mut bars = Bars::new(args.quiet);
    let result = chronocooked_pipeline::stages::train(&req, &mut bars);
    let (outcome, figure_error) = match &args.resume {
        Some(dir) => result.with_context(|| format!("resuming {}", dir.display()))?,
        None => result?,
    };
    if let Some(b) = bars.bar {
        b.finish();
    }
    println!("{}", serde_json::to_string_pretty(&outcome)?);
    if let Some(e) = figure_error {
        anyhow::bail!(
            "the run is trained and saved, but its learning-curve figure was not written: {e}; \
             draw it with `chronocooked train --resume {}`",
            outcome.dir().display()
        );
    }
    Ok(())
}
