//! A bounded 2-D minimiser: a coarse grid, then Nelder–Mead from the best grid point,
//! restarted once from its result. Candidate points outside the box are projected onto it
//! (clamped coordinate-wise). Non-finite objective values count as `+∞`.
//!
//! Not `argmin`'s Nelder–Mead: measured 2026-12-03 (`benches/optimisers`, 240 observer fits
//! to synthetic data with known parameters), the grid plus argmin reaches the same objective
//! on all 240 (within 1e-6 log-units) with a similar number of evaluations (median 204 vs
//! 211); argmin has no bounds or grid, so the box and the grid would stay here, and without
//! the grid it ends higher on 3 of 80 maximum-likelihood fits.

/// Grid points per axis of the coarse search.
pub(crate) const GRID: usize = 9;
/// Nelder–Mead stops when the simplex's objective values agree to this (absolute) …
const F_TOL: f64 = 1e-8;
/// … and its vertices to this (per coordinate), or when it is this small whatever the values.
const X_TOL: f64 = 1e-5;
/// Iteration cap per Nelder–Mead run.
const MAX_ITER: usize = 400;

/// The minimiser's result.
pub(crate) struct Optimum {
    /// The minimising point.
    pub x: [f64; 2],
    /// The objective there.
    pub value: f64,
    /// Objective evaluations used.
    pub evaluations: usize,
}

/// Minimises `f` over the box `[lo, hi]` (coordinate-wise, `lo < hi`).
pub(crate) fn minimise_box(f: impl FnMut([f64; 2]) -> f64, lo: [f64; 2], hi: [f64; 2]) -> Optimum {
    let mut f = f;
    let mut evaluations = 0;
    let mut eval = |x: [f64; 2]| {
        evaluations += 1;
        let v = f(x);
        if v.is_finite() { v } else { f64::INFINITY }
    };
    let step = [
        (hi[0] - lo[0]) / (GRID - 1) as f64,
        (hi[1] - lo[1]) / (GRID - 1) as f64,
    ];
    let (mut best, mut best_v) = (lo, f64::INFINITY);
    for i in 0..GRID {
        for j in 0..GRID {
            let x = [lo[0] + step[0] * i as f64, lo[1] + step[1] * j as f64];
            let v = eval(x);
            if v < best_v {
                best = x;
                best_v = v;
            }
        }
    }
    let (x1, v1) = nelder_mead(&mut eval, best, [0.5 * step[0], 0.5 * step[1]], lo, hi);
    let (x2, v2) = nelder_mead(&mut eval, x1, [0.05 * step[0], 0.05 * step[1]], lo, hi);
    let (x, value) = if v2 <= v1 { (x2, v2) } else { (x1, v1) };
    let (x, value) = if best_v < value {
        (best, best_v)
    } else {
        (x, value)
    };
    Optimum {
        x,
        value,
        evaluations,
    }
}

fn clamp(x: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> [f64; 2] {
    [x[0].clamp(lo[0], hi[0]), x[1].clamp(lo[1], hi[1])]
}

/// `a + t·(b − a)`.
fn along(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Standard Nelder–Mead (reflection 1, expansion 2, contraction ½, shrink ½) in the box.
fn nelder_mead(
    f: &mut impl FnMut([f64; 2]) -> f64,
    x0: [f64; 2],
    step: [f64; 2],
    lo: [f64; 2],
    hi: [f64; 2],
) -> ([f64; 2], f64) {
    let mut simplex: Vec<([f64; 2], f64)> = Vec::with_capacity(3);
    simplex.push((x0, f(x0)));
    for d in 0..2 {
        let mut x = x0;
        // Step inwards when the outward step would leave the box.
        x[d] = if x0[d] + step[d] <= hi[d] {
            x0[d] + step[d]
        } else {
            x0[d] - step[d]
        };
        let x = clamp(x, lo, hi);
        simplex.push((x, f(x)));
    }
    for _ in 0..MAX_ITER {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let spread_f = simplex[2].1 - simplex[0].1;
        let spread_x = (1..3)
            .flat_map(|i| (0..2).map(move |d| (i, d)))
            .map(|(i, d)| (simplex[i].0[d] - simplex[0].0[d]).abs())
            .fold(0.0, f64::max);
        if (spread_f <= F_TOL && spread_x <= X_TOL) || spread_x <= 1e-3 * X_TOL {
            break;
        }
        let (best, worst) = (simplex[0], simplex[2]);
        let centroid = along(simplex[0].0, simplex[1].0, 0.5);
        let xr = clamp(along(centroid, worst.0, -1.0), lo, hi);
        let fr = f(xr);
        if fr < best.1 {
            let xe = clamp(along(centroid, worst.0, -2.0), lo, hi);
            let fe = f(xe);
            simplex[2] = if fe < fr { (xe, fe) } else { (xr, fr) };
            continue;
        }
        if fr < simplex[1].1 {
            simplex[2] = (xr, fr);
            continue;
        }
        let (xc, fc) = if fr < worst.1 {
            let xc = clamp(along(centroid, xr, 0.5), lo, hi);
            (xc, f(xc))
        } else {
            let xc = clamp(along(centroid, worst.0, 0.5), lo, hi);
            (xc, f(xc))
        };
        if fc < fr.min(worst.1) {
            simplex[2] = (xc, fc);
            continue;
        }
        for vertex in simplex.iter_mut().skip(1) {
            let x = along(best.0, vertex.0, 0.5);
            *vertex = (x, f(x));
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    simplex[0]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_interior_and_boundary_minima() {
        // Rosenbrock-like valley with its minimum inside the box.
        let o = minimise_box(
            |x| (1.0 - x[0]).powi(2) + 20.0 * (x[1] - x[0] * x[0]).powi(2),
            [-2.0, -2.0],
            [2.0, 2.0],
        );
        assert!(
            (o.x[0] - 1.0).abs() < 1e-3 && (o.x[1] - 1.0).abs() < 2e-3,
            "{:?}",
            o.x
        );
        // Minimum outside the box: the constrained minimum is on the edge x = 0.5.
        let o = minimise_box(
            |x| (x[0] - 3.0).powi(2) + (x[1] + 0.2).powi(2),
            [-1.0, -1.0],
            [0.5, 1.0],
        );
        assert!(
            (o.x[0] - 0.5).abs() < 1e-6 && (o.x[1] + 0.2).abs() < 1e-3,
            "{:?}",
            o.x
        );
    }
}
