//! The zoo of trained agents: every agent loads by name, evaluates to the success its
//! provenance records (and to the committed paper-core job it reproduces), records
//! activity; corrupt or edited zoo files are refused with an error naming them; the copy
//! compiled into the program works outside the repository.

use crate::common;

use chronocooked_analysis::collect::EpisodeRow;
use common::{bin, run_err, run_ok, temp_dir};
use serde_json::Value;
use std::path::Path;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn read_json(p: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

fn agents() -> Vec<Value> {
    let list: Value = serde_json::from_str(&run_ok(&["zoo", "list", "--json"])).unwrap();
    list["trained"]["agents"].as_array().unwrap().clone()
}

#[test]
fn the_zoo_holds_the_four_paper_models_on_fi_and_bisection_in_a_few_megabytes() {
    let list = run_ok(&["zoo", "list"]);
    let agents = agents();
    let mut names: Vec<&str> = agents.iter().map(|a| a["name"].as_str().unwrap()).collect();
    names.sort_unstable();
    let mut want = Vec::new();
    for task in ["Bisection-v0", "FixedInterval-v0"] {
        for m in ["cnn-mlp", "ctrnn-reservoir125", "ctrnn125", "lstm125"] {
            want.push(format!("zoo:{m}/{task}"));
        }
    }
    // The memory control (issue #67): 4 stacked frames, fixed interval at TD 4.
    want.push("zoo:cnn-mlp-stack4/FixedInterval-v0".into());
    want.sort();
    assert_eq!(names, want);
    for n in &names {
        assert!(list.contains(n), "`zoo list` shows {n}");
    }
    let total: u64 = agents.iter().map(|a| a["bytes"].as_u64().unwrap()).sum();
    assert!(total < 4_000_000, "the zoo is {total} bytes");
    for a in &agents {
        let p = &a["provenance"];
        assert_eq!(p["preset"], "reference");
        let sweep = if p["model"] == "cnn-mlp-stack4" {
            "sweeps/frame-stack-control.toml"
        } else {
            "sweeps/paper-core.toml"
        };
        assert_eq!(p["sweep"], sweep);
        assert!(
            p["command"]
                .as_str()
                .unwrap()
                .contains(p["job"].as_str().unwrap())
        );
        assert_eq!(p["commit"].as_str().unwrap().len(), 40);
        let steps = if p["task"] == "Bisection-v0" {
            960_000
        } else {
            900_000
        };
        assert_eq!(
            p["env_steps"], steps,
            "{}: the full paper-core budget",
            p["name"]
        );
    }
}

#[test]
fn every_zoo_agent_evaluates_to_its_recorded_success_and_records_activity() {
    let dir = temp_dir("zoo-eval");
    for a in agents() {
        let name = a["name"].as_str().unwrap();
        let p = &a["provenance"];
        let out = dir.join(name.replace([':', '/'], "_"));
        run_ok(&["eval", "--run", name, "--out", out.to_str().unwrap()]);
        let m = read_json(&out.join("metrics.json"));
        // Success per condition within the evaluation's own spread (binomial SE of the
        // recorded rate over the condition's episodes; 0 for a rate of 0 or 1).
        let recorded = p["evaluation"]["conditions"].as_array().unwrap();
        let conditions = m["conditions"].as_array().unwrap();
        assert_eq!(conditions.len(), recorded.len(), "{name}");
        for (c, r) in conditions.iter().zip(recorded) {
            let (want, n) = (r[3].as_f64().unwrap(), r[2].as_f64().unwrap());
            let got = c["success_rate"].as_f64().unwrap();
            let se = (want * (1.0 - want) / n).sqrt();
            assert!(
                (got - want).abs() <= 2.0 * se + 1e-12,
                "{name} {r}: success {got}"
            );
        }
        // The agent is the committed paper-core job of the same seed: the same episodes,
        // line for line.
        assert_eq!(p["reproduces_study_job"], true, "{name}");
        let study = Path::new(ROOT).join(p["study_job"].as_str().unwrap());
        let records = chronocooked_analysis::evaluation::protocol::read_records(&out).unwrap();
        let mine: Vec<EpisodeRow> = records.iter().map(EpisodeRow::of).collect();
        let committed: Vec<EpisodeRow> = csv::Reader::from_path(study.join("episodes.csv"))
            .unwrap()
            .deserialize()
            .collect::<Result<_, _>>()
            .unwrap();
        assert_eq!(mine, committed, "{name} vs {}", study.display());
        // Activity: FI agents on peak-interval probes, bisection agents on their protocol.
        let act = out.join("activity.json");
        let mut args = vec!["record", "--run", name, "--out", act.to_str().unwrap()];
        if p["task"] == "FixedInterval-v0" {
            args.push("--probe");
        }
        let line = run_ok(&args);
        let trials: usize = line
            .split(" trials")
            .next()
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        let units: usize = line
            .split(" × ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        // Recurrent cores have 125 units; CNN-MLP's latent layer 64 (plus the value).
        let min_units = if p["model"]
            .as_str()
            .is_some_and(|m| m.starts_with("cnn-mlp"))
        {
            64
        } else {
            125
        };
        assert!(trials >= 12 && units > min_units, "{name}: {line}");
        assert!(act.is_file(), "{name}: activity written");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A copy of the zoo with one agent, for corrupting.
fn zoo_copy(dir: &Path, name: &str) -> std::path::PathBuf {
    let zoo = dir.join("zoo");
    let to = zoo.join(name);
    std::fs::create_dir_all(&to).unwrap();
    for e in std::fs::read_dir(Path::new(ROOT).join("zoo").join(name)).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
    let index = format!("{{\"format\": 1, \"agents\": [\"{name}\"]}}");
    std::fs::write(zoo.join("index.json"), index).unwrap();
    zoo
}

fn eval_with_zoo(zoo: &Path, name: &str, out: &Path) -> std::process::Output {
    bin()
        .env("CHRONOCOOKED_ZOO", zoo)
        .args([
            "eval",
            "--run",
            &format!("zoo:{name}"),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap()
}

/// A way to spoil an agent's folder: (what, how, words the error must contain).
type Case<'a> = (&'a str, &'a dyn Fn(&Path), &'a [&'a str]);

#[test]
fn corrupt_edited_or_unexpected_zoo_files_are_refused_naming_them() {
    let dir = temp_dir("zoo-corrupt");
    let name = "lstm125/FixedInterval-v0";
    let out = dir.join("eval");
    let zoo = zoo_copy(&dir, name);
    assert!(
        eval_with_zoo(&zoo, name, &out).status.success(),
        "the intact copy loads"
    );
    let cases: [Case; 5] = [
        (
            "a flipped weight byte",
            &|a| {
                let mut b = std::fs::read(a.join("model.bpk")).unwrap();
                let i = b.len() / 2;
                b[i] ^= 0x40;
                std::fs::write(a.join("model.bpk"), b).unwrap();
            },
            &["model.bpk", "does not match its SHA-256 record"],
        ),
        (
            "an edited provenance",
            &|a| {
                let t = std::fs::read_to_string(a.join("provenance.json")).unwrap();
                std::fs::write(
                    a.join("provenance.json"),
                    t.replace("\"seed\": 4", "\"seed\": 5"),
                )
                .unwrap();
            },
            &["provenance.json", "does not match"],
        ),
        (
            "an edited configuration",
            &|a| {
                let t = std::fs::read_to_string(a.join("config.json")).unwrap();
                std::fs::write(a.join("config.json"), t.replace("td=12", "td=13")).unwrap();
            },
            &["config.json", "does not match"],
        ),
        (
            "an unexpected file",
            &|a| std::fs::write(a.join("notes.txt"), "x").unwrap(),
            &["notes.txt", "unexpected file"],
        ),
        (
            "no records",
            &|a| std::fs::remove_file(a.join("SHA256SUMS")).unwrap(),
            &["SHA256SUMS", "missing or empty"],
        ),
    ];
    for (what, corrupt, needles) in cases {
        let zoo = zoo_copy(&dir.join(what.replace(' ', "-")), name);
        corrupt(&zoo.join(name));
        let o = eval_with_zoo(&zoo, name, &out);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{what}: accepted");
        for n in needles {
            assert!(err.contains(n), "{what}: `{n}` not in: {err}");
        }
    }
    let err = run_err(&[
        "eval",
        "--run",
        "zoo:lstm999/FixedInterval-v0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        err.contains("no zoo agent `lstm999/FixedInterval-v0`")
            && err.contains("lstm125/FixedInterval-v0"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_compiled_in_zoo_serves_agents_outside_the_repository_and_is_checked_there_too() {
    // A folder outside the repository (the target dir is inside it): the system temp dir,
    // removed with its guard.
    let guard = tempfile::tempdir().unwrap();
    let dir = guard.path().to_path_buf();
    let cache = dir.join("cache");
    let run = |args: &[&str]| {
        bin()
            .current_dir(&dir)
            .env_remove("CHRONOCOOKED_ZOO")
            .env("CHRONOCOOKED_CACHE", &cache)
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&["zoo", "list"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && text.contains("Trained agents (9 in"),
        "{text}"
    );
    assert!(
        text.contains(cache.to_str().unwrap()),
        "unpacked into the cache: {text}"
    );
    let o = run(&["eval", "--run", "zoo:cnn-mlp/Bisection-v0", "--out", "e"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The unpacked copy is checked like any other: a modified file is refused.
    let unpacked = std::fs::read_dir(&cache)
        .unwrap()
        .next()
        .unwrap()
        .unwrap()
        .path();
    let model = unpacked.join("cnn-mlp/Bisection-v0/model.bpk");
    let mut b = std::fs::read(&model).unwrap();
    b[100] ^= 1;
    std::fs::write(&model, b).unwrap();
    let o = run(&["eval", "--run", "zoo:cnn-mlp/Bisection-v0", "--out", "e"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("model.bpk") && err.contains("does not match"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
