//! Bisection as the paper analyses it: per run and probe P(long) (NaN when fewer than half
//! of the episodes delivered), runs whose final training episodes were long (mean length >
//! 100) excluded, the run-averaged curve fitted by least squares, per-run fits giving the
//! WF / DL tables (mean ± SD), and WF against log2(L/S). Beside it the lab's binomial
//! maximum-likelihood fit of the pooled counts.

use super::lsq::{LsqFit, fit_paper};
use chronocooked_analysis::behaviour::aggregate::Spread;
use chronocooked_analysis::behaviour::psychometric::{LogisticFit, ProbeCounts, fit_logistic};
use chronocooked_analysis::collect::CompactJob;
use chronocooked_analysis::records::ConditionKind;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Mean training episode length above which the notebook drops a run.
pub const EXCLUDE_EP_LEN: f64 = 100.0;

/// One run at one anchor pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BisectionRun {
    /// Training seed.
    pub seed: u64,
    /// Final mean training episode length.
    pub final_ep_len: f64,
    /// Dropped by the notebook's rule.
    pub excluded: bool,
    /// P(long) per probe 1 … L+4 (NaN: fewer than half valid).
    pub p_long: Vec<f64>,
    /// Fraction of anchor episodes (S and L) delivered to the right counter.
    pub anchor_accuracy: f64,
    /// The notebook's least-squares fit of this run's curve.
    pub fit: Option<LsqFit>,
}

/// One model at one anchor pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BisectionCell {
    /// Short anchor.
    pub short: u32,
    /// Long anchor.
    pub long: u32,
    /// Every run.
    pub runs: Vec<BisectionRun>,
    /// Run-averaged P(long) per probe over included runs.
    pub curve: Vec<f64>,
    /// Least-squares fit of the averaged curve (the paper's figure).
    pub fit: Option<LsqFit>,
    /// Binomial maximum-likelihood fit of the pooled counts of included runs (the lab's).
    pub mle: Option<LogisticFit>,
    /// Per-run WF (included runs with a fit).
    pub wf: Spread,
    /// Per-run DL.
    pub dl: Spread,
    /// Per-run BP.
    pub bp: Spread,
    /// Anchor accuracy across included runs.
    pub anchor_accuracy: Spread,
}

/// WF against log2(L/S) for one model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WfRegression {
    /// Pearson r.
    pub r: f64,
    /// Two-sided p-value (Student t, n − 2 degrees of freedom).
    pub p: f64,
    /// Points.
    pub n: usize,
    /// Least-squares slope.
    pub slope: f64,
}

/// One model's bisection results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BisectionModel {
    /// Zoo model name.
    pub model: String,
    /// Per anchor pair.
    pub cells: Vec<BisectionCell>,
    /// WF of the averaged-curve fits vs log2(L/S), one point per anchor pair (the paper's).
    pub wf_vs_ratio: Option<WfRegression>,
    /// Per-run WF vs log2(L/S), one point per run and anchor pair.
    pub wf_vs_ratio_runs: Option<WfRegression>,
}

