//! Where a trained timing agent's own rule puts its multi-anchor category boundaries
//! (`chronocooked_analysis::behaviour::predicted`): the agent's timer alone judges
//! `TRIALS` probe intervals at every whole step between each pair of neighbouring anchors,
//! and the lab's logistic fit over those probes gives the predicted boundary — the number a
//! trained run's fitted boundary is compared with.
//!
//!     cargo run --release --example predicted_boundaries -- RUN_DIR [RUN_DIR …]
//!
//! Prints one line per run: the run folder, then each boundary's predicted BP (steps).

use chronocooked_analysis::behaviour::predicted::predicted_boundaries;
use chronocooked_training::timing_run::load_timing_agent;
use std::path::Path;

/// Judged trials per probe duration.
const TRIALS: u32 = 2000;

fn main() {
    for dir in std::env::args().skip(1) {
        match predicted(Path::new(&dir)) {
            Ok(bps) => {
                let bps: Vec<String> = bps.iter().map(|b| format!("{b:.3}")).collect();
                println!("{dir} {}", bps.join(" "));
            }
            Err(e) => eprintln!("{dir}: {e}"),
        }
    }
}

/// The predicted boundary between every pair of neighbouring anchors of the run's task.
fn predicted(dir: &Path) -> Result<Vec<f64>, String> {
    let (cfg, mut agent) = load_timing_agent(dir).map_err(|e| e.to_string())?;
    let config = cfg.task.config().map_err(|e| e.to_string())?;
    let anchors = config
        .params
        .active_anchors()
        .ok_or("not a multi-anchor run")?
        .to_vec();
    predicted_boundaries(&mut agent.timer, &anchors, TRIALS, cfg.seed).map_err(|e| e.to_string())
}
