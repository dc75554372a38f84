//! A basis-free signature of a population's dynamics: features of the trial-averaged
//! population trajectory that do not change when the units are mixed by any orthogonal
//! matrix `Q` (the same dynamics seen in another basis: `x'(t) = Q x(t)`).
//!
//! Every feature is a function of the trajectory's Gram matrix `K[s, t] = (x_s − m)·(x_t −
//! m)` (`m` the mean state over the window): inner products, and so distances and angles,
//! are what an orthogonal change of basis keeps (`(Qx)·(Qy) = x·y`). Nothing reads a single
//! unit. The unit categories (`ramp`, `time_field`, `oscillating`, …) are properties of
//! single units and do change under mixing; [`crate::neural::categories`] is the
//! basis-dependent *unit view*, this module the *dynamics view*.
//!
//! The trajectory is the trial average `[time, units]` aligned to oven-on: the window of
//! `2 × TD` steps (row 0 one step after the onset, as the summary's windows), then the
//! steps recorded after it (the out-of-trial probe: peak-interval probe trials go on past
//! the window). Features, with their known answers (tests in
//! `analysis/tests/dynamics_known_answers.rs`):
//!
//! * [`Dynamics::dimension`] — participation ratio `PR = (Σλ)² / Σλ²` of `K`'s eigenvalues
//!   over the window (Gao & Ganguli 2015; Litwin-Kumar et al. 2017), rescaled to
//!   `(PR − 1) / (T − 2)` for `T` window steps: 0 for a one-dimensional trajectory (a ramp,
//!   a line attractor), 1 when every step is a new orthogonal direction (a delay line of
//!   one-hot units). Orthogonal mixing only: a non-orthogonal invertible map reweights the
//!   eigenvalues.
//! * [`Dynamics::speed_trend`] — slope of `ln ‖x_{t+1} − x_t‖` on `ln t` (t = steps since
//!   the onset) over the window: 0 for a trajectory at constant speed (a ramp, oscillators,
//!   a delay line), ≈ −1 for a code of log-time (time cells whose fields widen in
//!   proportion to their delay: microstimuli; decaying traces: Laplace) (Howard et al.
//!   2014; Zhou, Masset & Gao 2023). Orthogonal only.
//! * [`Dynamics::turning`] — mean cosine between successive velocity vectors: 1 for a
//!   straight path, `cos ω` for one oscillator of `ω` rad/step, −½ for a delay line (each
//!   step leaves the last unit and enters the next). Orthogonal only.
//! * [`Dynamics::straightness`] — distance from the first to the last state of the window
//!   over the path length: 1 for a ramp, `1 / (T − 1)` for a delay line. Orthogonal only.
//! * [`Dynamics::continuation`] — mean speed over the steps after the window (up to one
//!   more window) over the mean speed in it: 1 for dynamics that go on (a limit cycle, an
//!   accumulator), 0 for a chain that ends with the interval or a slow point that holds the
//!   last state (Kurtkaya, Dinc et al. 2025: slow-point and limit-cycle mechanisms differ
//!   only after the trial). `None` when fewer than two steps are recorded after the
//!   window. Orthogonal only.
//! * [`Dynamics::spectral_radius`], [`Dynamics::rotation`] — the eigenvalues `λ` of an
//!   affine linear dynamics fit `z_{t+1} = A z_t + b` on the principal-component scores of
//!   the window's delay-embedded states `(x_t, x_{t−1})` (dynamic mode decomposition,
//!   Schmid 2010, on a Hankel embedding as in HAVOK, Brunton et al. 2017; the
//!   linear-operator part of DSA, Ostrow et al. 2023): the radius `max |λ|` (1 for an accumulator or an undamped
//!   oscillator, < 1 for decaying traces, ≈ 0 for a shift) and the rotation `Σ |λ| |arg λ|
//!   / Σ |λ|` in cycles per TD (`× TD / 2π`): 0 for ramps and decays, `ω · TD / 2π` for an
//!   oscillator. The fit uses every principal component (no truncation, whose choice
//!   inside a degenerate eigenspace would depend on the basis) with a ridge of
//!   [`RIDGE`] × the mean squared score: equivariant under orthogonal maps. Under an
//!   invertible map `M` the eigenvalues of an exactly determined fit (rank < T − 2) are
//!   those of `M A M⁻¹`, the same; the ridge makes that approximate, so the spectrum is
//!   stated and tested to survive invertible maps of condition number ≤ 10 only on
//!   low-dimensional trajectories (the tests say within what).
//!
//! A population whose window has fewer than [`MIN_STEPS`] finite steps, or that does not
//! move, has no signature (`None` fields).

use nalgebra::{DMatrix, SymmetricEigen};
use serde::{Deserialize, Serialize};

/// Fewest finite window steps for a signature (a slope needs three speeds, a turn two).
pub const MIN_STEPS: usize = 4;

