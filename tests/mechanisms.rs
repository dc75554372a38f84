//! `chronocooked mechanisms` on constructed compact results whose answers are known: the
//! features read by hand from the job files, and an agent built as a copy of one mechanism
//! is nearest to it in every bootstrap resample.

use crate::common;

use chronocooked_analysis::mechanisms::{View, compare, signatures};
use common::run_ok;
use serde_json::json;
use std::path::Path;

/// Writes one compact job: FI at `td` (FOC mean `foc`, CV `cv`, PI peak `peak` and CV 0.3
/// on the 2 × TD probe) or, with `bis`, bisection 4-12 (BP, WF); `frac` the share of ramps
/// among 10 units of the timing population (the rest time fields), plus a value read-out
/// that must not count.
#[allow(clippy::too_many_arguments)]
fn job(
    root: &Path,
    model: &str,
    seed: u64,
    td: u32,
    foc: f64,
    cv: f64,
    bis: Option<(f64, f64)>,
    ramps: u64,
) {
    let task = if bis.is_some() {
        "Bisection-v0"
    } else {
        "FixedInterval-v0"
    };
    let dir = root
        .join("jobs")
        .join(task)
        .join(format!("{model}~td-{td}"))
        .join(format!("seed{seed}"));
    std::fs::create_dir_all(&dir).unwrap();
    let j = json!({"id": format!("{task}/{model}/seed{seed}"), "task": task, "model": model,
                   "row": model, "seed": seed, "env": []});
    std::fs::write(dir.join("job.json"), j.to_string()).unwrap();
    let metrics = match bis {
        Some((bp, wf)) => json!({"conditions": [], "bisection": {"short": 4, "long": 12,
                                  "fit": {"bp": bp, "wf": wf}}}),
        None => json!({"conditions": [],
                       "fi": {"foc": [{"td": td, "n": 48, "mean": foc, "sd": cv * foc, "cv": cv}]},
                       "pi": [{"factor": 2.0, "td": td, "fit": {"peak": 1.5 * td as f64, "cv": 0.3}},
                              {"factor": 5.0, "td": td, "fit": {"peak": 9.0 * td as f64, "cv": 0.9}}]}),
    };
    std::fs::write(dir.join("metrics.json"), metrics.to_string()).unwrap();
    if bis.is_none() {
        let counts = |r: u64, t: u64| {
            json!({"ramp": r, "time_field": t, "oscillating": 0,
                                            "mixed": 0, "untuned": 0})
        };
        let summary = json!([
            {"population": "cells", "td": td, "decode_ridge": 0.1 * td as f64,
             "categories": {"counts": counts(ramps, 10 - ramps)}},
            {"population": "value", "td": td, "decode_ridge": 9.0,
             "categories": {"counts": counts(0, 1)}}
        ]);
        std::fs::write(dir.join("activity.summary.json"), summary.to_string()).unwrap();
    }
}

