//! Per-population neural summary of an activity dataset: unit categories on windows of
//! `2 × TD` steps after oven-on (one window per recorded TD), temporal scaling and
//! population trajectory speed between the shortest and the longest TD, sequentiality and
//! the elapsed-time decoding error — `record --summary` and the leaderboard's neural
//! columns.
//!
//! Record on peak-interval probe trials (`record --probe`: the soup is withheld, so every
//! trial lasts the whole window); on other tasks a trial that ends early leaves NaN for
//! the rest of its window and the tests use the steps it has.
//!
//! * Constant units (range ≤ 1e-9 over a TD's window) are excluded and counted
//!   (`constant_units`).
//! * Categories ([`crate::neural::categories`]) count every analysed unit once; below
//!   [`MIN_UNITS_FOR_FRACTIONS`] units the fractions are `null` and only the counts and
//!   their Wilson 95% intervals are given.
//! * The headline fields (`units`, `categories`, …) are those of the longest TD (the
//!   longest window: the most cycles of a rhythm, the most room for a field); `by_td` has
//!   every TD.

use crate::neural::categories::{
    CATEGORIES, CategoryConfig, CategoryCounts, CategoryError, EXTENDED_WINDOWS, PerCategory,
    UnitTests, classify_units, wilson_interval,
};
use crate::neural::decode::{Decoder, decode_time};
use crate::neural::dynamics::{Dynamics, dynamics};
use crate::neural::production::{ProductionSpeed, production_speed};
use crate::neural::{Cube, scaling_factor_from, sequentiality_index};
use chronocooked_models::{ActivityDataset, Marker, population_oven};
use serde::{Deserialize, Serialize};

/// Populations smaller than this get counts and intervals, no fractions.
pub const MIN_UNITS_FOR_FRACTIONS: usize = 10;

/// Smallest R² of a unit's scaling match for it to enter the median scaling factor.
pub const MIN_SCALING_R2: f64 = 0.5;

/// Elapsed steps since oven-on at column 0 of an aligned window (the first recorded step
/// after the oven-on step).
pub const WINDOW_ORIGIN: f64 = 1.0;

/// How to summarise.
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryOptions {
    /// Window (steps after oven-on) for every TD; `None` = `2 × TD`.
    pub window: Option<usize>,
    /// Whether unit `j` is the same unit at every TD (one agent, or timing models of the
    /// same model and seed). When false (separately trained networks merged), the per-unit
    /// scaling factor is not computed.
    pub units_correspond: bool,
    /// The category tests (their `seed` seeds the surrogates).
    pub categories: CategoryConfig,
}

impl Default for SummaryOptions {
    fn default() -> Self {
        SummaryOptions {
            window: None,
            units_correspond: true,
            categories: CategoryConfig::default(),
        }
    }
}

/// Why a summary could not be made.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SummaryError {
    /// The dataset has no such population.
    #[error("no population `{0}` in the dataset")]
    UnknownPopulation(String),
    /// No trial turned the oven on (for a multi-oven population: its own oven).
    #[error("no trial turned the oven on: nothing to align")]
    NoOvenOn,
}

/// Categories of one window, with their intervals and (large populations) fractions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CategorySummary {
    /// Counts per category (sum = analysed units).
    pub counts: CategoryCounts,
    /// Wilson 95% interval of each category's proportion.
    pub ci: PerCategory<[f64; 2]>,
    /// Fractions; `null` below [`MIN_UNITS_FOR_FRACTIONS`] units.
    pub fractions: Option<PerCategory<f64>>,
    /// Units whose rhythm test was undefined (too few trials covering the window's first
    /// `min_window` steps): they could not be counted as oscillating.
    pub rhythm_undefined: usize,
    /// Version of the category rules that made these counts: 2 = induced rhythms on a
    /// 32-step minimum stretch, noise-corrected shape fits, centroid locking and the
    /// `beyond_window` category ([`CATEGORY_RULES`]); files without the field were made
    /// by version 1 (time-locked rhythms on the 2 × TD window, plain R²) and are not
    /// comparable count for count.
    #[serde(default = "first_rules")]
    pub rules: u32,
}

/// The version of the category rules this build applies (see [`CategorySummary::rules`]).
pub const CATEGORY_RULES: u32 = 2;

fn first_rules() -> u32 {
    1
}

