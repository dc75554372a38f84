//! Few-run statistics against values worked out by hand: the interquartile mean, the
//! stratified percentile bootstrap (against the exact bootstrap distribution, enumerated),
//! and the probability of improvement.

use chronocooked_analysis::stats::robust::{
    iqm, probability_of_improvement, quantile_sorted, stratified_bootstrap_ci,
};

#[test]
fn the_interquartile_mean_cuts_a_quarter_of_the_runs_at_each_end() {
    // n = 5: one cut at each end, mean of 2, 3, 4.
    assert_eq!(iqm(&[100.0, 2.0, 1.0, 4.0, 3.0]), 3.0);
    // n = 4: mean of the middle two.
    assert_eq!(iqm(&[4.0, 1.0, 3.0, 2.0]), 2.5);
    // n = 3 and 2: nothing cut (⌊n/4⌋ = 0): the mean.
    assert_eq!(iqm(&[5.0, 7.0]), 6.0);
    assert_eq!(iqm(&[1.0, 2.0, 9.0]), 4.0);
    // n = 8: two cut at each end, mean of 3, 4, 5, 6; n = 20 (scipy's trim_mean(range(20),
    // 0.25) = 9.5).
    assert_eq!(iqm(&[8.0, 7.0, 6.0, 5.0, 4.0, 3.0, 2.0, 1.0]), 4.5);
    let twenty: Vec<f64> = (0..20).map(f64::from).collect();
    assert_eq!(iqm(&twenty), 9.5);
    // NaN runs are left out; none left is NaN.
    assert_eq!(iqm(&[f64::NAN, 1.0, 3.0]), 2.0);
    assert!(iqm(&[f64::NAN]).is_nan());
}

#[test]
fn quantiles_interpolate_between_order_statistics_as_numpy_does() {
    let v = [1.0, 2.0, 4.0, 10.0];
    // numpy.percentile([1, 2, 4, 10], [0, 25, 50, 90, 100]) = 1, 1.75, 3, 8.2, 10.
    for (q, want) in [
        (0.0, 1.0),
        (0.25, 1.75),
        (0.5, 3.0),
        (0.9, 8.2),
        (1.0, 10.0),
    ] {
        assert!((quantile_sorted(&v, q) - want).abs() < 1e-12, "{q}");
    }
}

/// The exact bootstrap distribution of the IQM of four runs: all 4⁴ = 256 equally likely
/// resamples, enumerated. The Monte-Carlo interval's ends lie between the exact
/// distribution's 1.5% and 3.5% (and 96.5% and 98.5%) quantiles.
#[test]
fn the_bootstrap_interval_matches_the_enumerated_bootstrap_distribution() {
    let runs = [1.0, 2.0, 4.0, 10.0];
    let mut exact = Vec::new();
    for a in 0..4 {
        for b in 0..4 {
            for c in 0..4 {
                for d in 0..4 {
                    let mut r = [runs[a], runs[b], runs[c], runs[d]];
                    r.sort_by(f64::total_cmp);
                    exact.push((r[1] + r[2]) / 2.0);
                }
            }
        }
    }
    exact.sort_by(f64::total_cmp);
    let strata = vec![String::from("all"); 4];
    let (lo, hi) = stratified_bootstrap_ci(&runs, &strata, iqm, 0.95, 20_000, 7).unwrap();
    let q = |p: f64| quantile_sorted(&exact, p);
    assert!(
        q(0.015) <= lo && lo <= q(0.035),
        "{lo} vs {} – {}",
        q(0.015),
        q(0.035)
    );
    assert!(
        q(0.965) <= hi && hi <= q(0.985),
        "{hi} vs {} – {}",
        q(0.965),
        q(0.985)
    );
    // Seeded: the same interval again.
    assert_eq!(
        stratified_bootstrap_ci(&runs, &strata, iqm, 0.95, 20_000, 7),
        Some((lo, hi))
    );
}

/// Stratified: each stratum keeps its size in every resample. Three runs at 0 in one
/// stratum and three at 10 in the other: every resample's mean is exactly 5. Pooled into
/// one stratum the resampled mean varies.
#[test]
fn stratified_resamples_keep_every_strata_size() {
    let runs = [0.0, 0.0, 0.0, 10.0, 10.0, 10.0];
    let two: Vec<String> = ["a", "a", "a", "b", "b", "b"].map(String::from).to_vec();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    assert_eq!(
        stratified_bootstrap_ci(&runs, &two, mean, 0.95, 500, 1),
        Some((5.0, 5.0))
    );
    let one = vec![String::from("a"); 6];
    let (lo, hi) = stratified_bootstrap_ci(&runs, &one, mean, 0.95, 500, 1).unwrap();
    assert!(lo < 5.0 && hi > 5.0, "{lo} {hi}");
    // One run per stratum: every resample is the sample itself, so no interval.
    let each: Vec<String> = ["a", "b", "c"].map(String::from).to_vec();
    assert_eq!(
        stratified_bootstrap_ci(&[1.0, 2.0, 3.0], &each, mean, 0.95, 100, 1),
        None
    );
    // Fewer than two runs: no interval.
    assert_eq!(
        stratified_bootstrap_ci(&[1.0, f64::NAN], &one[..2], mean, 0.95, 100, 1),
        None
    );
}

#[test]
fn the_probability_of_improvement_counts_pairs_with_ties_as_halves() {
    // x = [1, 2, 3], y = [2, 2, 0]: wins 1 (1>0) + 1 + 0.5 + 0.5 (2 vs 2, 2, 0) + 3 (3 vs
    // all) = 6 of 9 pairs.
    let (x, y) = ([1.0, 2.0, 3.0], [2.0, 2.0, 0.0]);
    assert!((probability_of_improvement(&x, &y) - 6.0 / 9.0).abs() < 1e-12);
    assert!((probability_of_improvement(&y, &x) - 3.0 / 9.0).abs() < 1e-12);
    assert_eq!(probability_of_improvement(&x, &x), 0.5);
    assert!(probability_of_improvement(&x, &[]).is_nan());
}
