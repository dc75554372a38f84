//! End-to-end tests of the `chronocooked` binary's env commands: env list / replay /
//! render / play, the env demo and `bench env` (runs, evaluation and reports:
//! `tests/cli_runs.rs`).

use crate::common;

use common::{bin, json_lines, run_err, run_ok, temp_dir};
use serde_json::Value;
use std::io::Write;
use std::process::Stdio;

#[test]
fn env_list_shows_every_task_with_defaults_and_filters_by_tag() {
    let text = run_ok(&["env", "list"]);
    for id in [
        "FixedInterval-v0",
        "PeakInterval-v0",
        "Bisection-v0",
        "MultiTimer-v0",
        "DualTask-v0",
        "Uncertainty-v0",
        "MultiAnchor-v0",
        "MultiOven-v0",
        "Reproduction-v0",
    ] {
        assert!(text.contains(id), "{id} missing");
    }
    let json = run_ok(&["env", "list", "--json", "--tag", "paper"]);
    let ids: Vec<String> = json_lines(&json)
        .iter()
        .map(|l| l["id"].as_str().unwrap().to_string())
        .collect();
    assert!(ids.iter().any(|i| i == "Bisection-v0"));
    assert!(
        !ids.iter().any(|i| i == "MultiOven-v0"),
        "the extensions are not the paper's"
    );
    let json = run_ok(&["env", "list", "--json", "--tag", "categorization"]);
    let lines = json_lines(&json);
    assert_eq!(lines.len(), 1);
    assert_eq!(lines[0]["id"], "MultiAnchor-v0");
    assert_eq!(
        lines[0]["defaults"]["params"]["anchors"],
        serde_json::json!([4, 8, 12])
    );
    // The parameter rows come from the tables: key, aliases, default, allowed values.
    let ovens = run_ok(&["env", "list", "--json", "--tag", "concurrent"]);
    let row = &json_lines(&ovens)[0]["params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["key"] == "ovens")
        .cloned()
        .unwrap();
    assert_eq!(row["aliases"], serde_json::json!(["n_ovens"]));
    assert_eq!(row["default"], "2");
    assert_eq!(row["allowed"], "integer 1..=3");
    assert!(run_err(&["env", "list", "--tag", "nope"]).contains("tags in use"));
}

#[test]
fn env_replay_prints_reset_then_one_json_line_per_step() {
    let out = run_ok(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--reference",
        "--set",
        "oven_duration=1",
        "--set",
        "max_timesteps=200",
        "--start",
        "1,0",
        "--td",
        "1",
        "--actions",
        "2,5,1,5,5,3,3,5",
    ]);
    let lines = json_lines(&out);
    assert_eq!(lines.len(), 9);
    assert_eq!(lines[0]["step"], 0);
    assert_eq!(lines[0]["obs"][1][0], serde_json::json!([0, 1, 0, 0, 0, 0]));
    assert_eq!(lines[0]["obs"][2][0][0], 5, "oven code at (2,0)");
    for l in &lines {
        for key in ["obs", "reward", "terminated", "truncated", "info"] {
            assert!(l.get(key).is_some(), "missing {key}");
        }
    }
    assert_eq!(lines[4]["info"]["events"], serde_json::json!(["onion_in"]));
    assert_eq!(
        lines[5]["info"]["events"],
        serde_json::json!(["oven_check", "pickup"])
    );
    assert_eq!(lines[8]["reward"], 1.0);
    assert_eq!(lines[8]["terminated"], true);
    assert_eq!(lines[8]["info"]["counter"], "main");
}

#[test]
fn env_replay_rejects_bad_input_with_clear_messages() {
    let e = run_err(&["env", "replay", "FixedInterval-v0", "--actions", "1,7"]);
    assert!(
        e.contains("invalid action 7") && e.contains("5 interact"),
        "{e}"
    );
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--set",
        "td=0",
        "--actions",
        "1",
    ]);
    assert!(e.contains("`td`") && e.contains("1..=10000"), "{e}");
    let e = run_err(&["env", "replay", "Nope-v0", "--actions", "1"]);
    assert!(e.contains("registered"), "{e}");
    // A lost action and two spellings of one setting that disagree are refused.
    let e = run_err(&["env", "replay", "FixedInterval-v0", "--actions", "0,0,,0"]);
    assert!(e.contains("action 3 is empty"), "{e}");
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--set",
        "td=6",
        "--td",
        "9",
        "--actions",
        "0",
    ]);
    assert!(e.contains("--td 9 and --set td=6 disagree"), "{e}");
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--reference",
        "--set",
        "reference_compat=false",
        "--actions",
        "0",
    ]);
    assert!(e.contains("disagree"), "{e}");
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--start",
        "0,1",
        "--actions",
        "1",
    ]);
    assert!(e.contains("start") && e.contains("free cell"), "{e}");
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--start",
        "x",
        "--actions",
        "1",
    ]);
    assert!(e.contains("ROW,COL"), "{e}");
    let e = run_err(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--set",
        "max_timesteps=1",
        "--actions",
        "0,0,0",
    ]);
    assert!(e.contains("episode ended"), "{e}");
}

