//! `record`: the neural activity of any trained agent as an activity dataset (JSON), with
//! heat maps and the neural summary.

use anyhow::Result;
use chronocooked_env::{TaskConfig, make_config};
use chronocooked_models::activity::{ActivityMeta, TrialRecorder};
use chronocooked_models::{Agent, evaluate_agent};
use chronocooked_training::eval_tds;
use chronocooked_training::run_dir::write_atomic;
use chronocooked_training::timing_run::load_agent;
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `record`.
#[derive(Args, Debug)]
pub struct RecordArgs {
    /// Run folder of a trained agent (PPO or timing model).
    #[arg(long)]
    pub run: PathBuf,
    /// Task to play (default: the run's own task).
    #[arg(long)]
    pub task: Option<String>,
    /// Task overrides `key=value` (with --task).
    #[arg(long = "env", value_name = "KEY=VALUE")]
    pub env: Vec<String>,
    /// Target durations to record (default: the task's evaluation TDs), e.g. `4,6,9,12`.
    #[arg(long, value_delimiter = ',')]
    pub tds: Vec<u32>,
    /// Repetitions of the every-start-cell protocol (different seeds for the model's noise).
    #[arg(long, default_value_t = 1)]
    pub repeats: u64,
    /// Seed of the recording.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Output file (JSON activity dataset).
    #[arg(long, default_value = "activity.json")]
    pub out: PathBuf,
    /// Also write the neural summary of every population (fractions of ramping / time /
    /// oscillating units, sequentiality, decoding error) to `<out>.summary.json`.
    #[arg(long)]
    pub summary: bool,
    /// Also write heat maps (activity aligned to oven-on, units sorted by peak time) of every
    /// population with ≥ 2 units into this folder.
    #[arg(long)]
    pub figures: Option<PathBuf>,
}

/// Runs `record`.
pub fn record(args: RecordArgs) -> Result<()> {
    let (task, env) = match &args.task {
        Some(t) => (t.clone(), args.env.clone()),
        None => chronocooked_training::timing_run::run_task(&args.run)?,
    };
    let config: TaskConfig = make_config(&task, &env)?;
    let mut agent = load_agent(&args.run, Some(&config))?;
    let tds = if args.tds.is_empty() {
        eval_tds(&config)
    } else {
        args.tds.clone()
    };
    let dataset = record_dataset(
        agent.as_mut(),
        &config,
        &task,
        &env,
        &tds,
        args.repeats,
        args.seed,
    )?;
    write_atomic(&args.out, &serde_json::to_vec(&dataset)?)?;
    if let Some(dir) = &args.figures {
        write_heatmaps(&dataset, dir)?;
    }
    if args.summary {
        let summaries: Vec<_> = dataset
            .meta
            .populations
            .iter()
            .filter_map(|p| {
                chronocooked_analysis::neural::summary::neural_summary(
                    &dataset,
                    Some(&p.name),
                    None,
                    args.seed,
                )
            })
            .collect();
        write_atomic(
            &args.out.with_extension("summary.json"),
            serde_json::to_string_pretty(&summaries)?.as_bytes(),
        )?;
    }
    println!(
        "{} trials × {} units of {} on {task} → {}",
        dataset.trials.len(),
        dataset.meta.n_units(),
        dataset.meta.model,
        args.out.display()
    );
    Ok(())
}

/// Scalars every learner records (value estimate, reward-prediction error): not a timing
/// mechanism's signature.
const LEARNER_SIGNALS: [&str; 2] = ["value", "rpe"];

/// Heat maps and population figures of every population (≥ 2 units) of `dataset`, and —
/// for a model with only one-unit populations — their per-TD traces, aligned to oven-on.
fn write_heatmaps(dataset: &chronocooked_models::ActivityDataset, dir: &Path) -> Result<()> {
    use chronocooked_analysis::neural::Cube;
    use chronocooked_models::Marker;
    let window = dataset
        .trials
        .iter()
        .filter_map(|t| {
            t.first(Marker::OvenOn)
                .map(|on| t.steps.saturating_sub(on as usize + 1))
        })
        .max()
        .unwrap_or(0)
        .clamp(1, 60);
    let (aligned, used) = dataset.aligned(Marker::OvenOn, window - 1);
    let n = dataset.meta.n_units();
    if used.is_empty() {
        return Ok(());
    }
    let cube = Cube::from_f32(&aligned, used.len(), window, n);
    let avg = cube.average();
    // A model without a multi-unit population (drift-diffusion) is shown by the per-TD
    // traces of its own one-unit populations (not the learner's `value` / `rpe`).
    let only_scalars = dataset.meta.populations.iter().all(|p| p.size < 2);
    for p in &dataset.meta.populations {
        let r = dataset.meta.range(&p.name).expect("population exists");
        if p.size < 2 {
            if !only_scalars || LEARNER_SIGNALS.contains(&p.name.as_str()) {
                continue;
            }
            // One unit (an accumulator): its trace per TD is the signature.
            let title = format!(
                "{}: {} per TD (trial average, aligned to oven on)",
                dataset.meta.model, p.name
            );
            chronocooked_analysis::report::figures::unit_by_td(
                &dir.join(&p.name),
                &title,
                dataset,
                r.start,
                window,
            )?;
            continue;
        }
        let sub: Vec<f64> = avg
            .chunks_exact(n)
            .flat_map(|row| row[r.clone()].to_vec())
            .collect();
        let title = format!(
            "{}: {} (trial average, aligned to oven on)",
            dataset.meta.model, p.name
        );
        chronocooked_analysis::report::figures::write_heatmap(
            &dir.join(&p.name),
            &title,
            &sub,
            p.size,
        )?;
        let mut data = Vec::with_capacity(cube.trials * window * p.size);
        for k in 0..cube.trials {
            for t in 0..window {
                data.extend(r.clone().map(|i| cube.at(k, t, i)));
            }
        }
        let pop = Cube {
            trials: cube.trials,
            time: window,
            units: p.size,
            data,
        };
        let title = format!("{} {}", dataset.meta.model, p.name);
        chronocooked_analysis::report::figures::population_figures(
            &dir.join(&p.name),
            &title,
            &pop,
        )?;
    }
    Ok(())
}

/// Records `repeats` × (every start cell × `tds`) greedy episodes of `agent`.
pub fn record_dataset(
    agent: &mut dyn Agent,
    config: &TaskConfig,
    task: &str,
    env: &[String],
    tds: &[u32],
    repeats: u64,
    seed: u64,
) -> Result<chronocooked_models::ActivityDataset> {
    let meta = ActivityMeta::new(&agent.name(), task, env, seed);
    let mut rec = TrialRecorder::new(meta);
    for r in 0..repeats.max(1) {
        evaluate_agent(agent, config, tds, seed.wrapping_add(r), Some(&mut rec))?;
    }
    Ok(rec.finish())
}
