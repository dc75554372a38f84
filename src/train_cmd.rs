//! `train` and `zoo` subcommands.

use anyhow::{Context, Result, bail};
use chronocooked_models::Architecture;
use chronocooked_training::zoo::{Family, zoo, zoo_entry};
use chronocooked_training::{PRESETS, Progress, UpdateLog, preset_settings, resolve, run_training};
use clap::{Args, Subcommand};
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
    if timing_resume || chronocooked_models::zoo::is_timing_model(&args.model) {
        if args.steps.is_some() {
            bail!("timing models train by episodes: use --set episodes=N instead of --steps");
        }
        return crate::timing_cmd::train(
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
    if let Err(e) = chronocooked_analysis::figures::learning_curve(&summary.dir) {
        eprintln!("warning: learning-curve figure not written: {e}");
    }
    println!("{}", serde_json::to_string_pretty(&summary)?);
    Ok(())
}

/// `zoo` subcommands.
#[derive(Subcommand, Debug)]
pub enum ZooCommand {
    /// List every model (deep RL, timing models, baselines), tasks and presets.
    List {
        /// Print JSON (the whole registry: descriptions, parameters, presets).
        #[arg(long)]
        json: bool,
    },
    /// Show one model: description, parameters and (deep RL) the resolved preset for a task.
    Show {
        /// Model name (cnn-mlp, lstm125, ddm, timecells-ms, oracle, …).
        model: String,
        /// Task id (deep RL presets are keyed by task).
        #[arg(long, default_value = "FixedInterval-v0")]
        task: String,
        /// Preset (deep RL).
        #[arg(long, default_value = "reference")]
        preset: String,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
}

/// Runs `zoo`.
pub fn run_zoo(cmd: ZooCommand) -> Result<()> {
    match cmd {
        ZooCommand::List { json } => {
            let entries = zoo();
            let tasks: Vec<&str> = chronocooked_env::all_tasks().iter().map(|t| t.id).collect();
            if json {
                let v = serde_json::json!({"models": entries, "tasks": tasks, "presets": PRESETS});
                println!("{}", serde_json::to_string_pretty(&v)?);
                return Ok(());
            }
            for family in [Family::DeepRl, Family::Timing, Family::Baseline] {
                println!("{}:", family.label());
                for e in entries.iter().filter(|e| e.family == family) {
                    println!("  {:<19} {}", e.name, e.description);
                }
                println!();
            }
            println!("Tasks: {}", tasks.join(", "));
            println!("\nPresets (training/presets/*.toml, overridable with --set key=value):");
            println!(
                "  reference  the paper's: 1 env, n_steps 1000, n_epochs 20, batch 64 (CNN-MLP) / 128 (recurrent), lr 3e-4"
            );
            println!(
                "  fast       quickest wall-clock on a 2-core CPU: recurrent 1 env x 1000 steps, 10 epochs, batch 256 (16x16-step chunks), lr 3e-4 (CTRNN 1e-3); CNN-MLP 16 envs x 64 steps, 4 epochs, batch 256, lr 1e-3; greedy eval every 10k steps"
            );
            println!(
                "\n`chronocooked zoo show MODEL [--task ID --preset NAME]` describes one model."
            );
        }
        ZooCommand::Show {
            model,
            task,
            preset,
            json,
        } => {
            let entry = zoo_entry(&model)?;
            let settings = if entry.family == Family::DeepRl {
                let arch: Architecture = model.parse().map_err(anyhow::Error::msg)?;
                let pairs = preset_settings(&task, arch, &preset)?;
                let cfg = resolve::<&str>(&task, arch, &preset, 0, &[])?;
                Some((pairs, cfg))
            } else {
                None
            };
            if json {
                let v = serde_json::json!({
                    "model": entry,
                    "task": task,
                    "preset": settings.as_ref().map(|(pairs, cfg)| serde_json::json!({
                        "name": preset, "settings": pairs, "resolved": cfg
                    })),
                });
                println!("{}", serde_json::to_string_pretty(&v)?);
                return Ok(());
            }
            println!(
                "{} ({})\n  {}\n",
                entry.name,
                entry.family.label(),
                entry.description
            );
            if !entry.parameters.is_empty() {
                println!("parameters:");
                for p in &entry.parameters {
                    println!("  {:<18} {:<10} {}", p.name, p.value, p.meaning);
                }
                println!();
            }
            println!("usage: {}", entry.usage);
            if let Some((pairs, cfg)) = settings {
                println!("\n# {preset} preset on {task}: settings applied in order");
                for (k, v) in pairs {
                    println!("{k} = {v}");
                }
                println!("\n# resolved configuration");
                println!("{}", serde_json::to_string_pretty(&cfg)?);
            }
        }
    }
    Ok(())
}

/// `bench train`: mean env-steps/s over `updates` PPO updates (after one warm-up) per model.
pub fn bench_train(
    task: &str,
    models: &str,
    preset: &str,
    updates: u64,
    sets: &[String],
) -> Result<()> {
    for name in models.split(',').map(str::trim).filter(|m| !m.is_empty()) {
        let arch: Architecture = name.parse().map_err(anyhow::Error::msg)?;
        let mut cfg = resolve(task, arch, preset, 0, sets)?;
        cfg.total_steps = u64::MAX;
        let batch = (cfg.ppo.n_envs * cfg.ppo.n_steps) as f64;
        let engine = format!("{:?}", cfg.ppo.engine).to_ascii_lowercase();
        let mut trainer = chronocooked_training::Trainer::new(cfg)?;
        trainer.update()?;
        let (mut secs, mut roll, mut opt) = (0.0, 0.0, 0.0);
        for _ in 0..updates.max(1) {
            let r = trainer.update()?;
            secs += batch / r.steps_per_s;
            roll += r.rollout_s;
            opt += r.optimize_s;
        }
        let n = updates.max(1) as f64;
        println!(
            "{task:<18} {:<10} {preset:<9} {engine:<6} {:>8.0} env-steps/s  ({:.3} s/update: rollout {:.3} s, optimise {:.3} s; {} updates)",
            arch.name(),
            batch * n / secs,
            secs / n,
            roll / n,
            opt / n,
            updates.max(1)
        );
    }
    Ok(())
}
