//! Regression tests of issue #27 through the binary: a resume never loses history (`kill -9`
//! at several points, then `train --resume`, ends byte-identical to an uninterrupted run),
//! corrupt learned state is refused naming the file, walks never follow symlinks, sweep
//! files are checked fully by `--dry-run`, and every output is created with the umask.

use crate::common;

use common::{bin, curves_without_clock, files_below, run_err, run_ok, temp_dir};
use std::path::{Path, PathBuf};
use std::process::Stdio;
use std::time::{Duration, Instant};

const PPO: [&str; 10] = [
    "--model",
    "cnn-mlp",
    "--steps",
    "16000",
    "--set",
    "env.td=4",
    "--set",
    "checkpoint_every=1000",
    "--set",
    "keep_checkpoints=3",
];

pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn checkpoint_count(dir: &Path) -> usize {
    std::fs::read_dir(dir.join("checkpoints"))
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with("step-"))
        .count()
}

/// Trains the reference run once (shared by the tests that compare against it).
fn reference_run() -> &'static PathBuf {
    static R: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    R.get_or_init(|| {
        let dir = temp_dir("rel-reference").join("run");
        let mut args = vec!["train"];
        args.extend(PPO);
        args.extend(["--quiet", "--out", s(&dir)]);
        run_ok(&args);
        dir
    })
}

#[test]
fn kill_9_at_several_points_then_resume_is_byte_identical() {
    let reference = reference_run();
    let dir = temp_dir("rel-killed").join("run");
    // Kill points (ms after the start of each session), from a fixed seed: the run is
    // killed mid-update, mid-checkpoint or mid-evaluation wherever these land.
    let mut state: u64 = 0x2757;
    let mut delays = Vec::new();
    for _ in 0..6 {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        delays.push(20 + (state >> 33) % 800);
    }
    let mut sessions = 0;
    for (k, ms) in delays.iter().enumerate() {
        let mut cmd = bin();
        if k == 0 || !dir.join("config.json").is_file() {
            let mut args = vec!["train"];
            args.extend(PPO);
            args.extend(["--quiet", "--out", s(&dir)]);
            cmd.args(args);
        } else {
            cmd.args(["train", "--resume", s(&dir), "--quiet"]);
        }
        let mut child = cmd
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(*ms));
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        sessions += 1;
        // A kill between writing a checkpoint and deleting the oldest leaves one extra.
        assert!(
            checkpoint_count(&dir) <= 3 + 1,
            "more checkpoints than keep_checkpoints + 1"
        );
    }
    let out = bin()
        .args(["train", "--resume", s(&dir), "--quiet"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    sessions += 1;
    assert_eq!(curves_without_clock(&dir), curves_without_clock(reference));
    assert_eq!(
        std::fs::read(dir.join("model.bpk")).unwrap(),
        std::fs::read(reference.join("model.bpk")).unwrap(),
        "the final model differs from the uninterrupted run's"
    );
    let stray: Vec<_> = files_below(&dir)
        .into_iter()
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(chronocooked_env::fs::is_temp_name)
        })
        .collect();
    assert!(stray.is_empty(), "stray files: {stray:?}");
    assert!(checkpoint_count(&dir) <= 3);
    let commands = std::fs::read_to_string(dir.join("command.txt")).unwrap();
    assert!(
        commands.lines().count() >= 2 && commands.lines().count() <= sessions,
        "{commands}"
    );
}

