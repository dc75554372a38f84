//! Timing by speed: kinematic analysis of neural trajectories (KiNeT; Remington, Narain,
//! Hosseini & Jazayeri 2018, *Neuron* 98:1005, "Flexible sensorimotor computations through
//! rapid reconfiguration of cortical dynamics"; definitions checked against the public
//! jazlab/KiNeT code, reimplemented here).
//!
//! # Input
//!
//! One mean trajectory per condition: its sample interval `ts` (steps) and its states after
//! Set, `[T_i, N]` row-major (`T_i ≥ 2·edge_margin + 3` time steps — 5 by default — one
//! step apart, `t = 0` at Set; the same `N ≥ 1` dimensions — units or principal components
//! — in every condition). Options: [`SpeedOptions`] (reference, edge margin).
//!
//! # Definitions
//!
//! * **Reference.** By default the condition of middle `ts`: with conditions sorted by `ts`,
//!   index `⌊n/2⌋` (0-based), the upper middle for even `n` — KiNeT's
//!   `round(mean(1:n))` in 1-based MATLAB. Reference times are its steps `tr = 0..T_ref−1`.
//! * **Matched time and distance.** For every condition `i` and every `tr`, `t_i(tr)` is
//!   the time of minimum Euclidean distance between `x_i(t)` and `x_ref(tr)`. The discrete
//!   minimiser `k` (first on ties) is refined to sub-step precision by projecting
//!   `x_ref(tr)` on the two segments of the linearly interpolated trajectory that meet at
//!   `k` (`[k−1, k]` and `[k, k+1]`) and keeping the nearer projection. We prefer this to a
//!   parabola through the squared distances at `k−1, k, k+1`: it is exact for a
//!   piecewise-linear trajectory, returns `t = k` exactly when `x_ref(tr)` is a sample of
//!   `x_i` (a parabola is pulled off by unequal neighbouring steps), and the matched state
//!   `x_i(t_i)` (linear interpolation) then realises the reported minimum distance
//!   `‖x_ref(tr) − x_i(t_i(tr))‖`; for smooth, finely sampled curves the two agree to
//!   second order. When `k` is within `edge_margin` steps of the first or last step
//!   (default 1: the first two or last two steps; 0 = KiNeT's raw first/last step) the
//!   match **hits the boundary** (the condition has no interior state nearest to
//!   `x_ref(tr)`): no refinement, and the point is flagged ([`MatchKind::Start`] /
//!   [`MatchKind::End`]). The margin of 1 matters with noise: a condition that has run out
//!   of states otherwise keeps "matching" the reference's later states at its second-last
//!   sample whenever noise displaces its last one (over 40 random curves with noise of SD
//!   0.04 per entry this produced scaling-index errors up to 0.66 with margin 0, 0.15 with
//!   margin 1).
//! * **Matched window.** The points used for speed and distance are the interior matches
//!   strictly between the last start-boundary hit before the first end-boundary hit and
//!   that first end-boundary hit: once a condition's match reaches its end the
//!   reference has moved past the end of that condition, and a later interior match (some
//!   earlier state that happens to lie nearer, e.g. where the trajectory bends) is not a
//!   match in time; symmetrically for a condition that starts ahead of the reference. These
//!   are "the ends where the match hits the boundary", excluded.
//! * **Signed distance** (KiNeT's rule). The distance gets a sign from the direction of
//!   `x_ref(tr) − x_i(t_i)`: negative when it is closer in angle to the shortest
//!   condition's direction than to the longest's, positive when closer to the longest's,
//!   0 when equal or undefined (the reference itself, or an extreme condition that is the
//!   reference). Meaningful with ≥ 3 conditions.
//! * **Relative speed.** `t_i(tr)` grows as `tr·(speed_ref / speed_i)`: a condition that
//!   runs at half the reference's speed needs twice the time to reach the same states.
//!   The relative speed is the slope of `tr` against `t_i(tr)`, computed as `1/b` where `b`
//!   is the least-squares slope (with intercept) of `t_i` on `tr` over the matched window
//!   (above): the noise is in the matched times, so regressing them on the exact reference
//!   times avoids the errors-in-variables attenuation of the reverse regression (identical
//!   for noise-free data). Needs ≥ 3 such points and `b > 0`. The reference's speed is 1.
//! * **Scaling index.** `−` the least-squares slope of `ln speed_i` on `ln ts_i` over the
//!   conditions with a speed: 1 when the trajectories are time-stretched copies
//!   (`x_i(t) = g(t/ts_i)`, speed ∝ 1/ts), 0 for a fixed-speed clock (`x_i(t) = g(t)`
//!   truncated at `ts_i`), `α` for partial scaling (speed ∝ `ts^−α`).
//! * **Initial-condition order.** The `t = 0` states are projected on the axis from the
//!   shortest to the longest condition's `t = 0` state,
//!   `p_i = ⟨x_i(0) − x_S(0), u⟩ / ‖u‖²`, `u = x_L(0) − x_S(0)`; the order is the Spearman
//!   rank correlation (average ranks for ties) between `ts_i` and `p_i`. Undefined when
//!   `u = 0` (all conditions start together) or with < 3 conditions.
//! * **Distance order.** The Spearman rank correlation between `ts_i` and each condition's
//!   mean signed distance over its matched window (0 for the reference).
//!   Undefined with < 3 conditions or when the ranks are all tied; only meaningful when the
//!   distances exceed the noise in the trajectories.

