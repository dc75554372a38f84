//! The one reader of what every run's `config.json` shares ([`RunFolder`]): the configs the
//! two trainers write are read back as their kind, task and seed; a folder without a config
//! or with an unknown kind is refused naming the file.

use chronocooked_env::TaskParams;
use chronocooked_training::run_config::{says_timing, write_config};
use chronocooked_training::{RunFolder, RunKind, TimingRunConfig, TrainError, resolve};
use std::path::PathBuf;

fn folder(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("run_folder")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_configs_both_trainers_write_read_back_as_their_kind_task_and_seed() {
    // A timing run's config, as `timing_run` writes it.
    let mut timing = TimingRunConfig::new(
        &chronocooked_env::Task::new("Bisection-v0").unwrap(),
        "ddm",
        11,
    );
    timing.set("env.short=3").unwrap();
    timing.set("env.long=9").unwrap();
    let dir = folder("timing");
    write_config(&dir, &serde_json::to_vec(&timing).unwrap()).unwrap();
    let run = RunFolder::open(&dir).unwrap();
    assert_eq!(run.kind, RunKind::Timing);
    assert_eq!(run.task.id(), "Bisection-v0");
    assert_eq!(run.task.overrides(), vec!["short=3", "long=9"]);
    assert_eq!(run.seed, Some(11));
    assert!(!run.finished(), "no summary.json yet");
    assert!(says_timing(&dir));
    match run.task_config().unwrap().params {
        TaskParams::Bisection { short, long } => assert_eq!((short, long), (3, 9)),
        p => panic!("{p:?}"),
    }

    // A PPO run's config (no `kind`).
    let ppo = resolve(
        "FixedInterval-v0",
        "lstm8".parse().unwrap(),
        "fast",
        5,
        &["env.td=7"],
    )
    .unwrap();
    let dir = folder("ppo");
    write_config(&dir, &serde_json::to_vec(&ppo).unwrap()).unwrap();
    std::fs::write(dir.join("summary.json"), "{}").unwrap();
    let run = RunFolder::open(&dir).unwrap();
    assert_eq!(run.kind, RunKind::Ppo);
    assert_eq!((run.task.id(), run.seed), ("FixedInterval-v0", Some(5)));
    assert_eq!(run.task_config().unwrap().params.td(), Some(7));
    assert!(run.finished());
    assert!(!says_timing(&dir));
}

#[test]
fn a_folder_without_a_config_or_with_an_unknown_kind_is_refused_naming_the_file() {
    let dir = folder("empty");
    assert!(matches!(
        RunFolder::open(&dir),
        Err(TrainError::NotARun { .. })
    ));
    std::fs::write(
        dir.join("config.json"),
        r#"{"kind":"tabular","task":"FixedInterval-v0","env":[],"seed":1}"#,
    )
    .unwrap();
    let err = RunFolder::open(&dir).unwrap_err().to_string();
    assert!(
        err.contains("config.json") && err.contains("`kind`"),
        "{err}"
    );
    // A task parameter the task does not have: refused when the folder is opened.
    std::fs::write(
        dir.join("config.json"),
        r#"{"task":"FixedInterval-v0","env":["anchors=3,6"],"seed":1}"#,
    )
    .unwrap();
    let err = RunFolder::open(&dir).unwrap_err().to_string();
    assert!(
        err.contains("config.json") && err.contains("anchors"),
        "{err}"
    );
}
