//! Fault injection through the binary (issue #47): a full disk and a sudden death at every
//! write of each writing command, two writers on one folder, and SIGINT / SIGTERM during
//! training and sweeps.
//!
//! Faults come from `CHRONOCOOKED_FAULT` (`enospc@N`: the N-th write and all later ones fail
//! with ENOSPC, as on a full disk; `kill@N`: the process aborts at the N-th write, which
//! leaves the disk as `kill -9` does), so the suite needs neither root nor a tmpfs.
//! After each fault: the error names the path, nothing is left that a later command takes
//! for complete, and a rerun equals a clean run with no stray files.

use crate::common;

use common::{bin, curves_without_clock, files_below, run_ok, temp_dir};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::Output;

pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Temporary files of interrupted writes and lock files left anywhere below `dir`.
pub(crate) fn leftovers(dir: &Path) -> Vec<PathBuf> {
    files_below(dir)
        .into_iter()
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
            chronocooked_env::fs::is_temp_name(name)
                || name == chronocooked_env::fs::lock::LOCK_FILE
        })
        .collect()
}

/// What a command leaves that must equal a clean run's (file → content).
fn snapshot(out: &Path, files: &[&str]) -> Vec<(String, Vec<u8>)> {
    files
        .iter()
        .map(|f| {
            let p = out.join(f);
            let bytes = if *f == "curves.csv" && out.join("checkpoints").is_dir() {
                curves_without_clock(out).join("\n").into_bytes()
            } else if *f == "jobs" {
                // Every file below, by relative path.
                files_below(&p)
                    .iter()
                    .flat_map(|q| {
                        let mut v = q
                            .strip_prefix(out)
                            .unwrap()
                            .display()
                            .to_string()
                            .into_bytes();
                        v.extend(std::fs::read(q).unwrap());
                        v
                    })
                    .collect()
            } else {
                std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
            };
            (f.to_string(), bytes)
        })
        .collect()
}

/// One writing command of the campaign.
struct Case {
    name: &'static str,
    /// Arguments; `{OUT}` stands for the output folder.
    args: Vec<String>,
    /// Arguments of the rerun after a fault when the folder already holds a started run.
    resume: Option<Vec<String>>,
    /// Files (relative to the output folder) a rerun must reproduce byte for byte.
    compare: &'static [&'static str],
    /// What a faulted run may leave: returns why the folder would pass for complete.
    passes_for_complete: fn(&Path) -> Option<String>,
    /// A reader of the output and what its refusal of a faulted, incomplete output must
    /// name (`{OUT}` as in `args`); `None` when the output is not read back.
    reader: Option<Reader>,
}

/// A command that reads a case's output.
struct Reader {
    /// Arguments; `{OUT}` is the faulted output folder.
    args: Vec<String>,
    /// Whether the faulted output is complete anyway (the fault hit a write after its last
    /// essential file): then the reader must accept it.
    complete: fn(&Path) -> bool,
    /// Texts the refusal must contain: the missing file, the command that completes it.
    names: fn(&Path) -> Vec<String>,
}

fn with_out(args: &[String], out: &Path) -> Vec<String> {
    args.iter().map(|a| a.replace("{OUT}", s(out))).collect()
}

fn run(args: &[String], fault: Option<&str>) -> Output {
    let mut cmd = bin();
    cmd.args(args);
    if let Some(f) = fault {
        cmd.env(chronocooked_env::fs::fault::FAULT_ENV, f);
    }
    cmd.output().unwrap()
}

pub(crate) fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The inputs the commands read: a timing run, its evaluation, a small sweep's output.
struct Inputs {
    run: PathBuf,
    eval: PathBuf,
    sweep_out: PathBuf,
}

