//! Sweeps and the end-to-end CLI workflow: sweep-file expansion and validation, Slurm
//! emission (`bash -n`), an interrupted sweep finishing on rerun without redoing finished
//! jobs, and train → eval → record → export → report on tiny budgets.

use chronocooked_pipeline::sweep::{SweepFile, job_done};
use serde_json::Value;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_chronocooked"))
}

fn run_ok(args: &[&str]) -> (String, String) {
    let out = bin().args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{args:?} failed: {stderr}");
    (String::from_utf8(out.stdout).unwrap(), stderr)
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("chronocooked-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const PLAN: &str = r#"
name = "plan"
tasks = ["FixedInterval-v0", "Bisection-v0"]
models = ["oracle", "random", "ddm", "lstm", "cnn-mlp"]
sizes = [8, 125]
seeds = [0, 1]
preset = "fast"
steps = 5000
variants = [["learning_rate=1e-3"], ["learning_rate=3e-4"]]

[task_variants]
"FixedInterval-v0" = [["env.td=6"], ["env.td=12"]]
"#;

#[test]
fn sweep_file_expands_into_the_crossed_jobs() {
    let s = SweepFile::parse(PLAN, "plan").unwrap();
    assert_eq!(
        s.expanded_models(),
        ["oracle", "random", "ddm", "lstm8", "lstm125", "cnn-mlp"]
    );
    let jobs = s.jobs().unwrap();
    // FI: 2 TD variants x 2 global variants; trained models x 2 seeds; baselines take only
    // the task settings (2 TDs), the oracle one seed.
    let fi = |m: &str| {
        jobs.iter()
            .filter(|j| j.task.id() == "FixedInterval-v0" && j.model == m)
            .count()
    };
    assert_eq!(fi("lstm8"), 8);
    // The learning-rate variants are PPO settings: the timing model runs once per TD.
    assert_eq!(fi("ddm"), 4);
    assert_eq!(fi("random"), 4);
    assert_eq!(fi("oracle"), 2);
    let bis = |m: &str| {
        jobs.iter()
            .filter(|j| j.task.id() == "Bisection-v0" && j.model == m)
            .count()
    };
    assert_eq!(bis("lstm125"), 4);
    assert_eq!(bis("oracle"), 1);
    let mut ids: Vec<&str> = jobs.iter().map(|j| j.id.as_str()).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), jobs.len(), "job ids are unique");
    let j = jobs
        .iter()
        .find(|j| j.id == "FixedInterval-v0/lstm8~env.td-6_learning_rate-1e-3/seed1")
        .expect("job id layout");
    assert_eq!(
        j.sets,
        ["total_steps=5000", "env.td=6", "learning_rate=1e-3"]
    );
    assert_eq!(j.task.overrides(), ["td=6"]);
    assert_eq!(
        j.row, "lstm8~learning_rate-1e-3",
        "TDs share a leaderboard row"
    );
    let d = jobs
        .iter()
        .find(|j| j.model == "ddm" && j.task.id() == "FixedInterval-v0")
        .unwrap();
    assert!(
        !d.sets
            .iter()
            .any(|s| s.starts_with("total_steps") || s.starts_with("learning_rate"))
    );
    let o = jobs.iter().find(|j| j.model == "oracle").unwrap();
    assert!(o.sets.iter().all(|s| s.starts_with("env.")));
    // Same file, same plan.
    assert_eq!(
        SweepFile::parse(PLAN, "plan").unwrap().jobs().unwrap(),
        jobs
    );
}