/// A rejected input to the speed analysis.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpeedError {
    /// Fewer than two conditions.
    #[error("conditions has {got} entries; at least {min} needed")]
    TooFewConditions {
        /// How many were given.
        got: usize,
        /// How many are needed.
        min: usize,
    },
    /// A condition's `ts` is not a finite value > 0.
    #[error("condition {index}: ts must be finite and > 0 steps, got {value}")]
    BadTs {
        /// The condition's index.
        index: usize,
        /// Its `ts`.
        value: f64,
    },
    /// A condition has fewer time steps than an interior match needs (3).
    #[error("condition {index}: time has {time} steps; at least {min} needed")]
    TooShort {
        /// The condition's index.
        index: usize,
        /// Its number of time steps.
        time: usize,
        /// How many are needed.
        min: usize,
    },
    /// Zero dimensions, or dimensions differing from the first condition's.
    #[error("condition {index}: dims must be {expected} (≥ 1, as condition 0), got {dims}")]
    Dims {
        /// The condition's index.
        index: usize,
        /// Its dimensions.
        dims: usize,
        /// The required dimensions.
        expected: usize,
    },
    /// `states.len() != time × dims`.
    #[error("condition {index}: states has {len} values; time × dims = {expected}")]
    Shape {
        /// The condition's index.
        index: usize,
        /// `states.len()`.
        len: usize,
        /// `time × dims`.
        expected: usize,
    },
    /// A NaN or infinite state.
    #[error("condition {index}: state at t = {time}, dim {dim} is not finite")]
    NotFinite {
        /// The condition's index.
        index: usize,
        /// Time step.
        time: usize,
        /// Dimension.
        dim: usize,
    },
    /// A reference index that is not a condition.
    #[error("reference condition {index} out of range (0..{n})")]
    ReferenceOutOfRange {
        /// The requested index.
        index: usize,
        /// Number of conditions.
        n: usize,
    },
}

/// Minimum time steps of a trajectory beyond twice the edge margin: an interior step with
/// a neighbour on each side (`time ≥ 2·edge_margin + 3`).
pub const MIN_TIME: usize = 3;
/// Minimum non-boundary matched points for a relative speed.
pub const MIN_MATCHED: usize = 3;

/// One condition's mean trajectory after Set.
#[derive(Debug, Clone, PartialEq)]
pub struct ConditionTrajectory {
    /// Sample interval of the condition (steps, > 0).
    pub ts: f64,
    /// Time steps `T_i ≥ 3` (step 0 = Set).
    pub time: usize,
    /// Dimensions `N ≥ 1` (units or components), equal across conditions.
    pub dims: usize,
    /// States `[time, dims]` row-major.
    pub states: Vec<f64>,
}

impl ConditionTrajectory {
    fn state(&self, t: usize) -> &[f64] {
        &self.states[t * self.dims..(t + 1) * self.dims]
    }

    /// The state at fractional time `t ∈ [0, T−1]`, linearly interpolated.
    fn interpolate(&self, t: f64) -> Vec<f64> {
        let k = (t.floor() as usize).min(self.time - 2);
        let a = t - k as f64;
        let (x0, x1) = (self.state(k), self.state(k + 1));
        x0.iter().zip(x1).map(|(p, q)| p + a * (q - p)).collect()
    }
}

