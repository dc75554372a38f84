//! Regression tests of issue #27 through the binary, on inputs and outputs: walks never
//! follow symlinks, sweep files are checked fully by `--dry-run`, every output is created
//! with the umask, and counts beyond what the lab can run are refused before any work.
//! (Resume and corrupt learned state: `reliability.rs`.)

use crate::common;
use crate::reliability::s;

use common::{files_below, run_err, run_ok, temp_dir};

use std::time::{Duration, Instant};

#[cfg(unix)]
#[test]
fn symlink_loops_are_not_followed_and_each_folder_counts_once() {
    let root = temp_dir("rel-links");
    let run = root.join("runs").join("ddm");
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
    let eval = root.join("runs").join("eval");
    run_ok(&["eval", "--run", s(&run), "--out", s(&eval)]);
    // Two self-links (each a loop) and a link to the evaluation.
    std::os::unix::fs::symlink(root.join("runs"), root.join("runs").join("self")).unwrap();
    std::os::unix::fs::symlink(root.join("runs"), eval.join("up")).unwrap();
    std::os::unix::fs::symlink(&eval, root.join("runs").join("alias")).unwrap();
    let started = Instant::now();
    let found = chronocooked_present::report::leaderboard::find_eval_folders(&[root.join("runs")]);
    assert_eq!(found, vec![eval.clone()]);
    // Two roots that reach the same folder count it once.
    let both = chronocooked_present::report::leaderboard::find_eval_folders(&[
        root.join("runs"),
        root.join("runs").join("."),
    ]);
    assert_eq!(both.len(), 1, "{both:?}");
    run_ok(&[
        "report",
        "--runs",
        s(&root.join("runs")),
        "--out",
        s(&root.join("rep")),
    ]);
    assert!(started.elapsed() < Duration::from_secs(60));
    // paper collect's job walk: one job, however many links point at it.
    let sweep = root.join("sweep");
    let job = sweep.join("FixedInterval-v0").join("ddm").join("seed0");
    std::fs::create_dir_all(&job).unwrap();
    std::fs::write(job.join("job.json"), b"{}").unwrap();
    std::os::unix::fs::symlink(&sweep, sweep.join("FixedInterval-v0").join("loop")).unwrap();
    std::os::unix::fs::symlink(&job, sweep.join("alias")).unwrap();
    assert_eq!(
        chronocooked_analysis::collect::job_folders(&sweep),
        vec![job]
    );
}

#[test]
fn sweep_dry_run_catches_what_a_run_would_refuse() {
    let root = temp_dir("rel-sweep");
    for (name, text, needle) in [
        (
            "typo",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"ddm\"]\nset=[\"episdoes=50\"]\n",
            "episdoes",
        ),
        (
            "td0",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"cnn-mlp\"]\nset=[\"env.td=0\"]\n",
            "td",
        ),
        (
            "stop",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"cnn-mlp\",\"ddm\"]\nvariants=[[\"stop_at_success=2\"]]\n",
            "stop_at_success",
        ),
        (
            "nan",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"cnn-mlp\"]\nset=[\"learning_rate=nan\"]\n",
            "learning_rate",
        ),
        (
            "timing-nan",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"ddm\"]\nvariants=[[\"alpha=nan\"]]\n",
            "alpha",
        ),
        (
            // `set` reaches PPO runs only: a timing setting there would be dropped.
            "timing-set",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"ddm\"]\nset=[\"episodes=50\"]\n",
            "episodes",
        ),
        (
            "keep0",
            "tasks=[\"FixedInterval-v0\"]\nmodels=[\"cnn-mlp\"]\nset=[\"keep_checkpoints=0\"]\n",
            "keep_checkpoints",
        ),
    ] {
        let file = root.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        let err = run_err(&["sweep", s(&file), "--out", s(&root.join(name)), "--dry-run"]);
        assert!(
            err.contains(needle) && err.contains(&format!("{name}.toml")),
            "{name}: {err}"
        );
    }
    let ok = root.join("ok.toml");
    std::fs::write(
        &ok,
        "tasks=[\"FixedInterval-v0\"]\nmodels=[\"ddm\",\"cnn-mlp\"]\nepisodes=50\nset=[\"learning_rate=1e-3\",\"env.td=6\"]\nvariants=[[\"alpha=0.1\"],[\"ent_coef=0.01\"]]\n",
    )
    .unwrap();
    run_ok(&["sweep", s(&ok), "--out", s(&root.join("ok")), "--dry-run"]);
}

