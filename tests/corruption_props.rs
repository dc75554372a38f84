//! Property tests over every reader of the lab's files: a corrupted copy of a real file
//! (bytes flipped, cut, NULs inserted, spans deleted, or one JSON value replaced or one list
//! cut) gives a clear error naming the file — or a valid value — never a panic.
//!
//! Files of learned state (`policy.json`, `model.bpk`, checkpoints, `agent.json`) are tried
//! twice: as corrupted (their SHA-256 record then no longer matches: the load must fail), and
//! with the record rewritten to the corrupted content (as by hand), which exercises the
//! consistency checks behind the hash.

use crate::common;

use chronocooked_env::integrity;
use chronocooked_training::{RunDir, Trainer, load_policy, load_timing_agent};
use proptest::prelude::*;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Real files to corrupt: a PPO run, a timing run and an evaluation of it (with activity).
struct Fixtures {
    ppo: PathBuf,
    timing: PathBuf,
    eval: PathBuf,
}

fn fixtures() -> &'static Fixtures {
    static F: OnceLock<Fixtures> = OnceLock::new();
    F.get_or_init(|| {
        let root = common::temp_dir("corruption-props");
        let ppo = root.join("ppo");
        let timing = root.join("ddm");
        let eval = root.join("eval");
        let s = |p: &Path| p.to_str().unwrap().to_string();
        common::run_ok(&[
            "train",
            "--model",
            "lstm8",
            "--preset",
            "fast",
            "--steps",
            "512",
            "--set",
            "n_envs=2",
            "--set",
            "n_steps=64",
            "--set",
            "checkpoint_every=256",
            "--set",
            "env.td=4",
            "--quiet",
            "--out",
            &s(&ppo),
        ]);
        common::run_ok(&[
            "train",
            "--model",
            "ddm",
            "--set",
            "episodes=200",
            "--set",
            "env.td=4",
            "--quiet",
            "--out",
            &s(&timing),
        ]);
        common::run_ok(&["eval", "--run", &s(&timing), "--out", &s(&eval)]);
        common::run_ok(&[
            "record",
            "--run",
            &s(&timing),
            "--out",
            &s(&eval.join("activity.json")),
        ]);
        Fixtures { ppo, timing, eval }
    })
}

/// One corruption of a file's bytes.
#[derive(Debug, Clone)]
enum Mutation {
    Flip {
        at: usize,
        mask: u8,
    },
    Truncate {
        at: usize,
    },
    InsertNul {
        at: usize,
        n: usize,
    },
    Delete {
        at: usize,
        n: usize,
    },
    /// Replace the `k`-th JSON leaf (of line `line` for JSON lines) with a hostile value.
    JsonLeaf {
        line: usize,
        k: usize,
        with: usize,
    },
    /// Cut the `k`-th JSON list to `len` items.
    JsonCut {
        line: usize,
        k: usize,
        len: usize,
    },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1u8..=255).prop_map(|(at, mask)| Mutation::Flip { at, mask }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        (any::<usize>(), 1usize..8).prop_map(|(at, n)| Mutation::InsertNul { at, n }),
        (any::<usize>(), 1usize..64).prop_map(|(at, n)| Mutation::Delete { at, n }),
        (any::<usize>(), any::<usize>(), 0usize..HOSTILE.len())
            .prop_map(|(line, k, with)| Mutation::JsonLeaf { line, k, with }),
        (any::<usize>(), any::<usize>(), 0usize..3).prop_map(|(line, k, len)| Mutation::JsonCut {
            line,
            k,
            len
        }),
    ]
}

const HOSTILE: [&str; 12] = [
    "0",
    "-1",
    "1e308",
    "-1e308",
    "18446744073709551615",
    "4294967296",
    "0.5",
    "\"x\"",
    "null",
    "true",
    "[]",
    "{}",
];

/// Visits JSON leaves / lists in a fixed order, applying `f` to the `k`-th (mod count).
fn nth_node(v: &mut Value, want_list: bool, k: usize, f: &mut dyn FnMut(&mut Value)) -> bool {
    fn count(v: &Value, lists: bool) -> usize {
        let own = usize::from(if lists {
            v.is_array()
        } else {
            !v.is_array() && !v.is_object()
        });
        own + match v {
            Value::Array(a) => a.iter().map(|x| count(x, lists)).sum(),
            Value::Object(o) => o.values().map(|x| count(x, lists)).sum(),
            _ => 0,
        }
    }
    fn visit(v: &mut Value, lists: bool, k: &mut usize, f: &mut dyn FnMut(&mut Value)) -> bool {
        let me = if lists {
            v.is_array()
        } else {
            !v.is_array() && !v.is_object()
        };
        if me {
            if *k == 0 {
                f(v);
                return true;
            }
            *k -= 1;
        }
        match v {
            Value::Array(a) => a.iter_mut().any(|x| visit(x, lists, k, f)),
            Value::Object(o) => o.values_mut().any(|x| visit(x, lists, k, f)),
            _ => false,
        }
    }
    let n = count(v, want_list);
    if n == 0 {
        return false;
    }
    let mut k = k % n;
    visit(v, want_list, &mut k, f)
}

