//! The significance tests behind every verdict of `claims.csv`: a difference of means over
//! runs (2–8 runs a side) tested with Welch's t (Satterthwaite's degrees of freedom), and,
//! where every run of a side has the same value so that no variance can be estimated, the
//! exact randomisation test of the difference (two samples) or the exact sign-flip test
//! (one sample against a value).
//!
//! A normal z with threshold 2 is too lenient at these run counts: with 4 runs a side
//! Welch's df is about 3–6, whose two-sided 5% cut-off is 2.4–3.2, not 1.96.

use chronocooked_analysis::behaviour::aggregate::Spread;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Two-sided significance level of every test (`p < SIGNIFICANCE`: a difference).
pub const SIGNIFICANCE: f64 = 0.05;

/// Rewards are stored as `f32`: means closer than this are the same value (0.1 as `f32` is
/// 1.5e-9 above 0.1, which over a zero SD would read as a difference).
const SAME: f64 = 1e-6;

/// A difference of means over runs and its test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanTest {
    /// The difference `a − b` (or `a − value`), in the statistic's units; exactly 0 when the
    /// two are the same value.
    pub d: f64,
    /// Its standard error, `√(s_a²/n_a + s_b²/n_b)` (or `s_a/√n_a`); 0 when every run of
    /// each side has the same value (to within rounding, 1e-6).
    pub se: f64,
    /// Welch–Satterthwaite degrees of freedom (`n_a − 1` for one sample); NaN when `se` is 0.
    pub df: f64,
    /// `d / se` (±∞ for a difference with `se` 0; 0 for none).
    pub z: f64,
    /// Two-sided p: Student's t on `df`, or the exact test when `se` is 0.
    pub p: f64,
}

impl MeanTest {
    /// `a − b` over two sets of runs (`None` below two runs on a side).
    pub fn two_sample(a: &Spread, b: &Spread) -> Option<Self> {
        if a.n < 2 || b.n < 2 {
            return None;
        }
        let (va, vb) = (a.sd * a.sd / a.n as f64, b.sd * b.sd / b.n as f64);
        let df = (va + vb).powi(2) / (va * va / (a.n - 1) as f64 + vb * vb / (b.n - 1) as f64);
        // Every run of each side equal: the split of the runs into the two sides is the
        // most extreme of the C(n_a + n_b, n_a) equally likely splits, on either side.
        let exact = 2.0 / binomial(a.n + b.n, a.n);
        Some(Self::from_parts(
            a.mean - b.mean,
            (va + vb).sqrt(),
            df,
            exact,
        ))
    }

    /// `a − value` over one set of runs (`None` below two runs).
    pub fn one_sample(a: &Spread, value: f64) -> Option<Self> {
        if a.n < 2 {
            return None;
        }
        // Every run equal: all n signs agree, 2 of the 2ⁿ equally likely sign patterns.
        let exact = 2.0 * 0.5f64.powi(a.n as i32);
        Some(Self::from_parts(
            a.mean - value,
            a.sd / (a.n as f64).sqrt(),
            (a.n - 1) as f64,
            exact,
        ))
    }

    fn from_parts(d: f64, se: f64, df: f64, exact_p: f64) -> Self {
        let d = if d.abs() < SAME { 0.0 } else { d };
        // An SE this small is rounding in the SD of equal values (three equal f32 rewards can
        // give an SD of 1e-17), not a variance: the exact test decides.
        if se >= SAME && se.is_finite() {
            let z = d / se;
            let p = StudentsT::new(0.0, 1.0, df)
                .map_or(f64::NAN, |t| 2.0 * (1.0 - t.cdf(z.abs())))
                .min(1.0);
            Self { d, se, df, z, p }
        } else if d == 0.0 {
            Self {
                d,
                se: 0.0,
                df: f64::NAN,
                z: 0.0,
                p: 1.0,
            }
        } else {
            Self {
                d,
                se: 0.0,
                df: f64::NAN,
                z: d.signum() * f64::INFINITY,
                p: exact_p.min(1.0),
            }
        }
    }

    /// Whether the difference is significant (`p < SIGNIFICANCE`).
    pub fn significant(&self) -> bool {
        self.p < SIGNIFICANCE
    }

    /// Half-width of the two-sided `1 − SIGNIFICANCE` interval of `d`: `t(df) · se` (0 when
    /// `se` is 0).
    pub fn half_width(&self) -> f64 {
        if self.se == 0.0 {
            return 0.0;
        }
        StudentsT::new(0.0, 1.0, self.df)
            .map_or(f64::NAN, |t| t.inverse_cdf(1.0 - SIGNIFICANCE / 2.0))
            * self.se
    }
}

/// `C(n, k)` as a float (small n: run counts).
fn binomial(n: usize, k: usize) -> f64 {
    (0..k.min(n - k)).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}
