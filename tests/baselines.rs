//! The committed baselines on the leaderboard: `report --eval NEW --baselines` writes the
//! committed paper-core results as marked rows whose numbers equal those computed here,
//! independently, from the job files (`episodes.csv`, one line per evaluation episode) —
//! and equal the table of results/baselines/README.md ("Committed baselines on the leaderboard").

use crate::common;

use common::{run_ok, temp_dir};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Mean and sample SD (NaN below two values).
fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let sd = if v.len() > 1 {
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        f64::NAN
    };
    (m, sd)
}

/// One compact job: its row label, task, settings and episode lines (header → value).
struct Job {
    row: String,
    task: chronocooked_env::Task,
    episodes: Vec<BTreeMap<String, String>>,
}

fn jobs(root: &Path) -> Vec<Job> {
    fn walk(d: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            if p.join("job.json").is_file() {
                out.push(p);
            } else if p.is_dir() {
                walk(&p, out);
            }
        }
    }
    let mut dirs = Vec::new();
    walk(&root.join("jobs"), &mut dirs);
    dirs.iter()
        .map(|d| {
            let j: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(d.join("job.json")).unwrap())
                    .unwrap();
            let text = std::fs::read_to_string(d.join("episodes.csv")).unwrap();
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let episodes = lines
                .map(|l| {
                    header
                        .iter()
                        .zip(l.split(','))
                        .map(|(h, v)| (h.to_string(), v.to_string()))
                        .collect()
                })
                .collect();
            Job {
                // Jobs collected before sweep rows existed have none: the model is the row.
                row: j["row"]
                    .as_str()
                    .or(j["model"].as_str())
                    .unwrap()
                    .to_string(),
                task: serde::Deserialize::deserialize(&j).unwrap(),
                episodes,
            }
        })
        .collect()
}

fn setting(job: &Job, key: &str) -> f64 {
    job.task.value_set(key).unwrap().as_f64().unwrap()
}

/// The three headline numbers (mean, SD over jobs) of one row, from the episode lines:
/// FI success at the trained TD, bisection anchor accuracy among deliveries, and mean
/// first oven check / TD.
fn independent(all: &[Job], row: &str) -> BTreeMap<&'static str, (f64, f64)> {
    let mine: Vec<&Job> = all.iter().filter(|j| j.row == row).collect();
    let (mut success, mut accuracy, mut foc) = (vec![], vec![], vec![]);
    for j in &mine {
        if j.task.id() == "FixedInterval-v0" {
            let fi: Vec<_> = j.episodes.iter().filter(|e| e["kind"] == "fi").collect();
            let ok = fi.iter().filter(|e| e["success"] == "true").count();
            success.push(ok as f64 / fi.len() as f64);
            let checks: Vec<f64> = fi.iter().filter_map(|e| e["foc"].parse().ok()).collect();
            if !checks.is_empty() {
                foc.push(checks.iter().sum::<f64>() / checks.len() as f64 / setting(j, "td"));
            }
        }
        if j.task.id() == "Bisection-v0" {
            let (s, l) = (setting(j, "short"), setting(j, "long"));
            let (mut right, mut total) = (0, 0);
            for e in j.episodes.iter().filter(|e| e["kind"] == "bisection") {
                let td: f64 = e["td"].parse().unwrap();
                let counter: i32 = e["counter"].parse().unwrap();
                if (td == s || td == l) && (counter == 1 || counter == 2) {
                    total += 1;
                    right += usize::from((td == s && counter == 1) || (td == l && counter == 2));
                }
            }
            if total > 0 {
                accuracy.push(right as f64 / total as f64);
            }
        }
    }
    BTreeMap::from([
        ("fi_success", mean_sd(&success)),
        ("bisection_accuracy", mean_sd(&accuracy)),
        ("foc_over_td", mean_sd(&foc)),
        ("runs", (mine.len() as f64, f64::NAN)),
    ])
}

/// report.csv as rows of header → cell.
fn read_csv(path: &Path) -> Vec<BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(str::to_string))
                .collect()
        })
        .collect()
}

const MODELS: [&str; 4] = ["cnn-mlp", "lstm125", "ctrnn125", "ctrnn-reservoir125"];

