//! The stages of a sweep job and which of them a job needs.

use crate::sweep::file::{Job, SweepFile};
use chronocooked_training::zoo::Family;
use serde::{Deserialize, Serialize};

/// One stage of a job, in the order they run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Stage {
    /// Train the model (`run/`); baselines have nothing to train.
    Train,
    /// Evaluate with the task's reference protocol (`eval/`).
    Eval,
    /// Uncertainty pre-training jobs: keep learning once ovens stop readying (`adapt/`).
    Adapt,
    /// Record neural activity, its summary and figures (`activity.json`, `neural_figures/`).
    Record,
    /// Export activity and records (`export/`).
    Export,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 5] = [
        Stage::Train,
        Stage::Eval,
        Stage::Adapt,
        Stage::Record,
        Stage::Export,
    ];

    /// The stage's name in `progress.json` and progress messages.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Train => "train",
            Stage::Eval => "eval",
            Stage::Adapt => "adapt",
            Stage::Record => "record",
            Stage::Export => "export",
        }
    }

    /// The stages `job` of `sweep` needs, in order: baselines are only evaluated (and
    /// exported); `record` and `export` follow the sweep's switches; `adapt` runs for
    /// uncertainty jobs pre-trained without uncertainty (`env.never_ready_prob=0`) when the
    /// sweep asks for adaptation.
    pub fn for_job(sweep: &SweepFile, job: &Job) -> Vec<Stage> {
        let trained = job.family != Family::Baseline;
        let adapts = trained
            && sweep.adapt
            && job.task.id() == "Uncertainty-v0"
            && job
                .task
                .value_set("never_ready_prob")
                .and_then(serde_json::Value::as_f64)
                == Some(0.0);
        Stage::ALL
            .into_iter()
            .filter(|s| match s {
                Stage::Train => trained,
                Stage::Eval => true,
                Stage::Adapt => adapts,
                Stage::Record => trained && sweep.record,
                Stage::Export => sweep.export,
            })
            .collect()
    }
}

impl std::fmt::Display for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_job_gets_the_stages_it_needs() {
        let sweep = SweepFile::parse(
            r#"
name = "t"
tasks = ["FixedInterval-v0", "Uncertainty-v0"]
models = ["oracle", "ddm"]
adapt = true
[task_variants]
"Uncertainty-v0" = [["env.never_ready_prob=0"]]
"#,
            "test",
        )
        .unwrap();
        let jobs = sweep.jobs().unwrap();
        let stages = |task: &str, model: &str| {
            let job = jobs
                .iter()
                .find(|j| j.task.id() == task && j.model == model)
                .unwrap();
            Stage::for_job(&sweep, job)
        };
        use Stage::*;
        assert_eq!(stages("FixedInterval-v0", "oracle"), [Eval, Export]);
        assert_eq!(
            stages("FixedInterval-v0", "ddm"),
            [Train, Eval, Record, Export]
        );
        assert_eq!(
            stages("Uncertainty-v0", "ddm"),
            [Train, Eval, Adapt, Record, Export]
        );
        assert_eq!(stages("Uncertainty-v0", "oracle"), [Eval, Export]);
    }

    #[test]
    fn progress_files_keep_their_stage_names() {
        let p: crate::sweep::JobProgress = serde_json::from_str(
            r#"{"id": "x", "finished": ["train", "eval"], "seconds": [1.0, 2.0], "done": false}"#,
        )
        .unwrap();
        assert_eq!(p.finished, [Stage::Train, Stage::Eval]);
        assert_eq!(
            serde_json::to_string(&Stage::ALL).unwrap(),
            r#"["train","eval","adapt","record","export"]"#
        );
    }
}
