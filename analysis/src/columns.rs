//! The leaderboard's columns, declared once: each column's key, theme, short title,
//! description and how its value is computed. The headline numbers of an evaluation
//! ([`headline`]), the neural columns, the report's tables, their headers, tooltips and
//! legend all read this table, so a metric cannot be computed without a column, or shown
//! with a description of something else.

use crate::behaviour::metrics::Metrics;
use crate::neural::categories::Category;
use crate::neural::summary::{NeuralSummary, fraction};
use crate::records::ConditionKind;
use crate::stats::Spread;
use std::collections::BTreeMap;

/// How a column's value is obtained.
#[derive(Clone, Copy)]
pub enum Value {
    /// From one evaluation's metrics (`None`: the evaluation lacks it); aggregated over a
    /// row's runs as mean ± SD and IQM.
    Run(fn(&Metrics) -> Option<f64>),
    /// From one run's neural summary (the primary population; NaN where undefined).
    Neural(fn(&NeuralSummary) -> f64),
    /// From all of a row's runs together (computed in [`crate::report::leaderboard`]; the
    /// text says how).
    Row(&'static str),
}

/// One leaderboard column.
#[derive(Clone, Copy)]
pub struct Column {
    /// Key (CSV header, JSON key of `headline`, `Row::values` key).
    pub key: &'static str,
    /// Theme: the HTML report shows one table per theme, in first-appearance order.
    pub group: &'static str,
    /// Short header (units in parentheses), distinct within its theme.
    pub title: &'static str,
    /// Full description and which direction is better (tooltip, legend, Markdown).
    pub doc: &'static str,
    /// How the value is computed.
    pub value: Value,
}

/// Theme names (one table each).
const FI: &str = "Fixed interval";
const PI: &str = "Peak interval";
const BISECTION: &str = "Bisection";
const MULTI_TIMER: &str = "Multi-timer";
const DUAL: &str = "Dual task";
const UNCERTAINTY: &str = "Uncertainty";
const MULTI_ANCHOR: &str = "Multi-anchor categorization";
const MULTI_OVEN: &str = "Multi-oven bisection";
const REPRODUCTION: &str = "Temporal reproduction";
/// The neural columns' two themes (two tables, so that each fits a 1366-pixel screen).
pub const NEURAL_UNITS: &str = "Neural activity: unit categories";
/// See [`NEURAL_UNITS`].
pub const NEURAL_POPULATION: &str = "Neural activity: population";

/// Key of the Weber fraction's constancy across anchor pairs (a [`Value::Row`] column).
pub const WF_CV_ANCHORS: &str = "wf_cv_anchors";
/// Key of the episodes an agent needs to adapt to uncertainty (a [`Value::Row`] column).
pub const UNC_EPISODES_TO_ADAPT: &str = "unc_episodes_to_adapt";
/// Key of the share of runs that adapted (a [`Value::Row`] column).
pub const UNC_ADAPTED: &str = "unc_adapted";

/// Every column, in the order the report shows them.
pub const COLUMNS: [Column; 41] = [
    Column {
        key: "fi_success",
        group: FI,
        title: "success",
        doc: "FI: full-reward deliveries at the trained TD (higher is better)",
        value: Value::Run(fi_success),
    },
    Column {
        key: "bisection_accuracy",
        group: BISECTION,
        title: "anchor accuracy",
        doc: "correct counter on the two anchors (higher is better)",
        value: Value::Run(bisection_accuracy),
    },
    Column {
        key: "bp",
        group: BISECTION,
        title: "BP (steps)",
        doc: "bisection point of the logistic fit, steps",
        value: Value::Run(bp),
    },
    Column {
        key: "bp_over_gm",
        group: BISECTION,
        title: "BP / GM",
        doc: "BP / geometric mean of the anchors (1 = geometric-mean bisection, as in animals)",
        value: Value::Run(bp_over_gm),
    },
    Column {
        key: "bp_over_am",
        group: BISECTION,
        title: "BP / AM",
        doc: "BP / arithmetic mean of the anchors",
        value: Value::Run(bp_over_am),
    },
    Column {
        key: "wf",
        group: BISECTION,
        title: "Weber fraction",
        doc: "Weber fraction DL/BP (lower = sharper timing)",
        value: Value::Run(wf),
    },
    Column {
        key: WF_CV_ANCHORS,
        group: BISECTION,
        title: "WF CV across pairs",
        doc: "CV of the Weber fraction across anchor pairs (scalar timing: close to 0)",
        value: Value::Row(
            "the CV of the per-pair mean Weber fractions, over the row's runs on at least two anchor pairs",
        ),
    },
    Column {
        key: "foc_over_td",
        group: FI,
        title: "first check / TD",
        doc: "mean first oven check / TD (1 = checks exactly when the soup is ready)",
        value: Value::Run(foc_over_td),
    },
    Column {
        key: "foc_cv",
        group: FI,
        title: "first-check CV",
        doc: "CV of the first oven check (scalar timing: constant across TDs)",
        value: Value::Run(foc_cv),
    },
    Column {
        key: "r2_mean_vs_td",
        group: FI,
        title: "R² mean~TD",
        doc: "R² of mean FOC vs TD (timing: close to 1)",
        value: Value::Run(r2_mean_vs_td),
    },
    Column {
        key: "r2_sd_vs_mean",
        group: FI,
        title: "R² SD~mean",
        doc: "R² of FOC SD vs mean (scalar property: close to 1)",
        value: Value::Run(r2_sd_vs_mean),
    },
    Column {
        key: "pi_peak_over_td",
        group: PI,
        title: "peak / TD",
        doc: "peak-interval response peak / TD (1 = peaks at the trained time)",
        value: Value::Run(pi_peak_over_td),
    },
    Column {
        key: "pi_cv",
        group: PI,
        title: "spread / peak",
        doc: "peak-interval spread / peak (lower = sharper)",
        value: Value::Run(pi_cv),
    },
    Column {
        key: "mt_reward",
        group: MULTI_TIMER,
        title: "mean reward",
        doc: "multi-timer mean reward over TDs incl. OOD (higher is better)",
        value: Value::Run(mt_reward),
    },
    Column {
        key: "mt_plateaus",
        group: MULTI_TIMER,
        title: "timers stored",
        doc: "multi-timer timing plateaus (timers stored)",
        value: Value::Run(mt_plateaus),
    },
    Column {
        key: "dual_success",
        group: DUAL,
        title: "success",
        doc: "dual task: soup delivered inside the reward window (higher is better)",
        value: Value::Run(dual_success),
    },
    Column {
        key: "dual_reward",
        group: DUAL,
        title: "mean reward",
        doc: "dual-task mean reward (soup + sink)",
        value: Value::Run(dual_reward),
    },
    Column {
        key: "unc_success",
        group: UNCERTAINTY,
        title: "success (normal oven)",
        doc: "uncertainty task: success with a normal oven (higher is better)",
        value: Value::Run(unc_success),
    },
    Column {
        key: "unc_button_use",
        group: UNCERTAINTY,
        title: "button use (never ready)",
        doc: "uncertainty task: button use when the oven never readies",
        value: Value::Run(unc_button_use),
    },
    Column {
        key: UNC_EPISODES_TO_ADAPT,
        group: UNCERTAINTY,
        title: "episodes to adapt",
        doc: "uncertainty adaptation: episodes an agent trained without uncertainty plays until, in the last 100 episodes, 80% of the never-ready ovens are solved with the button and 80% of the normal ones without it (lower is better; runs that adapted)",
        value: Value::Row("from each run's `adapt/adapt.json` (`chronocooked adapt`)"),
    },
    Column {
        key: UNC_ADAPTED,
        group: UNCERTAINTY,
        title: "runs adapted",
        doc: "uncertainty adaptation: fraction of runs that adapted within the budget (higher is better)",
        value: Value::Row("from each run's `adapt/adapt.json` (`chronocooked adapt`)"),
    },
    Column {
        key: "ma_accuracy",
        group: MULTI_ANCHOR,
        title: "category accuracy",
        doc: "multi-anchor: deliveries to the anchor's own counter at the anchor TDs, among deliveries (higher is better; bounded by the anchors' spacing)",
        value: Value::Run(ma_accuracy),
    },
    Column {
        key: "ma_bp_over_gm",
        group: MULTI_ANCHOR,
        title: "boundary / GM",
        doc: "multi-anchor: boundary between neighbouring anchors / their geometric mean, mean over the fitted boundaries",
        value: Value::Run(ma_bp_over_gm),
    },
    Column {
        key: "ma_wf",
        group: MULTI_ANCHOR,
        title: "category WF",
        doc: "multi-anchor: Weber fraction DL/BP, mean over the fitted boundaries (lower = sharper)",
        value: Value::Run(ma_wf),
    },
    Column {
        key: "mo_accuracy",
        group: MULTI_OVEN,
        title: "oven accuracy",
        doc: "multi-oven: correct counter at S and L, mean over the ovens (higher is better)",
        value: Value::Run(mo_accuracy),
    },
    Column {
        key: "mo_wf",
        group: MULTI_OVEN,
        title: "oven WF",
        doc: "multi-oven: Weber fraction of each oven's curve, mean over the ovens",
        value: Value::Run(mo_wf),
    },
    Column {
        key: "mo_d_wf",
        group: MULTI_OVEN,
        title: "ΔWF vs one oven",
        doc: "multi-oven interference: each oven's WF minus the same agent's one-oven WF, mean over the ovens (0 = no interference)",
        value: Value::Run(mo_d_wf),
    },
    Column {
        key: "rp_success",
        group: REPRODUCTION,
        title: "in window",
        doc: "reproduction: productions inside the reward window (higher is better)",
        value: Value::Run(rp_success),
    },
    Column {
        key: "rp_slope",
        group: REPRODUCTION,
        title: "tp~ts slope",
        doc: "reproduction: slope of mean tp against g·ts per prior and gain, mean over contexts (1 = no regression to the mean, < 1 = central tendency)",
        value: Value::Run(rp_slope),
    },
    Column {
        key: "rp_bias",
        group: REPRODUCTION,
        title: "BIAS (steps)",
        doc: "reproduction: BIAS (root mean squared difference of mean tp and g·ts, steps), mean over contexts",
        value: Value::Run(rp_bias),
    },
    Column {
        key: "rp_weber",
        group: REPRODUCTION,
        title: "tp Weber fraction",
        doc: "reproduction: Weber fraction of tp (SD / mean), mean over contexts",
        value: Value::Run(rp_weber),
    },
    Column {
        key: "neural_units",
        group: NEURAL_UNITS,
        title: "units",
        doc: "neural: units analysed in the primary population (constant units excluded), window 2 x TD after oven-on at the longest recorded TD",
        value: Value::Neural(neural_units),
    },
    Column {
        key: "frac_ramp",
        group: NEURAL_UNITS,
        title: "ramps",
        doc: "neural: fraction of ramps (time-locked, monotone fit R² ≥ 0.9); – below 10 units (counts in activity.summary.json)",
        value: Value::Neural(frac_ramp),
    },
    Column {
        key: "frac_time_field",
        group: NEURAL_UNITS,
        title: "time fields",
        doc: "neural: fraction of time fields (time-locked, one interior peak falling by half its range on both sides)",
        value: Value::Neural(frac_time_field),
    },
    Column {
        key: "frac_oscillating",
        group: NEURAL_UNITS,
        title: "oscillating",
        doc: "neural: fraction of oscillating units (significant spectral peak with ≥ 2 cycles in the window, repeating autocorrelation)",
        value: Value::Neural(frac_oscillating),
    },
    Column {
        key: "frac_mixed",
        group: NEURAL_UNITS,
        title: "mixed",
        doc: "neural: fraction of mixed units (time-locked with several or none of the three shapes)",
        value: Value::Neural(frac_mixed),
    },
    Column {
        key: "frac_untuned",
        group: NEURAL_UNITS,
        title: "untuned",
        doc: "neural: fraction of untuned units (not time-locked: circular-shift surrogate p > 0.05)",
        value: Value::Neural(frac_untuned),
    },
    Column {
        key: "scaling",
        group: NEURAL_POPULATION,
        title: "scaling (long/short)",
        doc: "neural: median per-unit temporal scaling factor from the shortest to the longest recorded TD (= TD ratio when activity stretches with the interval, 1 for a fixed clock)",
        value: Value::Neural(scaling),
    },
    Column {
        key: "speed_ratio",
        group: NEURAL_POPULATION,
        title: "speed ratio",
        doc: "neural: population trajectory speed at the longest TD over that at the shortest (= TD_short/TD_long when dynamics stretch)",
        value: Value::Neural(speed_ratio),
    },
    Column {
        key: "sequentiality",
        group: NEURAL_POPULATION,
        title: "sequentiality",
        doc: "neural: sequentiality index (1 = tiling sequence, 0 = identical units)",
        value: Value::Neural(sequentiality),
    },
    Column {
        key: "decode_error",
        group: NEURAL_POPULATION,
        title: "decoding error (steps)",
        doc: "neural: cross-validated ridge decoding error of elapsed time, steps (lower is better)",
        value: Value::Neural(decode_error),
    },
];

/// The column of `key`, if there is one.
pub fn column(key: &str) -> Option<&'static Column> {
    COLUMNS.iter().find(|c| c.key == key)
}

