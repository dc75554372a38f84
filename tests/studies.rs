//! The committed studies are their sweep files' outputs: jobs rerun with `sweep-job` (what a
//! local worker and a Slurm array task run) give the committed numbers.

use crate::common::{run_ok, temp_dir};
use serde_json::Value;
use std::path::Path;

/// The numbers a multi-anchor study line prints to two decimals or more: the anchor accuracy
/// (`acc 0.967`) and each boundary's fitted BP (the number before its `[`).
fn printed_numbers(line: &str) -> Vec<String> {
    let mut out = vec![
        line.split("acc ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .to_string(),
    ];
    for boundary in line.split(" | ") {
        let before_ci = boundary.split('[').next().unwrap();
        out.push(before_ci.rsplit(' ').next().unwrap().to_string());
    }
    out
}

/// The committed multi-anchor timing study (results/extensions/timing-multi-anchor/lines.txt)
/// is its sweep file's output: one job of each model on the first anchor set, rerun here,
/// gives the committed line's anchor accuracy and every boundary's fitted BP to the printed
/// digits.
#[test]
fn the_multi_anchor_timing_study_is_reproduced_by_its_sweep_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let sweep = root.join("sweeps/timing-multi-anchor.toml");
    let lines =
        std::fs::read_to_string(root.join("results/extensions/timing-multi-anchor/lines.txt"))
            .unwrap();
    assert_eq!(
        printed_numbers(
            "4,8,16 ddm 1 acc 0.967 5.85[5.69,5.98]gm5.66 am6.0 wf0.11 | 11.47[11.26,11.65]gm11.31*am12.0 wf0.11"
        ),
        ["0.967", "5.85", "11.47"]
    );
    let dir = temp_dir("timing-multi-anchor");
    for model in [
        "ddm",
        "sbf",
        "timecells-csc",
        "timecells-ms",
        "timecells-laplace",
    ] {
        let id = format!("MultiAnchor-v0/{model}~env.anchors-4_8_16/seed1");
        run_ok(&[
            "sweep-job",
            sweep.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--id",
            &id,
        ]);
        let metrics: Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(&id).join("eval/metrics.json")).unwrap(),
        )
        .unwrap();
        let ma = &metrics["multi_anchor"];
        let mut got = vec![format!("{:.3}", ma["anchor_accuracy"].as_f64().unwrap())];
        for b in ma["boundaries"].as_array().unwrap() {
            got.push(format!("{:.2}", b["fit"]["bp"].as_f64().unwrap()));
        }
        let line = lines
            .lines()
            .find(|l| l.starts_with(&format!("4,8,16 {model} 1 ")))
            .unwrap_or_else(|| panic!("no committed line for {model}"));
        assert_eq!(
            got,
            printed_numbers(line),
            "{model}: sweep job against the committed line {line}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