#[test]
fn fingerprints_read_every_feature_and_find_the_mechanism_an_agent_copies() {
    let root = tempfile::tempdir().unwrap();
    for seed in 0..4 {
        let e = 0.01 * seed as f64;
        // "ddm": ramps, CV 0.15 at both TDs; "timecells-csc": time fields, CV 0.3 → 0.15.
        job(root.path(), "ddm", seed, 6, 6.6, 0.15 + e, None, 10);
        job(root.path(), "ddm", seed, 12, 12.0, 0.15 + e, None, 10);
        job(
            root.path(),
            "ddm",
            seed,
            0,
            0.0,
            0.0,
            Some((7.0, 0.1 + e)),
            0,
        );
        job(root.path(), "timecells-csc", seed, 6, 6.0, 0.3 + e, None, 1);
        job(
            root.path(),
            "timecells-csc",
            seed,
            12,
            12.0,
            0.15 + e,
            None,
            1,
        );
        job(
            root.path(),
            "timecells-csc",
            seed,
            0,
            0.0,
            0.0,
            Some((8.0, 0.2 + e)),
            0,
        );
        // The agent copies the ramp's behaviour and activity, up to small offsets.
        job(root.path(), "agent125", seed, 6, 6.5, 0.16 + e, None, 9);
        job(root.path(), "agent125", seed, 12, 12.1, 0.15 + e, None, 9);
        job(
            root.path(),
            "agent125",
            seed,
            0,
            0.0,
            0.0,
            Some((7.1, 0.11 + e)),
            0,
        );
    }
    let sigs = signatures(root.path()).unwrap();
    assert_eq!(sigs.len(), 12);
    let csc0 = sigs
        .iter()
        .find(|s| s.model == "timecells-csc" && s.seed == 0)
        .unwrap();
    let f = |k: &str| csc0.features[k];
    // By hand: FOC/TD (1 + 1)/2; CV (0.3 + 0.15)/2; trend ln(0.15/0.3); PI peak/TD 1.5 and
    // CV 0.3 from the 2 × TD probe only; BP/GM 8/√48; ramps 1 of 10 units (the value
    // read-out excluded); decoding error 0.1 × TD / TD.
    assert!((f("foc_over_td") - 1.0).abs() < 1e-12);
    assert!((f("foc_cv") - 0.225).abs() < 1e-12);
    assert!((f("foc_cv_trend") - 0.5f64.ln()).abs() < 1e-12);
    assert!((f("pi_peak_over_td") - 1.5).abs() < 1e-12 && (f("pi_cv") - 0.3).abs() < 1e-12);
    assert!((f("bp_over_gm") - 8.0 / 48f64.sqrt()).abs() < 1e-12);
    assert!((f("wf") - 0.2).abs() < 1e-12);
    assert!((f("frac_ramp") - 0.1).abs() < 1e-12 && (f("frac_time_field") - 0.9).abs() < 1e-12);
    assert!((f("decode_error_over_td") - 0.1).abs() < 1e-12);
    let c = compare(&sigs, &["ddm", "timecells-csc"], 300, 3, View::Units);
    let get = |m: &str| {
        c.iter()
            .find(|x| x.agent == "agent125" && x.mechanism == m)
            .unwrap()
    };
    assert!(get("ddm").distance < get("timecells-csc").distance, "{c:?}");
    assert_eq!(get("ddm").nearest_fraction, 1.0);
    // Through the CLI: the three tables, the agent's row naming its nearest mechanism.
    let out = root.path().join("out");
    run_ok(&[
        "mechanisms",
        root.path().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--resamples",
        "200",
    ]);
    let md = std::fs::read_to_string(out.join("mechanisms.md")).unwrap();
    let row = md
        .lines()
        .find(|l| l.starts_with("| agent125 |") && l.contains("ddm (1.00)"))
        .unwrap_or_default();
    assert!(!row.is_empty(), "{md}");
    assert!(out.join("fingerprints.svg").is_file() && out.join("fingerprints.png").is_file());
    let csv = std::fs::read_to_string(out.join("signatures.csv")).unwrap();
    assert_eq!(csv.lines().count(), 13, "{csv}");
    // An empty folder is an error naming it.
    let empty = root.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    assert!(
        signatures(&empty)
            .unwrap_err()
            .to_string()
            .contains("empty")
    );
}

#[test]
fn scaling_from_a_sweep_records_each_model_and_seed_at_both_tds_and_enters_the_fingerprint() {
    let root = tempfile::tempdir().unwrap();
    let (study, results) = (root.path().join("study"), root.path().join("results"));
    // A sweep's layout: the drift-diffusion model trained at TD 6 and 12, seed 0.
    for td in [6u32, 12] {
        let dir = study
            .join("FixedInterval-v0")
            .join(format!("ddm~env.td-{td}"))
            .join("seed0");
        std::fs::create_dir_all(&dir).unwrap();
        let j = json!({"task": "FixedInterval-v0", "model": "ddm", "row": "ddm", "seed": 0,
                       "env": [format!("td={td}")]});
        std::fs::write(dir.join("job.json"), j.to_string()).unwrap();
        run_ok(&[
            "train",
            "--task",
            "FixedInterval-v0",
            "--model",
            "ddm",
            "--set",
            &format!("env.td={td}"),
            "--quiet",
            "--out",
            dir.join("run").to_str().unwrap(),
        ]);
        job(&results, "ddm", 0, td, td as f64, 0.15, None, 10);
    }
    let args = [
        "mechanisms",
        results.to_str().unwrap(),
        "--resamples",
        "10",
        "--scaling-from",
        study.to_str().unwrap(),
    ];
    let out = run_ok(&args);
    assert!(out.contains("1 model x seed groups recorded"), "{out}");
    let dir = results.join("scaling/ddm/seed0");
    let job: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("scaling.json")).unwrap()).unwrap();
    assert_eq!(job["tds"], json!([6, 12]));
    assert!(
        !dir.join("activity.json").exists(),
        "only the compact summary is kept"
    );
    // The accumulator's scaling is measured between TD 6 and 12 and enters the signature.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("activity.summary.json")).unwrap())
            .unwrap();
    let acc = summary
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["population"] == "accumulator")
        .unwrap();
    assert_eq!(acc["scaling"]["td_short"], 6);
    assert_eq!(acc["scaling"]["td_long"], 12);
    let sig = signatures(&results).unwrap();
    let index = sig[0].features["scaling_index"];
    let view =
        chronocooked_analysis::mechanisms::PopulationView::read(&dir.join("activity.summary.json"))
            .unwrap();
    let expected = chronocooked_analysis::mechanisms::scaling_index_of_summary(&view).unwrap();
    assert_eq!(index, expected);
    // A second run finds it recorded.
    assert!(run_ok(&args).contains("0 model x seed groups recorded, 1 already there"));
}