impl CategorySummary {
    /// From the units' tests.
    pub fn of(units: &[UnitTests]) -> Self {
        let counts = CategoryCounts::of(units);
        let n = counts.total();
        CategorySummary {
            counts,
            ci: PerCategory::from_fn(|c| wilson_interval(counts.get(c), n)),
            fractions: (n >= MIN_UNITS_FOR_FRACTIONS)
                .then(|| PerCategory::from_fn(|c| counts.get(c) as f64 / n as f64)),
            rhythm_undefined: units.iter().filter(|u| u.spectral_p.is_nan()).count(),
            rules: CATEGORY_RULES,
        }
    }
}

/// The summary of one TD's window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TdSummary {
    /// Target duration of the trials (steps).
    pub td: u32,
    /// Window analysed (steps after oven-on).
    pub window: usize,
    /// Trials aligned to oven-on.
    pub trials: usize,
    /// Units analysed (varying in this window).
    pub units: usize,
    /// Constant units excluded.
    pub constant_units: usize,
    /// Categories; `null` when undefined (see `undefined`).
    pub categories: Option<CategorySummary>,
    /// Why the categories are undefined.
    pub undefined: Option<String>,
    /// Population trajectory speed: mean Euclidean distance per step between consecutive
    /// points of the trial-averaged population vector (every unit; activity units/step).
    pub speed: Option<f64>,
    /// Sequentiality index of the trial average.
    pub sequentiality: Option<f64>,
    /// Cross-validated ridge decoding error of elapsed time (steps).
    pub decode_ridge: Option<f64>,
    /// Cross-validated Bayesian decoding error (steps).
    pub decode_bayes: Option<f64>,
    /// The basis-free signature of the population's trajectory over the window and the
    /// window after it ([`crate::neural::dynamics`]); absent in summaries made before it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamics: Option<Dynamics>,
}

/// Temporal scaling between the shortest and the longest recorded TD.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scaling {
    /// Shortest TD (steps).
    pub td_short: u32,
    /// Longest TD (steps).
    pub td_long: u32,
    /// `td_long / td_short`: the factor of a unit that stretches with the interval.
    pub td_ratio: f64,
    /// Median per-unit scaling factor `s` (`b(τ) ≈ a(τ/s)`, τ = steps since oven-on) over
    /// units varying at both TDs whose match has R² ≥ [`MIN_SCALING_R2`]; `null` when none
    /// or when units do not correspond across TDs.
    pub median: Option<f64>,
    /// Units in the median.
    pub units: usize,
    /// Median R² of their matches.
    pub median_r2: Option<f64>,
    /// Trajectory speed at the longest TD over that at the shortest, both over the shorter
    /// window (the first `2 × td_short` steps after oven-on): `td_short / td_long` for
    /// dynamics that stretch with the interval (Wang, Narain, Hosseini & Jazayeri 2018),
    /// 1 for a fixed clock.
    pub speed_ratio: Option<f64>,
    /// Scaling factor of the population's geometry (the matrix of distances between its
    /// states at every pair of times; [`crate::neural::geometry`]): ≈ `td_ratio` for
    /// dynamics that stretch with the interval, ≈ 1 for a fixed clock; needs no unit
    /// correspondence, so it compares separately trained networks too. `null` when the
    /// geometry cannot tell the two apart (e.g. a straight ramp).
    #[serde(default)]
    pub geometry_factor: Option<f64>,
    /// `ln(geometry_factor) / ln(td_ratio)`: 1 = scales with the interval, 0 = fixed clock.
    #[serde(default)]
    pub geometry_index: Option<f64>,
    /// R² of the geometry match at `geometry_factor`.
    #[serde(default)]
    pub geometry_r2: Option<f64>,
}

/// Neural summary of one population.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NeuralSummary {
    /// Model.
    pub model: String,
    /// Population analysed (`all` for every unit).
    pub population: String,
    /// Units analysed at the longest TD (constant units excluded).
    pub units: usize,
    /// Constant units excluded at the longest TD.
    pub constant_units: usize,
    /// The longest recorded TD (steps): the headline fields are its window's.
    pub td: u32,
    /// Its window (steps after oven-on).
    pub window: usize,
    /// Its trials.
    pub trials: usize,
    /// Its categories (`null` when undefined).
    pub categories: Option<CategorySummary>,
    /// Why they are undefined.
    pub undefined: Option<String>,
    /// Its sequentiality index.
    pub sequentiality: Option<f64>,
    /// Its ridge decoding error (steps).
    pub decode_ridge: Option<f64>,
    /// Its Bayesian decoding error (steps).
    pub decode_bayes: Option<f64>,
    /// Its basis-free dynamics signature ([`crate::neural::dynamics`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamics: Option<Dynamics>,
    /// Scaling between the shortest and the longest TD (two or more TDs recorded).
    pub scaling: Option<Scaling>,
    /// Every TD, shortest first.
    pub by_td: Vec<TdSummary>,
    /// Reproduction datasets: timing by speed after Set, per context (prior × gain;
    /// [`crate::neural::production`]); empty for the other tasks.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub production_speed: Vec<ProductionSpeed>,
}