fn inputs() -> &'static Inputs {
    static I: std::sync::OnceLock<Inputs> = std::sync::OnceLock::new();
    I.get_or_init(|| {
        let dir = temp_dir("faults-inputs");
        let run = dir.join("run");
        run_ok(&[
            "train",
            "--model",
            "ddm",
            "--set",
            "episodes=200",
            "--set",
            "env.td=6",
            "--seed",
            "3",
            "--quiet",
            "--out",
            s(&run),
        ]);
        let eval = dir.join("eval");
        run_ok(&["eval", "--run", s(&run), "--out", s(&eval)]);
        let sweep = dir.join("s.toml");
        std::fs::write(
            &sweep,
            "name = \"faults\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"oracle\", \"ddm\"]\n\
             seeds = [1, 2, 3]\nepisodes = 200\nrecord = true\nexport = false\n\
             set = [\"env.td=6\"]\n",
        )
        .unwrap();
        let sweep_out = dir.join("sweep");
        run_ok(&[
            "sweep",
            s(&sweep),
            "--out",
            s(&sweep_out),
            "--workers",
            "2",
            "--no-report",
        ]);
        Inputs {
            run,
            eval,
            sweep_out,
        }
    })
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

fn cases() -> Vec<Case> {
    let i = inputs();
    vec![
        Case {
            name: "train-timing",
            args: strings(&[
                "train",
                "--model",
                "sbf",
                "--set",
                "episodes=150",
                "--set",
                "env.td=6",
                "--seed",
                "5",
                "--quiet",
                "--out",
                "{OUT}",
            ]),
            resume: Some(strings(&["train", "--resume", "{OUT}", "--quiet"])),
            compare: &["agent.json", "curves.csv"],
            passes_for_complete: |out| {
                (out.join("summary.json").is_file() && !out.join("agent.json").is_file())
                    .then(|| "summary.json without agent.json".into())
            },
            reader: Some(Reader {
                args: strings(&["eval", "--run", "{OUT}", "--out", "{OUT}-read"]),
                complete: |out| out.join("summary.json").is_file(),
                names: |out| {
                    if out.join("config.json").is_file() {
                        let mut v: Vec<String> = ["agent.json", "summary.json"]
                            .into_iter()
                            .filter(|f| !out.join(f).is_file())
                            .map(String::from)
                            .collect();
                        v.push("chronocooked train --resume".into());
                        v
                    } else {
                        vec!["chronocooked train".into()]
                    }
                },
            }),
        },
        Case {
            name: "train-ppo",
            args: strings(&[
                "train",
                "--model",
                "cnn-mlp",
                "--preset",
                "fast",
                "--steps",
                "6000",
                "--set",
                "env.td=4",
                "--set",
                "checkpoint_every=2000",
                "--quiet",
                "--out",
                "{OUT}",
            ]),
            resume: Some(strings(&["train", "--resume", "{OUT}", "--quiet"])),
            compare: &["curves.csv", "model.bpk"],
            passes_for_complete: |out| {
                (out.join("summary.json").is_file() && !out.join("model.bpk").is_file())
                    .then(|| "summary.json without model.bpk".into())
            },
            reader: None,
        },
        Case {
            name: "eval",
            args: strings(&["eval", "--run", s(&i.run), "--out", "{OUT}"]),
            resume: None,
            compare: &["metrics.json", "records.jsonl", "eval.json"],
            passes_for_complete: |out| {
                out.join("metrics.json")
                    .is_file()
                    .then(|| "metrics.json of a failed evaluation".into())
            },
            reader: Some(Reader {
                args: strings(&["report", "--eval", "{OUT}", "--out", "{OUT}-read"]),
                complete: |_| false,
                names: |out| {
                    if !out.join("eval.json").is_file() {
                        // Stopped at its first writes: not (yet) an evaluation folder.
                        return vec!["eval.json".into()];
                    }
                    let mut v = vec!["metrics.json".to_string()];
                    if out.join("records.jsonl").is_file() && out.join("eval.json").is_file() {
                        v.push("eval --from".into());
                    } else {
                        v.push("chronocooked eval".into());
                    }
                    v
                },
            }),
        },
        Case {
            name: "record",
            args: strings(&[
                "record",
                "--run",
                s(&i.run),
                "--probe",
                "--summary",
                "--figures",
                "{OUT}/figs",
                "--out",
                "{OUT}/activity.json",
            ]),
            resume: None,
            compare: &["activity.json", "activity.summary.json"],
            passes_for_complete: |out| {
                out.join("activity.summary.json")
                    .is_file()
                    .then(|| "a summary of a failed recording".into())
            },
            reader: None,
        },
        Case {
            name: "export",
            args: strings(&["export", "--eval", s(&i.eval), "--out", "{OUT}"]),
            resume: None,
            compare: &["episodes.csv", "export.json"],
            passes_for_complete: |out| {
                chronocooked_present::export::marker::check_export(out)
                    .is_ok()
                    .then(|| "an interrupted export passes its completeness check".into())
            },
            reader: None,
        },
        Case {
            name: "report",
            args: strings(&["report", "--eval", s(&i.eval), "--out", "{OUT}"]),
            resume: None,
            compare: &["report.md", "report.csv"],
            passes_for_complete: |_| None,
            reader: None,
        },
        Case {
            name: "collect",
            args: strings(&["paper", "collect", s(&i.sweep_out), "--out", "{OUT}"]),
            resume: None,
            compare: &["jobs"],
            passes_for_complete: |out| {
                chronocooked_analysis::collect::read_compact(out)
                    .is_ok_and(|jobs| !jobs.is_empty())
                    .then(|| "a half-collected folder is readable".into())
            },
            reader: None,
        },
    ]
}

