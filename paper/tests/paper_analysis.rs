//! The paper's analyses on constructed data with known answers: the least-squares
//! psychometric fit, the notebook's FI pooling rule, the run exclusion and per-run
//! fits of bisection, the WF regression and the agreement rules of the comparison.

use crate::common;

use chronocooked_analysis::collect::{CompactJob, EpisodeRow, JobSummary};
use chronocooked_paper::bisection::{analyse_bisection, pearson};
use chronocooked_paper::compare::{agree_mean, agree_sd};
use chronocooked_paper::fi::analyse_fi;
use chronocooked_paper::lsq::{LsqHow, fit_paper};
use common::{curve_at, ep, job, lstm_fi_job, mt_ep};

fn logistic(d: f64, x0: f64, k: f64) -> f64 {
    1.0 / (1.0 + (-(d - x0) / k).exp())
}

#[test]
fn least_squares_fit_recovers_a_known_curve() {
    let probes: Vec<f64> = (1..=16).map(f64::from).collect();
    for (x0, k) in [(7.3, 1.2), (5.0, 0.6), (9.5, 2.5)] {
        let p: Vec<f64> = probes.iter().map(|&d| logistic(d, x0, k)).collect();
        let fit = fit_paper(&probes, &p, 4.0, 12.0).expect("fits");
        assert_eq!(fit.how, LsqHow::Fit);
        assert!((fit.bp - x0).abs() < 1e-4, "{x0}: {}", fit.bp);
        assert!((fit.k - k).abs() < 1e-4, "{k}: {}", fit.k);
        assert!((fit.dl - k * 3f64.ln()).abs() < 1e-4);
        assert!((fit.wf - fit.dl / fit.bp).abs() < 1e-12);
    }
    // NaN proportions (fewer than half valid) are left out of the fit.
    let mut p: Vec<f64> = probes.iter().map(|&d| logistic(d, 8.0, 1.0)).collect();
    p[0] = f64::NAN;
    p[15] = f64::NAN;
    let fit = fit_paper(&probes, &p, 4.0, 12.0).unwrap();
    assert!((fit.bp - 8.0).abs() < 1e-4);
    // A flat curve has its BP outside the probes: "failed", as in the notebook.
    assert!(fit_paper(&probes, &[0.0; 16], 4.0, 12.0).is_none());
}

#[test]
fn a_perfect_step_gives_a_tiny_weber_fraction() {
    let probes: Vec<f64> = (1..=16).map(f64::from).collect();
    let p: Vec<f64> = probes
        .iter()
        .map(|&d| if d <= 7.0 { 0.0 } else { 1.0 })
        .collect();
    let fit = fit_paper(&probes, &p, 4.0, 12.0).expect("step fits or falls back");
    assert!(fit.wf.abs() < 0.01, "WF {}", fit.wf);
    match fit.how {
        // BP between the last short and the first long probe.
        LsqHow::Fit => assert!(fit.bp > 7.0 && fit.bp < 8.0, "BP {}", fit.bp),
        // The notebook's 0-based positions: one step below the probe durations.
        LsqHow::StepFallback => assert!((fit.bp - 6.5).abs() < 1e-12),
    }
}

