//! The comparison with power and the peak-interval test on constructed cases with by-hand
//! answers: z scores, the z rule's verdicts, the verdict counts and the negative control's
//! counting, the paper/notebook source of each number, and the uniformity test of
//! post-TD response rates (a flat curve against a peaked one).

use chronocooked_paper::agreement::{Counts, control_counts, table_counts};
use chronocooked_paper::compare::{ComparisonRow, agree_z, z_score, z_score_sd};
use chronocooked_paper::pi::{PiEntry, pi_row, pi_verdicts, slope, uniformity};
use chronocooked_paper::reference::{Source, appendix_numbers, lab_model, numbers, size8_numbers};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn z_scores_have_by_hand_values() {
    // Lab 1.0 ± 0.2 over 4 runs, paper 0.8 ± 0.1 over 4 runs:
    // SE = √(0.04/4 + 0.01/4) = √0.0125 = 0.1118034, z = 0.2 / 0.1118034 = 1.7888544.
    assert!(close(
        z_score(1.0, 0.2, 4, 0.8, 0.1, 4),
        1.788_854_381_999_832
    ));
    // No paper SD: the lab's standard error alone, 0.2/√4 = 0.1 → z = 2 (agrees, |z| ≤ 2) …
    let z = z_score(1.0, 0.2, 4, 0.8, f64::NAN, 0);
    assert!(close(z, 2.0));
    assert_eq!(agree_z(0.8, 1.0, z), "yes");
    // … and 0.7 is 3 standard errors away (the old rule's interval, ±3.18·0.2·√0.5 = ±0.45,
    // still holds it).
    let z = z_score(1.0, 0.2, 4, 0.7, f64::NAN, 0);
    assert!(close(z, 3.0));
    assert_eq!(agree_z(0.7, 1.0, z), "no");
    assert_eq!(
        chronocooked_paper::compare::agree_mean(0.7, 1.0, 0.2, 4),
        "yes"
    );
    // Negative differences give negative z.
    assert!(close(z_score(0.5, 0.2, 4, 0.8, f64::NAN, 0), -3.0));
    // SD against SD on the log scale: ln(0.2/0.1) / √(1/6 + 1/6) = 0.6931472 / 0.5773503
    // = 1.2005661; a printed SD of 0 against a positive one cannot agree.
    assert!(close(
        z_score_sd(0.2, 4, 0.1, 4),
        2f64.ln() / (1.0f64 / 3.0).sqrt()
    ));
    assert!(close(z_score_sd(0.2, 4, 0.1, 4), 1.200_566_133_852_943_6));
    assert_eq!(z_score_sd(0.01, 3, 0.0, 4), f64::INFINITY);
    assert_eq!(z_score_sd(0.0, 3, 0.0, 4), 0.0);
    assert!(z_score_sd(0.2, 1, 0.1, 4).is_nan());
    // Zero standard error: equal values z = 0, different values ±∞ (disagree).
    assert_eq!(z_score(1.0, 0.0, 4, 1.0, f64::NAN, 0), 0.0);
    let z = z_score(1.0, 0.0, 4, 2.0, f64::NAN, 0);
    assert_eq!(z, f64::NEG_INFINITY);
    assert_eq!(agree_z(2.0, 1.0, z), "no");
    // Undefined: one run, a NaN on either side.
    assert!(z_score(1.0, 0.2, 1, 0.8, 0.1, 4).is_nan());
    assert!(z_score(f64::NAN, 0.2, 4, 0.8, 0.1, 4).is_nan());
    assert_eq!(agree_z(0.8, 1.0, f64::NAN), "n/a");
    assert_eq!(agree_z(f64::NAN, f64::NAN, f64::NAN), "both-nan");
    assert_eq!(agree_z(0.8, f64::NAN, f64::NAN), "no");
}

#[test]
fn sources_follow_the_paper_and_the_notebook() {
    let all = numbers();
    let paper = all.iter().filter(|p| p.source == Source::Paper).count();
    let notebook = all.iter().filter(|p| p.source == Source::Notebook).count();
    // Printed: CV 12, R² 4, WF 12 + 12 SDs, DL 12 + 12 SDs = 64; notebook: FOC means 18,
    // FOC SDs 12, R² 4, multi-timer 2 = 36.
    assert_eq!((paper, notebook), (64, 36));
    assert!(
        all.iter()
            .filter(|p| p.table.ends_with("_notebook") || p.table.starts_with("multitimer"))
            .all(|p| p.source == Source::Notebook)
    );
    // The appendix prints NaN for every size-8 WF and DL.
    let s8 = size8_numbers();
    assert!(
        s8.iter()
            .filter(|p| p.source == Source::Paper)
            .all(|p| p.value.is_nan())
    );
    assert_eq!(s8.iter().filter(|p| p.source == Source::Paper).count(), 48);
}