#[test]
fn env_render_writes_a_gif_and_png_frames() {
    let dir = temp_dir("render");
    let gif = dir.join("ep.gif");
    let pngs = dir.join("frames");
    let out = run_ok(&[
        "env",
        "render",
        "Bisection-v0",
        "--td",
        "4",
        "--out",
        gif.to_str().unwrap(),
        "--png-dir",
        pngs.to_str().unwrap(),
        "--ascii",
    ]);
    assert!(out.contains("return 1.000"), "{out}");
    let bytes = std::fs::read(&gif).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    let frames = std::fs::read_dir(&pngs).unwrap().count();
    assert!(frames > 5);
    let png = std::fs::read(pngs.join("frame_0000.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

/// `env play` of FI at TD 2 from cell (1, 0), recorded into `record`, with `keys` typed.
fn play_fi_td2(record: &std::path::Path, extra: &[&str], keys: &[u8]) {
    let mut child = bin()
        .args([
            "env",
            "play",
            "FixedInterval-v0",
            "--set",
            "td=2",
            "--start",
            "1,0",
        ])
        .args(extra)
        .args(["--record", record.to_str().unwrap()])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(keys).unwrap();
    assert!(child.wait_with_output().unwrap().status.success());
}

#[test]
fn env_play_records_keyboard_steps_in_the_replay_shape() {
    let dir = temp_dir("play");
    let record = dir.join("human.jsonl");
    // up, interact, down, interact, wait, interact (pickup), right, right, interact.
    play_fi_td2(&record, &[], b"wese.eddeq");
    let lines = json_lines(&std::fs::read_to_string(&record).unwrap());
    assert_eq!(lines.len(), 10, "reset + 9 steps");
    assert_eq!(lines[0]["task"], "FixedInterval-v0");
    assert_eq!(lines[9]["reward"], 1.0);
    assert_eq!(lines[9]["terminated"], true);
    // Same shape as replay: replaying the recorded actions gives the same lines.
    let actions: Vec<String> = lines[1..].iter().map(|l| l["action"].to_string()).collect();
    let replay = run_ok(&[
        "env",
        "replay",
        "FixedInterval-v0",
        "--set",
        "td=2",
        "--start",
        "1,0",
        "--actions",
        &actions.join(","),
    ]);
    let replayed = json_lines(&replay);
    // The play's reset line also carries how to replay it (seed and reset options); the
    // rest is the replay's shape, line for line.
    let mut played = lines.clone();
    let key = played[0].as_object_mut().unwrap().remove("reset").unwrap();
    assert_eq!(key["options"]["start"], serde_json::json!([1, 0]), "{key}");
    assert!(key["seed"].is_u64(), "{key}");
    assert_eq!(replayed, played);
    // The recording is scored as human play, checked against the task first.
    let eval = dir.join("eval");
    run_ok(&[
        "eval",
        "--human",
        record.to_str().unwrap(),
        "--out",
        eval.to_str().unwrap(),
    ]);
    assert!(eval.join("metrics.json").is_file());
}

/// A recording with steps cut out of an episode before the session's next one (the
/// generator continued, so the episode must have ended) is refused naming the line.
#[test]
fn a_recording_with_an_episode_cut_short_is_refused() {
    let dir = temp_dir("play-cut");
    let record = dir.join("human.jsonl");
    play_fi_td2(&record, &["--episodes", "2"], b"wese.eddewese.eddeq");
    let text = std::fs::read_to_string(&record).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 20, "two episodes of a reset and 9 steps");
    let whole = dir.join("whole");
    run_ok(&[
        "eval",
        "--human",
        record.to_str().unwrap(),
        "--out",
        whole.to_str().unwrap(),
    ]);
    // Episode 1's delivery (line 10) removed.
    let cut: Vec<&str> = lines[..9].iter().chain(&lines[10..]).copied().collect();
    let edited = dir.join("cut.jsonl");
    std::fs::write(&edited, cut.join("\n") + "\n").unwrap();
    let err = run_err(&[
        "eval",
        "--human",
        edited.to_str().unwrap(),
        "--out",
        dir.join("e").to_str().unwrap(),
    ]);
    assert!(
        err.contains("line 10") && err.contains("did not end"),
        "{err}"
    );
}

/// An error that cannot be written because stderr is on a full disk (`/dev/full`) ends the
/// command with the error status 2, not with a panic (101) in `eprintln!`.
#[test]
fn a_full_disk_under_stderr_ends_with_the_error_status_not_a_panic() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("Linux has /dev/full");
    let status = bin()
        .args(["train", "--set", "bogus=1"])
        .stderr(Stdio::from(full))
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(2));
}

#[test]
fn demo_runs_every_task_and_writes_gifs() {
    let dir = temp_dir("demo");
    let out = run_ok(&["env", "demo", "--out", dir.to_str().unwrap()]);
    assert!(out.contains("Uncertainty-v0"));
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let rows = summary.as_array().unwrap();
    assert_eq!(rows.len(), chronocooked_env::all_tasks().len());
    for row in rows {
        assert!(
            row["oracle_mean_return"].as_f64().unwrap()
                > row["random_mean_return"].as_f64().unwrap()
        );
        let gif = std::fs::read(row["gif"].as_str().unwrap()).unwrap();
        assert_eq!(&gif[..3], b"GIF");
    }
}

