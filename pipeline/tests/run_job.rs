//! The sweep pipeline as a library: a job's stages run in order through `run_job`, each is
//! marked finished, a rerun redoes nothing, and the stage functions are deterministic and
//! check their requests. (The CLI end to end, including a PPO job resumed from its
//! checkpoint, is `tests/sweep.rs`.)

use chronocooked_pipeline::stages::{self, EvalRequest, EvalSubject};
use chronocooked_pipeline::sweep::{Job, Stage, SweepFile, finished_stages, job_dir, job_done};
use chronocooked_pipeline::{JobObserver, PipelineError, find_job, run_job};

/// Records which stages started and finished.
#[derive(Default)]
struct Seen {
    started: Vec<Stage>,
    finished: Vec<(Stage, String)>,
}

impl JobObserver for Seen {
    fn stage_started(&mut self, _job: &Job, stage: Stage) {
        self.started.push(stage);
    }
    fn stage_finished(&mut self, _job: &Job, stage: Stage, seconds: f64, summary: &str) {
        assert!(seconds >= 0.0);
        self.finished.push((stage, summary.to_string()));
    }
}

fn sweep_file(dir: &std::path::Path) -> (SweepFile, std::path::PathBuf) {
    let path = dir.join("tiny.toml");
    std::fs::write(
        &path,
        r#"name = "tiny"
tasks = ["FixedInterval-v0"]
models = ["oracle", "ddm"]
seeds = [3]
episodes = 300
record = true
export = true
set = ["env.td=6"]
"#,
    )
    .unwrap();
    (SweepFile::load(&path).unwrap(), path)
}

#[test]
fn run_job_runs_each_stage_once_in_order_and_skips_finished_stages() {
    let tmp = tempfile::tempdir().unwrap();
    let (sweep, path) = sweep_file(tmp.path());
    let out = tmp.path().join("out");
    let jobs = sweep.jobs().unwrap();
    let ddm = jobs.iter().find(|j| j.model == "ddm").expect("a ddm job");
    let oracle = jobs
        .iter()
        .find(|j| j.model == "oracle")
        .expect("an oracle job");

    let mut seen = Seen::default();
    run_job(&sweep, ddm, &out, &mut seen).unwrap();
    let want = vec![Stage::Train, Stage::Eval, Stage::Record, Stage::Export];
    assert_eq!(seen.started, want);
    assert_eq!(
        seen.finished.iter().map(|(s, _)| *s).collect::<Vec<_>>(),
        want
    );
    let dir = job_dir(&out, &ddm.id);
    assert_eq!(finished_stages(&dir), want);
    assert!(job_done(&dir));
    for f in [
        "job.json",
        "run/summary.json",
        "eval/metrics.json",
        "activity.json",
        "activity.summary.json",
        "export/activity.npz",
        "export/episodes.csv",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    // The eval summary line reports the evaluated model and its success.
    let eval_line = &seen.finished[1].1;
    assert!(eval_line.starts_with("ddm"), "{eval_line}");

    // A rerun finds every stage finished and runs none.
    let mut again = Seen::default();
    run_job(&sweep, ddm, &out, &mut again).unwrap();
    assert!(again.started.is_empty(), "{:?}", again.started);

    // A baseline is only evaluated and exported (nothing to train or record).
    let mut base = Seen::default();
    run_job(&sweep, oracle, &out, &mut base).unwrap();
    assert_eq!(base.started, vec![Stage::Eval, Stage::Export]);
    let m: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(job_dir(&out, &oracle.id).join("eval/metrics.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(m["success_rate"], 1.0, "the oracle solves FI TD 6");

    // Unknown job ids name the sweep file.
    let err = find_job(&sweep, &path, "nope/seed0").unwrap_err();
    assert!(matches!(err, PipelineError::UnknownJob { .. }));
    assert!(err.to_string().contains("tiny.toml"), "{err}");
}

#[test]
fn the_eval_stage_equals_a_rerun_of_itself_and_checks_its_request() {
    let tmp = tempfile::tempdir().unwrap();
    let req = |out: &str| EvalRequest {
        subject: EvalSubject::Reference("oracle".into()),
        task: Some(chronocooked_env::Task::new("FixedInterval-v0").unwrap()),
        mode: chronocooked_analysis::Mode::Reference,
        seed: 0,
        out: tmp.path().join(out),
        activity: false,
        unfinished: false,
    };
    let a = stages::evaluate(&req("a")).unwrap();
    let b = stages::evaluate(&req("b")).unwrap();
    let read = |d: &str| std::fs::read(tmp.path().join(d).join("records.jsonl")).unwrap();
    assert_eq!(read("a"), read("b"), "same request, same records");
    assert_eq!(a.metrics.episodes, b.metrics.episodes);
    assert_eq!(a.metrics.success_rate, 1.0);
    // Recomputing from the saved records gives the same metrics.
    let c = stages::rescore_eval_folder(&tmp.path().join("a"), &tmp.path().join("c")).unwrap();
    assert_eq!(
        serde_json::to_value(&a.metrics).unwrap(),
        serde_json::to_value(&c.metrics).unwrap()
    );

    let mut bad = req("d");
    bad.subject = EvalSubject::Reference("genius".into());
    let e = stages::evaluate(&bad).unwrap_err().to_string();
    assert!(e.contains("allowed: oracle, random"), "{e}");
    let mut none = req("e");
    none.mode = chronocooked_analysis::Mode::Stochastic { episodes: 0 };
    let e = stages::evaluate(&none).unwrap_err().to_string();
    assert!(e.contains("positive number of episodes"), "{e}");
    let e = stages::export(None, None, 200, tmp.path())
        .unwrap_err()
        .to_string();
    assert!(e.contains("say what to export"), "{e}");
}