/// Options of the analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpeedOptions {
    /// The reference condition (default: the middle `ts`).
    pub reference: ReferenceChoice,
    /// Steps at each end of a condition's trajectory within which a discrete minimum counts
    /// as a boundary hit (default 1: the first two and last two steps). 0 is KiNeT's raw
    /// rule; 1 guards against a trajectory that has run out of states matching the
    /// reference's later states at its second-last sample when noise displaces the last.
    pub edge_margin: usize,
}

impl Default for SpeedOptions {
    fn default() -> Self {
        SpeedOptions {
            reference: ReferenceChoice::MiddleTs,
            edge_margin: 1,
        }
    }
}

/// Which condition is the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ReferenceChoice {
    /// The condition of middle `ts` (upper middle for an even count), as KiNeT.
    #[default]
    MiddleTs,
    /// The condition at this index of the input.
    Condition(usize),
}

/// The match of one reference time in one condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MatchPoint {
    /// Reference time `tr` (steps).
    pub t_ref: f64,
    /// Matched time `t_i(tr)` (steps, sub-step refined).
    pub time: f64,
    /// Minimum Euclidean distance (state units).
    pub distance: f64,
    /// The distance signed by KiNeT's rule (negative on the short side).
    pub signed_distance: f64,
    /// Whether the discrete minimum was interior or the condition's first or last step.
    pub kind: MatchKind,
    /// Whether the point lies in the matched window (used for speed and distance).
    pub used: bool,
}

/// Where the discrete minimum of the distance fell in the condition's trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MatchKind {
    /// An interior step (sub-step refined).
    Interior,
    /// The first step (`t = 0`): the boundary at the start.
    Start,
    /// The last step: the boundary at the end.
    End,
}

/// One condition's kinematics relative to the reference.
#[derive(Debug, Clone, PartialEq)]
pub struct ConditionKinematics {
    /// Sample interval (steps).
    pub ts: f64,
    /// One match per reference time (`T_ref` entries).
    pub matches: Vec<MatchPoint>,
    /// Matched points in the window (used for speed and distance).
    pub n_used: usize,
    /// Speed relative to the reference (`None` with < 3 points in the window or a
    /// non-positive slope).
    pub relative_speed: Option<f64>,
    /// Mean signed distance over the window (`None` when it is empty).
    pub mean_signed_distance: Option<f64>,
    /// Projection of the `t = 0` state on the shortest→longest axis (0 = shortest,
    /// 1 = longest; `None` when their `t = 0` states coincide).
    pub initial_projection: Option<f64>,
}

/// The KiNeT speed analysis of a set of conditions.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedAnalysis {
    /// Index (in the input) of the reference condition.
    pub reference: usize,
    /// Kinematics per condition, in input order.
    pub conditions: Vec<ConditionKinematics>,
    /// `−` slope of `ln speed` on `ln ts` (≈ 1 time-stretched, ≈ 0 fixed speed); `None`
    /// with < 2 distinct `ts` among the conditions with a speed.
    pub scaling_index: Option<f64>,
    /// Spearman correlation of `ts` with the initial-state projection.
    pub initial_order: Option<f64>,
    /// Spearman correlation of `ts` with the mean signed distance.
    pub distance_order: Option<f64>,
}

