//! `chronocooked verify` (issue #65): what a folder claims, re-derived from what determines
//! it. Forgeries that recompute their SHA-256 records (a changed seed, edited metrics, a
//! deleted episode, an evaluation of another agent) are caught and named; untouched runs,
//! evaluations, committed baselines and zoo agents verify.

use crate::common::{bin, run_ok, temp_dir};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `verify` with `args`: (success, stdout + stderr).
fn verify(args: &[&str]) -> (bool, String) {
    let o = bin().arg("verify").args(args).output().unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    (o.status.success(), text)
}

/// Rewrites the JSON file `path` with `edit` and records its new SHA-256, as a forger who
/// knows the format would.
fn forge(path: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    edit(&mut v);
    let bytes = serde_json::to_vec_pretty(&v).unwrap();
    chronocooked_env::integrity::write_recorded(path, &bytes).unwrap();
}

fn train_ddm(dir: &Path, seed: &str) {
    run_ok(&[
        "train",
        "--model",
        "ddm",
        "--set",
        "episodes=150",
        "--set",
        "env.td=6",
        "--seed",
        seed,
        "--quiet",
        "--out",
        s(dir),
    ]);
}

#[test]
fn verify_passes_honest_folders_and_names_every_forgery() {
    let dir = temp_dir("verify");
    let (run, other) = (dir.join("run"), dir.join("other"));
    train_ddm(&run, "3");
    train_ddm(&other, "4");
    let eval = dir.join("eval");
    run_ok(&["eval", "--run", s(&run), "--out", s(&eval)]);
    let (ok, said) = verify(&[s(&run)]);
    assert!(ok && said.contains("trained again"), "{said}");
    let (ok, said) = verify(&[s(&eval), "--run", s(&run)]);
    assert!(ok && said.contains("played again"), "{said}");

    // A changed seed in the run's config: its learned state is not what that seed gives.
    let forged = dir.join("forged-seed");
    std::fs::create_dir_all(&forged).unwrap();
    for f in [
        "config.json",
        "agent.json",
        "summary.json",
        "curves.csv",
        "SHA256SUMS",
    ] {
        std::fs::copy(run.join(f), forged.join(f)).unwrap();
    }
    forge(&forged.join("config.json"), |v| v["seed"] = 9.into());
    let (ok, said) = verify(&[s(&forged)]);
    assert!(
        !ok && said.contains("agent.json") && said.contains("DIFFERS"),
        "{said}"
    );

    // Edited metrics: the records say otherwise.
    let edited = dir.join("edited");
    run_ok(&["eval", "--run", s(&run), "--out", s(&edited)]);
    forge(&edited.join("metrics.json"), |v| {
        v["success_rate"] = serde_json::json!(0.999)
    });
    let (ok, said) = verify(&[s(&edited)]);
    assert!(
        !ok && said.contains("metrics.json field `success_rate`"),
        "{said}"
    );

    // A deleted episode, with eval.json's count and both records forged to match.
    let cut = dir.join("cut");
    run_ok(&["eval", "--run", s(&run), "--out", s(&cut)]);
    let text = std::fs::read_to_string(cut.join("records.jsonl")).unwrap();
    let kept: Vec<&str> = text.lines().skip(1).collect();
    chronocooked_env::integrity::write_recorded(
        &cut.join("records.jsonl"),
        (kept.join("\n") + "\n").as_bytes(),
    )
    .unwrap();
    forge(&cut.join("eval.json"), |v| {
        v["episodes"] = kept.len().into()
    });
    let (ok, said) = verify(&[s(&cut), "--run", s(&run)]);
    assert!(!ok && said.contains("episodes"), "{said}");

    // The evaluation of another agent presented as this run's.
    let (ok, said) = verify(&[s(&eval), "--run", s(&other)]);
    assert!(!ok && said.contains("records.jsonl"), "{said}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn committed_baselines_and_zoo_agents_verify_and_an_edited_baseline_does_not() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let baseline = root.join("results/paper-core-lab-init");
    let (ok, said) = verify(&[s(&baseline)]);
    assert!(ok && said.contains("no difference"), "{said}");
    for agent in ["zoo:lstm125/FixedInterval-v0", "zoo:ctrnn125/Bisection-v0"] {
        let (ok, said) = verify(&[agent]);
        assert!(ok, "{agent}: {said}");
    }
    // A copy of the baseline with one job's success rate edited.
    let dir = temp_dir("verify-baseline");
    let copy = dir.join("b");
    let st = std::process::Command::new("cp")
        .args(["-r", s(&baseline), s(&copy)])
        .status()
        .unwrap();
    assert!(st.success());
    let job = chronocooked_analysis::collect::job_folders(&copy.join("jobs"))
        .into_iter()
        .next()
        .unwrap();
    forge(&job.join("metrics.json"), |v| {
        v["conditions"][0]["success_rate"] = serde_json::json!(0.123)
    });
    let (ok, said) = verify(&[s(&copy)]);
    assert!(
        !ok && said.contains("conditions[0].success_rate") && said.contains("0.123"),
        "{said}"
    );
    let o = bin()
        .args(["report", "--baselines", s(&copy), "--verified", "--out"])
        .arg(dir.join("r"))
        .output()
        .unwrap();
    assert!(
        !o.status.success() && String::from_utf8_lossy(&o.stderr).contains("does not verify"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
