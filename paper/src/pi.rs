//! `pi.csv`: the peak-interval probes of every FI run (the `pi` entries of each job's
//! `metrics.json`: the soup released at 2× or 5× the trained TD) and a test of the paper's
//! statement that the agents check the oven uniformly after the TD.
//!
//! Per run × TD × probe factor, over the window after the TD while the soup is not ready
//! (oven times `TD … factor·TD − 1`): the response rate there, its drop by 2×TD
//! (`r(TD) − r(2·TD − 1)`), the curve's peak over TD (first maximum over the whole curve,
//! and the Gaussian fit's μ/TD and σ/TD when there is one), the least-squares slope of the
//! rate against `(t − TD)/TD`, and a χ² test of homogeneity of the check proportions
//! across the window's time bins: `χ² = Σₜ n·(rₜ − r̄)² / (r̄(1 − r̄))`, `k − 1` degrees of
//! freedom (k bins, n probe episodes; each episode checks at most once per step). A curve
//! is `uniform` when p ≥ 0.05, `non-uniform` otherwise, `no checks` when it never checks
//! after the TD. The bins share episodes, so p is approximate (the test treats them as
//! independent samples of n episodes; an episode's checks are positively correlated over
//! time, which makes bins more alike than independent samples would be, so the test errs
//! towards `uniform`).

use chronocooked_analysis::collect::{CollectError, CompactJob, err};
use chronocooked_analysis::records::ConditionKind;
use chronocooked_analysis::records::METRICS;
use chronocooked_env::markdown::Table;
use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::path::Path;

/// Significance level of the uniformity test.
pub const ALPHA: f64 = 0.05;

/// One line of `pi.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PiRow {
    /// Lab model.
    pub model: String,
    /// Training seed (run).
    pub seed: u64,
    /// Trained TD.
    pub td: u32,
    /// Release factor of the probe (soup at factor × TD).
    pub factor: f64,
    /// Probe episodes.
    pub episodes: usize,
    /// Time bins after the TD (`TD … factor·TD − 1` with a rate).
    pub bins: usize,
    /// Mean response rate (checks per episode per step) after the TD.
    pub rate_after_td: f64,
    /// `r(TD)`.
    pub rate_td: f64,
    /// `r(2·TD − 1)`, the last step before 2×TD.
    pub rate_2td: f64,
    /// `r(TD) − r(2·TD − 1)` (a peak-interval curve falls by ~its peak; flat checking: 0).
    pub drop_2td: f64,
    /// First maximum of the whole curve over TD.
    pub peak_over_td: f64,
    /// Gaussian fit's μ/TD (NaN without a fit).
    pub fit_peak_over_td: f64,
    /// Gaussian fit's σ/TD (NaN without a fit).
    pub fit_spread_over_td: f64,
    /// Least-squares slope of the rate against `(t − TD)/TD` after the TD.
    pub slope_per_td: f64,
    /// χ² of homogeneity across the bins after the TD.
    pub chi2: f64,
    /// Its degrees of freedom (`bins − 1`).
    pub df: usize,
    /// Its p-value.
    pub p_uniform: f64,
    /// `uniform`, `non-uniform`, `no checks` or `n/a` (fewer than two bins).
    pub verdict: String,
    /// The rates after the TD, `;`-separated (3 decimals; NaN where no episode ran).
    pub curve_after_td: String,
}

/// The uniformity test of the rates `r` (NaN bins skipped) of `n` episodes:
/// `(χ², df, p, verdict)`.
pub fn uniformity(r: &[f64], n: usize) -> (f64, usize, f64, &'static str) {
    let v: Vec<f64> = r.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 2 || n == 0 {
        return (f64::NAN, v.len().saturating_sub(1), f64::NAN, "n/a");
    }
    let df = v.len() - 1;
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    if mean <= 0.0 {
        return (f64::NAN, df, f64::NAN, "no checks");
    }
    let var = mean * (1.0 - mean);
    let ss: f64 = v.iter().map(|x| (x - mean).powi(2)).sum();
    let chi2 = if var <= 0.0 || ss <= 1e-15 {
        0.0
    } else {
        n as f64 * ss / var
    };
    let p = ChiSquared::new(df as f64).map_or(f64::NAN, |d| 1.0 - d.cdf(chi2));
    let verdict = if p >= ALPHA { "uniform" } else { "non-uniform" };
    (chi2, df, p, verdict)
}