/// Runs the analysis (see the module documentation for every definition).
pub fn kinet_speed(
    conditions: &[ConditionTrajectory],
    options: SpeedOptions,
) -> Result<SpeedAnalysis, SpeedError> {
    validate(conditions, options.edge_margin)?;
    let n = conditions.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| conditions[a].ts.total_cmp(&conditions[b].ts));
    let (shortest, longest) = (order[0], order[n - 1]);
    let r = match options.reference {
        ReferenceChoice::MiddleTs => order[n / 2],
        ReferenceChoice::Condition(index) if index < n => index,
        ReferenceChoice::Condition(index) => {
            return Err(SpeedError::ReferenceOutOfRange { index, n });
        }
    };
    let reference = &conditions[r];
    let mut matches: Vec<Vec<MatchPoint>> = vec![Vec::with_capacity(reference.time); n];
    for tr in 0..reference.time {
        let x_ref = reference.state(tr);
        // Matched time, boundary flag and difference vector x_ref − x_i(t_i) per condition.
        let found: Vec<(f64, MatchKind, Vec<f64>)> = conditions
            .iter()
            .map(|c| {
                let (time, kind) = nearest_time(c, x_ref, options.edge_margin);
                let xi = c.interpolate(time);
                let diff = x_ref.iter().zip(&xi).map(|(a, b)| a - b).collect();
                (time, kind, diff)
            })
            .collect();
        let (dir_short, dir_long) = (&found[shortest].2, &found[longest].2);
        for (i, (time, kind, diff)) in found.iter().enumerate() {
            let distance = norm(diff);
            let cos_short = cosine(dir_short, diff);
            let cos_long = cosine(dir_long, diff);
            // Smaller angle = larger cosine; NaN (undefined direction) compares false → 0.
            let signed_distance = if cos_short > cos_long {
                -distance
            } else if cos_short < cos_long {
                distance
            } else {
                0.0
            };
            matches[i].push(MatchPoint {
                t_ref: tr as f64,
                time: *time,
                distance,
                signed_distance: if i == r { 0.0 } else { signed_distance },
                kind: *kind,
                used: false,
            });
        }
    }

    let x_short0 = conditions[shortest].state(0);
    let axis: Vec<f64> = conditions[longest]
        .state(0)
        .iter()
        .zip(x_short0)
        .map(|(l, s)| l - s)
        .collect();
    let axis_sq: f64 = axis.iter().map(|a| a * a).sum();
    let scale = conditions
        .iter()
        .flat_map(|c| c.state(0).iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let axis_defined = axis_sq.sqrt() > 1e-12 * (1.0 + scale);

    let kinematics: Vec<ConditionKinematics> = conditions
        .iter()
        .zip(matches)
        .map(|(c, mut matches)| {
            mark_window(&mut matches);
            let interior: Vec<&MatchPoint> = matches.iter().filter(|m| m.used).collect();
            let relative_speed = if interior.len() >= MIN_MATCHED {
                let xs: Vec<f64> = interior.iter().map(|m| m.t_ref).collect();
                let ys: Vec<f64> = interior.iter().map(|m| m.time).collect();
                ols_slope(&xs, &ys).filter(|b| *b > 0.0).map(|b| 1.0 / b)
            } else {
                None
            };
            let mean_signed_distance = (!interior.is_empty()).then(|| {
                interior.iter().map(|m| m.signed_distance).sum::<f64>() / interior.len() as f64
            });
            let initial_projection = axis_defined.then(|| {
                c.state(0)
                    .iter()
                    .zip(x_short0)
                    .zip(&axis)
                    .map(|((x, s), a)| (x - s) * a)
                    .sum::<f64>()
                    / axis_sq
            });
            ConditionKinematics {
                ts: c.ts,
                n_used: interior.len(),
                matches,
                relative_speed,
                mean_signed_distance,
                initial_projection,
            }
        })
        .collect();

    let (log_ts, log_speed): (Vec<f64>, Vec<f64>) = kinematics
        .iter()
        .filter_map(|k| k.relative_speed.map(|s| (k.ts.ln(), s.ln())))
        .unzip();
    let scaling_index = ols_slope(&log_ts, &log_speed).map(|b| -b);
    let ts: Vec<f64> = kinematics.iter().map(|k| k.ts).collect();
    let initial_order = if axis_defined && n >= 3 {
        let p: Vec<f64> = kinematics
            .iter()
            .filter_map(|k| k.initial_projection)
            .collect();
        spearman(&ts, &p)
    } else {
        None
    };
    let (ts_d, dist): (Vec<f64>, Vec<f64>) = kinematics
        .iter()
        .filter_map(|k| k.mean_signed_distance.map(|d| (k.ts, d)))
        .unzip();
    let distance_order = if ts_d.len() >= 3 {
        spearman(&ts_d, &dist)
    } else {
        None
    };
    Ok(SpeedAnalysis {
        reference: r,
        conditions: kinematics,
        scaling_index,
        initial_order,
        distance_order,
    })
}