#[test]
fn committed_baseline_rows_equal_numbers_computed_from_the_job_files_and_results_md() {
    let dir = temp_dir("baselines");
    let mine = dir.join("mine");
    run_ok(&[
        "eval",
        "--agent",
        "oracle",
        "--env",
        "td=12",
        "--out",
        mine.to_str().unwrap(),
    ]);
    let out = dir.join("report");
    // Default baselines: found from the test's folder (the repository root).
    run_ok(&[
        "report",
        "--eval",
        mine.to_str().unwrap(),
        "--baselines",
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = read_csv(&out.join("report.csv"));
    let all = jobs(&Path::new(ROOT).join("results/paper-core"));
    // paper-core's own four models: 224 jobs (the folder also holds the rest of the paper's
    // grid as it runs: sizes 8 and 256, more repeats).
    let core = all
        .iter()
        .filter(|j| MODELS.contains(&j.row.as_str()))
        .count();
    assert!(
        core >= 224,
        "paper-core's models have {core} jobs, fewer than its 224"
    );
    let oracle = rows
        .iter()
        .find(|r| r["model"] == "oracle")
        .expect("the new row");
    assert_eq!(
        (oracle["baseline"].as_str(), oracle["runs"].as_str()),
        ("", "1")
    );
    let results_md =
        std::fs::read_to_string(Path::new(ROOT).join("results/baselines/README.md")).unwrap();
    let section = results_md
        .split("## Committed baselines on the leaderboard")
        .nth(1)
        .expect("results/baselines/README.md has the baseline section");
    for model in MODELS {
        let label = format!("{model} (paper-core)");
        let row = rows
            .iter()
            .find(|r| r["model"] == label)
            .unwrap_or_else(|| panic!("{label} missing"));
        assert_eq!(row["baseline"], "paper-core");
        let want = independent(&all, model);
        assert_eq!(row["runs"], format!("{}", want["runs"].0), "{label} runs");
        for key in ["fi_success", "bisection_accuracy", "foc_over_td"] {
            let (m, sd) = want[key];
            let got: f64 = row[key].parse().unwrap();
            let got_sd: f64 = row[&format!("{key}_sd")].parse().unwrap();
            assert!(
                (got - m).abs() < 1e-9,
                "{label} {key}: report {got}, job files {m}"
            );
            assert!(
                (got_sd - sd).abs() < 1e-9,
                "{label} {key} SD: report {got_sd}, job files {sd}"
            );
        }
        // results/baselines/README.md's table row: `| model | runs | FI success | anchor accuracy | FOC / TD |`
        // with mean ± SD to 3 decimals.
        let line = section
            .lines()
            .find(|l| l.starts_with(&format!("| {model} |")))
            .unwrap_or_else(|| panic!("results/baselines/README.md: no row for {model}"));
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        assert_eq!(
            cells[2],
            format!("{}", want["runs"].0),
            "results/baselines/README.md runs of {model}"
        );
        for (i, key) in [
            (3, "fi_success"),
            (4, "bisection_accuracy"),
            (5, "foc_over_td"),
        ] {
            let (m, sd) = want[key];
            assert_eq!(
                cells[i],
                format!("{m:.3} ± {sd:.3}"),
                "results/baselines/README.md {model} {key}"
            );
        }
    }
    // The markdown and HTML name the baselines as such.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let lstm_runs = independent(&all, "lstm125")["runs"].0;
    assert!(
        md.contains(&format!("| lstm125 (paper-core) | {lstm_runs} |"))
            && md.contains("committed baselines")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn baselines_are_read_from_a_named_folder_and_bad_folders_are_named() {
    let dir = temp_dir("baselines-named");
    // A study of two jobs copied out of paper-core: its own name labels the rows.
    let study = dir.join("my-study");
    for id in [
        "FixedInterval-v0/lstm125~env.td-12/seed1",
        "FixedInterval-v0/lstm125~env.td-12/seed2",
    ] {
        let from = Path::new(ROOT).join("results/paper-core/jobs").join(id);
        let to = study.join("jobs").join(id);
        std::fs::create_dir_all(&to).unwrap();
        for f in ["job.json", "metrics.json", "episodes.csv", "curve.csv"] {
            std::fs::copy(from.join(f), to.join(f)).unwrap();
        }
    }
    let out = dir.join("r");
    run_ok(&[
        "report",
        "--baselines",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = read_csv(&out.join("report.csv"));
    assert_eq!(rows.len(), 1);
    assert_eq!(
        (
            rows[0]["model"].as_str(),
            rows[0]["baseline"].as_str(),
            rows[0]["runs"].as_str()
        ),
        ("lstm125 (my-study)", "my-study", "2")
    );
    // A corrupt metrics file is an error naming it.
    let bad = study.join("jobs/FixedInterval-v0/lstm125~env.td-12/seed2/metrics.json");
    std::fs::write(&bad, "{\"model\": 1}").unwrap();
    let err = common::run_err(&[
        "report",
        "--baselines",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        err.contains("seed2/metrics.json") && err.contains("not a metrics file"),
        "{err}"
    );
    // A folder without jobs.
    let err = common::run_err(&[
        "report",
        "--baselines",
        dir.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(err.contains("no `jobs/` folder"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A study with jobs that did not train with PPO (timing models: `wall_s` and the final
/// episode statistics are `null` in their `job.json`) is a baseline like any other: the
/// committed mechanisms reference study gives one row per mechanism with its 24 runs.
#[test]
fn a_study_of_timing_models_is_a_baseline() {
    let dir = temp_dir("baselines-timing");
    let out = dir.join("r");
    let study = Path::new(ROOT).join("results/mechanisms-reference");
    run_ok(&[
        "report",
        "--baselines",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let rows = read_csv(&out.join("report.csv"));
    let ddm = rows
        .iter()
        .find(|r| r["model"] == "ddm (mechanisms-reference)")
        .expect("a drift-diffusion row");
    // 8 seeds × (FI TD 6, FI TD 12, bisection 4-12).
    assert_eq!(ddm["runs"], "24");
    std::fs::remove_dir_all(&dir).unwrap();
}