/// The columns whose values come from neural summaries ([`Value::Neural`]), in order.
pub fn neural_columns() -> impl Iterator<Item = (&'static str, fn(&NeuralSummary) -> f64)> {
    COLUMNS.iter().filter_map(|c| match c.value {
        Value::Neural(f) => Some((c.key, f)),
        _ => None,
    })
}

/// Headline numbers of one evaluation, by key: every [`Value::Run`] column the evaluation
/// has.
pub fn headline(m: &Metrics) -> BTreeMap<String, f64> {
    COLUMNS
        .iter()
        .filter_map(|c| match c.value {
            Value::Run(f) => f(m).map(|v| (c.key.to_string(), v)),
            _ => None,
        })
        .collect()
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

// ---- per-run values -------------------------------------------------------------------

/// Mean success rate over the conditions of `kind` (the trained condition only: probes and
/// OOD conditions are not meant to pay).
fn success_of(m: &Metrics, kind: ConditionKind) -> Option<f64> {
    let c: Vec<f64> = m
        .conditions
        .iter()
        .filter(|c| c.kind == kind)
        .map(|c| c.success_rate)
        .collect();
    (!c.is_empty()).then(|| Spread::of(c).mean)
}

/// Mean of the finite values (`None` without any).
fn finite_mean(v: impl IntoIterator<Item = f64>) -> Option<f64> {
    let s = Spread::of(v.into_iter().filter(|x| x.is_finite()));
    (s.n > 0).then_some(s.mean)
}

fn fi_success(m: &Metrics) -> Option<f64> {
    success_of(m, ConditionKind::Fi)
}
fn dual_success(m: &Metrics) -> Option<f64> {
    success_of(m, ConditionKind::Dual)
}
fn bisection_accuracy(m: &Metrics) -> Option<f64> {
    m.bisection.as_ref().map(|b| b.anchor_accuracy)
}
fn bp(m: &Metrics) -> Option<f64> {
    m.bisection.as_ref()?.fit.as_ref().map(|f| f.bp)
}
fn wf(m: &Metrics) -> Option<f64> {
    m.bisection.as_ref()?.fit.as_ref().map(|f| f.wf)
}
fn bp_over_gm(m: &Metrics) -> Option<f64> {
    m.bisection.as_ref()?.bp_over_gm
}
fn bp_over_am(m: &Metrics) -> Option<f64> {
    m.bisection.as_ref()?.bp_over_am
}
fn foc_over_td(m: &Metrics) -> Option<f64> {
    let fi = m.fi.as_ref()?;
    Some(Spread::of(fi.foc.iter().map(|s| s.mean / f64::from(s.td))).mean)
}
fn foc_cv(m: &Metrics) -> Option<f64> {
    Some(Spread::of(m.fi.as_ref()?.foc.iter().map(|s| s.cv)).mean)
}
fn r2_mean_vs_td(m: &Metrics) -> Option<f64> {
    m.fi.as_ref().map(|fi| fi.scalar.r2_mean_vs_td)
}
fn r2_sd_vs_mean(m: &Metrics) -> Option<f64> {
    m.fi.as_ref().map(|fi| fi.scalar.r2_sd_vs_mean)
}
/// The first peak-interval condition with a fit: (its peak / TD, its CV).
fn pi_fit(m: &Metrics) -> Option<(f64, f64)> {
    let pi = m.pi.iter().find(|c| c.fit.is_some())?;
    let f = pi.fit.as_ref()?;
    Some((f.peak / f64::from(pi.td), f.cv))
}
fn pi_peak_over_td(m: &Metrics) -> Option<f64> {
    pi_fit(m).map(|p| p.0)
}
fn pi_cv(m: &Metrics) -> Option<f64> {
    pi_fit(m).map(|p| p.1)
}
fn mt_reward(m: &Metrics) -> Option<f64> {
    Some(Spread::of(m.multi_timer.as_ref()?.by_td.iter().map(|b| b.1)).mean)
}
fn mt_plateaus(m: &Metrics) -> Option<f64> {
    m.multi_timer.as_ref().map(|mt| mt.plateaus as f64)
}
fn dual_reward(m: &Metrics) -> Option<f64> {
    Some(Spread::of(m.dual.as_ref()?.by_td.iter().map(|b| b.1)).mean)
}
fn unc_success(m: &Metrics) -> Option<f64> {
    m.uncertainty.as_ref().map(|u| u.success_normal)
}
fn unc_button_use(m: &Metrics) -> Option<f64> {
    m.uncertainty.as_ref().map(|u| u.button_use)
}
fn ma_accuracy(m: &Metrics) -> Option<f64> {
    Some(m.multi_anchor.as_ref()?.anchor_accuracy).filter(|x| x.is_finite())
}
fn ma_bp_over_gm(m: &Metrics) -> Option<f64> {
    let ma = m.multi_anchor.as_ref()?;
    finite_mean(
        ma.boundaries
            .iter()
            .filter_map(|b| b.fit.as_ref().map(|f| f.bp / b.gm)),
    )
}
fn ma_wf(m: &Metrics) -> Option<f64> {
    let ma = m.multi_anchor.as_ref()?;
    finite_mean(
        ma.boundaries
            .iter()
            .filter_map(|b| b.fit.as_ref().map(|f| f.wf)),
    )
}
fn mo_accuracy(m: &Metrics) -> Option<f64> {
    finite_mean(m.multi_oven.as_ref()?.per_oven.iter().map(|o| o.accuracy))
}
fn mo_wf(m: &Metrics) -> Option<f64> {
    finite_mean(
        m.multi_oven
            .as_ref()?
            .per_oven
            .iter()
            .filter_map(|o| o.fit.as_ref().map(|f| f.wf)),
    )
}
fn mo_d_wf(m: &Metrics) -> Option<f64> {
    finite_mean(m.multi_oven.as_ref()?.interference.iter().map(|i| i.d_wf))
}
fn rp_success(m: &Metrics) -> Option<f64> {
    m.reproduction.as_ref()?;
    finite_mean(
        m.conditions
            .iter()
            .filter(|c| c.kind == ConditionKind::Reproduction)
            .map(|c| c.success_rate),
    )
}
/// Slope of tp on g·ts: 1 = no regression to the mean at any gain.
fn rp_slope(m: &Metrics) -> Option<f64> {
    finite_mean(
        m.reproduction
            .as_ref()?
            .contexts
            .iter()
            .filter_map(|c| c.slope.map(|s| s / c.gain)),
    )
}
fn rp_bias(m: &Metrics) -> Option<f64> {
    finite_mean(
        m.reproduction
            .as_ref()?
            .contexts
            .iter()
            .filter_map(|c| c.bias),
    )
}
fn rp_weber(m: &Metrics) -> Option<f64> {
    finite_mean(
        m.reproduction
            .as_ref()?
            .contexts
            .iter()
            .filter_map(|c| c.weber),
    )
}

// ---- per-run neural values ------------------------------------------------------------

fn neural_units(s: &NeuralSummary) -> f64 {
    s.units as f64
}
fn frac_ramp(s: &NeuralSummary) -> f64 {
    fraction(s, Category::Ramp).unwrap_or(f64::NAN)
}
fn frac_time_field(s: &NeuralSummary) -> f64 {
    fraction(s, Category::TimeField).unwrap_or(f64::NAN)
}
fn frac_oscillating(s: &NeuralSummary) -> f64 {
    fraction(s, Category::Oscillating).unwrap_or(f64::NAN)
}
fn frac_mixed(s: &NeuralSummary) -> f64 {
    fraction(s, Category::Mixed).unwrap_or(f64::NAN)
}
fn frac_untuned(s: &NeuralSummary) -> f64 {
    fraction(s, Category::Untuned).unwrap_or(f64::NAN)
}
fn scaling(s: &NeuralSummary) -> f64 {
    s.scaling
        .as_ref()
        .and_then(|x| x.median)
        .unwrap_or(f64::NAN)
}
fn speed_ratio(s: &NeuralSummary) -> f64 {
    s.scaling
        .as_ref()
        .and_then(|x| x.speed_ratio)
        .unwrap_or(f64::NAN)
}
fn sequentiality(s: &NeuralSummary) -> f64 {
    s.sequentiality.unwrap_or(f64::NAN)
}
fn decode_error(s: &NeuralSummary) -> f64 {
    s.decode_ridge.unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_column_has_a_short_title_distinct_within_its_theme_and_a_unique_key() {
        for c in &COLUMNS {
            assert!(
                c.title.chars().count() <= 24,
                "{}: title {:?} too long for the table",
                c.key,
                c.title
            );
            let same_key = COLUMNS.iter().filter(|o| o.key == c.key).count();
            assert_eq!(same_key, 1, "{} declared {same_key} times", c.key);
            let clash = COLUMNS
                .iter()
                .filter(|o| o.group == c.group && o.title == c.title)
                .count();
            assert_eq!(
                clash, 1,
                "{}: title {:?} repeats within {}",
                c.key, c.title, c.group
            );
            // Only the neural summary's columns sit under "Neural activity".
            assert_eq!(
                c.group.starts_with("Neural activity"),
                matches!(c.value, Value::Neural(_)),
                "{}",
                c.key
            );
            assert!(!c.doc.is_empty(), "{}", c.key);
        }
    }

    #[test]
    fn the_row_columns_are_the_ones_the_leaderboard_computes() {
        let row: Vec<&str> = COLUMNS
            .iter()
            .filter(|c| matches!(c.value, Value::Row(_)))
            .map(|c| c.key)
            .collect();
        assert_eq!(row, [WF_CV_ANCHORS, UNC_EPISODES_TO_ADAPT, UNC_ADAPTED]);
    }
}
