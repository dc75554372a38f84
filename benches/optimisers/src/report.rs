//! Problem outcomes, timing and the markdown summary tables shared by the three studies.

use std::time::Instant;

/// Objective values below this count as this value in the crate/lab ratio, so that the
/// ratio of two numerically zero sums of squares (noise-free data) stays finite.
const OBJECTIVE_FLOOR: f64 = 1e-12;

/// What one solver returned on one problem.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Fitted parameters (in the problem's parameter order); `None` = no fit.
    pub params: Option<Vec<f64>>,
    /// The common objective at `params` (computed by the study, not by the solver).
    pub objective: f64,
    /// Objective evaluations the solver used, where they can be counted.
    pub evaluations: Option<usize>,
}

impl Outcome {
    /// No fit.
    pub fn failed(evaluations: Option<usize>) -> Self {
        Outcome {
            params: None,
            objective: f64::NAN,
            evaluations,
        }
    }
}

/// One synthetic problem: its row group, true parameters and every solver's outcome and
/// wall time (median seconds over the repeats).
pub struct Trial {
    /// Row group (noise level or generating observer).
    pub group: String,
    /// True parameters.
    pub truth: Vec<f64>,
    /// Outcome per solver (solver 0 is the lab's).
    pub outcomes: Vec<Outcome>,
    /// Median wall time per solver (seconds).
    pub seconds: Vec<f64>,
}

/// A solver of problems of type `P`.
pub type Solver<'a, P> = &'a dyn Fn(&P) -> Outcome;

/// Runs each solver `repeats` times in rotating order (solver `s` first on repeat `s`, …)
/// and keeps the first outcome and the median time of each.
pub fn interleaved<P>(
    repeats: usize,
    solvers: &[Solver<P>],
    problem: &P,
) -> (Vec<Outcome>, Vec<f64>) {
    let n = solvers.len();
    let mut outcomes: Vec<Option<Outcome>> = vec![None; n];
    let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(repeats); n];
    for rep in 0..repeats {
        for i in 0..n {
            let s = (i + rep) % n;
            let start = Instant::now();
            let out = std::hint::black_box(solvers[s](std::hint::black_box(problem)));
            times[s].push(start.elapsed().as_secs_f64());
            outcomes[s].get_or_insert(out);
        }
    }
    let outcomes = outcomes.into_iter().map(Option::unwrap).collect();
    let seconds = times.into_iter().map(|mut t| median(&mut t)).collect();
    (outcomes, seconds)
}

/// Median (NaN for an empty slice); sorts `v`.
pub fn median(v: &mut [f64]) -> f64 {
    quantile(v, 0.5)
}

/// Nearest-rank quantile (NaN for an empty slice); sorts `v`.
pub fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let rank = ((q * v.len() as f64).ceil() as usize).clamp(1, v.len());
    v[rank - 1]
}

/// How a study's table is laid out.
pub struct TableSpec<'a> {
    /// Solver names (index 0 = the lab's).
    pub solvers: &'a [&'a str],
    /// `(name, index)` of the parameters whose absolute errors get columns.
    pub shown: &'a [(&'a str, usize)],
    /// Whether a fit is within the stated tolerance of the truth.
    pub within: &'a dyn Fn(&Trial, &[f64]) -> bool,
    /// Time unit: `(label, seconds per unit)`.
    pub time_unit: (&'a str, f64),
    /// `(absolute, relative)`: a solver's objective counts as lower/higher than the lab's
    /// when they differ by more than `absolute + relative·|lab's|`.
    pub objective_gap: (f64, f64),
}

/// A number for a table cell.
fn fmt(x: f64) -> String {
    if x.is_nan() {
        "–".into()
    } else if x == 0.0 {
        "0".into()
    } else if x.abs() >= 1e4 || x.abs() < 1e-3 {
        format!("{x:.1e}")
    } else {
        format!("{x:.4}")
    }
}