/// Copies `src` into `dst` recursively.
/// Copies the folder `src` to `dst` (files and subfolders).
pub(crate) fn copy_tree(src: &Path, dst: &Path) {
    std::fs::create_dir_all(dst).unwrap();
    for e in std::fs::read_dir(src).unwrap() {
        let e = e.unwrap();
        let to = dst.join(e.file_name());
        if e.file_type().unwrap().is_dir() {
            copy_tree(&e.path(), &to);
        } else {
            std::fs::copy(e.path(), &to).unwrap();
        }
    }
}

/// The committed mechanisms study proves its fingerprint: every mechanism's held-out seeds
/// are named as itself (leave one seed out), each nearer its own fingerprint than any
/// other; and a negative control — the random policy, evaluated on the study's three
/// conditions with four seeds and added to a copy of the study — is not identified.
#[test]
fn the_committed_study_names_every_held_out_mechanism_and_not_a_random_agent() {
    use chronocooked_analysis::mechanisms::{MECHANISMS, identify};
    let study = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/mechanisms");
    let id = identify(&signatures(&study).unwrap(), View::Units);
    for m in MECHANISMS {
        assert_eq!(id.accuracy(m), 1.0, "{m}: {:?}", id.held_out);
    }
    for h in &id.held_out {
        assert!(h.self_distance < h.other_distance, "{h:?}");
    }
    // The negative control.
    let root = tempfile::tempdir().unwrap();
    for part in ["jobs", "scaling"] {
        copy_tree(&study.join(part), &root.path().join(part));
    }
    for seed in 0..4u64 {
        for (task, env) in [
            ("FixedInterval-v0", vec!["td=6"]),
            ("FixedInterval-v0", vec!["td=12"]),
            ("Bisection-v0", vec!["short=4", "long=12"]),
        ] {
            let job = root
                .path()
                .join(format!("jobs/{task}/random~{}/seed{seed}", env.join("_")));
            let eval = root.path().join(format!("eval-{seed}"));
            let mut args = vec!["eval", "--agent", "random", "--task", task];
            for e in &env {
                args.extend(["--env", e]);
            }
            let seed_s = seed.to_string();
            args.extend([
                "--stochastic",
                "20",
                "--seed",
                &seed_s,
                "--out",
                eval.to_str().unwrap(),
            ]);
            run_ok(&args);
            std::fs::create_dir_all(&job).unwrap();
            std::fs::copy(eval.join("metrics.json"), job.join("metrics.json")).unwrap();
            let meta = json!({
                "id": format!("{task}/random/seed{seed}"), "task": task, "model": "random",
                "row": "random", "seed": seed, "env": env, "preset": "", "total_steps": 0,
                "steps_done": 0, "wall_s": null, "final_ep_len_mean": null,
                "final_ep_return_mean": null, "level_steps": [0], "ppo": null
            });
            std::fs::write(job.join("job.json"), meta.to_string()).unwrap();
        }
    }
    let out = run_ok(&[
        "mechanisms",
        root.path().to_str().unwrap(),
        "--resamples",
        "50",
    ]);
    let line = out
        .lines()
        .find(|l| l.trim_start().starts_with("random:"))
        .unwrap_or_default();
    assert!(line.contains("not identified"), "{out}");
    let id = identify(&signatures(root.path()).unwrap(), View::Units);
    let random = id.agents.iter().find(|a| a.agent == "random").unwrap();
    assert!(!random.identified, "{random:?}");
}

