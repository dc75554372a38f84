//! What a sweep costs: measured training throughput per model and the estimated
//! single-core time of a job.

use super::file::{Job, SweepFile};
use crate::zoo::Family;

/// Measured training throughput (env steps per second, one core, native engine) of the
/// reference preset on the lab's 2-core development machine (`BENCHMARKS.md`, "Study
/// throughput"): `(model, steps/s)`. With sequence minibatches the throughput grows as
/// episodes shorten; size-125 and CNN entries are whole-run averages of paper-core jobs, the
/// others `bench train` at the start of a run scaled by the size-125 ratio (×1.2).
pub const REFERENCE_THROUGHPUT: [(&str, f64); 10] = [
    ("cnn-mlp", 7_000.0),
    ("lstm8", 16_000.0),
    ("lstm125", 2_000.0),
    ("lstm256", 360.0),
    ("ctrnn8", 20_000.0),
    ("ctrnn125", 4_900.0),
    ("ctrnn256", 2_100.0),
    ("ctrnn-reservoir8", 20_000.0),
    ("ctrnn-reservoir125", 4_900.0),
    ("ctrnn-reservoir256", 1_800.0),
];

/// Estimated single-core training time of one job (seconds): its resolved step budget over
/// the measured throughput of its model ([`REFERENCE_THROUGHPUT`]); `None` for jobs without
/// PPO training (timing models train in seconds, baselines not at all) or unmeasured models.
pub fn estimate_seconds(sweep: &SweepFile, job: &Job) -> Option<f64> {
    if job.family != Family::DeepRl {
        return None;
    }
    let rate = REFERENCE_THROUGHPUT
        .iter()
        .find(|(m, _)| *m == job.model)?
        .1;
    let arch = job.model.parse().ok()?;
    let cfg =
        crate::ppo::presets::resolve(&job.task, arch, &sweep.preset, job.seed, &job.sets).ok()?;
    Some(cfg.total_steps as f64 / rate)
}