#[test]
fn fi_pooling_follows_the_notebook_rule() {
    // Run 1: FOCs 4, 6 then an episode without a check (cell (1,1)), then 10 (skipped by
    // the notebook). Run 2: 5, 5, 5.
    let r1 = CompactJob {
        job: job("FixedInterval-v0", "m", 1, &["td=6"], 20.0),
        episodes: vec![
            ep("fi", 6, (1, 2), Some(10), 0),
            ep("fi", 6, (0, 0), Some(4), 0),
            ep("fi", 6, (1, 0), Some(6), 0),
            ep("fi", 6, (1, 1), None, 0),
            ep("pi", 6, (0, 0), Some(1), 0),
        ],
        curve: vec![],
        levels: vec![],
    };
    let r2 = CompactJob {
        job: job("FixedInterval-v0", "m", 2, &["td=6"], 20.0),
        episodes: (0..3).map(|c| ep("fi", 6, (c, 0), Some(5), 0)).collect(),
        curve: vec![],
        levels: vec![],
    };
    let fi = analyse_fi(&[r1, r2]);
    let c = &fi[0].cells[0];
    assert_eq!(c.td, 6);
    // Notebook: 4, 6 (run 1, stops at (1,1)) + 5, 5, 5.
    assert_eq!(c.pooled.n, 5);
    assert!((c.pooled.mean - 5.0).abs() < 1e-12);
    let sd = ((1.0 + 1.0) / 4.0f64).sqrt();
    assert!((c.pooled.sd - sd).abs() < 1e-12);
    assert!((c.pooled.cv - sd / 5.0).abs() < 1e-12);
    // Without the rule, the 10 counts.
    assert_eq!(c.pooled_all.n, 6);
    // Per run: means 20/3 and 5.
    assert!((c.run_mean.mean - (20.0 / 3.0 + 5.0) / 2.0).abs() < 1e-12);
    assert_eq!(c.pooled_checks.as_ref().unwrap().mean, c.pooled.mean);
    // An agent interacting from the onion put: FOC 0 by the paper's convention, 1 by the
    // lab's (counted checks).
    let spam = CompactJob {
        job: job("FixedInterval-v0", "m", 3, &["td=6"], 20.0),
        episodes: (0..4)
            .map(|c| EpisodeRow {
                foc_checks: Some(1),
                ..ep("fi", 6, (c, 0), Some(0), 0)
            })
            .collect(),
        curve: vec![],
        levels: vec![],
    };
    let fi = analyse_fi(&[spam]);
    let c = &fi[0].cells[0];
    assert_eq!((c.pooled.mean, c.pooled.n), (0.0, 4));
    assert_eq!(c.pooled_checks.as_ref().unwrap().mean, 1.0);
}

fn bisection_job(seed: u64, ep_len: f64, bp: u32) -> CompactJob {
    // 8 start cells per probe 1..=16; long for probes above `bp`; probe 2 has 5 failures.
    let mut eps = Vec::new();
    for d in 1..=16u32 {
        for c in 0..8usize {
            let counter = if d == 2 && c < 5 {
                -1
            } else if d > bp {
                2
            } else {
                1
            };
            eps.push(ep("bisection", d, (c, 0), None, counter));
        }
    }
    CompactJob {
        job: job("Bisection-v0", "m", seed, &["short=4", "long=12"], ep_len),
        episodes: eps,
        curve: vec![],
        levels: vec![],
    }
}

#[test]
fn bisection_excludes_long_runs_and_marks_invalid_probes() {
    let jobs = vec![
        bisection_job(1, 30.0, 7),
        bisection_job(2, 40.0, 8),
        bisection_job(3, 150.0, 2), // excluded: its training episodes were long
    ];
    let b = analyse_bisection(&jobs);
    let cell = &b[0].cells[0];
    assert_eq!((cell.short, cell.long), (4, 12));
    assert_eq!(cell.runs.iter().filter(|r| r.excluded).count(), 1);
    // Probe 2: 3 of 8 valid (< 50%) → NaN.
    assert!(cell.runs[0].p_long[1].is_nan());
    // Averaged curve over the two kept runs: probe 8 is long in run 1 only.
    assert!((cell.curve[7] - 0.5).abs() < 1e-12);
    assert!((cell.anchor_accuracy.mean - 1.0).abs() < 1e-12);
    assert_eq!(cell.wf.n, 2);
    assert!(cell.fit.is_some());
    let mle = cell.mle.as_ref().unwrap();
    assert!(mle.bp > 7.0 && mle.bp < 9.0, "MLE BP {}", mle.bp);
}

#[test]
fn a_faithfulness_switch_is_analysed_as_its_own_group() {
    // Two runs of the reference model and one with a switch (its sweep row): three runs of
    // one model, two groups; a summary collected before rows existed falls back to the model.
    let mut switched = bisection_job(3, 30.0, 9);
    switched.job.row = Some("m~recurrent_batches-chunks".into());
    let mut reference = bisection_job(2, 30.0, 8);
    reference.job.row = Some("m".into());
    let jobs = vec![bisection_job(1, 30.0, 7), reference, switched];
    let b = analyse_bisection(&jobs);
    let groups: Vec<(&str, usize)> = b
        .iter()
        .map(|m| (m.model.as_str(), m.cells[0].runs.len()))
        .collect();
    assert_eq!(groups, vec![("m", 2), ("m~recurrent_batches-chunks", 1)]);
    // Old compact summaries (no `row` field) still load.
    let old = r#"{"id":"a/m/seed1","task":"Bisection-v0","model":"m","seed":1,"env":[],
        "preset":"reference","total_steps":1,"steps_done":1,"wall_s":1.0,
        "final_ep_len_mean":1.0,"final_ep_return_mean":1.0,"level_steps":[0],"ppo":null}"#;
    let job: JobSummary = serde_json::from_str(old).unwrap();
    assert_eq!(job.label(), "m");
}