fn validate(conditions: &[ConditionTrajectory], edge_margin: usize) -> Result<(), SpeedError> {
    let min_time = MIN_TIME.saturating_add(edge_margin.saturating_mul(2));
    if conditions.len() < 2 {
        return Err(SpeedError::TooFewConditions {
            got: conditions.len(),
            min: 2,
        });
    }
    let expected = conditions[0].dims;
    for (index, c) in conditions.iter().enumerate() {
        if !(c.ts.is_finite() && c.ts > 0.0) {
            return Err(SpeedError::BadTs { index, value: c.ts });
        }
        if c.dims == 0 || c.dims != expected {
            return Err(SpeedError::Dims {
                index,
                dims: c.dims,
                expected: expected.max(1),
            });
        }
        if c.time < min_time {
            return Err(SpeedError::TooShort {
                index,
                time: c.time,
                min: min_time,
            });
        }
        let want = c.time.saturating_mul(c.dims);
        if c.states.len() != want {
            return Err(SpeedError::Shape {
                index,
                len: c.states.len(),
                expected: want,
            });
        }
        if let Some(p) = c.states.iter().position(|v| !v.is_finite()) {
            return Err(SpeedError::NotFinite {
                index,
                time: p / c.dims,
                dim: p % c.dims,
            });
        }
    }
    Ok(())
}

/// Marks the matched window: interior matches after the last start hit that precedes the
/// first end hit, and before that end hit.
fn mark_window(matches: &mut [MatchPoint]) {
    let end = matches
        .iter()
        .position(|m| m.kind == MatchKind::End)
        .unwrap_or(matches.len());
    let start = matches[..end]
        .iter()
        .rposition(|m| m.kind == MatchKind::Start)
        .map_or(0, |p| p + 1);
    for m in &mut matches[start..end] {
        m.used = m.kind == MatchKind::Interior;
    }
}

/// The sub-step time of minimum distance from `x` to `c`, and where the discrete minimum
/// fell (within `margin` steps of an end = a boundary hit).
fn nearest_time(c: &ConditionTrajectory, x: &[f64], margin: usize) -> (f64, MatchKind) {
    let d2 = |t: usize| -> f64 {
        c.state(t)
            .iter()
            .zip(x)
            .map(|(a, b)| (a - b) * (a - b))
            .sum()
    };
    let mut k = 0;
    let mut best = d2(0);
    for t in 1..c.time {
        let d = d2(t);
        if d < best {
            k = t;
            best = d;
        }
    }
    if k <= margin {
        return (k as f64, MatchKind::Start);
    }
    if k + 1 + margin >= c.time {
        return (k as f64, MatchKind::End);
    }
    // Project x on the segments [k−1, k] and [k, k+1]; keep the nearer point.
    let project = |from: usize, to: usize| -> (f64, f64) {
        let (p, q) = (c.state(from), c.state(to));
        let seg: f64 = p.iter().zip(q).map(|(a, b)| (b - a) * (b - a)).sum();
        let along: f64 = p
            .iter()
            .zip(q)
            .zip(x)
            .map(|((a, b), y)| (y - a) * (b - a))
            .sum();
        let s = if seg > 0.0 {
            (along / seg).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let dist2: f64 = p
            .iter()
            .zip(q)
            .zip(x)
            .map(|((a, b), y)| (a + s * (b - a) - y).powi(2))
            .sum();
        (from as f64 + s, dist2)
    };
    let (t0, e0) = project(k - 1, k);
    let (t1, e1) = project(k, k + 1);
    (if e1 < e0 { t1 } else { t0 }, MatchKind::Interior)
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Cosine of the angle between `a` and `b` (NaN when either is zero).
fn cosine(a: &[f64], b: &[f64]) -> f64 {
    let dot: f64 = a.iter().zip(b).map(|(p, q)| p * q).sum();
    let (na, nb) = (norm(a), norm(b));
    if na > 0.0 && nb > 0.0 {
        dot / (na * nb)
    } else {
        f64::NAN
    }
}

/// Least-squares slope (with intercept) of `y` on `x`; `None` with < 2 points or no spread
/// in `x`.
fn ols_slope(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len() as f64;
    if x.len() < 2 || x.len() != y.len() {
        return None;
    }
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    (sxx > 1e-12 * (1.0 + mx * mx) * n).then(|| sxy / sxx)
}

/// Ranks `1..=n` with ties given their average rank.
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..v.len()).collect();
    idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < idx.len() {
        let mut j = i;
        while j + 1 < idx.len() && v[idx[j + 1]] == v[idx[i]] {
            j += 1;
        }
        let avg = (i + j) as f64 / 2.0 + 1.0;
        for &k in &idx[i..=j] {
            r[k] = avg;
        }
        i = j + 1;
    }
    r
}

