//! Where a trained timing agent's own rule puts its multi-anchor category boundaries: the
//! agent's timer alone (its learned anchor memories, its noise, its decision rule; no task,
//! no TD learner) judges `TRIALS` probe intervals at every whole step between each pair of
//! neighbouring anchors, and the lab's logistic fit over those probes gives the predicted
//! boundary — the number a trained run's fitted boundary is compared with.
//!
//!     cargo run --release --example predicted_boundaries -- RUN_DIR [RUN_DIR …]
//!
//! Prints one line per run: the run folder, then each boundary's predicted BP (steps).

use chronocooked_analysis::behaviour::psychometric::{ProbeCounts, fit_logistic};
use chronocooked_training::timing_run::load_timing_agent;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
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
    let anchors: Vec<u32> = config
        .params
        .active_anchors()
        .ok_or("not a multi-anchor run")?
        .to_vec();
    let k = anchors.len();
    let timer = &mut agent.timer;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(cfg.seed);
    let mut out = Vec::new();
    for (i, pair) in anchors.windows(2).enumerate() {
        let mut probes = Vec::new();
        for t in pair[0]..=pair[1] {
            let (mut valid, mut upper) = (0, 0);
            for _ in 0..TRIALS {
                timer.clear();
                timer.onset(1, k, &mut rng);
                for step in 1..=t {
                    timer.tick(step, &mut rng);
                }
                match timer.judge(k) {
                    Some(c) if c as usize == i => valid += 1,
                    Some(c) if c as usize == i + 1 => {
                        valid += 1;
                        upper += 1;
                    }
                    _ => {}
                }
            }
            probes.push(ProbeCounts {
                t: f64::from(t),
                valid,
                long: upper,
                failed: 0,
            });
        }
        let fit = fit_logistic(&probes).map_err(|e| format!("boundary {i}: {e}"))?;
        out.push(fit.bp);
    }
    Ok(out)
}
