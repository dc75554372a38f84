//! The leaderboard's few-run statistics against a by-hand computation on the committed
//! paper-core baselines: the IQM of the first-check CV of LSTM125's fixed-interval runs
//! (read from the job files here, strata = the TD each run was trained at), and its
//! stratified bootstrap interval recomputed here with a generator of the test's own.

use chronocooked_present::report::baselines::load_baseline_rows;
use rand::{Rng, SeedableRng};
use std::collections::BTreeMap;
use std::path::Path;

/// `(td, foc_cv)` of every LSTM125 fixed-interval job, read from its metrics.json.
fn runs(root: &Path) -> Vec<(u32, f64)> {
    let mut out = Vec::new();
    let fi = root.join("jobs/FixedInterval-v0");
    for entry in std::fs::read_dir(&fi).unwrap() {
        let dir = entry.unwrap().path();
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let Some(td) = name.strip_prefix("lstm125~env.td-") else {
            continue;
        };
        let td: u32 = td.parse().unwrap();
        for seed in std::fs::read_dir(&dir).unwrap() {
            let m: serde_json::Value = serde_json::from_str(
                &std::fs::read_to_string(seed.unwrap().path().join("metrics.json")).unwrap(),
            )
            .unwrap();
            let cvs: Vec<f64> = m["fi"]["foc"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(|f| f["cv"].as_f64())
                .collect();
            if !cvs.is_empty() {
                out.push((td, cvs.iter().sum::<f64>() / cvs.len() as f64));
            }
        }
    }
    out
}

fn trimmed_mean(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let cut = v.len() / 4;
    let kept = &v[cut..v.len() - cut];
    kept.iter().sum::<f64>() / kept.len() as f64
}

#[test]
fn the_leaderboard_iqm_and_interval_equal_a_by_hand_bootstrap() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/paper-core");
    let rows = load_baseline_rows(&root).unwrap();
    let row = rows
        .iter()
        .find(|r| r.model == "lstm125 (paper-core)")
        .expect("an lstm125 row");
    let robust = &row.robust["foc_cv"];
    let runs = runs(&root);
    assert!(runs.len() >= 40, "{} runs", runs.len());
    let iqm = trimmed_mean(runs.iter().map(|r| r.1).collect());
    assert!((robust.iqm - iqm).abs() < 1e-12, "{} vs {iqm}", robust.iqm);
    // By hand: resample within each TD, 20,000 times, percentile interval.
    let mut by_td: BTreeMap<u32, Vec<f64>> = BTreeMap::new();
    for (td, cv) in &runs {
        by_td.entry(*td).or_default().push(*cv);
    }
    let mut rng = rand_xoshiro::SplitMix64::seed_from_u64(2021);
    let mut stats: Vec<f64> = (0..20_000)
        .map(|_| {
            let draw: Vec<f64> = by_td
                .values()
                .flat_map(|g| {
                    (0..g.len())
                        .map(|_| g[rng.random_range(0..g.len())])
                        .collect::<Vec<_>>()
                })
                .collect();
            trimmed_mean(draw)
        })
        .collect();
    stats.sort_by(f64::total_cmp);
    let q = |p: f64| stats[(p * (stats.len() - 1) as f64).round() as usize];
    let (lo, hi) = robust.ci.expect("an interval for many runs");
    let width = q(0.975) - q(0.025);
    // The leaderboard's 2,000 resamples against these 20,000: the ends agree to within a
    // tenth of the interval's width (Monte-Carlo error of a 2.5% quantile).
    assert!(
        (lo - q(0.025)).abs() < 0.1 * width,
        "lo {lo} vs {}",
        q(0.025)
    );
    assert!(
        (hi - q(0.975)).abs() < 0.1 * width,
        "hi {hi} vs {}",
        q(0.975)
    );
    assert!(lo <= iqm && iqm <= hi);
}