#[test]
fn pearson_and_agreement_rules_have_known_answers() {
    let x = [1.0, 2.0, 3.0, 4.0];
    let w = pearson(&x, &[2.0, 4.0, 6.0, 8.0]).unwrap();
    assert!((w.r - 1.0).abs() < 1e-12 && w.p == 0.0 && (w.slope - 2.0).abs() < 1e-12);
    // r = 0.5 with n = 6: t = 0.5·√4/√0.75 = 1.1547, two-sided p = 0.3125 (t table).
    let y = [1.0, 3.0, 2.0, 5.0, 3.0, 4.0];
    let x6 = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    let w = pearson(&x6, &y).unwrap();
    let r = w.r;
    let t = r * (4.0 / (1.0 - r * r)).sqrt();
    assert!(t > 0.0 && w.p > 0.0 && w.p < 1.0);
    // Exact: p(r = 0.5, n = 6) = I_0.75(2, 1/2) = (5/12) / (4/3) = 0.3125.
    let p = chronocooked_analysis::neural::correlation_p(0.5, 6);
    assert!((p - 0.3125).abs() < 1e-12, "{p}");
    assert!(pearson(&x[..2], &[1.0, 2.0]).is_none());
    // Mean rule: t(0.975, 3) = 3.182; half-width = 3.182 · 1 · √(1/4 + 1/4) = 2.25.
    assert_eq!(agree_mean(2.2, 0.0, 1.0, 4), "yes");
    assert_eq!(agree_mean(2.3, 0.0, 1.0, 4), "no");
    assert_eq!(agree_mean(f64::NAN, f64::NAN, 1.0, 4), "both-nan");
    assert_eq!(agree_mean(1.0, f64::NAN, 1.0, 4), "no");
    assert_eq!(agree_mean(1.0, 1.0, f64::NAN, 1), "n/a");
    // SD rule (χ², 3 df): [0.566, 3.73] × SD.
    assert_eq!(agree_sd(0.6, 1.0, 4), "yes");
    assert_eq!(agree_sd(3.7, 1.0, 4), "yes");
    assert_eq!(agree_sd(0.5, 1.0, 4), "no");
    assert_eq!(agree_sd(4.0, 1.0, 4), "no");
}