/// Runs `case` with `fault` at write `n` = 1, 2, … until the fault no longer triggers;
/// checks each faulted run and its rerun. Returns how many runs were faulted.
fn campaign(case: &Case, kind: &str, root: &Path) -> usize {
    let clean = root.join(format!("{}-clean", case.name));
    let o = run(&with_out(&case.args, &clean), None);
    assert!(
        o.status.success(),
        "{}: clean run failed: {}",
        case.name,
        stderr(&o)
    );
    let reference = snapshot(&clean, case.compare);
    let mut faulted = 0;
    for n in 1..=200 {
        let out = root.join(format!("{}-{kind}{n}", case.name));
        let o = run(&with_out(&case.args, &out), Some(&format!("{kind}@{n}")));
        if o.status.success() {
            // Fewer writes than n: the fault never fired.
            break;
        }
        faulted += 1;
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "{} {kind}@{n}: {err}", case.name);
        if kind == "enospc" {
            assert_eq!(o.status.code(), Some(2), "{} {kind}@{n}: {err}", case.name);
            assert!(
                err.contains("No space left on device"),
                "{} {kind}@{n}: {err}",
                case.name
            );
            let name = out.file_name().unwrap().to_str().unwrap();
            assert!(
                err.contains(name),
                "{} {kind}@{n}: no path in {err}",
                case.name
            );
        } else {
            assert_eq!(
                o.status.signal(),
                Some(6),
                "{} {kind}@{n}: {err}",
                case.name
            );
        }
        if let Some(why) = (case.passes_for_complete)(&out) {
            panic!("{} {kind}@{n}: {why}", case.name);
        }
        if let Some(reader) = &case.reader {
            let o = run(&with_out(&reader.args, &out), None);
            let err = stderr(&o);
            if (reader.complete)(&out) {
                assert!(
                    o.status.success(),
                    "{} {kind}@{n}: reader: {err}",
                    case.name
                );
            } else {
                assert_eq!(
                    o.status.code(),
                    Some(2),
                    "{} {kind}@{n}: a reader accepted the incomplete output: {err}",
                    case.name
                );
                for what in (reader.names)(&out) {
                    assert!(
                        err.contains(&what),
                        "{} {kind}@{n}: the refusal does not name `{what}`: {err}",
                        case.name
                    );
                }
            }
            let _ = std::fs::remove_dir_all(PathBuf::from(format!("{}-read", s(&out))));
        }
        let rerun = match &case.resume {
            Some(r) if out.join("config.json").is_file() => with_out(r, &out),
            _ => with_out(&case.args, &out),
        };
        let o = run(&rerun, None);
        assert!(
            o.status.success(),
            "{} {kind}@{n}: rerun failed: {}",
            case.name,
            stderr(&o)
        );
        assert_eq!(
            snapshot(&out, case.compare),
            reference,
            "{} {kind}@{n}: the rerun differs from a clean run",
            case.name
        );
        let left = leftovers(&out);
        assert!(left.is_empty(), "{} {kind}@{n}: left {left:?}", case.name);
        let _ = std::fs::remove_dir_all(&out);
    }
    faulted
}