/// Ridge of the linear dynamics fit, as a share of the mean squared principal-component
/// score: small enough that a determined fit keeps its eigenvalues (tests: 1e-3 of the
/// radius), large enough to make an underdetermined one (a delay line) unique.
pub const RIDGE: f64 = 1e-6;

/// Speeds below this share of the window's largest are treated as standing still (left
/// out of the log-slope and of the turning angles).
const STILL: f64 = 1e-9;

/// The basis-free signature of one population's trajectory (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct Dynamics {
    /// Window steps used (finite rows of the trial average, ≤ `2 × TD`).
    pub steps: usize,
    /// `(PR − 1) / (T − 2)`: 0 one-dimensional … 1 every step orthogonal.
    pub dimension: Option<f64>,
    /// Slope of ln speed on ln steps since the onset.
    pub speed_trend: Option<f64>,
    /// Mean cosine between successive velocities (−1 … 1).
    pub turning: Option<f64>,
    /// End-to-end distance over path length over the window (0 … 1).
    pub straightness: Option<f64>,
    /// Mean speed after the window over the mean speed in it.
    pub continuation: Option<f64>,
    /// Largest eigenvalue modulus of the linear dynamics fit.
    pub spectral_radius: Option<f64>,
    /// Modulus-weighted mean eigenvalue angle, in cycles per TD.
    pub rotation: Option<f64>,
}

/// The finite leading rows of a row-major `[time, units]` trajectory: rows up to the
/// first that holds a NaN.
fn finite_rows(traj: &[f64], units: usize) -> Vec<&[f64]> {
    traj.chunks_exact(units)
        .take_while(|r| r.iter().all(|v| v.is_finite()))
        .collect()
}

/// Gram matrix `[R, R]` of the rows centred on the mean of the first `window` rows.
fn centred_gram(rows: &[&[f64]], window: usize, units: usize) -> DMatrix<f64> {
    let mut mean = vec![0.0; units];
    for r in &rows[..window] {
        for (m, v) in mean.iter_mut().zip(r.iter()) {
            *m += v;
        }
    }
    mean.iter_mut().for_each(|m| *m /= window as f64);
    let centred: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| r.iter().zip(&mean).map(|(v, m)| v - m).collect())
        .collect();
    let n = rows.len();
    let mut k = DMatrix::zeros(n, n);
    for i in 0..n {
        for j in i..n {
            let d: f64 = centred[i].iter().zip(&centred[j]).map(|(a, b)| a * b).sum();
            k[(i, j)] = d;
            k[(j, i)] = d;
        }
    }
    k
}

/// Squared distance between states `i` and `j` from the Gram matrix.
fn dist2(k: &DMatrix<f64>, i: usize, j: usize) -> f64 {
    (k[(i, i)] + k[(j, j)] - 2.0 * k[(i, j)]).max(0.0)
}

/// `(x_{i+1} − x_i) · (x_{j+1} − x_j)` from the Gram matrix.
fn velocity_dot(k: &DMatrix<f64>, i: usize, j: usize) -> f64 {
    k[(i + 1, j + 1)] - k[(i + 1, j)] - k[(i, j + 1)] + k[(i, j)]
}