#[test]
fn study_figures_and_comparison_come_out_of_constructed_jobs() {
    use chronocooked_paper::agreement::agreement;
    use chronocooked_paper::compare::compare;
    use chronocooked_paper::figures::write_figures;
    use chronocooked_paper::multitimer::analyse_multitimer;
    use chronocooked_paper::study::{PaperStudy, job_costs, write_study};
    let mut jobs = Vec::new();
    for seed in 1..=3u64 {
        for td in [4u32, 12] {
            jobs.push(lstm_fi_job(
                seed,
                td,
                (0..12)
                    .map(|c| ep("fi", td, (c, 0), Some((td + (c as u32 % 3)) as i32 - 1), 0))
                    .collect(),
            ));
        }
        let mut b = bisection_job(seed, 30.0, 7 + seed as u32 % 2);
        b.job.model = "lstm125".into();
        jobs.push(b);
    }
    let fi = analyse_fi(&jobs);
    let bisection = analyse_bisection(&jobs);
    let multitimer = analyse_multitimer(&jobs);
    let comparison = compare(&fi, &bisection, &multitimer);
    // FI CV at TD 4 and 12, FOC means and SDs at 4 and 12, both R² tables (2 × 2), the
    // bisection WF / DL rows of 4-12 (means and SDs).
    let tables: Vec<&str> = comparison.iter().map(|r| r.table.as_str()).collect();
    assert_eq!(tables.iter().filter(|t| **t == "fi_cv").count(), 2);
    assert_eq!(
        tables.iter().filter(|t| t.starts_with("bisection")).count(),
        4
    );
    assert!(comparison.iter().all(|r| r.n <= 3));
    let cv4 = comparison
        .iter()
        .find(|r| r.table == "fi_cv" && r.row == "4")
        .unwrap();
    // FOCs 3, 4, 5 repeated: mean 4, SD √(8/11)·… computed from the pooled list.
    let focs: Vec<f64> = (0..36).map(|i| f64::from(3 + (i % 12) % 3)).collect();
    let m = focs.iter().sum::<f64>() / 36.0;
    let sd = (focs.iter().map(|f| (f - m).powi(2)).sum::<f64>() / 35.0).sqrt();
    assert!((cv4.lab_mean - sd / m).abs() < 1e-12);
    // Every row carries its source and a z recomputed from its own columns.
    for r in &comparison {
        let want = if r.table.ends_with("_notebook") || r.table.starts_with("multitimer") {
            "notebook"
        } else {
            "paper"
        };
        assert_eq!(r.source, want, "{r:?}");
        if r.se_from == "lab" && r.n >= 2 && r.paper.is_finite() && r.lab_sd > 0.0 {
            let z = (r.lab_mean - r.paper) / (r.lab_sd / (r.n as f64).sqrt());
            assert!((r.z - z).abs() < 1e-9, "{r:?}");
        }
    }
    let agreement = agreement(&comparison, &fi, &bisection, &multitimer);
    let study = PaperStudy {
        jobs: jobs.len(),
        cost: job_costs(&jobs),
        agreement,
        pi: vec![],
        pi_verdicts: vec![],
        fi,
        bisection,
        multitimer,
        exact_timer: vec![],
        claims: vec![],
        spreads: vec![],
        ranges: vec![],
        comparison,
    };
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-paper-fig-{}", std::process::id()));
    let files = write_figures(&dir, &study).unwrap();
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
        .collect();
    for want in [
        "fi_foc.svg",
        "fi_scalar.png",
        "bisection_grid.svg",
        "wf_vs_ratio.png",
    ] {
        assert!(
            names.iter().any(|n| n == want),
            "{want} missing from {names:?}"
        );
    }
    let grid = std::fs::read_to_string(dir.join("bisection_grid.svg")).unwrap();
    assert!(grid.contains("least squares") && grid.contains("max. likelihood"));
    // comparison.csv has the new columns; agreement.json and pi.csv are written beside it.
    write_study(&dir, &study).unwrap();
    let csv = std::fs::read_to_string(dir.join("comparison.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "table,row,column,source,paper,paper_sd,paper_n,lab_mean,lab_sd,n,z,se_from,agree,agree_z"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("agreement.json")).unwrap())
            .unwrap();
    assert!(json["counts"].as_array().is_some_and(|a| !a.is_empty()));
    assert!(
        json["negative_control"]
            .as_array()
            .is_some_and(|a| !a.is_empty())
    );
    assert!(dir.join("pi.csv").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn multitimer_analysis_reads_levels_rewards_and_oven_off_times() {
    use chronocooked_paper::figures::{multitimer_panels, write_figures};
    use chronocooked_paper::multitimer::analyse_multitimer;
    use chronocooked_paper::report::write_paper_report;
    use chronocooked_paper::study::{PaperStudy, tables_markdown};
    let cat = ["mode=exact", "under_buffer=3"];
    // Run A reaches all five timers; TD 4 is evaluated but not trained (out of distribution).
    let mut a = job("MultiTimer-v0", "m", 1, &cat, 20.0);
    a.level_steps = vec![0, 100, 150, 300, 400, 500];
    let a = CompactJob {
        job: a,
        episodes: vec![
            mt_ep(3, 1.0, 3),
            mt_ep(6, 1.0, 6),
            mt_ep(6, 0.0, -1),
            mt_ep(4, 0.0, 2),
        ],
        curve: vec![
            curve_at(0, 0.2),
            curve_at(0, 0.4),
            curve_at(1, 0.9),
            curve_at(5, 1.0),
        ],
        levels: vec![],
    };
    // Run B stays at one timer and never takes the soup.
    let mut b = job("MultiTimer-v0", "m", 2, &cat, 200.0);
    b.level_steps = vec![0, 200];
    let b = CompactJob {
        job: b,
        episodes: vec![mt_ep(3, 0.0, -1)],
        curve: vec![curve_at(0, 0.5), curve_at(1, 0.1)],
        levels: vec![],
    };
    // An exact-curriculum run still in the warm-up.
    let c = CompactJob {
        job: job("MultiTimer-v0", "m", 1, &["mode=exact"], 200.0),
        episodes: vec![mt_ep(3, 0.0, -1)],
        curve: vec![curve_at(0, 0.0)],
        levels: vec![],
    };
    let mt = analyse_multitimer(&[a, b, c]);
    assert_eq!(mt.len(), 2);
    let cat = mt.iter().find(|c| c.curriculum == "categorical").unwrap();
    let exact = mt.iter().find(|c| c.curriculum == "exact").unwrap();
    assert_eq!((exact.runs.len(), exact.level.mean), (1, 0.0));
    assert!((cat.level.mean - 3.0).abs() < 1e-12);
    assert_eq!(cat.reached_last, 1);
    // Steps in level 0: 100 and 200; level 1: only run A left it (50 steps).
    assert!((cat.steps_in_level[0].mean - 150.0).abs() < 1e-12);
    assert_eq!(
        (cat.steps_in_level[1].mean, cat.steps_in_level[1].n),
        (50.0, 1)
    );
    // Trained TDs only in per_td; the out-of-distribution TD 4 in `tested`.
    let ra = cat.runs.iter().find(|r| r.seed == 1).unwrap();
    assert_eq!(ra.per_td, vec![(3, 1.0, 3.0), (6, 0.5, 2.5)]);
    assert_eq!(ra.tested, vec![(3, 1.0, 3.0), (4, 0.0, 2.0), (6, 0.5, 2.5)]);
    // Across runs at TD 3: rewards 1 and 0, oven-off times 3 and −1 (never taken).
    let (td, r, o) = &cat.per_td[0];
    assert_eq!((*td, r.n), (3, 2));
    assert!((r.mean - 0.5).abs() < 1e-12 && (o.mean - 1.0).abs() < 1e-12);
    // Training reward per level: run A 0.3 / 0.9 / – / – / – / 1.0; run B 0.5 / 0.1.
    assert_eq!(
        ra.level_reward,
        vec![
            Some(0.30000000000000004),
            Some(0.9),
            None,
            None,
            None,
            Some(1.0)
        ]
    );
    assert!((cat.level_reward[0].mean - 0.4).abs() < 1e-12);
    assert!((cat.level_reward[1].mean - 0.5).abs() < 1e-12);
    assert_eq!((cat.level_reward[5].n, cat.level_reward[2].n), (1, 0));
    let study = PaperStudy {
        jobs: 3,
        cost: vec![],
        fi: vec![],
        bisection: vec![],
        multitimer: mt,
        exact_timer: vec![],
        claims: vec![],
        spreads: vec![],
        ranges: vec![],
        comparison: vec![],
        agreement: Default::default(),
        pi: vec![],
        pi_verdicts: vec![],
    };
    let (grid, panels) = multitimer_panels(&study);
    assert_eq!(grid, (3, 1));
    assert_eq!(panels.len(), 3);
    let md = tables_markdown(&study, "paper-core");
    assert!(
        md.contains("| model | curriculum | TDs | TD 3 | TD 6 |"),
        "{md}"
    );
    let list = "3, 6, 9, 12, 15";
    assert!(
        md.contains(&format!(
            "| m | categorical | {list} | 0.50 / 1.0 | 0.50 / 2.5 |"
        )),
        "{md}"
    );
    assert!(
        md.contains(&format!("| m | exact | {list} | 0.00 / -1.0 | – |")),
        "{md}"
    );
    assert!(
        md.contains(&format!(
            "| m | categorical | {list} | 0.40 ± 0.14 | 0.50 ± 0.57 | – | – | – | 1.00 |"
        )),
        "{md}"
    );
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-paper-mt-{}", std::process::id()));
    let files = write_figures(&dir.join("figures"), &study).unwrap();
    assert!(files.iter().any(|p| p.ends_with("multitimer.svg")));
    let svg = std::fs::read_to_string(dir.join("figures/multitimer.svg")).unwrap();
    assert!(svg.contains("training reward per level") && svg.contains("oven-off time"));
    let report = write_paper_report(&dir, &study, &dir.join("figures")).unwrap();
    let html = std::fs::read_to_string(report).unwrap();
    assert!(
        html.contains("<svg")
            && html.contains(
                "Numbers printed in the paper's main text: 0 of 0 agree under the z rule (0 under the old rule)"
            )
    );
    assert!(!html.contains("http://"), "the page must hold no URL");
    let _ = std::fs::remove_dir_all(&dir);
}