#[test]
fn bench_env_runs_briefly() {
    let out = run_ok(&[
        "bench",
        "env",
        "--seconds",
        "0.05",
        "--n-envs",
        "8",
        "--json",
    ]);
    let rows = json_lines(&out);
    assert_eq!(rows.len(), 4);
    assert!(
        rows.iter()
            .all(|r| r["steps_per_sec"].as_f64().unwrap() > 0.0)
    );
    assert!(
        !bin()
            .args(["bench", "env", "--n-envs", "0"])
            .status()
            .unwrap()
            .success()
    );
}

#[test]
fn bench_train_measures_its_updates() {
    // One warm-up and one measured update of the smallest model: a rate and its parts.
    let out = run_ok(&[
        "bench",
        "train",
        "--models",
        "cnn-mlp",
        "--updates",
        "1",
        "--preset",
        "fast",
    ]);
    let line = out
        .lines()
        .find(|l| l.contains("cnn-mlp"))
        .unwrap_or_else(|| panic!("no cnn-mlp line in {out}"));
    let rate: f64 = line
        .split_whitespace()
        .nth(4)
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no rate in {line}"));
    assert!(
        rate > 0.0 && line.contains("env-steps/s") && line.contains("1 updates"),
        "{line}"
    );
}

#[test]
fn env_replay_accepts_reference_parameter_names_for_multi_timer() {
    let out = run_ok(&[
        "env",
        "replay",
        "MultiTimer-v0",
        "--reference",
        "--set",
        "oven_duration_list=3,6,9",
        "--set",
        "num_timers=3",
        "--set",
        "oven_duration=6",
        "--set",
        "undercooked_possible=True",
        "--set",
        "overcooked_buffer=0",
        "--set",
        "undercooked_buffer=0",
        "--set",
        "reduced_reward=0.1",
        "--set",
        "max_timesteps=100",
        "--start",
        "1,0",
        "--actions",
        "2,5,1,5,5,3,3,5",
    ]);
    let lines = json_lines(&out);
    assert_eq!(
        lines[4]["obs"][2][0][4], 6,
        "oven channel holds the TD value"
    );
    assert_eq!(lines[5]["info"]["oven_off_time"], 1);
    assert!(
        (lines[8]["reward"].as_f64().unwrap() - 0.1).abs() < 1e-6,
        "undercooked soup"
    );
    assert_eq!(lines[8]["terminated"], true);
}

#[test]
fn a_reader_that_goes_away_ends_the_command_quietly() {
    // `chronocooked env replay … | head -0`: the read end of stdout is closed while the
    // command writes ≈ 110 KB of JSON lines, more than a pipe holds (64 KiB), so some write
    // finds no reader. A command-line tool then ends on SIGPIPE with nothing on stderr; it
    // must not panic ("failed printing to stdout: Broken pipe", exit 101).
    let waits = vec!["0"; 190].join(",");
    let mut child = bin()
        .args(["env", "replay", "FixedInterval-v0", "--actions", &waits])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_ne!(out.status.code(), Some(101), "{:?} {stderr}", out.status);
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(out.status.signal(), Some(13), "{:?}", out.status);
    }
}

/// Copies a folder tree (the committed held-out jobs) into `to`.
fn copy_tree(from: &std::path::Path, to: &std::path::Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), &target).unwrap();
        }
    }
}

#[test]
fn paper_check_held_out_judges_each_statistic_and_refuses_a_used_seed() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = temp_dir("held-out");
    let held = dir.join("held");
    copy_tree(
        &root.join("results/paper-core-heldout/jobs"),
        &held.join("jobs"),
    );
    let held_s = held.to_str().unwrap();
    let study = root.join("results/paper-core");
    let out = run_ok(&[
        "paper",
        "check-held-out",
        held_s,
        "--study",
        study.to_str().unwrap(),
    ]);
    // Every row of the table carries a verdict; the CSV has one row per job × statistic.
    let rows: Vec<&str> = out.lines().filter(|l| l.contains("/seed")).collect();
    assert!(!rows.is_empty(), "{out}");
    assert!(
        rows.iter()
            .all(|l| ["inside", "outside", "no value", "no range"]
                .iter()
                .any(|v| l.trim_end().ends_with(&format!("{v} |")))),
        "{out}"
    );
    let csv = std::fs::read_to_string(held.join("held-out.csv")).unwrap();
    assert!(csv.starts_with("id,seed,task,model,condition,statistic,value,"));
    assert_eq!(csv.lines().count(), rows.len() + 1);
    // The held-out jobs as their own study: every seed is "used", a typed refusal.
    let err = run_err(&["paper", "check-held-out", held_s, "--study", held_s]);
    assert!(
        err.contains("is already one of the study's runs of this condition"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