/// Least-squares slope of `y` against `x` (NaN pairs skipped; NaN with fewer than two
/// distinct x).
pub fn slope(x: &[f64], y: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return f64::NAN;
    }
    pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / sxx
}

/// The Gaussian fit's peak and spread, when `metrics.json` has one.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PiFit {
    /// μ (steps).
    pub peak: Option<f64>,
    /// σ (steps).
    pub spread: Option<f64>,
}

/// One `pi` entry of `metrics.json` (NaN rates are written as `null`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PiEntry {
    /// Release factor.
    pub factor: f64,
    /// Trained TD.
    pub td: u32,
    /// Rate at oven time 0, 1, ….
    pub rate: Vec<Option<f64>>,
    /// Gaussian fit.
    #[serde(default)]
    pub fit: Option<PiFit>,
}

/// The `pi.csv` line of one probe curve of run `seed` of `model` with `n` probe episodes.
pub fn pi_row(model: &str, seed: u64, e: &PiEntry, n: usize) -> PiRow {
    let td = e.td as usize;
    let tdf = f64::from(e.td.max(1));
    let r: Vec<f64> = e.rate.iter().map(|x| x.unwrap_or(f64::NAN)).collect();
    let end = ((e.factor * tdf).round() as usize).min(r.len());
    let window: &[f64] = if td < end { &r[td..end] } else { &[] };
    let at = |t: usize| r.get(t).copied().unwrap_or(f64::NAN);
    let rate_td = at(td);
    let rate_2td = if 2 * td > 0 && 2 * td - 1 < end {
        at(2 * td - 1)
    } else {
        f64::NAN
    };
    let finite: Vec<f64> = window.iter().copied().filter(|x| x.is_finite()).collect();
    let mean = if finite.is_empty() {
        f64::NAN
    } else {
        finite.iter().sum::<f64>() / finite.len() as f64
    };
    let peak_t = r
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .fold(None::<(usize, f64)>, |b, (t, &v)| match b {
            Some((_, bv)) if bv >= v => b,
            _ => Some((t, v)),
        })
        .map_or(f64::NAN, |(t, _)| t as f64 / tdf);
    let xs: Vec<f64> = (0..window.len()).map(|i| i as f64 / tdf).collect();
    let (chi2, df, p, verdict) = uniformity(window, n);
    let fit = e.fit.unwrap_or_default();
    PiRow {
        model: model.into(),
        seed,
        td: e.td,
        factor: e.factor,
        episodes: n,
        bins: finite.len(),
        rate_after_td: mean,
        rate_td,
        rate_2td,
        drop_2td: rate_td - rate_2td,
        peak_over_td: peak_t,
        fit_peak_over_td: fit.peak.map_or(f64::NAN, |x| x / tdf),
        fit_spread_over_td: fit.spread.map_or(f64::NAN, |x| x / tdf),
        slope_per_td: slope(&xs, window),
        chi2,
        df,
        p_uniform: p,
        verdict: verdict.into(),
        curve_after_td: window
            .iter()
            .map(|x| format!("{x:.3}"))
            .collect::<Vec<_>>()
            .join(";"),
    }
}

/// Every FI job's probe curves under `root` (`jobs/<id>/metrics.json`; a job without
/// metrics is skipped, an unreadable one is an error).
pub fn analyse_pi(root: &Path, jobs: &[CompactJob]) -> Result<Vec<PiRow>, CollectError> {
    #[derive(Deserialize)]
    struct M {
        #[serde(default)]
        pi: Vec<PiEntry>,
    }
    let mut out = Vec::new();
    for j in jobs
        .iter()
        .filter(|j| j.job.task.id().starts_with("FixedInterval"))
    {
        let p = root.join("jobs").join(&j.job.id).join(METRICS);
        if !p.is_file() {
            continue;
        }
        let text = std::fs::read_to_string(&p).map_err(|e| err(&p, e))?;
        let m: M = serde_json::from_str(&text).map_err(|e| err(&p, e))?;
        for e in &m.pi {
            let n = j
                .episodes
                .iter()
                .filter(|x| {
                    x.kind == ConditionKind::Pi && x.td == e.td && x.factor == Some(e.factor)
                })
                .count();
            out.push(pi_row(j.job.label(), j.job.seed, e, n));
        }
    }
    out.sort_by(|a, b| {
        a.model
            .cmp(&b.model)
            .then(a.factor.total_cmp(&b.factor))
            .then(a.td.cmp(&b.td))
            .then(a.seed.cmp(&b.seed))
    });
    Ok(out)
}