/// Least-squares slope of `y` on `x` (`None` below 3 points or without spread in `x`).
fn slope(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Gram matrix `[T − 1, T − 1]` of the delay-embedded states `(x_t, x_{t−1})`, t = 1 …
/// T − 1, centred on their mean (double centring), from the Gram matrix `kw` of the states.
fn embedded_gram(kw: &DMatrix<f64>) -> DMatrix<f64> {
    let n = kw.nrows() - 1;
    let e = DMatrix::from_fn(n, n, |i, j| kw[(i + 1, j + 1)] + kw[(i, j)]);
    let row_mean: Vec<f64> = (0..n).map(|i| e.row(i).sum() / n as f64).collect();
    let all = row_mean.iter().sum::<f64>() / n as f64;
    DMatrix::from_fn(n, n, |i, j| e[(i, j)] - row_mean[i] - row_mean[j] + all)
}

/// Eigenvalues (modulus, angle in rad) of the affine fit `z_{t+1} = A z_t + b` on the
/// principal-component scores of the delay-embedded window (Gram matrix `kw`, `[T, T]`).
///
/// The embedding `(x_t, x_{t−1})` (Hankel alternative view, Brunton et al. 2017) makes a
/// population that reads only part of a linear system's state (phase-reset cosines without
/// their sines) a linear system again; centring the embedded states leaves the intercept
/// `b` alone to carry a constant drift, so that a ramp's one direction has eigenvalue 1.
fn linear_spectrum(kw: &DMatrix<f64>) -> Option<Vec<(f64, f64)>> {
    let ke = embedded_gram(kw);
    let t = ke.nrows();
    let eig = SymmetricEigen::new(ke);
    let top = eig.eigenvalues.iter().copied().fold(0.0, f64::max);
    if top <= 0.0 || t < 3 {
        return None;
    }
    let keep: Vec<usize> = (0..t)
        .filter(|&i| eig.eigenvalues[i] > 1e-10 * top)
        .collect();
    let r = keep.len();
    // Scores z_t = U √Λ: the state's coordinates on the principal axes.
    let z = DMatrix::from_fn(t, r, |row, c| {
        let i = keep[c];
        eig.eigenvectors[(row, i)] * eig.eigenvalues[i].sqrt()
    });
    // X = [z_t, 1] for t < T − 1, Y = z_{t+1}.
    let x = DMatrix::from_fn(t - 1, r + 1, |row, c| if c < r { z[(row, c)] } else { 1.0 });
    let y = z.rows(1, t - 1).into_owned();
    let mean_sq = z.iter().map(|v| v * v).sum::<f64>() / (t * r) as f64;
    let mut gram = x.transpose() * &x;
    // The ridge shrinks the dynamics, not the intercept (whose column is 1 whatever the
    // activity's scale).
    for i in 0..r {
        gram[(i, i)] += RIDGE * mean_sq * (t - 1) as f64;
    }
    let b = gram.cholesky()?.solve(&(x.transpose() * y));
    // z_{t+1}ᵀ = z_tᵀ B[..r] + bᵀ: the dynamics matrix is B[..r]ᵀ (same eigenvalues).
    let a = b.rows(0, r).into_owned();
    let ev = a.complex_eigenvalues();
    Some(ev.iter().map(|c| (c.norm(), c.im.atan2(c.re))).collect())
}

/// The signature of a trial-averaged trajectory `traj` (row-major `[time, units]`, NaN rows
/// where no trial is recorded), whose first `window` rows are the `2 × TD` window after
/// the onset of a trial of TD `td` (steps).
pub fn dynamics(traj: &[f64], units: usize, window: usize, td: u32) -> Dynamics {
    if units == 0 {
        return Dynamics::default();
    }
    let rows = finite_rows(traj, units);
    let t = window.min(rows.len());
    let mut out = Dynamics {
        steps: t,
        ..Dynamics::default()
    };
    if t < MIN_STEPS {
        return out;
    }
    // Window plus at most one window after it.
    let span = rows.len().min(2 * window);
    let k = centred_gram(&rows[..span], t, units);
    let speeds: Vec<f64> = (0..span - 1).map(|i| dist2(&k, i, i + 1).sqrt()).collect();
    let inside = &speeds[..t - 1];
    let fastest = inside.iter().copied().fold(0.0, f64::max);
    if fastest <= 0.0 || !fastest.is_finite() {
        return out;
    }
    let moving = |s: f64| s > STILL * fastest;
    let kw = k.view((0, 0), (t, t)).into_owned();
    let trace = kw.trace();
    let frob2 = kw.iter().map(|v| v * v).sum::<f64>();
    if frob2 > 0.0 && t > 2 {
        let pr = trace * trace / frob2;
        out.dimension = Some(((pr - 1.0) / (t - 2) as f64).clamp(0.0, 1.0));
    }
    // Speed i joins rows i and i + 1: `i + 1.5` steps after the onset (row 0 is one step
    // after it).
    let points: Vec<(f64, f64)> = inside
        .iter()
        .enumerate()
        .filter(|(_, s)| moving(**s))
        .map(|(i, s)| ((i as f64 + 1.5).ln(), s.ln()))
        .collect();
    out.speed_trend = slope(&points);
    let cosines: Vec<f64> = (0..t.saturating_sub(2))
        .filter(|&i| moving(inside[i]) && moving(inside[i + 1]))
        .map(|i| (velocity_dot(&k, i, i + 1) / (inside[i] * inside[i + 1])).clamp(-1.0, 1.0))
        .collect();
    if !cosines.is_empty() {
        out.turning = Some(cosines.iter().sum::<f64>() / cosines.len() as f64);
    }
    let path: f64 = inside.iter().sum();
    out.straightness = Some((dist2(&k, 0, t - 1).sqrt() / path).clamp(0.0, 1.0));
    let after = &speeds[t - 1..];
    if after.len() >= 2 {
        let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
        out.continuation = Some(mean(after) / mean(inside));
    }
    if let Some(spectrum) = linear_spectrum(&kw) {
        let total: f64 = spectrum.iter().map(|(m, _)| m).sum();
        out.spectral_radius = spectrum.iter().map(|(m, _)| *m).reduce(f64::max);
        if total > 0.0 {
            let angle = spectrum.iter().map(|(m, a)| m * a.abs()).sum::<f64>() / total;
            out.rotation = Some(angle * f64::from(td) / std::f64::consts::TAU);
        }
    }
    out
}

/// The names and values of a signature's features, in table order (`None` = undefined).
pub fn features(d: &Dynamics) -> [(&'static str, Option<f64>); 7] {
    [
        ("dimension", d.dimension),
        ("speed_trend", d.speed_trend),
        ("turning", d.turning),
        ("straightness", d.straightness),
        ("continuation", d.continuation),
        ("spectral_radius", d.spectral_radius),
        ("rotation", d.rotation),
    ]
}