fn mutate(bytes: &[u8], m: &Mutation) -> Vec<u8> {
    let mut b = bytes.to_vec();
    let at = |x: usize, len: usize| if len == 0 { 0 } else { x % len };
    match *m {
        Mutation::Flip { at: a, mask } => {
            if !b.is_empty() {
                let i = at(a, b.len());
                b[i] ^= mask;
            }
        }
        Mutation::Truncate { at: a } => b.truncate(at(a, b.len())),
        Mutation::InsertNul { at: a, n } => {
            let i = at(a, b.len() + 1);
            b.splice(i..i, std::iter::repeat_n(0u8, n));
        }
        Mutation::Delete { at: a, n } => {
            let i = at(a, b.len());
            let j = (i + n).min(b.len());
            b.drain(i..j);
        }
        Mutation::JsonLeaf { line, k, with } | Mutation::JsonCut { line, k, len: with } => {
            let lists = matches!(m, Mutation::JsonCut { .. });
            let Ok(text) = String::from_utf8(b.clone()) else {
                return b;
            };
            let mut lines: Vec<String> = text.lines().map(String::from).collect();
            // A whole JSON document, or one line of JSON lines.
            let whole = serde_json::from_str::<Value>(&text).is_ok();
            let targets: Vec<usize> = if whole {
                vec![usize::MAX]
            } else {
                (0..lines.len()).collect()
            };
            if targets.is_empty() {
                return b;
            }
            let t = targets[line % targets.len()];
            let src = if whole {
                text.clone()
            } else {
                lines[t].clone()
            };
            let Ok(mut v) = serde_json::from_str::<Value>(&src) else {
                return b;
            };
            let mut f = |x: &mut Value| {
                if lists {
                    if let Value::Array(a) = x {
                        a.truncate(with);
                    }
                } else {
                    *x = serde_json::from_str(HOSTILE[with]).unwrap();
                }
            };
            nth_node(&mut v, lists, k, &mut f);
            let out = serde_json::to_string(&v).unwrap();
            if whole {
                return out.into_bytes();
            }
            lines[t] = out;
            let mut s = lines.join("\n");
            s.push('\n');
            return s.into_bytes();
        }
    }
    b
}

/// A fresh copy of `src` (files only, one level, plus `checkpoints/` when `with_ckpt`).
fn copy_dir(src: &Path, dst: &Path, with_ckpt: bool) {
    let _ = std::fs::remove_dir_all(dst);
    std::fs::create_dir_all(dst).unwrap();
    for e in std::fs::read_dir(src).unwrap().flatten() {
        let p = e.path();
        if p.is_file() {
            std::fs::copy(&p, dst.join(e.file_name())).unwrap();
        } else if with_ckpt && e.file_name() == "checkpoints" {
            copy_dir(&p, &dst.join("checkpoints"), false);
        }
    }
}

fn case_dir(name: &str) -> PathBuf {
    std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("chronocooked-prop-{name}-{}", std::process::id()))
}

/// Writes the corrupted `bytes` over `file`; `rerecord` also rewrites its SHA-256 record.
fn plant(file: &Path, bytes: &[u8], rerecord: bool) {
    if rerecord {
        integrity::write_recorded(file, bytes).unwrap();
    } else {
        std::fs::write(file, bytes).unwrap();
    }
}

/// 64 cases per reader with a fixed seed (CI reruns the same corruptions); a wider campaign:
/// `PROPTEST_CASES=2000 PROPTEST_RNG_SEED=<n> cargo test --release --test integration corruption_props`.
fn config() -> ProptestConfig {
    let default = ProptestConfig::default();
    let rng_seed = match std::env::var("PROPTEST_RNG_SEED") {
        Ok(_) => default.rng_seed,
        Err(_) => proptest::test_runner::RngSeed::Fixed(27),
    };
    ProptestConfig {
        rng_seed,
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(64),
        failure_persistence: None,
        ..default
    }
}