/// Spearman's rank correlation (Pearson correlation of average ranks) of `x` and `y`;
/// `None` with < 2 pairs, different lengths or all-tied ranks in either.
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() < 2 || x.len() != y.len() {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let n = rx.len() as f64;
    let m = (n + 1.0) / 2.0;
    let sxy: f64 = rx.iter().zip(&ry).map(|(a, b)| (a - m) * (b - m)).sum();
    let sxx: f64 = rx.iter().map(|a| (a - m) * (a - m)).sum();
    let syy: f64 = ry.iter().map(|b| (b - m) * (b - m)).sum();
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranks_and_spearman_by_hand() {
        assert_eq!(ranks(&[3.0, 1.0, 3.0, 2.0]), vec![3.5, 1.0, 3.5, 2.0]);
        // Reversed order: −1; monotone non-linear: +1; all tied: undefined.
        assert_eq!(spearman(&[1.0, 2.0, 3.0], &[9.0, 4.0, 1.0]), Some(-1.0));
        assert_eq!(
            spearman(&[1.0, 2.0, 3.0, 4.0], &[1.0, 8.0, 27.0, 64.0]),
            Some(1.0)
        );
        assert_eq!(spearman(&[1.0, 2.0, 3.0], &[5.0, 5.0, 5.0]), None);
        // x = 1..4, y = 1,3,2,4: ranks differ by (0,1,−1,0), ρ = 1 − 6·2/(4·15) = 0.8.
        let r = spearman(&[1.0, 2.0, 3.0, 4.0], &[1.0, 3.0, 2.0, 4.0]).unwrap();
        assert!((r - 0.8).abs() < 1e-12);
    }

    #[test]
    fn segment_refinement_recovers_a_sub_step_minimum() {
        // A straight line through 1-D states 0, 1, 2, …; the nearest point to 2.3 is at
        // t = 2.3.
        let c = ConditionTrajectory {
            ts: 1.0,
            time: 6,
            dims: 1,
            states: (0..6).map(f64::from).collect(),
        };
        let (t, k) = nearest_time(&c, &[2.3], 0);
        assert!(k == MatchKind::Interior && (t - 2.3).abs() < 1e-12, "{t}");
        assert_eq!(nearest_time(&c, &[-4.0], 0), (0.0, MatchKind::Start));
        assert_eq!(nearest_time(&c, &[9.0], 0), (5.0, MatchKind::End));
        // With an edge margin of 1 the second and second-last steps are boundary hits.
        assert_eq!(nearest_time(&c, &[1.2], 1), (1.0, MatchKind::Start));
        assert_eq!(nearest_time(&c, &[3.9], 1), (4.0, MatchKind::End));
        assert_eq!(nearest_time(&c, &[2.3], 1).1, MatchKind::Interior);
        // A corner (0,0) → (1,0) → (1,1) → (1,2): the point (0.6, 0.2) projects on the
        // first segment at 0.6 (distance 0.2) rather than the second (distance 0.4).
        let c = ConditionTrajectory {
            ts: 1.0,
            time: 4,
            dims: 2,
            states: vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 2.0],
        };
        let (t, k) = nearest_time(&c, &[0.6, 0.2], 0);
        assert!(k == MatchKind::Interior && (t - 0.6).abs() < 1e-12, "{t}");
        // A sample of the trajectory matches exactly at its own time.
        let (t, _) = nearest_time(&c, &[1.0, 1.0], 0);
        assert_eq!(t, 2.0);
    }
}

#[cfg(test)]
mod window_tests {
    use super::*;

    fn point(kind: MatchKind) -> MatchPoint {
        MatchPoint {
            t_ref: 0.0,
            time: 0.0,
            distance: 0.0,
            signed_distance: 0.0,
            kind,
            used: false,
        }
    }

    #[test]
    fn window_runs_from_the_last_start_hit_to_the_first_end_hit() {
        use MatchKind::{End as E, Interior as I, Start as S};
        // A bogus interior match before the start hits and after the first end hit.
        let kinds = [I, S, S, I, I, S, I, I, E, I, E, I];
        let mut m: Vec<MatchPoint> = kinds.iter().map(|&k| point(k)).collect();
        mark_window(&mut m);
        let used: Vec<usize> = (0..m.len()).filter(|&i| m[i].used).collect();
        assert_eq!(used, vec![6, 7]);
        // No boundary hits at all: everything is used.
        let mut m: Vec<MatchPoint> = [I, I, I].iter().map(|&k| point(k)).collect();
        mark_window(&mut m);
        assert!(m.iter().all(|p| p.used));
    }
}