#[cfg(unix)]
#[test]
fn every_file_the_cli_writes_is_0644_under_umask_022() {
    use std::os::unix::fs::PermissionsExt;
    let root = temp_dir("rel-umask");
    let b = env!("CARGO_BIN_EXE_chronocooked");
    let r = |p: &str| s(&root.join(p)).to_string();
    let script = format!(
        "umask 022 && {b} train --model cnn-mlp --steps 2000 --set env.td=4 --quiet --out {ppo} >/dev/null \
         && {b} train --model ddm --set episodes=100 --set env.td=4 --quiet --out {ddm} >/dev/null \
         && {b} eval --run {ddm} --out {ev} >/dev/null \
         && {b} record --run {ddm} --out {act} --summary --figures {nf} >/dev/null \
         && {b} export --activity {act} --eval {ev} --out {ex} >/dev/null \
         && {b} report --eval {ev} --out {rep} >/dev/null",
        ppo = r("ppo"),
        ddm = r("ddm"),
        ev = r("eval"),
        act = r("activity.json"),
        nf = r("neural_figures"),
        ex = r("export"),
        rep = r("report"),
    );
    let out = std::process::Command::new("sh")
        .args(["-c", &script])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let files = files_below(&root);
    assert!(files.len() > 20, "{files:?}");
    for f in files {
        let mode = std::fs::metadata(&f).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o644, "{}: {mode:o}", f.display());
    }
}

#[test]
fn counts_beyond_what_the_lab_can_run_are_refused_before_any_work() {
    // Issue #47 item 1: each bound named with its flag or key and the allowed range; nothing
    // runs (each of these used to run for hours or abort allocating gigabytes).
    let dir = temp_dir("bounds");
    let out = dir.join("never");
    let cases: [(&[&str], &str); 5] = [
        (
            &[
                "train",
                "--model",
                "cnn-mlp",
                "--task",
                "FixedInterval-v0",
                "--set",
                "total_steps=2000000001",
                "--out",
                s(&out),
            ],
            "total_steps",
        ),
        (
            &["record", "--run", s(&out), "--repeats", "101"],
            "--repeats",
        ),
        (
            &["eval", "--run", s(&out), "--stochastic", "10001"],
            "--stochastic",
        ),
        (
            &["mechanisms", s(&out), "--resamples", "100001"],
            "--resamples",
        ),
        (
            &["adapt", "--run", s(&out), "--episodes", "10000001"],
            "--episodes",
        ),
    ];
    for (args, key) in cases {
        let err = run_err(args);
        assert!(err.contains(key), "{args:?}: {err}");
        assert!(
            err.contains("1..=") || err.contains("allowed"),
            "{args:?}: no allowed range in {err}"
        );
    }
    assert!(!out.exists(), "a refused command wrote {}", out.display());
    // The same bounds in a sweep file, and a bound on the jobs one sweep expands to.
    let seeds: Vec<String> = (0..100_001).map(|i| i.to_string()).collect();
    let sweeps = [
        ("stochastic = 10001", "stochastic", "1..=10000"),
        ("steps = 2000000001", "steps", "1..=2000000000"),
        ("episodes = 10000001", "episodes", "1..=10000000"),
        (
            "adapt_episodes = 10000001",
            "adapt_episodes",
            "1..=10000000",
        ),
        ("adapt_steps = 2000000001", "adapt_steps", "1..=2000000000"),
        (&*format!("seeds = [{}]", seeds.join(",")), "jobs", "100000"),
    ];
    for (k, (line, key, allowed)) in sweeps.iter().enumerate() {
        let file = dir.join(format!("s{k}.toml"));
        std::fs::write(
            &file,
            format!("name = \"b\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"ddm\"]\n{line}\n"),
        )
        .unwrap();
        let err = run_err(&["sweep", s(&file), "--out", s(&out), "--dry-run"]);
        assert!(err.contains(key) && err.contains(allowed), "{key}: {err}");
    }
    assert!(!out.exists(), "a refused sweep wrote {}", out.display());
    let _ = std::fs::remove_dir_all(&dir);
}
