//! End-to-end tests of the `chronocooked` binary on runs: train and zoo, timing models,
//! eval, report, and the errors for folders and files that are not what they should be.

use crate::common;

use common::{bin, run_err, run_ok, temp_dir};
use serde_json::Value;

#[test]
fn train_and_zoo_commands_work_and_reject_bad_input() {
    let list = run_ok(&["zoo", "list"]);
    for m in [
        "cnn-mlp",
        "lstm",
        "ctrnn",
        "gru",
        "rnn",
        "FixedInterval-v0",
        "reference",
        "fast",
    ] {
        assert!(list.contains(m), "zoo list lacks {m}");
    }
    let show = run_ok(&["zoo", "show", "lstm125", "--task", "Bisection-v0"]);
    assert!(
        show.contains("\"total_steps\": 960000") && show.contains("bptt_len"),
        "{show}"
    );
    for (args, needle) in [
        (vec!["train", "--model", "transformer"], "unknown model"),
        (vec!["train", "--task", "Nope-v0"], "Nope-v0"),
        (vec!["train", "--preset", "turbo"], "unknown preset"),
        (vec!["train", "--set", "n_epochs=0"], "n_epochs"),
        (vec!["train", "--set", "bogus=1"], "unknown setting"),
        (vec!["train", "--set", "env.td=0"], "td"),
        // zoo show checks every argument, also those the model does not use.
        (
            vec!["zoo", "show", "oracle", "--task", "Nope-v0"],
            "Nope-v0",
        ),
        (vec!["zoo", "show", "ddm", "--task", "Nope-v0"], "Nope-v0"),
        (
            vec!["zoo", "show", "ddm", "--preset", "fast"],
            "deep-RL models only",
        ),
        // Also the default preset's name: given, it would be silently ignored.
        (
            vec!["zoo", "show", "random", "--preset", "reference"],
            "deep-RL models only",
        ),
        (
            vec!["train", "--resume", "/nonexistent/run"],
            "not a run folder",
        ),
    ] {
        let err = run_err(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    let dir = temp_dir("train-cli");
    let out = run_ok(&[
        "train",
        "--model",
        "cnn-mlp",
        "--steps",
        "2000",
        "--set",
        "env.td=4",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let summary: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(summary["env_steps"], 2000);
    for f in [
        "config.json",
        "policy.json",
        "command.txt",
        "curves.csv",
        "model.bpk",
        "summary.json",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let csv = std::fs::read_to_string(dir.join("curves.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "header + one row per update");
    // A finished folder is not silently overwritten.
    let err = run_err(&[
        "train",
        "--model",
        "cnn-mlp",
        "--steps",
        "2000",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(err.contains("already holds a run"), "{err}");
}

#[test]
fn timing_models_train_and_record_from_the_cli() {
    let list = run_ok(&["zoo", "list"]);
    for m in [
        "ddm",
        "sbf",
        "timecells-csc",
        "timecells-ms",
        "timecells-laplace",
    ] {
        assert!(list.contains(m), "zoo list lacks {m}");
    }
    let dir = temp_dir("timing-cli");
    let run = dir.join("ddm");
    let out = run_ok(&[
        "train",
        "--model",
        "ddm",
        "--task",
        "Bisection-v0",
        "--set",
        "episodes=3000",
        "--quiet",
        "--out",
        run.to_str().unwrap(),
    ]);
    let summary: Value = serde_json::from_str(&out).unwrap();
    assert!(summary["eval_success"].as_f64().unwrap() >= 0.95, "{out}");
    for f in [
        "config.json",
        "command.txt",
        "curves.csv",
        "agent.json",
        "summary.json",
    ] {
        assert!(run.join(f).is_file(), "{f} missing");
    }
    // Same config and seed → identical trained agent.
    let again = dir.join("ddm-again");
    run_ok(&[
        "train",
        "--model",
        "ddm",
        "--task",
        "Bisection-v0",
        "--set",
        "episodes=3000",
        "--quiet",
        "--out",
        again.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read(run.join("agent.json")).unwrap(),
        std::fs::read(again.join("agent.json")).unwrap()
    );
    let act = dir.join("act.json");
    let msg = run_ok(&[
        "record",
        "--run",
        run.to_str().unwrap(),
        "--tds",
        "4,6,8,12",
        "--out",
        act.to_str().unwrap(),
    ]);
    assert!(msg.contains("32 trials"), "{msg}");
    let ds: Value = serde_json::from_str(&std::fs::read_to_string(&act).unwrap()).unwrap();
    assert_eq!(ds["meta"]["model"], "ddm");
    assert_eq!(ds["trials"].as_array().unwrap().len(), 32);
    for (args, needle) in [
        (
            vec!["train", "--model", "ddm", "--set", "episodes=0"],
            "episodes",
        ),
        (
            vec!["train", "--model", "ddm", "--set", "bogus=1"],
            "allowed",
        ),
        (
            vec!["train", "--model", "ddm", "--steps", "100"],
            "episodes",
        ),
        (
            vec!["record", "--run", "/nonexistent/run"],
            "not a run folder",
        ),
    ] {
        let err = run_err(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    let err = run_err(&["train", "--model", "ddm", "--out", run.to_str().unwrap()]);
    assert!(err.contains("already holds"), "{err}");
}

#[test]
fn eval_writes_records_and_metrics_that_recompute_identically() {
    let dir = temp_dir("eval-cli");
    let out = dir.join("oracle");
    let msg = run_ok(&[
        "eval",
        "--agent",
        "oracle",
        "--task",
        "FixedInterval-v0",
        "--env",
        "td=6",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(msg.contains("oracle"), "{msg}");
    let m: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("metrics.json")).unwrap()).unwrap();
    assert_eq!(m["fi"]["foc"][0]["mean"], 6.0);
    assert_eq!(m["fi"]["foc"][0]["td"], 6);
    let lines = std::fs::read_to_string(out.join("records.jsonl")).unwrap();
    assert_eq!(
        lines.lines().count(),
        36,
        "FI + PI 2x + PI 5x, 12 start cells each"
    );
    // Figures: FOC strip and PI curves, SVG and PNG, non-empty.
    for f in ["foc.svg", "foc.png", "pi.svg", "pi.png"] {
        let p = out.join("figures").join(f);
        let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        assert!(len > 2000, "{f}: {len} bytes");
    }
    let svg = std::fs::read_to_string(out.join("figures/foc.svg")).unwrap();
    assert!(
        svg.contains("<svg") && svg.contains("first oven check"),
        "title missing"
    );
    let re = dir.join("re");
    run_ok(&[
        "eval",
        "--from",
        out.to_str().unwrap(),
        "--out",
        re.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read(out.join("metrics.json")).unwrap(),
        std::fs::read(re.join("metrics.json")).unwrap()
    );
    // A random agent: metrics with failed fits, not a crash.
    let rnd = dir.join("random");
    run_ok(&[
        "eval",
        "--agent",
        "random",
        "--task",
        "Bisection-v0",
        "--stochastic",
        "3",
        "--out",
        rnd.to_str().unwrap(),
    ]);
    let m: Value =
        serde_json::from_str(&std::fs::read_to_string(rnd.join("metrics.json")).unwrap()).unwrap();
    assert!(
        m["bisection"]["fit"].is_null() && m["bisection"]["fit_error"].is_string(),
        "{m}"
    );
    assert!(rnd.join("figures/psychometric.png").is_file());
    for (args, needle) in [
        (vec!["eval", "--agent", "sage"], "unknown --agent"),
        (vec!["eval"], "say what to evaluate"),
        (
            vec!["eval", "--agent", "random", "--stochastic", "0"],
            "1..=10000",
        ),
        (vec!["eval", "--from", "/nonexistent"], "not an eval folder"),
    ] {
        let err = run_err(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // Export of the evaluation records: NPZ + metadata + CSV.
    let exp = dir.join("export");
    let listed = run_ok(&[
        "export",
        "--eval",
        out.to_str().unwrap(),
        "--out",
        exp.to_str().unwrap(),
    ]);
    assert!(listed.contains("episodes.npz"), "{listed}");
    let meta: Value =
        serde_json::from_str(&std::fs::read_to_string(exp.join("episodes.meta.json")).unwrap())
            .unwrap();
    assert!(meta["arrays"]["foc"]["shape"][0] == 36, "{meta}");
    assert_eq!(
        std::fs::read_to_string(exp.join("episodes.csv"))
            .unwrap()
            .lines()
            .count(),
        37
    );
    for (args, needle) in [
        (vec!["export"], "say what to export"),
        (
            vec!["export", "--eval", "/nonexistent"],
            "not an eval folder",
        ),
        (vec!["export", "--activity", "/nonexistent.json"], "reading"),
    ] {
        let err = run_err(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // A failed eval leaves no output folder behind (run in an empty working directory).
    let cwd = temp_dir("eval-cwd");
    let status = bin()
        .current_dir(&cwd)
        .args(["eval", "--agent", "sage"])
        .output()
        .unwrap()
        .status;
    assert!(!status.success());
    assert_eq!(
        std::fs::read_dir(&cwd).unwrap().count(),
        0,
        "output folder left behind"
    );
}

#[test]
fn report_is_self_contained_and_has_every_model() {
    let dir = temp_dir("report-cli");
    let mut evals = Vec::new();
    for agent in ["oracle", "random"] {
        for task in ["FixedInterval-v0", "Bisection-v0"] {
            let out = dir.join(format!("{agent}-{task}"));
            run_ok(&[
                "eval",
                "--agent",
                agent,
                "--task",
                task,
                "--out",
                out.to_str().unwrap(),
            ]);
            evals.push(out.to_str().unwrap().to_string());
        }
    }
    let rep = dir.join("report");
    let mut args = vec!["report", "--out", rep.to_str().unwrap(), "--eval"];
    args.extend(evals.iter().map(String::as_str));
    run_ok(&args);
    let html = std::fs::read_to_string(rep.join("report.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>") && html.trim_end().ends_with("</html>"));
    assert!(
        !html.contains("http") && !html.contains("href="),
        "external reference"
    );
    // Figures are inline SVG or, where smaller, inline PNG data (never a file or URL).
    assert_eq!(
        html.matches("src=").count(),
        html.matches("src=\"data:image/png;base64,").count()
    );
    for model in ["<td>oracle</td>", "<td>random</td>"] {
        assert!(html.contains(model), "{model} row missing");
    }
    assert!(html.matches("<svg").count() >= 6, "figures inline");
    for col in ["fi_success", "bisection_accuracy", "foc_over_td", "wf"] {
        assert!(html.contains(col), "{col} column missing");
    }
    // Readable headers with the description as a tooltip.
    assert!(html.contains(">first check / TD</th>") && html.contains("<th title=\""));
    // The per-TD fixed-interval table: the oracle checks exactly when the soup is ready.
    let per_td = &html[html.find("Fixed interval per TD").expect("per-TD table")..];
    let oracle = per_td
        .split("<tr>")
        .find_map(|r| {
            r.starts_with("<td>oracle</td>")
                .then(|| r.split("</tr>").next())
        })
        .flatten()
        .expect("oracle row");
    assert!(oracle.contains("<td>1.00</td>"), "{oracle}");
    // The paper's psychometric grid: one panel per model and anchor pair.
    let grid = std::fs::read_to_string(rep.join("psychometric_grid.svg")).unwrap();
    for title in ["oracle · 4–12", "random · 4–12"] {
        assert!(grid.contains(title), "{title} panel missing");
    }
    assert!(
        std::fs::metadata(rep.join("psychometric_grid.png"))
            .unwrap()
            .len()
            > 1000
    );
    assert!(html.contains("Psychometric curves"));
    let csv = std::fs::read_to_string(rep.join("report.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "header + 2 models");
    assert!(
        std::fs::read_to_string(rep.join("report.md"))
            .unwrap()
            .contains("| oracle | 2 |")
    );
    let err = run_err(&["report", "--eval", "/nonexistent"]);
    assert!(err.contains("not an `eval` output folder"), "{err}");
    let err = run_err(&["report"]);
    assert!(err.contains("--eval"), "{err}");
}

#[test]
fn a_folder_that_is_not_a_run_and_a_file_that_is_not_a_sweep_say_so() {
    let dir = temp_dir("not-a-run");
    std::fs::create_dir_all(&dir).unwrap();
    let folder = dir.to_str().unwrap();
    for args in [
        vec!["eval", "--run", folder],
        vec!["record", "--run", folder],
        vec!["train", "--resume", folder],
    ] {
        let err = run_err(&args);
        assert!(err.contains("is not a run folder"), "{args:?}: {err}");
        assert!(!err.contains("cannot resume"), "{args:?}: {err}");
    }
    let file = dir.join("sweep.toml");
    std::fs::write(&file, "name = \"x\"\nmodels = [ddm\n").unwrap();
    let err = run_err(&["sweep", file.to_str().unwrap(), "--dry-run"]);
    assert!(
        err.contains("sweep file")
            && err.contains(file.to_str().unwrap())
            && err.contains("line 2"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Rewrites `run/config.json` through `edit` (a hand edit of a run's settings) and
/// records the new content in the folder's `SHA256SUMS`, as a user who means the edit does
/// (`sha256sum`): the settings' own checks must still refuse a bad value. Without the new
/// record, the edit itself is refused.
fn edit_run_config(run: &std::path::Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let path = run.join("config.json");
    let mut cfg: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    edit(&mut cfg);
    let text = serde_json::to_string(&cfg).unwrap();
    std::fs::write(&path, &text).unwrap();
    let dir = run.display().to_string();
    let err = run_err(&[
        "eval",
        "--run",
        &dir,
        "--out",
        &format!("{dir}-unrecorded-eval"),
    ]);
    assert!(
        err.contains("config.json") && err.contains("does not match its SHA-256 record"),
        "an unrecorded edit was not refused: {err}"
    );
    chronocooked_env::integrity::write_recorded(&path, text.as_bytes()).unwrap();
}

/// The error of `eval --run RUN` (output into `dir/e`).
fn eval_err(run: &std::path::Path, dir: &std::path::Path) -> String {
    run_err(&[
        "eval",
        "--run",
        run.to_str().unwrap(),
        "--out",
        dir.join("e").to_str().unwrap(),
    ])
}

#[test]
fn a_hand_edited_run_config_is_checked_like_a_set_override() {
    let dir = temp_dir("edited-config");
    let run = dir.join("run");
    run_ok(&[
        "train",
        "--model",
        "cnn-mlp",
        "--preset",
        "fast",
        "--steps",
        "1000",
        "--quiet",
        "--out",
        run.to_str().unwrap(),
    ]);
    edit_run_config(&run, |cfg| cfg["ppo"]["n_epochs"] = serde_json::json!(0));
    let err = eval_err(&run, &dir);
    assert!(
        err.contains("config.json") && err.contains("n_epochs") && err.contains("1..=1000"),
        "{err}"
    );
    // A misspelt setting is an error naming the file and the field, not silently dropped.
    edit_run_config(&run, |cfg| {
        cfg["ppo"]["n_epochs"] = serde_json::json!(4);
        cfg["ppo"]["learning_rte"] = serde_json::json!(0.001);
    });
    let err = run_err(&["train", "--resume", run.to_str().unwrap(), "--quiet"]);
    assert!(
        err.contains("config.json") && err.contains("unknown field `learning_rte`"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_timing_run_config_with_an_unknown_field_names_it() {
    let dir = temp_dir("edited-timing-config");
    let run = dir.join("run");
    run_ok(&[
        "train",
        "--model",
        "ddm",
        "--set",
        "episodes=50",
        "--quiet",
        "--out",
        run.to_str().unwrap(),
    ]);
    edit_run_config(&run, |cfg| cfg["train"]["episdoes"] = serde_json::json!(10));
    let err = eval_err(&run, &dir);
    assert!(
        err.contains("config.json") && err.contains("unknown field `episdoes`"),
        "{err}"
    );
    // An agent override out of range is refused as `--set` refuses it.
    edit_run_config(&run, |cfg| {
        cfg["train"].as_object_mut().unwrap().remove("episdoes");
        cfg["agent"] = serde_json::json!(["overdue_factor=0.5"]);
    });
    let err = eval_err(&run, &dir);
    assert!(
        err.contains("config.json") && err.contains("overdue_factor") && err.contains(">= 1"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `record --figures` on a reproduction run draws each clock population's speed after Set
/// (KiNeT) with both known answers, and none for the learner's value signal: drift-diffusion
/// (whose accumulator times the production by speed).
#[test]
fn a_reproduction_recording_draws_the_speed_figure() {
    let dir = temp_dir("reproduction_speed_figure");
    let p = |s: &str| dir.join(s).to_string_lossy().to_string();
    run_ok(&[
        "train",
        "--task",
        "Reproduction-v0",
        "--model",
        "ddm",
        "--set",
        "episodes=300",
        "--quiet",
        "--out",
        &p("run"),
    ]);
    run_ok(&[
        "record",
        "--run",
        &p("run"),
        "--figures",
        &p("figures"),
        "--out",
        &p("activity.json"),
    ]);
    let svg = std::fs::read_to_string(dir.join("figures/accumulator/speed.svg"))
        .expect("the accumulator's speed figure");
    for needle in ["time-stretched", "fixed-speed clock", "scaling index"] {
        assert!(svg.contains(needle), "speed.svg lacks {needle}");
    }
    assert!(!dir.join("figures/value/speed.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A finished timing run resumed from another working directory than the one it was made
/// in (its summary names the folder relatively) draws its learning-curve figure in the
/// folder given now.
#[test]
fn a_finished_timing_run_redraws_its_figure_from_any_working_directory() {
    let dir = temp_dir("resume-cwd");
    let made_in = dir.join("a");
    let other = dir.join("b");
    std::fs::create_dir_all(&made_in).unwrap();
    std::fs::create_dir_all(&other).unwrap();
    let o = bin()
        .current_dir(&made_in)
        .args(["train", "--model", "ddm", "--set", "episodes=30", "--quiet"])
        .args(["--out", "run"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let run = made_in.join("run");
    let figures = run.join("figures");
    std::fs::remove_dir_all(&figures).unwrap();
    let o = bin()
        .current_dir(&other)
        .args(["train", "--resume", run.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        std::fs::read_dir(&figures).is_ok_and(|mut d| d.next().is_some()),
        "the figure is drawn again in {}",
        figures.display()
    );
}
