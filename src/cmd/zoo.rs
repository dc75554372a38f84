//! `zoo`: every model of the lab (deep RL, timing models, baselines), its parameters and
//! the resolved preset.

use anyhow::Result;
use chronocooked_models::Architecture;
use chronocooked_training::zoo::{Family, zoo, zoo_entry};
use chronocooked_training::{PRESETS, TimingRunConfig, preset_settings, resolve};
use clap::Subcommand;

/// `zoo` subcommands.
#[derive(Subcommand, Debug)]
pub enum ZooCommand {
    /// List every model (deep RL, timing models, baselines), tasks and presets.
    List {
        /// Print JSON (the whole registry: descriptions, parameters, presets).
        #[arg(long)]
        json: bool,
    },
    /// Add a finished sweep job's trained agent to the zoo (final model, configuration,
    /// summary and provenance; every file recorded in SHA256SUMS).
    Add(crate::cmd::zoo_agents::ZooAddArgs),
    /// Show one model: description, parameters and (deep RL) the resolved preset for a task.
    Show {
        /// Model name (cnn-mlp, lstm125, ddm, timecells-ms, oracle, …).
        model: String,
        /// Task id (deep RL presets are keyed by task).
        #[arg(long, default_value = "FixedInterval-v0")]
        task: String,
        /// Preset (deep RL; `reference` when not given). Refused for other models.
        #[arg(long)]
        preset: Option<String>,
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
                let (_, agents) = crate::cmd::zoo_agents::agents_listing()?;
                let v = serde_json::json!({"models": entries, "tasks": tasks, "presets": PRESETS, "trained": agents});
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
                "  reference  the paper's code: 1 env, n_steps 1000, n_epochs 20, batch 64 (CNN-MLP) / 128-transition sequence windows (recurrent, sb3-contrib), detached critic, PyTorch core init, lr 3e-4"
            );
            println!(
                "  fast       the lab's quickest wall-clock on a 2-core CPU: recurrent 4 envs x 250 steps, 10 epochs, batch 256 (16x16-step chunks), lr 3e-4 (CTRNN 1e-3); CNN-MLP 16 envs x 64 steps, 4 epochs, batch 256, lr 1e-3; greedy eval every 10k steps"
            );
            println!(
                "\n`chronocooked zoo show MODEL [--task ID --preset NAME]` describes one model.\n"
            );
            for line in crate::cmd::zoo_agents::agents_listing()?.0 {
                println!("{line}");
            }
        }
        ZooCommand::Add(args) => crate::cmd::zoo_agents::add(args)?,
        ZooCommand::Show {
            model,
            task,
            preset,
            json,
        } => {
            let mut entry = zoo_entry(&model)?;
            // Every argument is checked, also those this model does not use: a typo never
            // passes unnoticed.
            chronocooked_env::find_task(&task)?;
            if entry.family != Family::DeepRl
                && let Some(preset) = &preset
            {
                anyhow::bail!(
                    "--preset `{preset}`: presets configure deep-RL models only; {model} is a {} (drop --preset)",
                    entry.family.label()
                );
            }
            let preset = preset.unwrap_or_else(|| "reference".to_string());
            let settings = if entry.family == Family::DeepRl {
                let arch: Architecture = model.parse().map_err(anyhow::Error::msg)?;
                let pairs = preset_settings(&task, arch, &preset)?;
                let cfg = resolve::<&str>(&task, arch, &preset, 0, &[])?;
                Some((pairs, cfg))
            } else {
                None
            };
            // The settings on this task (and preset): every one a `--set` key.
            entry.parameters = match &settings {
                Some((_, cfg)) => cfg.listing(),
                None if entry.family == Family::Timing => {
                    TimingRunConfig::new(&chronocooked_env::Task::new(&task)?, &model, 0).listing()
                }
                None => entry.parameters,
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
            if !entry.structure.is_empty() {
                println!("structure (fixed by the model):");
                for p in &entry.structure {
                    println!("  {:<18} {:<10} {}", p.name, p.value, p.meaning);
                }
                println!();
            }
            if !entry.parameters.is_empty() {
                println!("settings (--set key=value; and env.<task parameter>=value):");
                for s in &entry.parameters {
                    println!("  {:<22} {:<10} {} ({})", s.key, s.value, s.doc, s.allowed);
                }
                println!();
            }
            if !entry.tasks.is_empty() {
                println!("tasks (measured success: results/timing-models/README.md):");
                for t in &entry.tasks {
                    match &t.limit {
                        None => println!("  {:<34} no mechanistic limit", t.task),
                        Some(why) => println!("  {:<34} cannot: {why}", t.task),
                    }
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