/// `fingerprint` on the lab's own runs: timing mechanisms trained as the reference study
/// trains them, with a seed no study or doc uses (43), are identified as themselves —
/// within their own held-out seeds' distances — and the runs of a condition outside the
/// protocol, or two runs of one condition, are refused naming them.
#[test]
fn fingerprint_identifies_held_out_seeds_of_the_mechanisms_from_their_runs() {
    let dir = common::temp_dir("fingerprint");
    let d = |name: &str| dir.join(name).to_str().unwrap().to_string();
    for m in ["ddm", "timecells-ms", "timecells-csc"] {
        let runs = [
            (
                "fi6",
                "FixedInterval-v0",
                vec!["env.td=6", "stop_at_success=none"],
            ),
            (
                "fi12",
                "FixedInterval-v0",
                vec!["env.td=12", "stop_at_success=none"],
            ),
            (
                "bis",
                "Bisection-v0",
                vec!["env.short=4", "env.long=12", "stop_at_success=0.95"],
            ),
        ];
        let mut args = vec!["fingerprint".to_string()];
        for (name, task, sets) in &runs {
            let out = d(&format!("{m}-{name}"));
            let mut train = vec!["train", "--model", m, "--task", task, "--seed", "43"];
            for s in sets {
                train.extend(["--set", s]);
            }
            train.extend(["--out", &out]);
            run_ok(&train);
            args.extend(["--run".to_string(), out]);
        }
        args.extend([
            "--out".into(),
            d(&format!("fp-{m}")),
            "--resamples".into(),
            "200".into(),
        ]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_ok(&args);
        assert!(
            out.contains(&format!("is identified as {m}:")),
            "{m}: {out}"
        );
        let fp: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(format!("fp-{m}/fingerprint.json"))).unwrap(),
        )
        .unwrap();
        for view in ["units", "dynamics"] {
            assert_eq!(fp[view]["nearest"], m, "{view}");
        }
        for view in ["units", "dynamics"] {
            assert_eq!(fp[view]["missing"], json!([]), "{view}");
        }
        for f in [
            "fingerprint.html",
            "fingerprint.png",
            "fi-td6/activity.summary.json",
        ] {
            assert!(dir.join(format!("fp-{m}/{f}")).is_file(), "{f}");
        }
    }
    // A run of no protocol condition (FI at TD 9), and two runs of one condition.
    run_ok(&[
        "train",
        "--model",
        "ddm",
        "--task",
        "FixedInterval-v0",
        "--set",
        "env.td=9",
        "--seed",
        "43",
        "--out",
        &d("fi9"),
    ]);
    let err = common::run_err(&["fingerprint", "--run", &d("fi9"), "--out", &d("x")]);
    assert!(
        err.contains("no condition of the fingerprint protocol"),
        "{err}"
    );
    let err = common::run_err(&[
        "fingerprint",
        "--run",
        &d("ddm-fi6"),
        "--run",
        &d("timecells-ms-fi6"),
        "--out",
        &d("x"),
    ]);
    assert!(err.contains("both runs of the condition fi-td6"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The reference study behind `chronocooked.fingerprint` (8 seeds per mechanism, rules 2):
/// leave one seed out, at least 95% of the held-out seeds are named as their own mechanism.
#[test]
fn the_reference_study_names_its_held_out_seeds() {
    use chronocooked_analysis::mechanisms::identify;
    let study = Path::new(env!("CARGO_MANIFEST_DIR")).join("results/mechanisms-reference");
    let id = identify(&signatures(&study).unwrap(), View::Units);
    let correct = id
        .held_out
        .iter()
        .filter(|h| h.named.as_deref() == Some(h.mechanism.as_str()))
        .count();
    assert_eq!(id.held_out.len(), 40);
    assert!(
        correct as f64 >= 0.95 * 40.0,
        "{correct}/40: {:?}",
        id.held_out
    );
}

/// `mechanisms RESULTS --scaling-from SWEEP_OUT` (documented in docs/python.md and RESULTS)
/// on a sweep written by today's binary: its jobs' typed `job.json` are read, each (row,
/// seed) with fixed-interval runs at two TDs is recorded together for the scaling feature.
#[test]
fn mechanisms_scaling_from_reads_a_fresh_sweep() {
    let dir = crate::common::temp_dir("mechanisms-scaling-from");
    let sweep = dir.join("s.toml");
    std::fs::write(
        &sweep,
        "name = \"sc\"\ntasks = [\"FixedInterval-v0\"]\nmodels = [\"ddm\"]\nseeds = [1]\n\
         episodes = 100\nrecord = true\nexport = false\n\n[task_variants]\n\
         \"FixedInterval-v0\" = [[\"env.td=6\"], [\"env.td=12\"]]\n",
    )
    .unwrap();
    let (out, res) = (dir.join("out"), dir.join("res"));
    let p = |p: &std::path::Path| p.to_str().unwrap().to_string();
    crate::common::run_ok(&["sweep", &p(&sweep), "--out", &p(&out), "--no-report"]);
    crate::common::run_ok(&["paper", "collect", &p(&out), "--out", &p(&res)]);
    crate::common::run_ok(&[
        "mechanisms",
        &p(&res),
        "--scaling-from",
        &p(&out),
        "--resamples",
        "20",
    ]);
    let scaling = res.join("scaling/ddm/seed1/scaling.json");
    assert!(scaling.is_file(), "{} missing", scaling.display());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `fingerprint --sweep` over the held-out study's sweep (two of its mechanisms at one of
/// its seeds): each agent's line is the committed study's line for it (made by the study's
/// earlier per-agent `fingerprint --run` loop), a rerun places the agents again from their
/// folders without replaying them and gives the same lines, and a sweep output with no
/// protocol condition is refused, naming the conditions.
#[test]
fn fingerprint_sweep_gives_the_held_out_study_lines_and_resumes() {
    let dir = common::temp_dir("fingerprint-sweep");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let study = std::fs::read_to_string(root.join("sweeps/mechanisms-heldout.toml")).unwrap();
    let mut sweep = String::new();
    for line in study.lines() {
        if line.starts_with("models =") {
            sweep.push_str("models = [\"ddm\", \"timecells-ms\"]\n");
        } else if line.starts_with("seeds =") {
            sweep.push_str("seeds = [44]\n");
        } else {
            sweep.push_str(line);
            sweep.push('\n');
        }
    }
    let file = dir.join("heldout.toml");
    std::fs::write(&file, sweep).unwrap();
    let (f, out, fp) = (
        file.to_str().unwrap(),
        dir.join("sweep"),
        dir.join("fingerprints"),
    );
    let (out, fp) = (out.to_str().unwrap(), fp.to_str().unwrap());
    run_ok(&["sweep", f, "--out", out, "--workers", "2", "--no-report"]);
    let committed =
        std::fs::read_to_string(root.join("results/mechanisms-reference/heldout-fingerprints.txt"))
            .unwrap();
    let want: Vec<&str> = ["ddm seed 44:", "timecells-ms seed 44:"]
        .iter()
        .map(|p| committed.lines().find(|l| l.starts_with(p)).unwrap())
        .collect();
    let args = [
        "fingerprint",
        "--sweep",
        out,
        "--out",
        fp,
        "--resamples",
        "200",
    ];
    let first = run_ok(&args);
    let lines = std::fs::read_to_string(dir.join("fingerprints/fingerprints.txt")).unwrap();
    assert_eq!(lines.lines().collect::<Vec<_>>(), want, "{first}");
    assert!(first.contains("2 agents (2 played now"), "{first}");
    let again = run_ok(&args);
    assert!(again.contains("(0 played now, 2 placed again"), "{again}");
    let lines = std::fs::read_to_string(dir.join("fingerprints/fingerprints.txt")).unwrap();
    assert_eq!(lines.lines().collect::<Vec<_>>(), want);
    // A sweep output without any protocol condition.
    let empty = dir.join("empty");
    std::fs::create_dir_all(empty.join("FixedInterval-v0")).unwrap();
    let err = common::run_err(&[
        "fingerprint",
        "--sweep",
        empty.to_str().unwrap(),
        "--out",
        fp,
    ]);
    assert!(
        err.contains("no finished job of a fingerprint protocol condition"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The committed mechanisms tables are what today's binary makes of the committed compact
/// results: `mechanisms DIR --out TMP` on each study folder writes the same signatures,
/// comparisons, pairwise distances and Markdown, byte for byte.
#[test]
fn the_committed_mechanisms_tables_regenerate_byte_for_byte() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for study in ["results/mechanisms", "results/mechanisms-reference"] {
        let dir = root.join(study);
        let out = common::temp_dir(&format!("regen-{}", study.replace('/', "-")));
        run_ok(&[
            "mechanisms",
            dir.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        for file in [
            "signatures.csv",
            "mechanisms.csv",
            "pairwise.csv",
            "mechanisms.md",
        ] {
            let committed = std::fs::read(dir.join(file)).unwrap();
            let made = std::fs::read(out.join(file)).unwrap();
            assert!(
                committed == made,
                "{study}/{file} differs from today's output"
            );
        }
        std::fs::remove_dir_all(&out).unwrap();
    }
}
