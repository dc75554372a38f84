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
    let mean_of = |v: Vec<f64>| {
        let s = Spread::of(v.into_iter().filter(|x| x.is_finite()));
        (s.n > 0).then_some(s.mean)
    };
    let mut insert = |key: &str, v: Option<f64>| {
        if let Some(v) = v {
            h.insert(key.into(), v);
        }
    };
    if let Some(ma) = &m.multi_anchor {
        let fits: Vec<_> = ma
            .boundaries
            .iter()
            .filter_map(|b| b.fit.as_ref().map(|f| (b, f)))
            .collect();
        insert(
            "ma_accuracy",
            Some(ma.anchor_accuracy).filter(|x| x.is_finite()),
        );
        insert(
            "ma_bp_over_gm",
            mean_of(fits.iter().map(|(b, f)| f.bp / b.gm).collect()),
        );
        insert("ma_wf", mean_of(fits.iter().map(|(_, f)| f.wf).collect()));
    }
    if let Some(mo) = &m.multi_oven {
        insert(
            "mo_accuracy",
            mean_of(mo.per_oven.iter().map(|o| o.accuracy).collect()),
        );
        insert(
            "mo_wf",
            mean_of(
                mo.per_oven
                    .iter()
                    .filter_map(|o| o.fit.as_ref().map(|f| f.wf))
                    .collect(),
            ),
        );
        insert(
            "mo_d_wf",
            mean_of(mo.interference.iter().map(|i| i.d_wf).collect()),
        );
    }
    if let Some(rp) = &m.reproduction {
        let success: Vec<f64> = m
            .conditions
            .iter()
            .filter(|c| c.kind == ConditionKind::Reproduction)
            .map(|c| c.success_rate)
            .collect();
        insert("rp_success", mean_of(success));
        // Slope of tp on g·ts: 1 = no regression to the mean at any gain.
        insert(
            "rp_slope",
            mean_of(
                rp.contexts
                    .iter()
                    .filter_map(|c| c.slope.map(|s| s / c.gain))
                    .collect(),
            ),
        );
        insert(
            "rp_bias",
            mean_of(rp.contexts.iter().filter_map(|c| c.bias).collect()),
        );
        insert(
            "rp_weber",
            mean_of(rp.contexts.iter().filter_map(|c| c.weber).collect()),
        );
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