/// Pearson correlation with its two-sided p-value and slope (`None` below 3 points or
/// without spread).
pub fn pearson(x: &[f64], y: &[f64]) -> Option<WfRegression> {
    let n = x.len().min(y.len());
    if n < 3 {
        return None;
    }
    let (mx, my) = (
        x.iter().sum::<f64>() / n as f64,
        y.iter().sum::<f64>() / n as f64,
    );
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let syy: f64 = y.iter().map(|b| (b - my).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    if sxx <= 0.0 || syy <= 0.0 {
        return None;
    }
    let r = (sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0);
    let p = chronocooked_analysis::neural::correlation_p(r, n);
    Some(WfRegression {
        r,
        p,
        n,
        slope: sxy / sxx,
    })
}

fn run_of(job: &CompactJob, short: u32, long: u32) -> (BisectionRun, Vec<ProbeCounts>) {
    let mut counts = Vec::new();
    let mut p_long = Vec::new();
    for d in 1..=long + 4 {
        let eps: Vec<_> = job
            .episodes
            .iter()
            .filter(|e| e.kind == ConditionKind::Bisection && e.td == d)
            .collect();
        let valid = eps
            .iter()
            .filter(|e| e.counter == 1 || e.counter == 2)
            .count();
        let n_long = eps.iter().filter(|e| e.counter == 2).count();
        let c = ProbeCounts {
            t: f64::from(d),
            valid: valid as u32,
            long: n_long as u32,
            failed: (eps.len() - valid) as u32,
        };
        counts.push(c);
        p_long.push(if eps.is_empty() || 2 * valid < eps.len() {
            f64::NAN
        } else {
            n_long as f64 / valid as f64
        });
    }
    let anchors: Vec<_> = job
        .episodes
        .iter()
        .filter(|e| e.kind == ConditionKind::Bisection && (e.td == short || e.td == long))
        .collect();
    let right = anchors
        .iter()
        .filter(|e| (e.td == short && e.counter == 1) || (e.td == long && e.counter == 2))
        .count();
    let probes: Vec<f64> = (1..=long + 4).map(f64::from).collect();
    let final_ep_len = job.job.final_ep_len_mean;
    (
        BisectionRun {
            seed: job.job.seed,
            final_ep_len,
            excluded: final_ep_len.is_nan() || final_ep_len > EXCLUDE_EP_LEN,
            fit: fit_paper(&probes, &p_long, f64::from(short), f64::from(long)),
            p_long,
            anchor_accuracy: right as f64 / anchors.len().max(1) as f64,
        },
        counts,
    )
}

/// Bisection analysis of every model among `jobs`.
pub fn analyse_bisection(jobs: &[CompactJob]) -> Vec<BisectionModel> {
    let mut by_model: BTreeMap<&str, BTreeMap<(u32, u32), Vec<&CompactJob>>> = BTreeMap::new();
    for j in jobs.iter().filter(|j| j.job.task.id() == "Bisection-v0") {
        let get = |k: &str| j.env_int(k);
        let (Some(s), Some(l)) = (get("short"), get("long")) else {
            continue;
        };
        by_model
            .entry(j.job.label())
            .or_default()
            .entry((s, l))
            .or_default()
            .push(j);
    }
    by_model
        .into_iter()
        .map(|(model, anchors)| {
            let mut cells = Vec::new();
            for ((short, long), jobs) in anchors {
                let mut runs = Vec::new();
                let mut pooled: Vec<ProbeCounts> = Vec::new();
                for j in jobs {
                    let (run, counts) = run_of(j, short, long);
                    if !run.excluded {
                        if pooled.is_empty() {
                            pooled = counts;
                        } else {
                            for (a, b) in pooled.iter_mut().zip(counts) {
                                a.valid += b.valid;
                                a.long += b.long;
                                a.failed += b.failed;
                            }
                        }
                    }
                    runs.push(run);
                }
                let kept: Vec<&BisectionRun> = runs.iter().filter(|r| !r.excluded).collect();
                let curve: Vec<f64> = (0..(long + 4) as usize)
                    .map(|i| {
                        let s = Spread::of(kept.iter().map(|r| r.p_long[i]));
                        s.mean
                    })
                    .collect();
                let probes: Vec<f64> = (1..=long + 4).map(f64::from).collect();
                let fits: Vec<&LsqFit> = kept.iter().filter_map(|r| r.fit.as_ref()).collect();
                cells.push(BisectionCell {
                    short,
                    long,
                    fit: fit_paper(&probes, &curve, f64::from(short), f64::from(long)),
                    mle: fit_logistic(&pooled).ok(),
                    wf: Spread::of(fits.iter().map(|f| f.wf)),
                    dl: Spread::of(fits.iter().map(|f| f.dl)),
                    bp: Spread::of(fits.iter().map(|f| f.bp)),
                    anchor_accuracy: Spread::of(kept.iter().map(|r| r.anchor_accuracy)),
                    curve,
                    runs,
                });
            }
            let ratio = |c: &BisectionCell| (f64::from(c.long) / f64::from(c.short)).log2();
            let (x, y): (Vec<f64>, Vec<f64>) = cells
                .iter()
                .filter_map(|c| c.fit.map(|f| (ratio(c), f.wf)))
                .filter(|(_, wf)| wf.is_finite() && *wf > 0.0)
                .unzip();
            let (xr, yr): (Vec<f64>, Vec<f64>) = cells
                .iter()
                .flat_map(|c| {
                    c.runs
                        .iter()
                        .filter(|r| !r.excluded)
                        .filter_map(move |r| r.fit.map(|f| (ratio(c), f.wf)))
                })
                .filter(|(_, wf)| wf.is_finite() && *wf > 0.0)
                .unzip();
            BisectionModel {
                model: model.to_string(),
                wf_vs_ratio: pearson(&x, &y),
                wf_vs_ratio_runs: pearson(&xr, &yr),
                cells,
            }
        })
        .collect()
}
