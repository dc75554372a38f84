//! Aggregation of metrics across seeds / runs (mean, SD, n of each headline number), and
//! the adaptation measure of the uncertainty experiment.

use crate::behaviour::metrics::Metrics;
use crate::records::ConditionKind;
use std::collections::BTreeMap;

pub use crate::stats::Spread;

/// Headline numbers of one evaluation, by name (the leaderboard's columns).
pub fn headline(m: &Metrics) -> BTreeMap<String, f64> {
    let mut h = BTreeMap::new();
    // Success of the trained condition only (probes and OOD conditions are not meant to pay).
    for (kind, key) in [
        (ConditionKind::Fi, "fi_success"),
        (ConditionKind::Dual, "dual_success"),
    ] {
        let c: Vec<f64> = m
            .conditions
            .iter()
            .filter(|c| c.kind == kind)
            .map(|c| c.success_rate)
            .collect();
        if !c.is_empty() {
            h.insert(key.into(), Spread::of(c).mean);
        }
    }
    if let Some(b) = &m.bisection {
        h.insert("bisection_accuracy".into(), b.anchor_accuracy);
        if let Some(f) = &b.fit {
            h.insert("bp".into(), f.bp);
            h.insert("wf".into(), f.wf);
        }
        if let Some(v) = b.bp_over_gm {
            h.insert("bp_over_gm".into(), v);
        }
        if let Some(v) = b.bp_over_am {
            h.insert("bp_over_am".into(), v);
        }
    }
    if let Some(fi) = &m.fi {
        let ratio: Vec<f64> = fi.foc.iter().map(|s| s.mean / f64::from(s.td)).collect();
        h.insert("foc_over_td".into(), Spread::of(ratio).mean);
        h.insert(
            "foc_cv".into(),
            Spread::of(fi.foc.iter().map(|s| s.cv)).mean,
        );
        h.insert("r2_mean_vs_td".into(), fi.scalar.r2_mean_vs_td);
        h.insert("r2_sd_vs_mean".into(), fi.scalar.r2_sd_vs_mean);
    }
    if let Some(pi) = m.pi.iter().find(|c| c.fit.is_some()) {
        let f = pi.fit.as_ref().expect("checked");
        h.insert("pi_peak_over_td".into(), f.peak / f64::from(pi.td));
        h.insert("pi_cv".into(), f.cv);
    }
    if let Some(mt) = &m.multi_timer {
        h.insert(
            "mt_reward".into(),
            Spread::of(mt.by_td.iter().map(|b| b.1)).mean,
        );
        h.insert("mt_plateaus".into(), mt.plateaus as f64);
    }
    if let Some(d) = &m.dual {
        h.insert(
            "dual_reward".into(),
            Spread::of(d.by_td.iter().map(|b| b.1)).mean,
        );
    }
    if let Some(u) = &m.uncertainty {
        h.insert("unc_success".into(), u.success_normal);
        h.insert("unc_button_use".into(), u.button_use);
    }
    h
}

/// Mean ± SD across runs of every headline number that any run has.
pub fn aggregate(runs: &[Metrics]) -> BTreeMap<String, Spread> {
    let heads: Vec<BTreeMap<String, f64>> = runs.iter().map(headline).collect();
    let mut keys: Vec<&String> = heads.iter().flat_map(|h| h.keys()).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .map(|k| {
            (
                k.clone(),
                Spread::of(heads.iter().filter_map(|h| h.get(k).copied())),
            )
        })
        .collect()
}
