//! Evaluation folders through the binary: a second evaluation into one folder equals a
//! clean one, and records edited together with their SHA-256 record are still refused.

use crate::common;

use common::{run_err, run_ok, temp_dir};
use serde_json::Value;

/// A second evaluation into a folder that holds an earlier one leaves nothing of the
/// earlier: its figures of conditions the new one lacks are gone (a rerun equals a clean
/// evaluation into an empty folder).
#[test]
fn a_second_evaluation_into_one_folder_leaves_nothing_of_the_first() {
    let dir = temp_dir("eval-twice");
    let (twice, clean) = (dir.join("twice"), dir.join("clean"));
    run_ok(&[
        "eval",
        "--agent",
        "oracle",
        "--out",
        twice.to_str().unwrap(),
    ]);
    assert!(twice.join("figures/foc.svg").is_file());
    let second = [
        "eval",
        "--agent",
        "random",
        "--task",
        "Bisection-v0",
        "--out",
    ];
    run_ok(&[&second[..], &[twice.to_str().unwrap()]].concat());
    run_ok(&[&second[..], &[clean.to_str().unwrap()]].concat());
    let names = |d: &std::path::Path| {
        let mut v: Vec<String> = std::fs::read_dir(d.join("figures"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    assert_eq!(names(&twice), names(&clean));
    assert!(!twice.join("figures/foc.svg").exists());
    for f in ["metrics.json", "records.jsonl", "eval.json", "SHA256SUMS"] {
        assert_eq!(
            std::fs::read(twice.join(f)).unwrap(),
            std::fs::read(clean.join(f)).unwrap(),
            "{f}"
        );
    }
}

/// Records edited with their SHA-256 record updated too (or the record removed) are still
/// refused where the edit breaks what an episode is: moves its actions do not make, another
/// condition's duration, a return no task pays, a success the last step does not show, a
/// deleted or repeated line.
#[test]
fn edited_evaluation_records_are_refused_even_when_re_recorded() {
    use chronocooked_env::integrity::{remove_recorded, write_recorded};
    let dir = temp_dir("records-semantic");
    let clean = dir.join("clean");
    run_ok(&[
        "eval",
        "--agent",
        "oracle",
        "--out",
        clean.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(clean.join("records.jsonl")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let edit = |first: &dyn Fn(&mut Value)| -> String {
        let mut v: Value = serde_json::from_str(lines[0]).unwrap();
        first(&mut v);
        let mut out = vec![serde_json::to_string(&v).unwrap()];
        out.extend(lines[1..].iter().map(|l| l.to_string()));
        out.join("\n") + "\n"
    };
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "actions",
            edit(&|v| {
                let n = v["episode"]["actions"].as_array().unwrap().len();
                v["episode"]["actions"] = serde_json::json!(vec![0; n]);
            }),
            "its action",
        ),
        (
            "condition td",
            edit(&|v| v["condition"]["td"] = serde_json::json!(99)),
            "`condition.td`",
        ),
        (
            "start",
            edit(&|v| v["episode"]["start"] = serde_json::json!([9, 9])),
            "moves the agent",
        ),
        (
            "reward",
            edit(&|v| v["episode"]["reward"] = serde_json::json!(1e9)),
            "`reward`",
        ),
        (
            "success",
            edit(&|v| v["episode"]["success"] = serde_json::json!(false)),
            "`success`",
        ),
        (
            "step",
            edit(&|v| v["episode"]["infos"][0]["timestep"] = serde_json::json!(5)),
            "timestep",
        ),
        ("deleted line", lines[1..].join("\n") + "\n", "`episodes`"),
        (
            "repeated line",
            format!("{}\n{text}", lines[0]),
            "`episodes`",
        ),
    ];
    for (name, records, needle) in cases {
        let d = copy_of(&clean, &dir.join(name.replace(' ', "-")));
        write_recorded(&d.join("records.jsonl"), records.as_bytes()).unwrap();
        let err = rescore_err(&d);
        assert!(
            err.contains("records.jsonl") && err.contains(needle),
            "{name}: {err}"
        );
    }
    // The record removed: the file is no longer vouched for.
    let d = copy_of(&clean, &dir.join("unrecorded"));
    let kept = std::fs::read(d.join("records.jsonl")).unwrap();
    remove_recorded(&d.join("records.jsonl")).unwrap();
    std::fs::write(d.join("records.jsonl"), kept).unwrap();
    let err = rescore_err(&d);
    assert!(err.contains("records.jsonl"), "{err}");
}

/// A fresh copy of the evaluation folder `clean`'s files at `to`.
fn copy_of(clean: &std::path::Path, to: &std::path::Path) -> std::path::PathBuf {
    let _ = std::fs::remove_dir_all(to);
    std::fs::create_dir_all(to).unwrap();
    for f in ["eval.json", "metrics.json", "SHA256SUMS", "records.jsonl"] {
        std::fs::copy(clean.join(f), to.join(f)).unwrap();
    }
    to.to_path_buf()
}

/// The error of `eval --from d` (rescoring the folder's records), which must fail.
fn rescore_err(d: &std::path::Path) -> String {
    run_err(&[
        "eval",
        "--from",
        d.to_str().unwrap(),
        "--out",
        d.join("re").to_str().unwrap(),
    ])
}