/// The verdict of one model × probe factor over its runs and TDs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PiVerdict {
    /// Lab model.
    pub model: String,
    /// Release factor.
    pub factor: f64,
    /// Curves (runs × TDs).
    pub curves: usize,
    /// `uniform` curves.
    pub uniform: usize,
    /// `non-uniform` curves.
    pub non_uniform: usize,
    /// Curves without a check after the TD, or with fewer than two bins.
    pub no_checks: usize,
    /// Mean rate after the TD over the curves.
    pub mean_rate: f64,
    /// Mean `drop_2td`.
    pub mean_drop_2td: f64,
    /// Mean slope per TD.
    pub mean_slope_per_td: f64,
    /// `uniform` when at least 3/4 of the curves with checks are uniform, else
    /// `not uniform`; `no data` without such curves.
    pub verdict: String,
}

/// Per model × factor verdicts of `rows`.
pub fn pi_verdicts(rows: &[PiRow]) -> Vec<PiVerdict> {
    let mut keys: Vec<(String, f64)> = Vec::new();
    for r in rows {
        if !keys.iter().any(|k| k.0 == r.model && k.1 == r.factor) {
            keys.push((r.model.clone(), r.factor));
        }
    }
    let mean = |v: Vec<f64>| {
        let v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            f64::NAN
        } else {
            v.iter().sum::<f64>() / v.len() as f64
        }
    };
    keys.into_iter()
        .map(|(model, factor)| {
            let g: Vec<&PiRow> = rows
                .iter()
                .filter(|r| r.model == model && r.factor == factor)
                .collect();
            let count = |v: &str| g.iter().filter(|r| r.verdict == v).count();
            let (uniform, non_uniform) = (count("uniform"), count("non-uniform"));
            let decided = uniform + non_uniform;
            let verdict = if decided == 0 {
                "no data"
            } else if 4 * uniform >= 3 * decided {
                "uniform"
            } else {
                "not uniform"
            };
            PiVerdict {
                curves: g.len(),
                uniform,
                non_uniform,
                no_checks: g.len() - decided,
                mean_rate: mean(g.iter().map(|r| r.rate_after_td).collect()),
                mean_drop_2td: mean(g.iter().map(|r| r.drop_2td).collect()),
                mean_slope_per_td: mean(g.iter().map(|r| r.slope_per_td).collect()),
                verdict: verdict.into(),
                model,
                factor,
            }
        })
        .collect()
}

fn f(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.2}")
    } else {
        "–".into()
    }
}

/// The peak-interval section of `tables.md`: the uniform-checking verdict per model ×
/// probe factor (nothing in a study without FI probes).
pub fn pi_markdown(m: &mut String, v: &[PiVerdict]) {
    use std::fmt::Write as _;
    if v.is_empty() {
        return;
    }
    let _ = writeln!(
        m,
        "\n## Peak interval: does the agent check uniformly after the TD?\n\nPer run × TD \
         (`pi.csv`): χ² test of homogeneity of the check proportions over oven times \
         TD … factor·TD − 1 (p ≥ {ALPHA} = uniform); a model × factor is `uniform` when at \
         least 3/4 of its curves with checks are.\n"
    );
    let mut table = Table::new([
        "model",
        "factor",
        "curves",
        "uniform",
        "non-uniform",
        "no checks or no bins",
        "mean rate after TD",
        "mean drop by 2×TD",
        "mean slope per TD",
        "verdict",
    ])
    .right(1..9);
    for x in v {
        table.row([
            x.model.to_string(),
            x.factor.to_string(),
            x.curves.to_string(),
            x.uniform.to_string(),
            x.non_uniform.to_string(),
            x.no_checks.to_string(),
            f(x.mean_rate),
            f(x.mean_drop_2td),
            f(x.mean_slope_per_td),
            x.verdict.to_string(),
        ]);
    }
    m.push_str(&table.render());
}
