//! The file names of a sweep job's folder — one model trained, evaluated and recorded on
//! one task — in one place. The pipeline writes job folders; the report, the paper's
//! study, the mechanisms study and the CLI read them by these names.
//!
//! ```text
//! JOB_DIR/job.json                what the job is (id, model, task, seed, settings)
//! JOB_DIR/progress.json           its finished stages, and whether all are (`done`)
//! JOB_DIR/run/                    the run folder (names: chronocooked_models::run_folder)
//! JOB_DIR/eval/                   the eval folder (names: crate::records)
//! JOB_DIR/activity.json           recorded activity (plus its .npz arrays)
//! JOB_DIR/activity.summary.json   the neural summary of each population
//! ```
//!
//! A study's scaling folders (`<results>/scaling/<row>/seed<N>/`) hold [`SCALING`] and
//! [`ACTIVITY_SUMMARY`].

/// Which stages of the job finished, and whether all did (JSON, written by the pipeline).
pub const PROGRESS: &str = "progress.json";
/// What the job is (JSON).
pub const JOB: &str = "job.json";
/// The job's run folder.
pub const RUN: &str = "run";
/// The job's evaluation folder.
pub const EVAL: &str = "eval";
/// The recorded activity dataset (JSON; an evaluation that records activity writes the
/// same file into its eval folder).
pub const ACTIVITY: &str = "activity.json";
/// The neural summary of every population of [`ACTIVITY`] (JSON list).
pub const ACTIVITY_SUMMARY: &str = "activity.summary.json";
/// The scaling stage's description of a scaling folder: the runs it recorded (JSON).
pub const SCALING: &str = "scaling.json";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_activity_summary_sits_beside_the_activity_with_the_summary_extension() {
        // The record stage names the summary after the dataset it summarises.
        let summary = std::path::Path::new(ACTIVITY).with_extension("summary.json");
        assert_eq!(summary.to_str(), Some(ACTIVITY_SUMMARY));
    }
}
