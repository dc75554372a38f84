//! Signals through the binary (issue #47): SIGINT / SIGTERM stop `train` with a resumable
//! checkpoint and an exit code that says so, and a stopped or killed sweep leaves no worker
//! writing. (Disk-full, kill and two-writer faults: `faults.rs`.)

use crate::common;
use crate::faults::{leftovers, s, stderr};

use common::{bin, curves_without_clock, files_below, run_ok, temp_dir};
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// Starts `train` of a PPO run long enough to be stopped, and waits until it has written
/// `rows` learning-curve rows. SIGINT and SIGTERM get their default disposition in the child:
/// a test suite started as a background job of a non-interactive shell inherits SIGINT
/// ignored (POSIX), which the binary rightly keeps ignored, while a user at a terminal has it.
fn start_training(out: &Path, steps: &str, rows: usize) -> std::process::Child {
    use std::os::unix::process::CommandExt;
    let mut command = bin();
    // SAFETY: `signal` is async-signal-safe; nothing else runs between fork and exec.
    unsafe {
        command.pre_exec(|| {
            for sig in [libc::SIGINT, libc::SIGTERM] {
                libc::signal(sig, libc::SIG_DFL);
            }
            Ok(())
        });
    }
    let child = command
        .args([
            "train",
            "--model",
            "cnn-mlp",
            "--preset",
            "fast",
            "--steps",
            steps,
            "--set",
            "env.td=4",
            "--set",
            "checkpoint_every=4000",
            "--quiet",
            "--out",
            s(out),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while std::fs::read_to_string(out.join("curves.csv")).map_or(0, |t| t.lines().count()) <= rows {
        assert!(t0.elapsed() < Duration::from_secs(120), "no progress");
        std::thread::sleep(Duration::from_millis(20));
    }
    child
}

fn signal(child: &std::process::Child, sig: i32) {
    let status = std::process::Command::new("kill")
        .args([format!("-{sig}"), child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

#[test]
fn sigint_and_sigterm_stop_training_with_a_checkpoint_and_the_resume_equals_a_clean_run() {
    let dir = temp_dir("faults-signals");
    let steps = "40000";
    let clean = dir.join("clean");
    let c = start_training(&clean, steps, 0);
    assert!(c.wait_with_output().unwrap().status.success());
    for (sig, code) in [(2, 130), (15, 143)] {
        let out = dir.join(format!("sig{sig}"));
        let child = start_training(&out, steps, 3);
        signal(&child, sig);
        let o = child.wait_with_output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{err}");
        assert!(
            err.contains("--resume") && err.contains("checkpoint"),
            "{err}"
        );
        assert!(!out.join("summary.json").exists());
        // An unfinished run is not evaluated as if it were finished.
        let o = bin()
            .args(["eval", "--run", s(&out), "--out", s(&dir.join("e"))])
            .output()
            .unwrap();
        assert!(stderr(&o).contains("did not finish"), "{}", stderr(&o));
        let o = bin()
            .args([
                "eval",
                "--run",
                s(&out),
                "--unfinished",
                "--out",
                s(&dir.join("e")),
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let info = std::fs::read_to_string(dir.join("e/eval.json")).unwrap();
        assert!(info.contains("unfinished_at_step"), "{info}");
        // A deleted checkpoint that the manifest still lists is an error, not a restart.
        let copy = dir.join(format!("sig{sig}-lost"));
        std::process::Command::new("cp")
            .args(["-r", s(&out), s(&copy)])
            .status()
            .unwrap();
        let newest = files_below(&copy.join("checkpoints"))
            .into_iter()
            .rfind(|p| p.extension().is_some_and(|e| e == "json"))
            .unwrap();
        std::fs::remove_file(&newest).unwrap();
        let before = std::fs::read(copy.join("curves.csv")).unwrap();
        let o = bin()
            .args(["train", "--resume", s(&copy), "--quiet"])
            .output()
            .unwrap();
        let name = newest.file_name().unwrap().to_str().unwrap();
        assert!(
            !o.status.success() && stderr(&o).contains(name),
            "{}",
            stderr(&o)
        );
        assert_eq!(std::fs::read(copy.join("curves.csv")).unwrap(), before);
        // The resume of the stopped run ends where the uninterrupted run ends.
        run_ok(&["train", "--resume", s(&out), "--quiet"]);
        assert_eq!(curves_without_clock(&out), curves_without_clock(&clean));
        assert_eq!(
            std::fs::read(out.join("model.bpk")).unwrap(),
            std::fs::read(clean.join("model.bpk")).unwrap()
        );
        assert!(leftovers(&out).is_empty(), "{:?}", leftovers(&out));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_stopped_or_killed_sweep_leaves_no_worker_writing_and_its_rerun_finishes() {
    let dir = temp_dir("faults-sweep");
    let file = dir.join("s.toml");
    std::fs::write(
        &file,
        "name = \"stop\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"cnn-mlp\"]\nseeds = [1]\n\
         preset = \"fast\"\nsteps = 40000\nrecord = false\nexport = false\n\
         set = [\"env.td=4\", \"checkpoint_every=4000\"]\n",
    )
    .unwrap();
    let job = |out: &Path| out.join("FixedInterval-v0/cnn-mlp/seed1");
    for (how, sig) in [("term", 15), ("kill", 9)] {
        let out = dir.join(how);
        let child = bin()
            .args([
                "sweep",
                s(&file),
                "--out",
                s(&out),
                "--workers",
                "1",
                "--no-report",
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let curves = job(&out).join("run/curves.csv");
        let t0 = Instant::now();
        while std::fs::read_to_string(&curves).map_or(0, |t| t.lines().count()) <= 3 {
            assert!(t0.elapsed() < Duration::from_secs(120), "no progress");
            std::thread::sleep(Duration::from_millis(20));
        }
        signal(&child, sig);
        let o = child.wait_with_output().unwrap();
        if sig == 15 {
            assert_eq!(o.status.code(), Some(143));
            // The sweep ended after its worker: nobody holds the job any more.
            chronocooked_env::fs::ensure_not_being_written(&job(&out)).unwrap();
        }
        // The rerun starts at once (waiting for a killed sweep's worker to stop) and ends
        // with every update once in the learning curve.
        run_ok(&[
            "sweep",
            s(&file),
            "--out",
            s(&out),
            "--workers",
            "1",
            "--no-report",
        ]);
        let rows = curves_without_clock(&job(&out).join("run"));
        let steps: Vec<u64> = rows[1..]
            .iter()
            .map(|r| r.split(',').nth(1).unwrap().parse().unwrap())
            .collect();
        assert!(steps.windows(2).all(|w| w[0] < w[1]), "{steps:?}");
        assert!(steps.last().is_some_and(|&l| l >= 40_000), "{steps:?}");
        assert!(leftovers(&out).is_empty(), "{:?}", leftovers(&out));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
