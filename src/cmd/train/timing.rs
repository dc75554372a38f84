//! Timing-model training (`train --model ddm|sbf|timecells-*`).

use anyhow::{Context, Result};
use chronocooked_training::{TimingRunConfig, run_timing_training};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

/// Trains a timing model (`args` of `train`); `resume` reruns a stopped run from its config.
pub fn train(
    task: &str,
    model: &str,
    seed: u64,
    sets: &[String],
    out: Option<PathBuf>,
    resume: Option<&Path>,
    quiet: bool,
) -> Result<()> {
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let (cfg, dir) = match resume {
        Some(dir) => {
            let text = std::fs::read_to_string(dir.join("config.json"))
                .with_context(|| format!("{} is not a run folder", dir.display()))?;
            (
                serde_json::from_str::<TimingRunConfig>(&text)?,
                dir.to_path_buf(),
            )
        }
        None => {
            let mut cfg = TimingRunConfig::new(task, model, seed);
            for kv in sets {
                cfg.set(kv)?;
            }
            let dir =
                out.unwrap_or_else(|| PathBuf::from(format!("runs/{task}/{model}/seed{seed}")));
            (cfg, dir)
        }
    };
    let bar = (!quiet).then(|| {
        let b = ProgressBar::new(cfg.train.episodes as u64);
        b.set_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} episodes {msg}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        b
    });
    let summary = run_timing_training(&cfg, &dir, &command, |p| {
        if let Some(b) = &bar {
            b.set_position(p.episode as u64);
            b.set_message(format!(
                "success {:.0}%  eval {:.0}%",
                p.train_success * 100.0,
                p.eval_success.unwrap_or(f64::NAN) * 100.0
            ));
        }
    })?;
    if let Some(b) = bar {
        b.finish();
    }
    if let Err(e) = chronocooked_analysis::report::figures::learning_curve(&dir) {
        eprintln!("warning: learning-curve figure not written: {e}");
    }
    println!("{}", serde_json::to_string_pretty(&summary)?);
    Ok(())
}