/// One TD's window of a population: the cube of its varying units and their tests.
#[derive(Debug, Clone, PartialEq)]
pub struct TdClassification {
    /// Target duration (steps).
    pub td: u32,
    /// Window (steps).
    pub window: usize,
    /// `[trials, window, units]` of the population's varying units.
    pub cube: Cube,
    /// The trial average `[window, population size]` of every unit of the population.
    pub average_all: Vec<f64>,
    /// The trial average `[2 × window, population size]` of every unit: the window and the
    /// steps recorded after it (NaN where no trial reaches), for the dynamics signature.
    pub trajectory: Vec<f64>,
    /// Population size (all units).
    pub size: usize,
    /// Population index of each varying unit (column `j` of `cube`).
    pub varying: Vec<usize>,
    /// The category tests of the varying units.
    pub tests: Result<Vec<UnitTests>, CategoryError>,
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// TDs of the trials that turned the oven on, ascending.
pub fn recorded_tds(dataset: &ActivityDataset) -> Vec<u32> {
    recorded_oven_tds(dataset, 1)
}

/// Durations of oven `oven` (1 …) on the trials that turned it on, ascending (oven 1: the
/// trials' TDs; reproduction: the sample intervals of the trials that reached Set).
pub fn recorded_oven_tds(dataset: &ActivityDataset, oven: usize) -> Vec<u32> {
    let marker = alignment(dataset, oven);
    let gain = first_gain(dataset);
    let mut tds: Vec<u32> = dataset
        .trials
        .iter()
        .filter(|t| t.first(marker).is_some())
        .filter(|t| t.reproduction.map(|r| r.gain) == gain)
        .filter_map(|t| t.oven_td(oven))
        .collect();
    tds.sort_unstable();
    tds.dedup();
    tds
}

/// The event a population's windows start after: on reproduction trials Set (the window is
/// the production epoch, `td` its sample interval), otherwise the onset of the
/// population's oven.
fn alignment(dataset: &ActivityDataset, oven: usize) -> Marker {
    if dataset.trials.iter().any(|t| t.reproduction.is_some()) {
        Marker::Set
    } else {
        Marker::oven_on(oven)
    }
}

/// The lowest gain index among a reproduction dataset's trials (`None` for other tasks):
/// the unit categories use that gain's trials.
fn first_gain(dataset: &ActivityDataset) -> Option<u8> {
    dataset
        .trials
        .iter()
        .filter_map(|t| t.reproduction.map(|r| r.gain))
        .min()
}

/// Classifies the units of `population` (every unit when `None`) on the trials of TD `td`.
/// A multi-oven agent's population of oven k (`<name>_ovenk`, [`population_oven`]) is
/// classified on the trials whose oven k lasted `td`, aligned to that oven's onset. A
/// reproduction dataset is classified on its production epochs (aligned to Set, `td` =
/// `ts`) of the first gain it holds (a gain changes the production's length; its other
/// gains' speed is in [`NeuralSummary::production_speed`]).
pub fn classify_td(
    dataset: &ActivityDataset,
    population: Option<&str>,
    td: u32,
    opts: &SummaryOptions,
) -> Result<TdClassification, SummaryError> {
    let a = align_population(dataset, population, td, opts)?;
    let (full, cols, window, span) = (&a.full, &a.cols, a.window, a.span);
    let size = cols.len();
    let pick = |units: &[usize], time: usize| {
        let columns: Vec<usize> = units.iter().map(|&j| cols.start + j).collect();
        full.select(time, &columns)
    };
    let all: Vec<usize> = (0..size).collect();
    let average_all = pick(&all, window).average();
    let trajectory = pick(&all, (2 * window).min(span)).average();
    let varying: Vec<usize> = all
        .into_iter()
        .filter(|&j| {
            let (lo, hi) = crate::neural::finite_range(
                (0..full.trials())
                    .flat_map(|k| (0..window).map(move |t| (k, t)))
                    .map(|(k, t)| full.at(k, t, cols.start + j)),
            );
            hi - lo > 1e-9
        })
        .collect();
    let cube = pick(&varying, window);
    let mut cfg = opts.categories.clone();
    cfg.seed = cfg.seed.wrapping_add(u64::from(td));
    let tests = classify_units(&pick(&varying, span), window, &cfg);
    Ok(TdClassification {
        td,
        window,
        cube,
        average_all,
        trajectory,
        size,
        varying,
        tests,
    })
}

/// The trials of one TD of a population, aligned (see [`classify_td`]).
struct AlignedPopulation {
    /// `[trials, span, every unit of the dataset]`.
    full: Cube,
    /// The population's columns.
    cols: std::ops::Range<usize>,
    /// The window (steps).
    window: usize,
    /// Steps aligned (the window and the steps the category tests read after it).
    span: usize,
}

fn align_population(
    dataset: &ActivityDataset,
    population: Option<&str>,
    td: u32,
    opts: &SummaryOptions,
) -> Result<AlignedPopulation, SummaryError> {
    let n = dataset.meta.n_units();
    let cols = match population {
        Some(p) => dataset
            .meta
            .range(p)
            .ok_or_else(|| SummaryError::UnknownPopulation(p.into()))?,
        None => 0..n,
    };
    let oven = population.map_or(1, population_oven);
    let marker = alignment(dataset, oven);
    let gain = first_gain(dataset);
    let window = opts.window.unwrap_or(2 * td as usize).max(2);
    let sub = ActivityDataset {
        meta: dataset.meta.clone(),
        trials: dataset
            .trials
            .iter()
            .filter(|t| t.oven_td(oven) == Some(td))
            .filter(|t| t.reproduction.map(|r| r.gain) == gain)
            .cloned()
            .collect(),
    };
    // The category tests also read the steps after the window: the rhythm test up to
    // `rhythm_window`, the beyond-window test up to `EXTENDED_WINDOWS` windows.
    let span = (EXTENDED_WINDOWS * window).max(opts.categories.rhythm_window);
    let (aligned, used) = sub.aligned(marker, span - 1);
    if used.is_empty() {
        return Err(SummaryError::NoOvenOn);
    }
    Ok(AlignedPopulation {
        full: Cube::from_f32(&aligned, used.len(), span, n),
        cols,
        window,
        span,
    })
}

/// The dynamics signature alone of `population` on the trials of TD `td` (as
/// [`classify_td`] aligns them; no category tests): what [`TdSummary::dynamics`] holds.
pub fn population_dynamics(
    dataset: &ActivityDataset,
    population: Option<&str>,
    td: u32,
    opts: &SummaryOptions,
) -> Result<Dynamics, SummaryError> {
    let a = align_population(dataset, population, td, opts)?;
    let columns: Vec<usize> = a.cols.clone().collect();
    let trajectory = a
        .full
        .select((2 * a.window).min(a.span), &columns)
        .average();
    Ok(dynamics(&trajectory, columns.len(), a.window, td))
}

/// Mean distance per step of a `[time, units]` trajectory (rows with NaN skipped).
pub fn trajectory_speed(avg: &[f64], units: usize) -> Option<f64> {
    let rows: Vec<&[f64]> = avg
        .chunks_exact(units.max(1))
        .filter(|r| r.iter().all(|v| v.is_finite()))
        .collect();
    if rows.len() < 2 || units == 0 {
        return None;
    }
    let total: f64 = rows
        .windows(2)
        .map(|w| {
            w[0].iter()
                .zip(w[1])
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .sum();
    Some(total / (rows.len() - 1) as f64)
}

fn td_summary(c: &TdClassification) -> TdSummary {
    let u = c.cube.units();
    let avg = c.cube.average();
    let (categories, undefined) = match &c.tests {
        Ok(t) => (Some(CategorySummary::of(t)), None),
        Err(e) => (None, Some(e.to_string())),
    };
    let decode = |d| {
        (u > 0)
            .then(|| decode_time(&c.cube, d, 5, 1.0).mean_abs_error)
            .and_then(finite)
    };
    TdSummary {
        td: c.td,
        window: c.window,
        trials: c.cube.trials(),
        units: u,
        constant_units: c.size - u,
        categories,
        undefined,
        speed: trajectory_speed(&c.average_all, c.size),
        sequentiality: (u > 0)
            .then(|| sequentiality_index(&avg, u))
            .and_then(finite),
        decode_ridge: decode(Decoder::Ridge),
        decode_bayes: decode(Decoder::Bayes),
        dynamics: Some(dynamics(&c.trajectory, c.size, c.window, c.td)),
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    Some(if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    })
}

/// Per-unit scaling factors `(unit, s, R²)` between two TDs' windows of the same population
/// (units varying in both; time origin [`WINDOW_ORIGIN`]).
pub fn unit_scaling(short: &TdClassification, long: &TdClassification) -> Vec<(usize, f64, f64)> {
    let size = short.size.min(long.size);
    let col = |c: &TdClassification, j: usize| -> Vec<f64> {
        c.average_all
            .iter()
            .skip(j)
            .step_by(c.size)
            .copied()
            .take_while(|v| v.is_finite())
            .collect()
    };
    (0..size)
        .filter(|j| short.varying.contains(j) && long.varying.contains(j))
        .map(|j| {
            let (s, r2) = scaling_factor_from(&col(short, j), &col(long, j), WINDOW_ORIGIN);
            (j, s, r2)
        })
        .collect()
}

fn scaling(short: &TdClassification, long: &TdClassification, opts: &SummaryOptions) -> Scaling {
    let good: Vec<(usize, f64, f64)> = if opts.units_correspond {
        unit_scaling(short, long)
            .into_iter()
            .filter(|&(_, s, r2)| s.is_finite() && r2 >= MIN_SCALING_R2)
            .collect()
    } else {
        Vec::new()
    };
    let td_ratio = f64::from(long.td) / f64::from(short.td.max(1));
    let geometry = crate::neural::geometry::geometry_scaling(
        &short.average_all,
        short.size,
        &long.average_all,
        long.size,
        td_ratio,
        WINDOW_ORIGIN,
    );
    let common = short.window.min(long.window);
    let speed = |c: &TdClassification| trajectory_speed(&c.average_all[..common * c.size], c.size);
    Scaling {
        td_short: short.td,
        td_long: long.td,
        td_ratio,
        median: median(good.iter().map(|g| g.1).collect()),
        units: good.len(),
        median_r2: median(good.iter().map(|g| g.2).collect()),
        speed_ratio: match (speed(short), speed(long)) {
            (Some(a), Some(b)) if a > 0.0 => Some(b / a),
            _ => None,
        },
        geometry_factor: geometry.map(|g| g.factor),
        geometry_index: geometry.map(|g| g.index),
        geometry_r2: geometry.map(|g| g.r2),
    }
}

/// Summarises `population` (every unit when `None`) of `dataset`: one window per recorded
/// TD (`2 × TD` steps after oven-on unless `opts.window`), scaling between the shortest and
/// the longest TD when there are two or more.
pub fn neural_summary(
    dataset: &ActivityDataset,
    population: Option<&str>,
    opts: &SummaryOptions,
) -> Result<NeuralSummary, SummaryError> {
    let tds = recorded_oven_tds(dataset, population.map_or(1, population_oven));
    if tds.is_empty() {
        return Err(SummaryError::NoOvenOn);
    }
    let classes = tds
        .iter()
        .map(|&td| classify_td(dataset, population, td, opts))
        .collect::<Result<Vec<_>, _>>()?;
    let by_td: Vec<TdSummary> = classes.iter().map(td_summary).collect();
    let (first, last) = (&classes[0], &classes[classes.len() - 1]);
    let head = by_td[by_td.len() - 1].clone();
    Ok(NeuralSummary {
        model: dataset.meta.model.clone(),
        population: population.unwrap_or("all").to_string(),
        units: head.units,
        constant_units: head.constant_units,
        td: head.td,
        window: head.window,
        trials: head.trials,
        categories: head.categories,
        undefined: head.undefined,
        sequentiality: head.sequentiality,
        decode_ridge: head.decode_ridge,
        decode_bayes: head.decode_bayes,
        dynamics: head.dynamics,
        scaling: (classes.len() >= 2).then(|| scaling(first, last, opts)),
        by_td,
        production_speed: production_speed(dataset, population),
    })
}

/// The fraction of `cat` in a summary's categories (`None` when undefined or the
/// population is below [`MIN_UNITS_FOR_FRACTIONS`]).
pub fn fraction(s: &NeuralSummary, cat: crate::neural::categories::Category) -> Option<f64> {
    s.categories
        .as_ref()
        .and_then(|c| c.fractions.as_ref())
        .map(|f| f.get(cat))
}

/// Every category name, in report order.
pub fn category_names() -> Vec<&'static str> {
    CATEGORIES.iter().map(|c| c.name()).collect()
}