#[test]
fn sweep_file_errors_name_the_field_and_allowed_values() {
    let base = "tasks = [\"FixedInterval-v0\"]\nmodels = [\"ddm\"]\n";
    for (extra, needle) in [
        ("models2 = 1\n", "unknown field"),
        ("seeds = []\n", "seeds"),
        ("preset = \"slow\"\n", "reference, fast"),
        ("steps = 0\n", "steps"),
        ("variants = [[\"lr\"]]\n", "key=value"),
        (
            "variants = [[\"learning_rate=1e-3\"]]\n",
            "some model of the sweep accepts",
        ),
        (
            "[task_variants]\n\"Bisection-v0\" = [[\"env.short=4\"]]\n",
            "task_variants",
        ),
        // One key twice in one list: the later value would silently win.
        ("set = [\"env.td=6\", \"env.td=9\"]\n", "set twice"),
        (
            "variants = [[\"episodes=10\", \"episodes=20\"]]\n",
            "set twice",
        ),
        // One variant twice.
        (
            "variants = [[\"episodes=10\"], [\"episodes=10\"]]\n",
            "each variant once",
        ),
    ] {
        let err = SweepFile::parse(&format!("{base}{extra}"), "f.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(needle), "{extra}: {err}");
    }
    let err = SweepFile::parse("tasks = [\"Nope-v0\"]\nmodels = [\"ddm\"]\n", "f.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("FixedInterval-v0"), "{err}");
    let err = SweepFile::parse(
        "tasks = [\"FixedInterval-v0\"]\nmodels = [\"transformer\"]\n",
        "f.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("timecells-ms") && err.contains("oracle"),
        "{err}"
    );
    // The CLI turns them into a non-zero exit with the message.
    let dir = temp_dir("bad");
    let f = dir.join("bad.toml");
    std::fs::write(&f, "tasks = []\nmodels = [\"ddm\"]\n").unwrap();
    let out = bin().args(["sweep", f.to_str().unwrap()]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("tasks"));
}

#[test]
fn slurm_emission_passes_bash_n_and_lists_every_job() {
    let dir = temp_dir("slurm");
    let file = dir.join("plan.toml");
    std::fs::write(&file, PLAN).unwrap();
    let out = dir.join("out");
    let (stdout, _) = run_ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--emit",
        "slurm",
        "--max-parallel",
        "8",
        "--time",
        "01:30:00",
    ]);
    assert!(stdout.contains("sbatch"), "{stdout}");
    let jobs = SweepFile::parse(PLAN, "plan").unwrap().jobs().unwrap();
    let slurm = out.join("slurm");
    let commands = std::fs::read_to_string(slurm.join("commands.txt")).unwrap();
    let lines: Vec<&str> = commands.lines().collect();
    assert_eq!(lines.len(), jobs.len());
    for (line, job) in lines.iter().zip(&jobs) {
        assert!(line.contains(" sweep-job "), "{line}");
        assert!(line.contains(&format!("--id {}", job.id)), "{line}");
        assert!(line.contains(file.to_str().unwrap()), "{line}");
    }
    let script = std::fs::read_to_string(slurm.join("sweep.sbatch")).unwrap();
    assert!(script.contains(&format!("#SBATCH --array=0-{}%8", jobs.len() - 1)));
    assert!(script.contains("#SBATCH --time=01:30:00"));
    assert!(script.contains("SLURM_ARRAY_TASK_ID"));
    for name in ["sweep.sbatch", "report.sbatch"] {
        let status = Command::new("bash")
            .arg("-n")
            .arg(slurm.join(name))
            .status()
            .unwrap();
        assert!(status.success(), "{name} fails bash -n");
    }
    let report = std::fs::read_to_string(slurm.join("report.sbatch")).unwrap();
    assert!(report.contains("report --runs"), "{report}");
    // One line of commands.txt, run by hand as a Slurm task would, runs that job.
    let tiny = "name = \"t\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"oracle\"]\n";
    std::fs::write(&file, tiny).unwrap();
    run_ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--emit",
        "slurm",
    ]);
    let line = std::fs::read_to_string(slurm.join("commands.txt")).unwrap();
    let status = Command::new("bash")
        .arg("-c")
        .arg(line.trim())
        .status()
        .unwrap();
    assert!(status.success());
    assert!(job_done(&out.join("FixedInterval-v0/oracle/seed0")));
    // Bad scheduler / time.
    for (flag, value, needle) in [("--emit", "pbs", "slurm"), ("--time", "90min", "HH:MM:SS")] {
        let mut args = vec![
            "sweep",
            file.to_str().unwrap(),
            "--emit",
            "slurm",
            flag,
            value,
        ];
        if flag == "--emit" {
            args.truncate(2);
            args.extend([flag, value]);
        }
        let o = bin().args(&args).output().unwrap();
        assert!(!o.status.success());
        assert!(String::from_utf8_lossy(&o.stderr).contains(needle));
    }
}

/// Modification times of every finished job's `progress.json`.
/// The job ids of the sweep file `file`, in order.
fn job_ids(file: &Path) -> Vec<String> {
    SweepFile::load(file)
        .unwrap()
        .jobs()
        .unwrap()
        .into_iter()
        .map(|j| j.id)
        .collect()
}

fn finished(out: &Path, ids: &[String]) -> Vec<(String, SystemTime)> {
    ids.iter()
        .filter(|id| job_done(&out.join(id)))
        .map(|id| {
            let m = std::fs::metadata(out.join(id).join("progress.json")).unwrap();
            (id.clone(), m.modified().unwrap())
        })
        .collect()
}

fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    if let Ok(rd) = std::fs::read_dir(dir) {
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                out.extend(files_under(&p));
            } else {
                out.push(p);
            }
        }
    }
    out
}

#[test]
fn interrupted_sweep_rerun_finishes_without_redoing_finished_jobs() {
    let dir = temp_dir("resume");
    let file = dir.join("s.toml");
    std::fs::write(
        &file,
        r#"
name = "resume"
tasks = ["FixedInterval-v0"]
models = ["oracle", "ddm", "lstm", "timecells-csc"]
sizes = [8]
preset = "fast"
steps = 40000
episodes = 300
set = ["checkpoint_every=4000", "eval_every=0"]
"#,
    )
    .unwrap();
    let out = dir.join("out");
    let ids = job_ids(&file);
    assert_eq!(ids.len(), 4);
    // One worker: oracle, ddm, then the LSTM run, which is killed mid-training with the
    // whole process group (as Ctrl-C or a scheduler would).
    let mut child = bin()
        .args([
            "sweep",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--workers", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .process_group(0)
        .spawn()
        .unwrap();
    let lstm = out.join(&ids[2]);
    let t0 = Instant::now();
    while !lstm
        .join("run/checkpoints")
        .read_dir()
        .is_ok_and(|mut d| d.next().is_some())
    {
        assert!(t0.elapsed() < Duration::from_secs(300), "no checkpoint");
        assert!(
            child.try_wait().unwrap().is_none(),
            "sweep ended before the kill"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    Command::new("kill")
        .args(["-KILL", "--", &format!("-{}", child.id())])
        .status()
        .unwrap();
    child.wait().unwrap();
    let before = finished(&out, &ids);
    assert_eq!(
        before.iter().map(|b| b.0.as_str()).collect::<Vec<_>>(),
        [ids[0].as_str(), ids[1].as_str()],
        "oracle and ddm finished before the kill"
    );
    assert!(!job_done(&lstm));
    std::thread::sleep(Duration::from_millis(20));
    let (_, stderr) = run_ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--workers",
        "2",
    ]);
    assert!(
        stderr.contains("4 jobs, 2 already finished, running 2"),
        "{stderr}"
    );
    let after = finished(&out, &ids);
    assert_eq!(after.len(), 4, "every job finished");
    for (id, t) in &before {
        let again = after.iter().find(|a| &a.0 == id).unwrap();
        assert_eq!(again.1, *t, "{id} was redone");
    }
    // The LSTM run continued from its checkpoint (its command log shows the resume) and
    // reached the full budget.
    let commands = std::fs::read_to_string(lstm.join("run/command.txt")).unwrap();
    assert!(commands.lines().count() >= 2, "{commands}");
    assert!(
        commands.lines().last().unwrap().ends_with("(resumed)"),
        "{commands}"
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(lstm.join("run/summary.json")).unwrap())
            .unwrap();
    assert!(summary["env_steps"].as_u64().unwrap() >= 40000, "{summary}");
    // No temporary or half-written file is left, every JSON parses, the report is there.
    for f in files_under(&out) {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        assert!(!name.contains(".tmp"), "leftover {}", f.display());
        if name.ends_with(".json") {
            let text = std::fs::read_to_string(&f).unwrap();
            serde_json::from_str::<Value>(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
        }
    }
    let html = std::fs::read_to_string(out.join("report/report.html")).unwrap();
    for model in ["oracle", "ddm", "lstm8", "timecells-csc"] {
        assert!(html.contains(&format!("<td>{model}</td>")), "{model} row");
    }
    // A third run has nothing to do.
    let (_, stderr) = run_ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(stderr.contains("4 already finished, running 0"), "{stderr}");
}

#[test]
fn train_eval_record_export_report_end_to_end() {
    use chronocooked_present::export::npz::{NpyData, read_npz};
    let dir = temp_dir("e2e");
    let p = |rel: &str| dir.join(rel).to_str().unwrap().to_string();
    // A PPO agent (tiny budget) and a timing model, each in the layout `sweep` uses.
    run_ok(&[
        "train",
        "--task",
        "FixedInterval-v0",
        "--model",
        "lstm8",
        "--preset",
        "fast",
        "--steps",
        "2000",
        "--set",
        "env.td=6",
        "--quiet",
        "--out",
        &p("lstm8/run"),
    ]);
    run_ok(&[
        "train",
        "--task",
        "FixedInterval-v0",
        "--model",
        "ddm",
        "--set",
        "env.td=6",
        "--quiet",
        "--out",
        &p("ddm/run"),
    ]);
    for model in ["lstm8", "ddm"] {
        let (stdout, _) = run_ok(&[
            "eval",
            "--run",
            &p(&format!("{model}/run")),
            "--out",
            &p(&format!("{model}/eval")),
        ]);
        assert!(stdout.contains("episodes"), "{stdout}");
        run_ok(&[
            "record",
            "--run",
            &p(&format!("{model}/run")),
            "--probe",
            "--summary",
            "--figures",
            &p(&format!("{model}/neural_figures")),
            "--out",
            &p(&format!("{model}/activity.json")),
        ]);
        run_ok(&[
            "export",
            "--activity",
            &p(&format!("{model}/activity.json")),
            "--eval",
            &p(&format!("{model}/eval")),
            "--out",
            &p(&format!("{model}/export")),
        ]);
        // The exported activity equals the recorded dataset value by value.
        let ds: chronocooked_models::ActivityDataset = serde_json::from_str(
            &std::fs::read_to_string(dir.join(model).join("activity.json")).unwrap(),
        )
        .unwrap();
        let arrays =
            read_npz(&std::fs::read(dir.join(model).join("export/activity.npz")).unwrap()).unwrap();
        let a = arrays.iter().find(|a| a.name == "activity").unwrap();
        let total: usize = ds.trials.iter().map(|t| t.steps).sum();
        assert_eq!(a.shape, vec![total, ds.meta.n_units()]);
        let NpyData::F32(values) = a.data.clone() else {
            panic!("activity is float32")
        };
        let expected: Vec<f32> = ds.trials.iter().flat_map(|t| t.activity.clone()).collect();
        assert_eq!(values, expected, "{model}");
        let meta: Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(model).join("export/activity.meta.json")).unwrap(),
        )
        .unwrap();
        for name in arrays.iter().map(|a| &a.name) {
            assert!(
                meta["arrays"][name]["shape"].is_array(),
                "{model}: {name} undescribed"
            );
        }
    }
    let (stdout, _) = run_ok(&["report", "--runs", &p(""), "--out", &p("report")]);
    assert!(stdout.contains("report.html"), "{stdout}");
    let html = std::fs::read_to_string(dir.join("report/report.html")).unwrap();
    assert!(!html.contains("http") && !html.contains("src=") && !html.contains("href="));
    for needle in [
        "<td>lstm8</td>",
        "<td>ddm</td>",
        "frac_ramp",
        "sequentiality",
        "decode_error",
        "learning_curve",
        "foc_over_td",
        // The "Mechanisms" section: a signature card per model whose recording has trials
        // with the oven on (the DDM's timing population is its accumulator, not its value
        // read-out; the 2,000-step LSTM never turns the oven on, so it has no card).
        "<h2>Mechanisms</h2>",
        "ddm — accumulator",
        // One headline table per theme (readable in a 1366 px window).
        "<h2 class=\"group\">Fixed interval</h2>",
        "<h2 class=\"group\">Neural activity: unit categories</h2>",
        "<h2 class=\"group\">Neural activity: population</h2>",
    ] {
        assert!(html.contains(needle), "{needle} missing from the report");
    }
    assert!(!html.contains("lstm8 — "), "a card without oven-on trials");
    let csv = std::fs::read_to_string(dir.join("report/report.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let ddm: Vec<&str> = csv
        .lines()
        .find(|l| l.starts_with("ddm,"))
        .unwrap()
        .split(',')
        .collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    // The DDM's accumulator is the population summarised: one unit, so no fraction in the
    // table; its count in the summary says it is a ramp.
    assert_eq!(ddm[col("neural_units")], "1");
    assert_eq!(ddm[col("frac_ramp")], "NaN");
    let summary: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("ddm/activity.summary.json")).unwrap(),
    )
    .unwrap();
    let acc = summary
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["population"] == "accumulator")
        .unwrap();
    assert_eq!(acc["categories"]["counts"]["ramp"], 1, "{acc}");
    assert_eq!(acc["window"], 12, "2 x TD 6");
    assert_eq!(ddm[col("fi_success")], "1");
    // Bad input: a folder with no evaluation, a missing folder.
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let o = bin()
        .args(["report", "--runs", empty.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("no evaluation folders"));
    let o = bin()
        .args(["report", "--runs", "/nonexistent-dir"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("no such folder"));
}

#[test]
fn sweep_adapts_agents_pretrained_without_uncertainty() {
    let dir = temp_dir("adapt");
    let file = dir.join("s.toml");
    std::fs::write(
        &file,
        r#"
name = "adapt"
tasks = ["Uncertainty-v0"]
models = ["oracle", "ddm", "lstm"]
sizes = [8]
preset = "fast"
steps = 2000
episodes = 300
record = false
export = false
adapt = true
adapt_episodes = 200
adapt_steps = 2000
[task_variants]
"Uncertainty-v0" = [["env.never_ready_prob=0", "curriculum=none"]]
"#,
    )
    .unwrap();
    let out = dir.join("out");
    let jobs = SweepFile::load(&file).unwrap().jobs().unwrap();
    // curriculum=none is a PPO setting: the timing model's job does not carry it, and the
    // row labels carry no task condition.
    let ddm = jobs.iter().find(|j| j.model == "ddm").unwrap();
    assert!(!ddm.sets.iter().any(|s| s.starts_with("curriculum")));
    assert_eq!(ddm.row, "ddm");
    let lstm = jobs.iter().find(|j| j.model == "lstm8").unwrap();
    assert!(lstm.sets.contains(&"curriculum=none".to_string()));
    assert_eq!(lstm.row, "lstm8");
    run_ok(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    for job in &jobs {
        let adapt = out.join(&job.id).join("adapt/adapt.json");
        if job.model == "oracle" {
            assert!(!adapt.exists(), "the oracle has nothing to adapt");
            continue;
        }
        let a: Value = serde_json::from_str(&std::fs::read_to_string(&adapt).unwrap()).unwrap();
        assert_eq!(a["task"], "Uncertainty-v0");
        assert!(
            !a["env"]
                .as_object()
                .unwrap()
                .keys()
                .any(|k| k.starts_with("never_ready")),
            "adaptation runs with the task's own never-ready probability: {a}"
        );
        assert!(a["episodes"].as_u64().unwrap() > 0);
    }
    let html = std::fs::read_to_string(out.join("report/report.html")).unwrap();
    assert!(html.contains("unc_adapted") && html.contains("unc_episodes_to_adapt"));
}

#[test]
fn paper_study_files_list_the_paper_grid_with_its_cost() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = temp_dir("paper-dry");
    let count = |file: &str| {
        let f = root.join("sweeps").join(file);
        let (stdout, _) = run_ok(&[
            "sweep",
            f.to_str().unwrap(),
            "--dry-run",
            "--out",
            out.to_str().unwrap(),
            "--workers",
            "2",
        ]);
        let jobs = stdout.lines().filter(|l| l.starts_with("todo ")).count();
        let last = stdout.lines().last().unwrap_or_default().to_string();
        (jobs, last)
    };
    // 4 models × (8, 125, 256) (+ CNN-MLP) × (6 FI TDs + 6 anchor pairs + 4 multi-timer
    // variants + uncertainty) × 4 repeats.
    let (jobs, last) = count("paper.toml");
    assert_eq!(jobs, 10 * (6 + 6 + 4 + 1) * 4);
    assert!(
        last.starts_with("680 jobs (680 to do); estimated "),
        "{last}"
    );
    let hours: f64 = last
        .split("estimated ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!(hours > 10.0 && hours < 1000.0, "{hours}");
    // paper-core: CNN, LSTM125, CTRNN125 trained and reservoir × (6 + 6 + 2) × 4.
    let (jobs, _) = count("paper-core.toml");
    assert_eq!(jobs, 4 * 14 * 4);
    let f = SweepFile::load(&root.join("sweeps/paper-core.toml")).unwrap();
    let ids: Vec<String> = f.jobs().unwrap().into_iter().map(|j| j.id).collect();
    assert!(ids.iter().any(|i| i.contains("ctrnn-reservoir125")));
    let _ = std::fs::remove_dir_all(&out);
}

/// A sweep whose report cannot be written (here: `report` is a file) while a job also
/// failed names both: the report's failure never hides the failed jobs (a full disk often
/// fails both).
#[test]
fn a_failed_report_does_not_hide_the_failed_jobs() {
    let dir = temp_dir("report-and-jobs");
    let file = dir.join("s.toml");
    std::fs::write(
        &file,
        "name = \"both\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"oracle\", \"random\"]\n",
    )
    .unwrap();
    let out = dir.join("out");
    let ids = job_ids(&file);
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("report"), "not a folder").unwrap();
    // The second job's folder is a file: that job fails.
    let blocked = out.join(&ids[1]);
    std::fs::create_dir_all(blocked.parent().unwrap()).unwrap();
    std::fs::write(&blocked, "not a folder").unwrap();
    let o = bin()
        .args([
            "sweep",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("1 of 2 jobs failed") && err.contains(&ids[1]) && err.contains("report"),
        "{err}"
    );
}