/// A share as a percentage.
fn pct(num: usize, den: usize) -> String {
    if den == 0 {
        "–".into()
    } else {
        format!("{:.1} %", 100.0 * num as f64 / den as f64)
    }
}

/// Prints one markdown table: a row per (group, solver), then the groups together.
pub fn print_table(trials: &[Trial], spec: &TableSpec) {
    let mut groups: Vec<&str> = Vec::new();
    for t in trials {
        if !groups.contains(&t.group.as_str()) {
            groups.push(&t.group);
        }
    }
    let mut header = String::from("| data | solver | problems | solved | within tol |");
    for (name, _) in spec.shown {
        header += &format!(" median \\|Δ{name}\\| | p95 \\|Δ{name}\\| |");
    }
    header += &format!(
        " objective ratio vs lab (median) | objective lower / higher than lab | evaluations (median) | {} per fit (median) |",
        spec.time_unit.0
    );
    println!("{header}");
    let cols = 9 + 2 * spec.shown.len();
    println!("|{}", "---|".repeat(cols));
    let all = "all".to_string();
    for group in groups.iter().copied().chain([all.as_str()]) {
        let rows: Vec<&Trial> = trials
            .iter()
            .filter(|t| group == "all" || t.group == group)
            .collect();
        for (s, name) in spec.solvers.iter().enumerate() {
            print_row(group, name, s, &rows, spec);
        }
    }
    println!();
}

/// One table row: solver `s` on `rows`.
fn print_row(group: &str, name: &str, s: usize, rows: &[&Trial], spec: &TableSpec) {
    let solved: Vec<(&Trial, &[f64])> = rows
        .iter()
        .filter_map(|t| t.outcomes[s].params.as_deref().map(|p| (*t, p)))
        .collect();
    let within = solved.iter().filter(|(t, p)| (spec.within)(t, p)).count();
    let mut line = format!(
        "| {group} | {name} | {} | {} | {} |",
        rows.len(),
        pct(solved.len(), rows.len()),
        pct(within, rows.len())
    );
    for &(_, i) in spec.shown {
        let mut err: Vec<f64> = solved
            .iter()
            .map(|(t, p)| (p[i] - t.truth[i]).abs())
            .collect();
        line += &format!(
            " {} | {} |",
            fmt(median(&mut err)),
            fmt(quantile(&mut err, 0.95))
        );
    }
    // Objective against the lab's, on the problems both solved.
    let both: Vec<(f64, f64)> = rows
        .iter()
        .filter(|t| t.outcomes[0].params.is_some() && t.outcomes[s].params.is_some())
        .map(|t| (t.outcomes[s].objective, t.outcomes[0].objective))
        .collect();
    let mut ratio: Vec<f64> = both
        .iter()
        .map(|&(c, l)| c.max(OBJECTIVE_FLOOR) / l.max(OBJECTIVE_FLOOR))
        .collect();
    let gap = |l: f64| spec.objective_gap.0 + spec.objective_gap.1 * l.abs();
    let lower = both.iter().filter(|&&(c, l)| c < l - gap(l)).count();
    let higher = both.iter().filter(|&&(c, l)| c > l + gap(l)).count();
    let mut evals: Vec<f64> = rows
        .iter()
        .filter_map(|t| t.outcomes[s].evaluations.map(|e| e as f64))
        .collect();
    let mut time: Vec<f64> = rows
        .iter()
        .map(|t| t.seconds[s] / spec.time_unit.1)
        .collect();
    if s == 0 {
        line += " 1 (reference) | – |";
    } else {
        line += &format!(
            " {:.6} | {lower} / {higher} of {} |",
            median(&mut ratio),
            both.len()
        );
    }
    let evals = if evals.is_empty() {
        "n/a".to_string()
    } else {
        format!("{:.0}", median(&mut evals))
    };
    line += &format!(" {evals} | {} |", fmt(median(&mut time)));
    println!("{line}");
}
