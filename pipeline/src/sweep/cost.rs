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

/// Measured training throughput of the fast preset (env steps per second, one core, native
/// engine): each model's [`REFERENCE_THROUGHPUT`] times the fast/reference ratio that `bench
/// train --preset P --updates 5` measured for it in one sitting (two alternations per preset,
/// 2026-12-03; BENCHMARKS.md, "Study throughput"), so the same safety margin carries over.
/// Checked against whole runs of the demo study (fast preset, evaluations included, two
/// workers): CTRNN125 17,400–20,900 and LSTM125 8,900–9,600 steps/s.
pub const FAST_THROUGHPUT: [(&str, f64); 10] = [
    ("cnn-mlp", 43_000.0),
    ("lstm8", 52_000.0),
    ("lstm125", 9_300.0),
    ("lstm256", 3_900.0),
    ("ctrnn8", 82_000.0),
    ("ctrnn125", 21_000.0),
    ("ctrnn256", 9_000.0),
    ("ctrnn-reservoir8", 63_000.0),
    ("ctrnn-reservoir125", 22_000.0),
    ("ctrnn-reservoir256", 9_500.0),
];

/// The measured throughput of `model` at `preset` (env steps per second, one core), `None`
/// for a preset or model not measured.
pub fn throughput(preset: &str, model: &str) -> Option<f64> {
    let table: &[(&str, f64)] = match preset {
        "reference" => &REFERENCE_THROUGHPUT,
        "fast" => &FAST_THROUGHPUT,
        _ => return None,
    };
    table.iter().find(|(m, _)| *m == model).map(|&(_, r)| r)
}

/// Estimated single-core training time of one job (seconds): its resolved step budget over
/// the measured throughput of its model at the sweep's preset ([`throughput`]); `None` for
/// jobs without PPO training (timing models train in seconds, baselines not at all) or
/// unmeasured models and presets.
pub fn estimate_seconds(sweep: &SweepFile, job: &Job) -> Option<f64> {
    if job.family != Family::DeepRl {
        return None;
    }
    let rate = throughput(&sweep.preset, &job.model)?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_preset_has_a_rate_for_every_measured_model_and_fast_is_faster() {
        assert_eq!(REFERENCE_THROUGHPUT.len(), FAST_THROUGHPUT.len());
        for (model, reference) in REFERENCE_THROUGHPUT {
            let fast = throughput("fast", model).expect(model);
            // Bigger batches and fewer epochs per transition: at least 1.5× (measured 1.7–4.7×).
            assert!(fast > 1.5 * reference, "{model}: {fast} vs {reference}");
            assert_eq!(throughput("reference", model), Some(reference));
        }
        assert_eq!(throughput("custom", "lstm125"), None);
        assert_eq!(throughput("fast", "gru125"), None);
    }
}