fn row(table: &str, source: &str, agree: &str, agree_z: &str) -> ComparisonRow {
    ComparisonRow {
        table: table.into(),
        row: "r".into(),
        column: "c".into(),
        source: source.into(),
        paper: 1.0,
        paper_sd: f64::NAN,
        paper_n: 0,
        lab_mean: 1.0,
        lab_sd: 0.1,
        n: 4,
        z: 0.0,
        se_from: "lab".into(),
        agree: agree.into(),
        agree_z: agree_z.into(),
    }
}

#[test]
fn verdict_counts_and_negative_control_count_by_hand() {
    let c = Counts::of(["yes", "no", "n/a", "both-nan", "yes"]);
    assert_eq!((c.rows, c.yes, c.no, c.na, c.both_nan), (5, 2, 1, 1, 1));
    assert!(close(c.rate, 2.0 / 3.0));
    assert!(Counts::of(["n/a"]).rate.is_nan());
    // A mismatched pairing: 4 printed numbers (old rule agrees on 3, z rule on 1) and 2
    // notebook numbers (old 2, z 0).
    let rows = vec![
        row("t1", "paper", "yes", "yes"),
        row("t1", "paper", "yes", "no"),
        row("t2", "paper", "yes", "no"),
        row("t2", "paper", "no", "no"),
        row("t3", "notebook", "yes", "no"),
        row("t3", "notebook", "yes", "n/a"),
    ];
    let cc = control_counts("paper X vs lab Y", false, &rows);
    let get = |src: &str, rule: &str| {
        cc.iter()
            .find(|c| c.source == src && c.rule == rule)
            .unwrap()
            .counts
            .clone()
    };
    assert_eq!((get("paper", "old").yes, get("paper", "old").no), (3, 1));
    assert!(close(get("paper", "old").rate, 0.75));
    assert_eq!((get("paper", "z").yes, get("paper", "z").no), (1, 3));
    assert!(close(get("paper", "z").rate, 0.25));
    assert_eq!((get("notebook", "z").yes, get("notebook", "z").na), (0, 1));
    assert_eq!(get("all", "old").rows, 6);
    assert_eq!(get("all", "old").yes, 5);
    assert!(
        cc.iter()
            .all(|c| !c.matched && c.pairing == "paper X vs lab Y")
    );
    // Per table × source × rule, then `all` per source.
    let tc = table_counts(&rows);
    let t = |table: &str, src: &str, rule: &str| {
        tc.iter()
            .find(|c| c.table == table && c.source == src && c.rule == rule)
            .unwrap()
            .counts
            .yes
    };
    assert_eq!((t("t1", "paper", "old"), t("t1", "paper", "z")), (2, 1));
    assert_eq!((t("t2", "paper", "old"), t("t2", "paper", "z")), (1, 0));
    assert_eq!((t("all", "paper", "old"), t("all", "paper", "z")), (3, 1));
    assert_eq!(t("all", "notebook", "old"), 2);
    assert_eq!(tc.len(), (3 + 2) * 2);
}

fn entry(td: u32, factor: f64, rate: Vec<Option<f64>>) -> PiEntry {
    PiEntry {
        factor,
        td,
        rate,
        fit: None,
    }
}