/// The assertion of every reader: an error names `file`, and a changed file of learned state
/// without a matching record is never accepted.
fn judge<T>(result: Result<T, String>, file: &str, changed: bool, must_fail: bool) {
    match result {
        Ok(_) => assert!(
            !(changed && must_fail),
            "{file}: a corrupted file was accepted"
        ),
        Err(e) => assert!(e.contains(file), "the error does not name {file}: {e}"),
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn ppo_config_policy_and_model(m in mutation(), which in 0usize..3, rerecord: bool) {
        let f = fixtures();
        let dir = case_dir("ppo-model");
        copy_dir(&f.ppo, &dir, false);
        let name = ["config.json", "policy.json", "model.bpk"][which];
        let file = dir.join(name);
        let orig = std::fs::read(&file).unwrap();
        let bad = mutate(&orig, &m);
        let learned = which > 0;
        plant(&file, &bad, rerecord && learned);
        let r = load_policy(&dir).map(|_| ()).map_err(|e| e.to_string());
        judge(r, name, bad != orig, learned && !rerecord);
    }

    #[test]
    fn checkpoints(m in mutation(), rerecord: bool) {
        let f = fixtures();
        let dir = case_dir("ppo-ckpt");
        copy_dir(&f.ppo, &dir, true);
        let run = RunDir::open(&dir).unwrap();
        let cfg = run.config().unwrap();
        let file = run.checkpoints().pop().unwrap();
        let orig = std::fs::read(&file).unwrap();
        let bad = mutate(&orig, &m);
        plant(&file, &bad, rerecord);
        let r = RunDir::read_checkpoint(&file)
            .and_then(|s| Trainer::restore(cfg, s))
            .map(|_| ())
            .map_err(|e| format!("{}: {e}", file.display()));
        judge(r, "step-", bad != orig, !rerecord);
        // The resume itself never panics and never silently starts over.
        match chronocooked_training::resume_trainer(&run, &run.config().unwrap()) {
            Ok(t) => prop_assert!(t.is_some()),
            Err(e) => prop_assert!(e.to_string().contains("checkpoint"), "{e}"),
        }
    }

    #[test]
    fn timing_config_and_agent(m in mutation(), which in 0usize..2, rerecord: bool) {
        let f = fixtures();
        let dir = case_dir("timing");
        copy_dir(&f.timing, &dir, false);
        let name = ["config.json", "agent.json"][which];
        let file = dir.join(name);
        let orig = std::fs::read(&file).unwrap();
        let bad = mutate(&orig, &m);
        plant(&file, &bad, rerecord && which == 1);
        let r = load_timing_agent(&dir).map(|_| ()).map_err(|e| e.to_string());
        judge(r, name, bad != orig, which == 1 && !rerecord);
    }

    #[test]
    fn eval_records_info_and_metrics(m in mutation(), which in 0usize..2) {
        let f = fixtures();
        let dir = case_dir("eval");
        copy_dir(&f.eval, &dir, false);
        let name = ["records.jsonl", "eval.json"][which];
        let file = dir.join(name);
        let bad = mutate(&std::fs::read(&file).unwrap(), &m);
        std::fs::write(&file, &bad).unwrap();
        let r = chronocooked_present::report::leaderboard::load_metrics(&dir);
        judge(r, name, true, false);
        if which == 0 {
            // Export and the figures read the same records.
            let r = chronocooked_analysis::evaluation::protocol::read_records(&dir).and_then(|recs| {
                chronocooked_present::export::export_eval(&recs, &dir.join("export"))
            });
            judge(r, name, true, false);
        }
    }

    #[test]
    fn activity_datasets(m in mutation()) {
        let f = fixtures();
        let orig = std::fs::read(f.eval.join("activity.json")).unwrap();
        let bad = mutate(&orig, &m);
        let out = case_dir("activity");
        let r = chronocooked_models::ActivityDataset::from_json(&bad).and_then(|ds| {
            chronocooked_present::export::export_activity(&ds, &out, 50).map(|_| ())
        });
        // The reader names no file (the caller adds it); it must not panic.
        let _ = r;
    }

    #[test]
    fn npz_archives(m in mutation()) {
        let f = fixtures();
        let dir = case_dir("npz");
        let ds = chronocooked_models::ActivityDataset::from_json(
            &std::fs::read(f.eval.join("activity.json")).unwrap(),
        )
        .unwrap();
        let files = chronocooked_present::export::export_activity(&ds, &dir, 50).unwrap();
        let npz = files.iter().find(|p| p.extension().is_some_and(|e| e == "npz")).unwrap();
        let bad = mutate(&std::fs::read(npz).unwrap(), &m);
        let _ = chronocooked_present::export::npz::read_npz(&bad);
    }

    #[test]
    fn sweep_files(m in mutation()) {
        let text = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/sweeps/demo.toml")).unwrap();
        let bad = mutate(&text, &m);
        let s = String::from_utf8_lossy(&bad);
        if let Err(e) = chronocooked_pipeline::sweep::SweepFile::parse(&s, "demo.toml") {
            prop_assert!(e.to_string().contains("demo.toml"), "{e}");
        }
    }

    #[test]
    fn human_play_traces(m in mutation()) {
        let f = fixtures();
        let trace = f.eval.join("trace.jsonl");
        if !trace.is_file() {
            let lines = common::run_ok(&[
                "env", "replay", "FixedInterval-v0", "--set", "td=4",
                "--actions", "2,2,5,1,1,5,0,0,0,0,5,2,5",
            ]);
            std::fs::write(&trace, lines).unwrap();
        }
        let bad = mutate(&std::fs::read(&trace).unwrap(), &m);
        let text = String::from_utf8_lossy(&bad);
        if let Ok(recs) = chronocooked_analysis::behaviour::human::records_from_trace(&text) {
            let _ = chronocooked_analysis::behaviour::metrics::compute_metrics("human", &recs, 0);
        }
    }
}