#[test]
fn a_corrupt_newest_checkpoint_is_skipped_with_a_warning_and_history_kept() {
    let reference = reference_run();
    let root = temp_dir("rel-truncated");
    let dir = root.join("run");
    copy_tree(reference, &dir);
    std::fs::remove_file(dir.join("model.bpk")).unwrap();
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    let ckpts = sorted(&dir.join("checkpoints"));
    let newest = ckpts
        .iter()
        .rev()
        .find(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("step-")
        })
        .unwrap()
        .clone();
    let text = std::fs::read(&newest).unwrap();
    std::fs::write(&newest, &text[..text.len() / 3]).unwrap();
    // A killed writer's leftovers.
    std::fs::write(dir.join(".tmp-AbC123"), b"half").unwrap();
    std::fs::write(dir.join("checkpoints").join(".tmp-XyZ789"), b"half").unwrap();
    std::fs::create_dir_all(dir.join("figures")).unwrap();
    std::fs::write(dir.join("figures").join(".tmp-Fig456.svg"), b"<svg").unwrap();
    let out = bin()
        .args(["train", "--resume", s(&dir), "--quiet"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let name = newest.file_name().unwrap().to_string_lossy().to_string();
    assert!(
        err.contains("warning") && err.contains(&name),
        "no warning naming {name}: {err}"
    );
    assert!(!dir.join(".tmp-AbC123").exists());
    assert!(!dir.join("checkpoints").join(".tmp-XyZ789").exists());
    assert!(!dir.join("figures").join(".tmp-Fig456.svg").exists());
    assert_eq!(curves_without_clock(&dir), curves_without_clock(reference));
    assert_eq!(
        std::fs::read(dir.join("model.bpk")).unwrap(),
        std::fs::read(reference.join("model.bpk")).unwrap()
    );
    let commands = std::fs::read_to_string(dir.join("command.txt")).unwrap();
    assert_eq!(
        commands.lines().count(),
        2,
        "command.txt not appended: {commands}"
    );
}

#[test]
fn no_valid_checkpoint_is_an_error_naming_them_and_how_to_start_over() {
    let reference = reference_run();
    let dir = temp_dir("rel-none-valid").join("run");
    copy_tree(reference, &dir);
    std::fs::remove_file(dir.join("model.bpk")).unwrap();
    let curves_before = std::fs::read(dir.join("curves.csv")).unwrap();
    for p in sorted(&dir.join("checkpoints")) {
        if p.file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("step-")
        {
            std::fs::write(&p, b"{\"steps\": 1").unwrap();
        }
    }
    let err = run_err(&["train", "--resume", s(&dir), "--quiet"]);
    assert!(err.contains("no valid checkpoint"), "{err}");
    assert!(err.contains("step-000000016000.json"), "{err}");
    assert!(err.contains("start over"), "{err}");
    // Nothing was rewritten from step 0.
    assert_eq!(
        std::fs::read(dir.join("curves.csv")).unwrap(),
        curves_before
    );
    // Loading the policy says the checkpoints are corrupt (not that there are none).
    let err = run_err(&["eval", "--run", s(&dir), "--out", s(&dir.join("e"))]);
    assert!(err.contains("corrupt"), "{err}");
}

#[test]
fn a_run_whose_checkpoints_folder_was_deleted_is_not_restarted_from_step_0() {
    let reference = reference_run();
    let dir = temp_dir("rel-no-checkpoints").join("run");
    copy_tree(reference, &dir);
    // The whole folder, with the manifest that would have named the missing files.
    std::fs::remove_dir_all(dir.join("checkpoints")).unwrap();
    let curves_before = std::fs::read(dir.join("curves.csv")).unwrap();
    let err = run_err(&["train", "--resume", s(&dir), "--quiet"]);
    assert!(
        err.contains("no checkpoint") && err.contains("start over on purpose"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(dir.join("curves.csv")).unwrap(),
        curves_before,
        "nothing was rewritten from step 0"
    );
    // Also without the final model and summary: the curve's rows past the first checkpoint
    // say a checkpoint existed.
    std::fs::remove_file(dir.join("model.bpk")).unwrap();
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    let err = run_err(&["train", "--resume", s(&dir), "--quiet"]);
    assert!(
        err.contains("no checkpoint") && err.contains("curves.csv"),
        "{err}"
    );
    assert_eq!(
        std::fs::read(dir.join("curves.csv")).unwrap(),
        curves_before
    );
}

#[test]
fn a_checkpoint_of_another_model_is_named() {
    let reference = reference_run();
    let root = temp_dir("rel-other-model");
    let other = root.join("lstm");
    run_ok(&[
        "train",
        "--model",
        "lstm8",
        "--steps",
        "1000",
        "--set",
        "env.td=4",
        "--quiet",
        "--out",
        s(&other),
    ]);
    let dir = root.join("run");
    copy_tree(reference, &dir);
    std::fs::remove_file(dir.join("model.bpk")).unwrap();
    let theirs = sorted(&other.join("checkpoints"))
        .into_iter()
        .find(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("step-")
        })
        .unwrap();
    for p in sorted(&dir.join("checkpoints")) {
        if p.file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("step-")
        {
            chronocooked_env::integrity::remove_recorded(&p).unwrap();
        }
    }
    let planted = dir.join("checkpoints").join("step-000000016000.json");
    chronocooked_env::integrity::write_recorded(&planted, &std::fs::read(theirs).unwrap()).unwrap();
    let err = run_err(&["train", "--resume", s(&dir), "--quiet"]);
    assert!(
        err.contains("step-000000016000.json") && err.contains("theta"),
        "{err}"
    );
}

#[test]
fn corrupt_models_are_refused_naming_the_file_never_a_fallback() {
    let reference = reference_run();
    let root = temp_dir("rel-model");
    let good = std::fs::read(reference.join("model.bpk")).unwrap();
    let mut flipped = good.clone();
    for i in (0..flipped.len()).step_by(flipped.len() / 200) {
        flipped[i] ^= 0x5A;
    }
    let mut nuls = good.clone();
    nuls.splice(100..100, [0u8; 16]);
    for (case, bytes) in [
        ("flipped", Some(flipped)),
        ("nuls", Some(nuls)),
        ("dir", None),
    ] {
        let dir = root.join(case);
        copy_tree(reference, &dir);
        let model = dir.join("model.bpk");
        match bytes {
            Some(b) => std::fs::write(&model, b).unwrap(),
            None => {
                std::fs::remove_file(&model).unwrap();
                std::fs::create_dir(&model).unwrap();
            }
        }
        let err = run_err(&["eval", "--run", s(&dir), "--out", s(&dir.join("e"))]);
        assert!(err.contains("model.bpk"), "{case}: {err}");
    }
    #[cfg(unix)]
    {
        let dir = root.join("loop");
        copy_tree(reference, &dir);
        let model = dir.join("model.bpk");
        std::fs::remove_file(&model).unwrap();
        std::os::unix::fs::symlink(&model, &model).unwrap();
        let err = run_err(&["eval", "--run", s(&dir), "--out", s(&dir.join("e"))]);
        assert!(err.contains("model.bpk"), "symlink loop: {err}");
    }
}

#[test]
fn timing_agents_cut_weights_missing_agent_and_command_history() {
    let root = temp_dir("rel-timing");
    let dir = root.join("ddm");
    let train = [
        "train",
        "--model",
        "ddm",
        "--set",
        "episodes=200",
        "--set",
        "env.td=4",
        "--quiet",
        "--out",
        s(&dir),
    ];
    run_ok(&train);
    // Weight vectors cut to one value, the record rewritten to match (as by hand).
    let agent = dir.join("agent.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&agent).unwrap()).unwrap();
    for (_, w) in v["learner"]["weights"].as_object_mut().unwrap() {
        w.as_array_mut().unwrap().truncate(1);
    }
    let cut = serde_json::to_vec(&v).unwrap();
    std::fs::write(&agent, &cut).unwrap();
    let err = run_err(&["eval", "--run", s(&dir), "--out", s(&root.join("e1"))]);
    assert!(
        err.contains("agent.json") && err.contains("SHA-256"),
        "{err}"
    );
    chronocooked_env::integrity::write_recorded(&agent, &cut).unwrap();
    let err = run_err(&["eval", "--run", s(&dir), "--out", s(&root.join("e2"))]);
    assert!(
        err.contains("agent.json") && err.contains("learner.weights"),
        "{err}"
    );
    // A missing agent is reported as such, not as a PPO config error.
    std::fs::remove_file(&agent).unwrap();
    let err = run_err(&["eval", "--run", s(&dir), "--out", s(&root.join("e3"))]);
    assert!(
        err.contains("agent.json") && !err.contains("unknown field"),
        "{err}"
    );
    // The unfinished run is retrained by --resume, and command.txt keeps both commands.
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    run_ok(&["train", "--resume", s(&dir), "--quiet"]);
    let commands = std::fs::read_to_string(dir.join("command.txt")).unwrap();
    assert_eq!(commands.lines().count(), 2, "{commands}");
    assert!(commands.contains("--resume"), "{commands}");
}

#[test]
fn bad_records_and_eval_folders_are_named() {
    let root = temp_dir("rel-records");
    let run = root.join("ddm");
    run_ok(&[
        "train",
        "--model",
        "ddm",
        "--set",
        "episodes=100",
        "--set",
        "env.td=4",
        "--quiet",
        "--out",
        s(&run),
    ]);
    let good = root.join("good");
    run_ok(&["eval", "--run", s(&run), "--out", s(&good)]);
    // An episode record with an empty action list.
    let empty_actions = root.join("empty-actions");
    copy_tree(&good, &empty_actions);
    let path = empty_actions.join("records.jsonl");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut r: serde_json::Value = serde_json::from_str(&lines[0]).unwrap();
    r["episode"]["actions"] = serde_json::json!([]);
    r["episode"]["infos"] = serde_json::json!([]);
    lines[0] = r.to_string();
    let edited = lines.join("\n") + "\n";
    std::fs::write(&path, &edited).unwrap();
    // The folder keeps SHA-256 records: the edit itself is refused, naming the file.
    let err = run_err(&[
        "report",
        "--eval",
        s(&empty_actions),
        "--out",
        s(&root.join("r0")),
    ]);
    assert!(
        err.contains("records.jsonl") && err.contains("does not match its SHA-256 record"),
        "{err}"
    );
    // Recorded as meant (as a hand-made folder would be): the record's meaning is checked.
    chronocooked_env::integrity::write_recorded(&path, edited.as_bytes()).unwrap();
    for args in [
        vec![
            "report",
            "--eval",
            s(&empty_actions),
            "--out",
            s(&root.join("r1")),
        ],
        vec![
            "export",
            "--eval",
            s(&empty_actions),
            "--out",
            s(&root.join("x1")),
        ],
    ] {
        let err = run_err(&args);
        assert!(
            err.contains("records.jsonl line 1") && err.contains("actions"),
            "{args:?}: {err}"
        );
    }
    // An empty records.jsonl: "no episodes", not a row of NaN.
    let empty = root.join("empty");
    copy_tree(&good, &empty);
    chronocooked_env::integrity::write_recorded(&empty.join("records.jsonl"), b"").unwrap();
    let err = run_err(&["report", "--eval", s(&empty), "--out", s(&root.join("r2"))]);
    assert!(
        err.contains("no episodes") && err.contains("records.jsonl"),
        "{err}"
    );
    // One bad eval.json among several: named.
    let bad = root.join("bad-info");
    copy_tree(&good, &bad);
    chronocooked_env::integrity::write_recorded(&bad.join("eval.json"), b"{").unwrap();
    let err = run_err(&[
        "report",
        "--eval",
        s(&good),
        s(&bad),
        s(&good),
        "--out",
        s(&root.join("r3")),
    ]);
    assert!(
        err.contains(&format!("{}", bad.join("eval.json").display())),
        "{err}"
    );
    // eval --out onto a file names the path.
    let file = root.join("a-file");
    std::fs::write(&file, b"x").unwrap();
    let err = run_err(&["eval", "--run", s(&run), "--out", s(&file)]);
    assert!(err.contains(s(&file)), "{err}");
}

#[test]
fn zoo_show_counts_parameters_without_building_the_network() {
    let started = Instant::now();
    let out = run_ok(&["zoo", "show", "lstm4096"]);
    // 4 gates × 4096 × (64 + 4096 + 1) + trunk and heads, from the parameter spec.
    let core = 4 * 4096 * (64 + 4096 + 1);
    let trunk = 6 * 8 + 8 + 8 * 6 + 6 + 15 * 6 * 64 + 64;
    let heads = 4096 * 128 + 128 + 64 * 6 + 6 + 64 + 1;
    assert!(out.contains(&format!("{}", core + trunk + heads)), "{out}");
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "{:?}",
        started.elapsed()
    );
}

fn sorted(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    v.sort();
    v
}

fn copy_tree(src: &Path, dst: &Path) {
    std::fs::create_dir_all(dst).unwrap();
    for e in std::fs::read_dir(src).unwrap().flatten() {
        let t = e.file_type().unwrap();
        if t.is_dir() {
            copy_tree(&e.path(), &dst.join(e.file_name()));
        } else if t.is_file() {
            std::fs::copy(e.path(), dst.join(e.file_name())).unwrap();
        }
    }
}
