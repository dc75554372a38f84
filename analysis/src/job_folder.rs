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

/// What readers need of a job's [`JOB`] file, typed: a sweep job's (written by the
/// pipeline) and a compact result's (written by `paper collect`) share these fields. The
/// task reads today's parameter map and the older `td=N` list alike
/// ([`chronocooked_env::Task`]'s own deserialiser); other fields are left to their writer.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct JobRecord {
    /// Job id (`task/model~variant/seedN`); empty in job files older than it.
    #[serde(default)]
    pub id: String,
    /// The task with the job's parameters.
    #[serde(flatten)]
    pub task: chronocooked_env::Task,
    /// Zoo model name.
    pub model: String,
    /// Leaderboard row (the model plus its variant's non-task settings); absent in older
    /// job files, whose row is the model.
    #[serde(default)]
    pub row: Option<String>,
    /// Training seed.
    #[serde(default)]
    pub seed: u64,
}

impl JobRecord {
    /// The row the job belongs to: its `row`, else its model.
    pub fn label(&self) -> &str {
        self.row.as_deref().unwrap_or(&self.model)
    }
}

/// Reads the [`JOB`] file of the job folder `dir`; the error names the file and the field.
pub fn read_job(dir: &std::path::Path) -> Result<JobRecord, String> {
    let path = dir.join(JOB);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: not a job file: {e}", path.display()))
}

/// Whether the [`PROGRESS`] file of the job folder `dir` says every stage finished
/// (`false` when it is absent or unreadable: a damaged file only causes work to be redone).
pub fn job_done(dir: &std::path::Path) -> bool {
    #[derive(serde::Deserialize)]
    struct Done {
        #[serde(default)]
        done: bool,
    }
    std::fs::read_to_string(dir.join(PROGRESS))
        .ok()
        .and_then(|t| serde_json::from_str::<Done>(&t).ok())
        .is_some_and(|p| p.done)
}

/// A study's scaling folder's [`SCALING`] file: one (row, seed) whose fixed-interval runs
/// were recorded together (written by the pipeline's scaling stage, read by the mechanisms
/// study).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ScalingJob {
    /// The sweep row (model name with its variant).
    pub model: String,
    /// Training seed.
    pub seed: u64,
    /// TDs of the runs recorded together (steps), shortest first.
    pub tds: Vec<u32>,
    /// The run folders, relative to the sweep output, in `tds` order.
    pub runs: Vec<String>,
}

/// Reads a [`SCALING`] file; the error names the file and the field.
pub fn read_scaling(path: &std::path::Path) -> Result<ScalingJob, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text)
        .map_err(|e| format!("{}: not a scaling record: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_activity_summary_sits_beside_the_activity_with_the_summary_extension() {
        // The record stage names the summary after the dataset it summarises.
        let summary = std::path::Path::new(ACTIVITY).with_extension("summary.json");
        assert_eq!(summary.to_str(), Some(ACTIVITY_SUMMARY));
    }

    #[test]
    fn a_sweep_job_file_a_compact_one_and_an_old_one_read_alike() {
        let dir = tempfile::tempdir().unwrap();
        let write = |text: &str| std::fs::write(dir.path().join(JOB), text).unwrap();
        // Today's sweep job.
        write(
            r#"{"id":"FixedInterval-v0/ddm~env.td-6/seed3","task":"FixedInterval-v0","env":{"td":6},"model":"ddm","family":"timing","seed":3,"sets":["env.td=6"],"row":"ddm"}"#,
        );
        let a = read_job(dir.path()).unwrap();
        assert_eq!(
            (a.label(), a.seed, a.task.id()),
            ("ddm", 3, "FixedInterval-v0")
        );
        assert_eq!(a.task.overrides(), ["td=6"]);
        // An older one: the parameters as `key=value` texts, no row, no id.
        write(r#"{"task":"FixedInterval-v0","env":["td=6"],"model":"ddm","seed":3}"#);
        let b = read_job(dir.path()).unwrap();
        assert_eq!(
            (b.label(), b.task.overrides()),
            ("ddm", vec!["td=6".to_string()])
        );
        // A file without a model is refused, naming the file and the field.
        write(r#"{"task":"FixedInterval-v0","env":{},"seed":3}"#);
        let e = read_job(dir.path()).unwrap_err();
        assert!(e.contains("job.json") && e.contains("model"), "{e}");
    }
}
