//! A task family defined outside the lab's crates (`examples/interval_production`): it
//! trains, evaluates and appears in a report, from the command line (the example's binary,
//! which registers the family and runs the lab's CLI) and from Rust (the same family file,
//! registered in this test binary).

#[path = "../examples/interval_production/family.rs"]
#[allow(dead_code)]
mod family;

use chronocooked_analysis::{Mode, reference_conditions, run_protocol};
use chronocooked_env::ChronoEnv;
use chronocooked_env::Task;
use chronocooked_models::agent::OracleAgent;
use chronocooked_training::timing_run::load_agent;
use chronocooked_training::{TimingRunConfig, run_timing_training};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The example's binary, built next to the lab's by `cargo test` (examples are built with
/// the tests).
fn example_bin() -> PathBuf {
    let lab = Path::new(env!("CARGO_BIN_EXE_chronocooked"));
    let bin = lab
        .parent()
        .expect("the binary has a folder")
        .join("examples")
        .join("interval_production");
    assert!(
        bin.exists(),
        "{} is missing: `cargo test` builds the examples (or `cargo build --examples`)",
        bin.display()
    );
    bin
}

fn temp_dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-external-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(bin: &Path, args: &[&str]) -> Output {
    let out = Command::new(bin).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "{} {}: {}",
        bin.display(),
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn success_rate(eval_dir: &Path) -> f64 {
    let text = std::fs::read_to_string(eval_dir.join("metrics.json")).unwrap();
    let metrics: serde_json::Value = serde_json::from_str(&text).unwrap();
    metrics["success_rate"].as_f64().unwrap()
}

#[test]
fn the_example_task_trains_evaluates_and_is_reported_from_the_command_line() {
    let bin = example_bin();
    let dir = temp_dir("cli");
    let p = |name: &str| dir.join(name).to_str().unwrap().to_string();

    let listed = String::from_utf8(run(&bin, &["env", "list"]).stdout).unwrap();
    assert!(listed.contains(family::ID), "{listed}");
    // The built-in tasks are all still there.
    for id in ["FixedInterval-v0", "Reproduction-v0"] {
        assert!(listed.contains(id), "{id} missing from {listed}");
    }

    // PPO with the family's own fast preset (its declared budget: 300k steps).
    run(
        &bin,
        &[
            "train",
            "--task",
            family::ID,
            "--model",
            "cnn-mlp",
            "--preset",
            "fast",
            "--quiet",
            "--out",
            &p("ppo"),
        ],
    );
    let config = std::fs::read_to_string(dir.join("ppo/config.json")).unwrap();
    let config: serde_json::Value = serde_json::from_str(&config).unwrap();
    assert_eq!(config["task"], family::ID);
    assert_eq!(config["total_steps"], 300_000, "the family's fast preset");
    run(&bin, &["eval", "--run", &p("ppo"), "--out", &p("ppo-eval")]);

    // A timing model plays it (the family declares interval production), and the oracle
    // and the random agent are its baselines.
    run(
        &bin,
        &[
            "train",
            "--task",
            family::ID,
            "--model",
            "timecells-csc",
            "--quiet",
            "--out",
            &p("tc"),
        ],
    );
    run(&bin, &["eval", "--run", &p("tc"), "--out", &p("tc-eval")]);
    for agent in ["oracle", "random"] {
        run(
            &bin,
            &[
                "eval",
                "--agent",
                agent,
                "--task",
                family::ID,
                "--out",
                &p(agent),
            ],
        );
    }
    // The oracle turns the oven off at TD exactly: paid in every window, the narrowest
    // (0 steps) included.
    assert_eq!(success_rate(&dir.join("oracle")), 1.0);

    run(
        &bin,
        &[
            "report",
            "--eval",
            &p("ppo-eval"),
            &p("tc-eval"),
            &p("oracle"),
            &p("random"),
            "--out",
            &p("report"),
        ],
    );
    let html = std::fs::read_to_string(dir.join("report/report.html")).unwrap();
    assert!(html.contains(family::ID), "the report names the task");
    let table = std::fs::read_to_string(dir.join("report/report.md")).unwrap();
    for row in [
        "| cnn-mlp |",
        "| timecells-csc |",
        "| oracle |",
        "| random |",
    ] {
        assert!(table.contains(row), "{row} missing from\n{table}");
    }

    // The lab's own binary does not know the task, and says so, naming it and the file.
    let lab = Command::new(env!("CARGO_BIN_EXE_chronocooked"))
        .args(["eval", "--run", &p("ppo"), "--out", &p("refused")])
        .output()
        .unwrap();
    assert!(!lab.status.success());
    let err = String::from_utf8_lossy(&lab.stderr);
    assert!(
        err.contains("unknown task `IntervalProduction-v0`") && err.contains("config.json"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_example_task_is_played_from_rust_by_the_oracle_and_a_timing_model() {
    family::register_once().unwrap();
    let task = Task::new(family::ID).unwrap();
    // The family's cross-field check runs on every edit.
    let err = task.with(&["window=12"]).unwrap_err().to_string();
    assert!(err.contains("window") && err.contains("< td"), "{err}");

    let conditions = reference_conditions(&task).unwrap();
    assert_eq!(conditions.len(), 5, "the trained window and four probes");
    let mut oracle = OracleAgent::new(&ChronoEnv::new(&task.config().unwrap()).unwrap());
    let records = run_protocol(&mut oracle, &conditions, Mode::Reference, 0).unwrap();
    assert!(records.iter().all(|r| r.episode.success));

    // The serial-compound time cells learn the window: measured 0.67–0.92 success over
    // seeds 0–7 in the reference evaluation (random agent: 0.03–0.10 over seeds 0–3).
    let dir = temp_dir("rust");
    for seed in [0, 1] {
        let cfg = TimingRunConfig::new(&task, "timecells-csc", seed);
        let run = dir.join(format!("tc{seed}"));
        run_timing_training(&cfg, &run, "test", |_| {}).unwrap();
        let mut agent = load_agent(&run, None).unwrap();
        let records = run_protocol(agent.as_mut(), &conditions, Mode::Reference, seed).unwrap();
        let rate =
            records.iter().filter(|r| r.episode.success).count() as f64 / records.len() as f64;
        assert!(rate >= 0.5, "seed {seed}: success {rate}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