fn fault_suite(kind: &str) {
    let root = temp_dir(&format!("faults-{kind}"));
    for case in cases() {
        let n = campaign(&case, kind, &root);
        eprintln!(
            "{} {kind}: {n} faulted runs, each rerun equal to a clean run",
            case.name
        );
        assert!(n > 0, "{}: the fault never fired", case.name);
    }
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_full_disk_at_any_write_is_an_error_naming_the_path_and_a_rerun_equals_a_clean_run() {
    fault_suite("enospc");
}

#[test]
fn kill_at_any_write_then_rerun_equals_a_clean_run_with_no_stray_files() {
    fault_suite("kill");
}

#[test]
fn a_folder_held_by_another_process_refuses_writers_and_readers_naming_the_holder() {
    let i = inputs();
    let dir = temp_dir("faults-held");
    let held = dir.join("held");
    let lock = chronocooked_env::fs::FolderLock::acquire(&held).unwrap();
    let pid = format!("pid {}", std::process::id());
    let results = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/mechanisms");
    let sweep_file = i.sweep_out.parent().unwrap().join("s.toml");
    let writers: Vec<Vec<&str>> = vec![
        vec![
            "train",
            "--model",
            "ddm",
            "--set",
            "episodes=50",
            "--quiet",
            "--out",
            s(&held),
        ],
        vec!["eval", "--agent", "oracle", "--out", s(&held)],
        vec!["report", "--eval", s(&i.eval), "--out", s(&held)],
        vec!["export", "--eval", s(&i.eval), "--out", s(&held)],
        vec!["paper", "collect", s(&i.sweep_out), "--out", s(&held)],
        vec!["sweep", s(&sweep_file), "--out", s(&held), "--no-report"],
        vec![
            "mechanisms",
            s(&results),
            "--out",
            s(&held),
            "--resamples",
            "10",
        ],
    ];
    for args in &writers {
        let o = bin().args(args).output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("another process is writing") && err.contains(&pid),
            "{args:?}: {err}"
        );
    }
    let record = held.join("activity.json");
    let o = bin()
        .args(["record", "--run", s(&i.run), "--out", s(&record)])
        .output()
        .unwrap();
    assert!(stderr(&o).contains(&pid), "{}", stderr(&o));
    // Nothing was written beside the lock.
    let names: Vec<_> = files_below(&held);
    assert_eq!(names, [held.join(chronocooked_env::fs::lock::LOCK_FILE)]);
    drop(lock);

    // Readers refuse a folder that is being written.
    let eval_lock = chronocooked_env::fs::FolderLock::acquire(&i.eval).unwrap();
    let o = bin()
        .args(["report", "--eval", s(&i.eval), "--out", s(&dir.join("r"))])
        .output()
        .unwrap();
    assert!(
        !o.status.success() && stderr(&o).contains(&pid),
        "{}",
        stderr(&o)
    );
    drop(eval_lock);
    let run_lock = chronocooked_env::fs::FolderLock::acquire(&i.run).unwrap();
    for args in [
        vec!["eval", "--run", s(&i.run), "--out", s(&dir.join("e"))],
        vec![
            "record",
            "--run",
            s(&i.run),
            "--out",
            s(&dir.join("a.json")),
        ],
    ] {
        let o = bin().args(&args).output().unwrap();
        assert!(
            !o.status.success() && stderr(&o).contains(&pid),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    drop(run_lock);
    // Once free, the same commands run.
    run_ok(&["eval", "--run", s(&i.run), "--out", s(&dir.join("e"))]);
    run_ok(&["report", "--eval", s(&i.eval), "--out", s(&dir.join("r"))]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn collect_takes_only_finished_jobs_and_readers_refuse_an_unfinished_collect() {
    let i = inputs();
    let dir = temp_dir("faults-collect");
    // A copy of the sweep output in which one job did not finish (its record stage failed)
    // and another is being written by a worker.
    let sweep = dir.join("sweep");
    let status = std::process::Command::new("cp")
        .args(["-r", s(&i.sweep_out), s(&sweep)])
        .status()
        .unwrap();
    assert!(status.success());
    let unfinished = sweep.join("FixedInterval-v0/ddm/seed1");
    let progress = unfinished.join("progress.json");
    let text = std::fs::read_to_string(&progress).unwrap();
    std::fs::write(&progress, text.replace("\"done\": true", "\"done\": false")).unwrap();
    let busy = chronocooked_env::fs::FolderLock::acquire(&sweep.join("FixedInterval-v0/ddm/seed2"))
        .unwrap();
    let out = dir.join("results");
    let said = run_ok(&["paper", "collect", s(&sweep), "--out", s(&out)]);
    assert!(
        said.contains("2 finished jobs") && said.contains("2 unfinished"),
        "{said}"
    );
    let collected: Vec<_> = files_below(&out.join("jobs"))
        .iter()
        .filter(|p| p.ends_with("job.json"))
        .map(|p| {
            p.parent()
                .unwrap()
                .strip_prefix(&out)
                .unwrap()
                .to_path_buf()
        })
        .collect();
    assert_eq!(
        collected,
        [
            PathBuf::from("jobs/FixedInterval-v0/ddm/seed3"),
            PathBuf::from("jobs/FixedInterval-v0/oracle/seed1")
        ]
    );
    drop(busy);
    // A collect that did not finish leaves its marker; every reader refuses the folder.
    let marker = out.join(chronocooked_analysis::collect::UNFINISHED_MARKER);
    std::fs::write(&marker, "{}").unwrap();
    for args in [
        vec![
            "mechanisms",
            s(&out),
            "--out",
            s(&dir.join("m")),
            "--resamples",
            "10",
        ],
        vec!["paper", "analyse", s(&out)],
        vec!["report", "--baselines", s(&out), "--out", s(&dir.join("r"))],
    ] {
        let o = bin().args(&args).output().unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("did not finish") && err.contains("paper collect"),
            "{args:?}: {err}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A sweep killed at any write of any of its processes (the sweep or a worker: kill -9 of
/// one of the group), then rerun, equals an uninterrupted sweep: the same files (figures
/// included), the same learned state and metrics, and no lock or temporary file left.
#[test]
fn a_sweep_killed_at_any_write_then_rerun_equals_an_uninterrupted_sweep() {
    let dir = temp_dir("faults-sweep-kill");
    let sweep = dir.join("k.toml");
    std::fs::write(
        &sweep,
        "name = \"kill\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"ddm\"]\n\
         seeds = [1]\nepisodes = 60\nrecord = false\nexport = false\n\
         set = [\"env.td=6\"]\n",
    )
    .unwrap();
    let args = |out: &Path| -> Vec<String> {
        strings(&[
            "sweep",
            s(&sweep),
            "--out",
            s(out),
            "--workers",
            "1",
            "--no-report",
        ])
    };
    let clean = dir.join("clean");
    let o = run(&args(&clean), None);
    assert!(o.status.success(), "{}", stderr(&o));
    // Files by relative path; the bytes of those that are a function of the seed alone.
    let listing = |out: &Path| -> Vec<(String, Option<Vec<u8>>)> {
        files_below(out)
            .into_iter()
            .map(|p| {
                let rel = p.strip_prefix(out).unwrap().display().to_string();
                let stable = ["agent.json", "curves.csv", "metrics.json", "records.jsonl"]
                    .iter()
                    .any(|f| rel.ends_with(f))
                    || rel.ends_with(".png")
                    || rel.ends_with(".svg");
                let bytes = stable.then(|| std::fs::read(&p).unwrap());
                (rel, bytes)
            })
            .collect()
    };
    let reference = listing(&clean);
    assert!(
        reference
            .iter()
            .any(|(f, _)| f.ends_with("run/figures/learning_curve.png")),
        "{reference:?}"
    );
    let mut killed = 0;
    for n in 1..=200 {
        let out = dir.join(format!("kill{n}"));
        let o = run(&args(&out), Some(&format!("kill@{n}")));
        if o.status.success() {
            break;
        }
        killed += 1;
        assert!(!stderr(&o).contains("panicked"), "kill@{n}: {}", stderr(&o));
        let o = run(&args(&out), None);
        assert!(o.status.success(), "kill@{n}: rerun failed: {}", stderr(&o));
        let got = listing(&out);
        let names = |v: &[(String, Option<Vec<u8>>)]| -> Vec<String> {
            v.iter().map(|(f, _)| f.clone()).collect()
        };
        assert_eq!(names(&got), names(&reference), "kill@{n}: other files");
        assert_eq!(got, reference, "kill@{n}: other contents");
        let _ = std::fs::remove_dir_all(&out);
    }
    assert!(killed > 3, "the fault fired {killed} times");
    let _ = std::fs::remove_dir_all(&dir);
}