#[test]
fn uniform_and_peaked_post_td_curves_are_told_apart() {
    // TD 4, released at 2×TD = 8: the window after the TD is oven times 4…7.
    let mut flat: Vec<Option<f64>> = vec![None, Some(0.1), Some(0.2), Some(0.3)];
    flat.extend([0.5, 0.5, 0.5, 0.5, 1.0].map(Some));
    let r = pi_row("m", 1, &entry(4, 2.0, flat), 12);
    assert_eq!((r.bins, r.df), (4, 3));
    assert_eq!(r.chi2, 0.0);
    assert!(close(r.p_uniform, 1.0));
    assert_eq!(r.verdict, "uniform");
    assert!(close(r.slope_per_td, 0.0) && close(r.drop_2td, 0.0));
    assert!(close(r.rate_after_td, 0.5));
    assert_eq!(r.curve_after_td, "0.500;0.500;0.500;0.500");
    // Peaked at the TD and falling to 0 by 2×TD: mean 0.4375, Σ(r − r̄)² = 0.546875,
    // χ² = 12·0.546875 / (0.4375·0.5625) = 26.667 on 3 df (p ≈ 7e-6); slope against
    // (t − TD)/TD = 0, .25, .5, .75 is −1.3; drop by 2×TD 1; first maximum at TD.
    let mut peaked: Vec<Option<f64>> = vec![None, Some(0.1), Some(0.2), Some(0.3)];
    peaked.extend([1.0, 0.5, 0.25, 0.0, 1.0].map(Some));
    let r = pi_row("m", 2, &entry(4, 2.0, peaked), 12);
    assert!(close(r.chi2, 12.0 * 0.546875 / (0.4375 * 0.5625)));
    assert!(r.p_uniform < 1e-4 && r.p_uniform > 1e-6, "{}", r.p_uniform);
    assert_eq!(r.verdict, "non-uniform");
    assert!(close(r.slope_per_td, -1.3));
    assert!(close(r.drop_2td, 1.0));
    assert!(close(r.peak_over_td, 1.0));
    // A curve that never checks after the TD, and checks at every step (rate 1: uniform).
    let r0 = pi_row("n", 1, &entry(4, 2.0, vec![Some(0.0); 9]), 12);
    assert_eq!(r0.verdict, "no checks");
    let (chi2, df, p, v) = uniformity(&[1.0, 1.0, 1.0, f64::NAN], 12);
    assert_eq!((chi2, df, p, v), (0.0, 2, 1.0, "uniform"));
    assert_eq!(uniformity(&[0.5], 12).3, "n/a");
    assert!(slope(&[1.0, 1.0], &[0.0, 1.0]).is_nan());
    // Per model: m has one non-uniform curve (not uniform); n one without checks and one
    // uniform (1 of 1 decided: uniform).
    let flat2 = pi_row("n", 2, &entry(4, 2.0, vec![Some(1.0); 9]), 12);
    let rows = vec![r, r0, flat2];
    let v = pi_verdicts(&rows);
    let n = v.iter().find(|x| x.model == "n").unwrap();
    assert_eq!((n.curves, n.uniform, n.no_checks), (2, 1, 1));
    assert_eq!(n.verdict, "uniform");
    let m = v.iter().find(|x| x.model == "m").unwrap();
    assert_eq!((m.uniform, m.non_uniform), (0, 1));
    assert_eq!(m.verdict, "not uniform");
    // metrics.json writes NaN rates as null.
    let e: PiEntry =
        serde_json::from_str(r#"{"factor":2.0,"td":2,"rate":[null,0.5,1.0,1.0,1.0],"fit":null}"#)
            .unwrap();
    let r = pi_row("j", 1, &e, 12);
    assert_eq!((r.bins, r.verdict.as_str()), (2, "uniform"));
}

#[test]
fn appendix_tables_are_transcribed_from_the_paper() {
    let a = appendix_numbers();
    // tab:wf_supp and tab:dl_supp: 2 sizes × 2 models × (mean, SD) × 2 statistics × 6 pairs.
    assert_eq!(a.len(), 96);
    assert!(a.iter().all(|p| p.source == Source::Paper));
    let get = |table: &str, column: &str, row: &str| {
        a.iter()
            .find(|p| p.table == table && p.column == column && p.row == row)
            .map(|p| p.value)
            .unwrap()
    };
    // By hand from the LaTeX tables (row order 6-8, 4-8, 6-12, 4-12, 6-18, 4-18).
    assert_eq!(get("appendix_wf", "CTRNN256", "4-8"), 0.29);
    assert_eq!(get("appendix_wf_sd", "CTRNN256", "4-18"), 0.00);
    assert_eq!(get("appendix_wf", "LSTM256", "4-18"), 0.18);
    assert_eq!(get("appendix_dl", "LSTM256", "6-18"), 1.30);
    assert_eq!(get("appendix_dl_sd", "LSTM256", "6-18"), 0.95);
    assert_eq!(get("appendix_dl", "CTRNN256", "6-12"), 0.28);
    // NaN: the 6-8 row everywhere and every size-8 entry; 20 finite means at size 256.
    assert!(
        a.iter()
            .filter(|p| p.row == "6-8")
            .all(|p| p.value.is_nan())
    );
    assert!(
        a.iter()
            .filter(|p| p.column.ends_with("8") && !p.column.ends_with("256"))
            .all(|p| p.value.is_nan())
    );
    let finite_means = a
        .iter()
        .filter(|p| matches!(p.table, "appendix_wf" | "appendix_dl") && p.value.is_finite())
        .count();
    assert_eq!(finite_means, 20);
    // The paper's CTRNN is the untrained reservoir at every size.
    assert_eq!(lab_model("CTRNN256"), Some("ctrnn-reservoir256"));
    assert_eq!(lab_model("CTRNN8"), Some("ctrnn-reservoir8"));
    assert_eq!(lab_model("LSTM256"), Some("lstm256"));
    // The main text's counts are unchanged by the appendix (kept in its own tables).
    assert!(numbers().iter().all(|p| !p.table.starts_with("appendix")));
}
