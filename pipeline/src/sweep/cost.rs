//! What a sweep costs: measured training throughput per model and the estimated
//! single-core time of a job.

use super::file::{Job, SweepFile};
use chronocooked_training::zoo::Family;

/// Measured training throughput (env steps per second, one core, native engine) of the
/// reference preset on the lab's 2-core development machine (`BENCHMARKS.md`, "Study
/// throughput" and "Recurrent kernels", issue #28): `(model, steps/s)`. With sequence
/// minibatches the throughput grows as episodes shorten. Each entry is the previous
/// whole-run estimate (size-125 and CNN entries: whole-run averages of paper-core jobs; the
/// others `bench train` at the start of a run ×1.2) times the new/old speed ratio that
/// `scripts/bench-compare.sh` measured side by side for the AVX-512 engine (3 rounds,
/// start of a run), divided by 1.13: the same run's ratio for the unchanged env crate,
/// i.e. its measurement bias, so the estimate stays on the safe side.
pub const REFERENCE_THROUGHPUT: [(&str, f64); 10] = [
    ("cnn-mlp", 9_200.0),
    ("lstm8", 31_000.0),
    ("lstm125", 4_100.0),
    ("lstm256", 1_340.0),
    ("ctrnn8", 35_000.0),
    ("ctrnn125", 9_500.0),
    ("ctrnn256", 3_850.0),
    ("ctrnn-reservoir8", 30_000.0),
    ("ctrnn-reservoir125", 8_800.0),
    ("ctrnn-reservoir256", 3_250.0),
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
    let cfg = chronocooked_training::ppo::presets::resolve(
        job.task.id(),
        arch,
        &sweep.preset,
        job.seed,
        &job.sets,
    )
    .ok()?;
    Some(cfg.total_steps as f64 / rate)
}
