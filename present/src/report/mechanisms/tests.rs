//! Known-answer tests of the "Mechanisms" section.

use super::card::card_and_scaling;
use super::*;
use chronocooked_analysis::neural::categories::Category;
use chronocooked_models::ActivityDataset;
use chronocooked_models::Marker;
use chronocooked_models::activity::{ActivityMeta, Event, Population, Trial};
use rand::{Rng, SeedableRng};
use std::collections::BTreeMap;

/// A recording at `td` of a population `cells` (unit activity `f(unit, τ, td)`, τ =
/// steps since oven-on) plus a `value` read-out, 16 noisy trials, oven-on at step 2.
fn dataset(
    model: &str,
    td: u32,
    units: usize,
    f: &dyn Fn(usize, f64, f64) -> f64,
) -> ActivityDataset {
    let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(u64::from(td));
    let steps = 2 + 2 * td as usize + 4;
    let trials = (0..16)
        .map(|_| {
            let mut activity = Vec::with_capacity(steps * (units + 1));
            for s in 0..steps {
                let tau = s as f64 - 2.0;
                for u in 0..units {
                    let v = if tau >= 0.0 {
                        f(u, tau, f64::from(td))
                    } else {
                        0.0
                    };
                    activity.push((v + 0.03 * (rng.random::<f64>() - 0.5)) as f32);
                }
                activity.push((tau / f64::from(td)) as f32);
            }
            Trial {
                td,
                start: (1, 1),
                steps,
                activity,
                events: vec![Event {
                    step: 2,
                    marker: Marker::OvenOn,
                }],
                reward: 0.0,
                success: false,
                oven_tds: Vec::new(),
                reproduction: None,
            }
        })
        .collect();
    let mut meta = ActivityMeta::new(
        model,
        &chronocooked_env::Task::new("PeakInterval-v0").unwrap(),
        0,
    );
    meta.populations = vec![
        Population {
            name: "cells".into(),
            size: units,
        },
        Population {
            name: "value".into(),
            size: 1,
        },
    ];
    ActivityDataset { meta, trials }
}

/// Evaluation folders (eval.json only: the card needs task and seed) with the dataset
/// beside each, as a sweep lays them out.
fn row(root: &Path, model: &str, sets: Vec<ActivityDataset>) -> Row {
    let mut runs = Vec::new();
    for ds in sets {
        let job = root.join(format!("{model}-{}", ds.trials[0].td));
        std::fs::create_dir_all(job.join("eval")).unwrap();
        let info = chronocooked_analysis::records::EvalInfo {
            model: model.into(),
            task: chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
            mode: chronocooked_analysis::records::Mode::Reference,
            seed: 0,
            unfinished_at_step: None,
            episodes: None,
        };
        chronocooked_env::integrity::write_recorded(
            &job.join("eval/eval.json"),
            &serde_json::to_vec(&info).unwrap(),
        )
        .unwrap();
        std::fs::write(job.join("eval/metrics.json"), "{}").unwrap();
        std::fs::write(job.join("activity.json"), serde_json::to_vec(&ds).unwrap()).unwrap();
        runs.push(job.join("eval"));
    }
    Row {
        model: model.into(),
        runs,
        values: BTreeMap::new(),
        bisection: Vec::new(),
        reproduction: Vec::new(),
        speed: Vec::new(),
        foc: Vec::new(),
        robust: Default::default(),
        baseline: None,
    }
}

fn stretched(u: usize, tau: f64, td: f64) -> f64 {
    let peak = td * (0.25 + 0.25 * u as f64);
    (-(tau - peak).powi(2) / (2.0 * (0.2 * peak).powi(2))).exp()
}

fn oscillator(u: usize, tau: f64, _td: f64) -> f64 {
    (2.0 * std::f64::consts::PI * (0.12 + 0.05 * u as f64) * tau).sin()
}

#[test]
fn cards_show_the_stretching_sequence_and_the_fixed_clock_for_what_they_are() {
    let guard = tempfile::tempdir().unwrap();
    let root = guard.path().to_path_buf();
    let seq = row(
        &root,
        "seq",
        vec![
            dataset("seq", 6, 6, &stretched),
            dataset("seq", 12, 6, &stretched),
        ],
    );
    let osc = row(
        &root,
        "osc",
        vec![
            dataset("osc", 6, 5, &oscillator),
            dataset("osc", 12, 5, &oscillator),
        ],
    );
    let infos = |r: &Row| r.runs.iter().map(|e| run_info(e)).collect::<Vec<_>>();
    let (card, scaling) = card_and_scaling(&seq, &infos(&seq)).unwrap();
    let card = card.unwrap();
    // The read-out is not the timing population; both TDs are on the card.
    assert_eq!(card.population, "cells");
    assert_eq!(card.by_td.iter().map(|c| c.td).collect::<Vec<_>>(), [6, 12]);
    let tests = card.by_td[1].tests.as_ref().unwrap();
    let fields = tests
        .iter()
        .filter(|u| u.category == Category::TimeField)
        .count();
    assert!(fields >= 4, "{tests:?}");
    // Fields at fixed fractions of TD: the geometry stretches by the TD ratio.
    assert_eq!(scaling[0].2, "scaling_index");
    let s = scaling[0].3;
    assert!((s - 1.0).abs() < 0.15, "sequence scaling index {s}");
    let (card, scaling) = card_and_scaling(&osc, &infos(&osc)).unwrap();
    let tests = card.unwrap().by_td[1].tests.clone().unwrap();
    assert!(
        tests
            .iter()
            .filter(|u| u.category == Category::Oscillating)
            .count()
            >= 3
    );
    assert!(
        scaling[0].3.abs() < 0.15,
        "oscillator scaling index {}",
        scaling[0].3
    );
    // The section: a card per model with its four panels and the category bar.
    let out = root.join("report");
    let (html, md) = mechanisms_section(&[seq, osc], &out).unwrap();
    let html = html.into_string();
    assert!(html.starts_with("<h2>Mechanisms</h2>"));
    assert_eq!(html.matches("<div class=\"card\">").count(), 2);
    assert_eq!(html.matches("<figure class=\"panel\">").count(), 8);
    assert!(html.contains("title=\"time_field ") && html.contains("title=\"oscillating "));
    for name in [
        "seq-heatmap",
        "seq-units",
        "seq-spectrum",
        "seq-scaling",
        "fingerprints",
    ] {
        assert!(
            out.join("mechanisms").join(format!("{name}.svg")).is_file(),
            "{name}"
        );
    }
    assert!(
        md.contains("| seq | cells |") && md.contains("| osc | cells |"),
        "{md}"
    );
}

#[test]
fn a_report_without_recordings_has_no_section() {
    let guard = tempfile::tempdir().unwrap();
    let root = guard.path().join("report");
    let r = row(&root, "none", Vec::new());
    let (html, md) = mechanisms_section(&[r], &root).unwrap();
    assert_eq!((html.into_string(), md), (String::new(), String::new()));
    assert!(!root.join("mechanisms").exists());
}
