//! Known answers for the temporal-reproduction (Ready–Set–Go) observers of Jazayeri &
//! Shadlen (2010): every expected value here is derived independently — by hand, in closed
//! form, or by a trapezoid integral written in this file — never copied from the library's
//! output.
//!
//! * BLS: slope, BIAS and VAR of the predicted productions equal a by-hand trapezoid
//!   integral over the measurement (and differ measurably if the likelihood's `1/(wm·ts)`
//!   factor is dropped, so the comparison can fail);
//! * ML: the estimate is the brute-force maximiser of the likelihood over the positive
//!   line, `E[te|ts] = c·ts` with `c = (−1 + √(1 + 4wm²))/(2wm²)`, and `Var[tp|ts]` has a
//!   closed form;
//! * MAP: every estimate is a prior value (the support's likelihood argmax), and its mean
//!   equals a by-hand integral of that step function;
//! * simulated data with known `(wm, wp)` are recovered within 10 % and the fit picks the
//!   generating observer (`reproduction_recovery.rs`);
//! * simulated summaries converge to the predicted ones;
//! * the summary formulas on a tiny data set worked by hand;
//! * bad input gives typed errors naming the field.

use chronocooked_analysis::reproduction::{
    Observer, ObserverError, Prior, Record, Rounding, TsMoments, W_MAX, W_MIN, fit_observers,
    log_likelihood, ml_gain, predict, predict_at, predicted_summary, simulate, summarize,
    summary_from_moments,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

// ---------------------------------------------------------------------------------------
// Independent by-hand machinery (does not call the library's estimators or integrator).
// ---------------------------------------------------------------------------------------

/// The BLS estimate written out: `Σ s·p(tm|s) / Σ p(tm|s)` with the scalar density
/// `p(tm|s) = exp(−(tm − s)²/(2 wm² s²)) / (√(2π)·wm·s)`; `normalised = false` drops the
/// `1/(wm·s)` factor (the mistake the comparison must be able to detect).
fn by_hand_bls(tm: f64, wm: f64, values: &[f64], normalised: bool) -> f64 {
    let expo: Vec<f64> = values
        .iter()
        .map(|&s| -(tm - s).powi(2) / (2.0 * wm * wm * s * s))
        .collect();
    let top = expo.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let (mut num, mut den) = (0.0, 0.0);
    for (&s, &e) in values.iter().zip(&expo) {
        let dens = (e - top).exp() / if normalised { wm * s } else { 1.0 };
        num += s * dens;
        den += dens;
    }
    num / den
}

/// `(E[g(tm)], E[g(tm)²])` for `tm ~ N(ts, (wm·ts)²)` by the trapezoid rule on
/// `[ts − 10σ, ts + 10σ]` with 40 000 intervals.
fn trapezoid_moments(ts: f64, wm: f64, g: impl Fn(f64) -> f64) -> (f64, f64) {
    let sigma = wm * ts;
    let n = 40_000;
    let (a, b) = (ts - 10.0 * sigma, ts + 10.0 * sigma);
    let h = (b - a) / n as f64;
    let (mut m1, mut m2, mut mass) = (0.0, 0.0, 0.0);
    for i in 0..=n {
        let tm = a + h * i as f64;
        let end = if i == 0 || i == n { 0.5 } else { 1.0 };
        let w = end * h * (-(tm - ts).powi(2) / (2.0 * sigma * sigma)).exp()
            / (sigma * (2.0 * std::f64::consts::PI).sqrt());
        let v = g(tm);
        m1 += w * v;
        m2 += w * v * v;
        mass += w;
    }
    (m1 / mass, m2 / mass)
}

/// Ordinary least-squares slope of `y` on `x`.
fn ols_slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

/// By-hand (slope, BIAS, VAR) of continuous BLS productions over a prior.
fn by_hand_bls_summary(wm: f64, wp: f64, values: &[f64], normalised: bool) -> (f64, f64, f64) {
    let moments: Vec<(f64, f64)> = values
        .iter()
        .map(|&ts| trapezoid_moments(ts, wm, |tm| by_hand_bls(tm, wm, values, normalised)))
        .collect();
    let means: Vec<f64> = moments.iter().map(|m| m.0).collect();
    // Var[tp] = E[te²](1 + wp²) − E[te]²   (tp = te + wp·te·ε).
    let vars: Vec<f64> = moments
        .iter()
        .map(|&(m1, m2)| m2 * (1.0 + wp * wp) - m1 * m1)
        .collect();
    let k = values.len() as f64;
    let bias = (means
        .iter()
        .zip(values)
        .map(|(m, t)| (m - t).powi(2))
        .sum::<f64>()
        / k)
        .sqrt();
    (
        ols_slope(values, &means),
        bias,
        vars.iter().sum::<f64>() / k,
    )
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-300)
}

// ---------------------------------------------------------------------------------------
// BLS against a by-hand integral.
// ---------------------------------------------------------------------------------------

#[test]
fn bls_slope_bias_and_var_equal_a_by_hand_integral() {
    let cases: [(f64, f64, &[f64]); 3] = [
        (0.15, 0.08, &[18.0, 22.0, 26.0, 30.0, 34.0, 38.0]),
        (0.25, 0.05, &[10.0, 13.0, 17.0, 22.0]),
        // Small wm and spacing comparable to wm·ts: a near-step BLS.
        (0.05, 0.1, &[40.0, 44.0, 48.0, 52.0]),
    ];
    for (wm, wp, values) in cases {
        let prior = Prior::new(values).unwrap();
        let lib = predicted_summary(Observer::Bls, wm, wp, &prior, Rounding::None).unwrap();
        let (slope, bias, var) = by_hand_bls_summary(wm, wp, values, true);
        assert!(
            (lib.slope - slope).abs() < 1e-6,
            "wm {wm}: slope {} vs {slope}",
            lib.slope
        );
        assert!(
            rel(lib.bias, bias) < 1e-6,
            "wm {wm}: BIAS {} vs {bias}",
            lib.bias
        );
        assert!(
            rel(lib.var, var) < 1e-6,
            "wm {wm}: VAR {} vs {var}",
            lib.var
        );
        assert!((lib.rmse - (bias * bias + var).sqrt()).abs() < 1e-5);
        // Regression to the mean: slope < 1 (J&S Fig. 2).
        assert!(lib.slope < 1.0 && lib.slope > 0.0);
        // The comparison is sensitive: without the 1/(wm·ts) factor the BIAS differs by far
        // more than the tolerance.
        let (_, bias_unnorm, _) = by_hand_bls_summary(wm, wp, values, false);
        assert!(
            rel(bias_unnorm, bias) > 1e-3,
            "wm {wm}: {bias_unnorm} vs {bias}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// ML: closed form and brute-force argmax.
// ---------------------------------------------------------------------------------------

/// The closed form derived in the test: ∂/∂ts [−ln ts − (tm − ts)²/(2wm²ts²)] = 0
/// ⇔ wm²ts² + tm·ts − tm² = 0 ⇔ ts = tm·(−1 + √(1 + 4wm²))/(2wm²).
fn closed_form_gain(wm: f64) -> f64 {
    (-1.0 + (1.0 + 4.0 * wm * wm).sqrt()) / (2.0 * wm * wm)
}

#[test]
fn ml_estimate_is_the_unconstrained_likelihood_maximum() {
    let prior = Prior::new(&[20.0, 25.0, 30.0]).unwrap();
    for wm in [0.05, 0.15, 0.4, 0.9] {
        let c = closed_form_gain(wm);
        assert!(rel(ml_gain(wm).unwrap(), c) < 1e-12);
        for tm in [3.0, 17.5, 26.0, 55.0] {
            // Brute force over the positive line (0, 4·tm] on a 1e-4-step grid.
            let ln_lik = |s: f64| -s.ln() - (tm - s).powi(2) / (2.0 * wm * wm * s * s);
            let (mut best, mut best_l) = (0.0, f64::NEG_INFINITY);
            let steps = 400_000;
            for i in 1..=steps {
                let s = 4.0 * tm * i as f64 / steps as f64;
                if ln_lik(s) > best_l {
                    best = s;
                    best_l = ln_lik(s);
                }
            }
            let est = Observer::Ml.estimate(tm, wm, &prior).unwrap();
            assert!(
                (est - best).abs() <= 4.0 * tm / steps as f64,
                "wm {wm} tm {tm}: {est} vs {best}"
            );
            assert!(rel(est, c * tm) < 1e-12);
            // Not confined to the prior: a measurement far outside gives an estimate outside.
            if tm > 50.0 {
                assert!(est > prior.max());
            }
        }
    }
}

#[test]
fn ml_moments_equal_the_closed_form() {
    let prior = Prior::new(&[24.0, 30.0, 36.0, 42.0]).unwrap();
    for (wm, wp) in [(0.1, 0.05), (0.22, 0.13), (0.6, 0.3)] {
        let c = closed_form_gain(wm);
        for p in predict(Observer::Ml, wm, wp, &prior, Rounding::None).unwrap() {
            // E[te|ts] = c·ts; E[te²|ts] = c²ts²(1 + wm²);
            // Var[tp|ts] = (1 + wp²)·E[te²] − E[te]².
            let m2 = c * c * p.ts * p.ts * (1.0 + wm * wm);
            assert!(
                rel(p.mean_te, c * p.ts) < 1e-9,
                "wm {wm}: {} vs {}",
                p.mean_te,
                c * p.ts
            );
            assert!(rel(p.mean_tp, c * p.ts) < 1e-9);
            assert!(rel(p.var_te, m2 - (c * p.ts).powi(2)) < 1e-7);
            let var_tp = (1.0 + wp * wp) * m2 - (c * p.ts).powi(2);
            assert!(
                rel(p.var_tp, var_tp) < 1e-7,
                "wm {wm}: {} vs {var_tp}",
                p.var_tp
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// MAP: in the support; its mean equals a by-hand integral of the step function.
// ---------------------------------------------------------------------------------------

#[test]
fn map_lies_in_the_prior_and_matches_a_by_hand_integral() {
    let values = [14.0, 19.0, 21.0, 30.0, 33.0];
    let prior = Prior::new(&values).unwrap();
    let wm = 0.18;
    // By-hand MAP: the support value of largest p(tm|s) (uniform prior).
    let by_hand_map = |tm: f64| {
        let dens = |s: f64| (-(tm - s).powi(2) / (2.0 * wm * wm * s * s)).exp() / (wm * s);
        values
            .iter()
            .cloned()
            .fold((values[0], f64::NEG_INFINITY), |(b, bd), s| {
                if dens(s) > bd { (s, dens(s)) } else { (b, bd) }
            })
            .0
    };
    for i in 0..=600 {
        let tm = -40.0 + 0.5 * i as f64;
        let est = Observer::Map.estimate(tm, wm, &prior).unwrap();
        assert!(values.contains(&est), "tm {tm}: {est} not a prior value");
        assert!(est >= prior.min() && est <= prior.max());
        assert_eq!(est, by_hand_map(tm), "tm {tm}");
    }
    for p in predict(Observer::Map, wm, 0.1, &prior, Rounding::None).unwrap() {
        assert!(p.mean_te >= prior.min() && p.mean_te <= prior.max());
        let (m1, _) = trapezoid_moments(p.ts, wm, by_hand_map);
        // Trapezoid on a step function: error ≲ h·jump·density, h = 20σ/40 000.
        assert!(
            (p.mean_te - m1).abs() < 2e-3,
            "ts {}: {} vs {m1}",
            p.ts,
            p.mean_te
        );
    }
}

#[test]
fn simulated_summaries_converge_to_predictions() {
    // n = 6 000 trials per ts (30 000 in all). Tolerances are 4 standard errors, computed
    // from the predicted moments (a scale, not an expected value):
    //   SE(slope) = √(VAR / Σₖ n(tsₖ − ts̄)²),
    //   SE(BIAS) ≈ √(Σₖ bₖ² varₖ / n) / (K·BIAS)   (bₖ = mean tpₖ − tsₖ),
    //   SE(√VAR)/√VAR ≈ ½·√(2/n)·√(κ/3)/√K with a kurtosis allowance κ = 6,
    //   SE(mean tpₖ) = sdₖ/√n; the Weber fraction within 0.005.
    let n = 6000;
    let prior = Prior::new(&[20.0, 25.0, 30.0, 35.0, 40.0]).unwrap();
    let values = prior.values();
    let k = values.len() as f64;
    let ts_bar = values.iter().sum::<f64>() / k;
    let sxx: f64 = values.iter().map(|t| n as f64 * (t - ts_bar).powi(2)).sum();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2024);
    for (observer, wm, wp) in [
        (Observer::Bls, 0.15, 0.08),
        (Observer::Map, 0.1, 0.1),
        (Observer::Ml, 0.2, 0.1),
    ] {
        for rounding in [Rounding::None, Rounding::WholeSteps] {
            let recs = simulate(observer, wm, wp, &prior, n, rounding, &mut rng).unwrap();
            let sim = summarize(&recs).unwrap();
            let pred = predicted_summary(observer, wm, wp, &prior, rounding).unwrap();
            let tag = format!("{} {rounding:?}", observer.name());
            let se_slope = (pred.var / sxx).sqrt();
            let se_bias = (pred
                .per_ts
                .iter()
                .map(|m| (m.mean - m.ts).powi(2) * m.var)
                .sum::<f64>()
                / n as f64)
                .sqrt()
                / (k * pred.bias);
            let se_sqrt_var = 0.5 * (2.0 / n as f64).sqrt() * (6.0f64 / 3.0).sqrt() / k.sqrt();
            eprintln!(
                "{tag}: slope {:.4}/{:.4} (±{:.4}) BIAS {:.3}/{:.3} (±{:.3}) √VAR {:.3}/{:.3} Weber {:.4}/{:.4}",
                sim.slope,
                pred.slope,
                4.0 * se_slope,
                sim.bias,
                pred.bias,
                4.0 * se_bias,
                sim.sqrt_var(),
                pred.sqrt_var(),
                sim.weber,
                pred.weber
            );
            assert!(
                (sim.slope - pred.slope).abs() < 4.0 * se_slope,
                "{tag} slope"
            );
            assert!((sim.bias - pred.bias).abs() < 4.0 * se_bias, "{tag} BIAS");
            assert!(
                rel(sim.sqrt_var(), pred.sqrt_var()) < 4.0 * se_sqrt_var,
                "{tag} √VAR"
            );
            assert!((sim.weber - pred.weber).abs() < 0.005, "{tag} Weber");
            for (s, p) in sim.per_ts.iter().zip(&pred.per_ts) {
                let se = (p.var / n as f64).sqrt();
                assert!((s.mean - p.mean).abs() < 4.0 * se, "{tag} mean at {}", s.ts);
            }
        }
    }
    // Rounding adds ≈ 1/12 step² (Sheppard) to the variance when the production SD is
    // several steps: here SD ≈ 0.1·te ≈ 3 steps except in the far lower tail of te, where
    // the exact rounding variance departs from 1/12 (weight ~1e-3 at te < 10).
    let a = predict_at(Observer::Ml, 0.2, 0.1, &prior, 30.0, Rounding::None).unwrap();
    let b = predict_at(Observer::Ml, 0.2, 0.1, &prior, 30.0, Rounding::WholeSteps).unwrap();
    assert!(
        (b.var_tp - a.var_tp - 1.0 / 12.0).abs() < 1e-4,
        "{} {}",
        a.var_tp,
        b.var_tp
    );
    assert!((b.mean_tp - a.mean_tp).abs() < 1e-6);
}

// ---------------------------------------------------------------------------------------
// The summary formulas by hand.
// ---------------------------------------------------------------------------------------

#[test]
fn summary_formulas_on_a_tiny_data_set() {
    // ts = 10: tp = 9, 11, 13      → mean 11, var ((−2)² + 0 + 2²)/2 = 4, sd 2.
    // ts = 20: tp = 18, 19, 20, 23 → mean 20, var (4 + 1 + 0 + 9)/3 = 14/3.
    // OLS over the 7 trials: ts̄ = 110/7, tp̄ = 113/7;
    //   Sxy = 3·(−40/7)(−36/7) + 4·(30/7)(27/7) = 7560/49,
    //   Sxx = 3·(40/7)² + 4·(30/7)² = 8400/49  → slope 0.9, intercept 113/7 − 0.9·110/7 = 2.
    // BIAS = √(((11 − 10)² + 0²)/2) = √0.5; VAR = (4 + 14/3)/2 = 13/3;
    // RMSE = √(1/2 + 13/3) = √(29/6); Weber = (2/11 + √(14/3)/20)/2.
    let tp10 = [9.0, 11.0, 13.0];
    let tp20 = [18.0, 19.0, 20.0, 23.0];
    let mut recs: Vec<Record> = tp20.iter().map(|&tp| Record { ts: 20.0, tp }).collect();
    recs.extend(tp10.iter().map(|&tp| Record { ts: 10.0, tp }));
    let s = summarize(&recs).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    assert_eq!(s.per_ts.len(), 2);
    assert!(s.per_ts[0].ts == 10.0 && s.per_ts[0].weight == 3.0);
    assert!(close(s.per_ts[0].mean, 11.0) && close(s.per_ts[0].sd(), 2.0));
    assert!(close(s.per_ts[1].mean, 20.0) && close(s.per_ts[1].var, 14.0 / 3.0));
    assert!(close(s.slope, 0.9), "{}", s.slope);
    assert!(close(s.intercept, 2.0), "{}", s.intercept);
    assert!(close(s.bias, 0.5f64.sqrt()));
    assert!(close(s.var, 13.0 / 3.0));
    assert!(close(s.rmse, (29.0f64 / 6.0).sqrt()));
    assert!(close(
        s.weber,
        (2.0 / 11.0 + (14.0f64 / 3.0).sqrt() / 20.0) / 2.0
    ));
    // The same from moments, with weights: identical.
    let m = summary_from_moments(&[
        TsMoments {
            ts: 20.0,
            weight: 4.0,
            mean: 20.0,
            var: 14.0 / 3.0,
        },
        TsMoments {
            ts: 10.0,
            weight: 3.0,
            mean: 11.0,
            var: 4.0,
        },
    ])
    .unwrap();
    assert!(close(m.slope, 0.9) && close(m.bias, s.bias) && close(m.var, s.var));
}

// ---------------------------------------------------------------------------------------
// Determinism and typed errors.
// ---------------------------------------------------------------------------------------

#[test]
fn simulation_is_deterministic_given_the_seed() {
    let prior = Prior::new(&[10.0, 20.0]).unwrap();
    let run = |seed| {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        simulate(
            Observer::Bls,
            0.1,
            0.1,
            &prior,
            50,
            Rounding::WholeSteps,
            &mut rng,
        )
        .unwrap()
    };
    assert_eq!(run(3), run(3));
    assert_ne!(run(3), run(4));
    assert!(run(3).iter().all(|r| r.tp.fract() == 0.0));
}

#[test]
fn bad_input_gives_typed_errors() {
    use ObserverError as E;
    let prior = Prior::new(&[10.0, 20.0]).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let ok = [Record { ts: 10.0, tp: 11.0 }, Record { ts: 20.0, tp: 19.0 }];

    assert!(matches!(
        Prior::new(&[10.0]),
        Err(E::TooFew {
            field: "prior values",
            got: 1,
            min: 2
        })
    ));
    assert!(matches!(
        Prior::new(&[10.0, 10.0]),
        Err(E::DuplicateValue { .. })
    ));
    assert!(matches!(
        Prior::new(&[10.0, 0.0]),
        Err(E::NotPositive {
            field: "prior value",
            ..
        })
    ));
    assert!(matches!(
        Prior::new(&[10.0, f64::NAN]),
        Err(E::NotFinite {
            field: "prior value",
            ..
        })
    ));
    assert!(matches!(
        Prior::from_records(&[]),
        Err(E::TooFew {
            field: "records",
            ..
        })
    ));

    for (wm, wp, field) in [
        (0.0, 0.1, "wm"),
        (0.1, 1.5, "wp"),
        (f64::NAN, 0.1, "wm"),
        (0.1, 0.009, "wp"),
    ] {
        let err = simulate(Observer::Bls, wm, wp, &prior, 5, Rounding::None, &mut rng).unwrap_err();
        match err {
            E::OutOfRange {
                field: f, min, max, ..
            } => {
                assert_eq!((f, min, max), (field, W_MIN, W_MAX));
                assert!(err.to_string().contains("[0.01, 1]"), "{err}");
            }
            E::NotFinite { field: f, .. } => assert_eq!(f, field),
            other => panic!("unexpected {other:?}"),
        }
        assert!(predict(Observer::Ml, wm, wp, &prior, Rounding::None).is_err());
        assert!(log_likelihood(Observer::Map, wm, wp, &ok, &prior, Rounding::None).is_err());
    }
    assert!(matches!(
        Observer::Bls.estimate(10.0, 2.0, &prior),
        Err(E::OutOfRange { field: "wm", .. })
    ));
    assert!(matches!(
        Observer::Bls.estimate(f64::INFINITY, 0.1, &prior),
        Err(E::NotFinite { field: "tm", .. })
    ));
    assert!(matches!(
        simulate(Observer::Bls, 0.1, 0.1, &prior, 0, Rounding::None, &mut rng),
        Err(E::TooFew {
            field: "trials_per_ts",
            ..
        })
    ));
    assert!(matches!(
        predict_at(Observer::Bls, 0.1, 0.1, &prior, -3.0, Rounding::None),
        Err(E::NotPositive { field: "ts", .. })
    ));

    // Records: empty, non-finite, ts ≤ 0, fractional tp under WholeSteps.
    assert!(matches!(
        fit_observers(&[], &prior, Rounding::None),
        Err(E::TooFew {
            field: "records",
            ..
        })
    ));
    assert!(matches!(
        summarize(&[]),
        Err(E::TooFew {
            field: "records",
            ..
        })
    ));
    let nan_tp = [Record {
        ts: 10.0,
        tp: f64::NAN,
    }];
    assert!(matches!(
        fit_observers(&nan_tp, &prior, Rounding::None),
        Err(E::NotFinite { field: "tp", .. })
    ));
    let zero_ts = [Record { ts: 0.0, tp: 3.0 }];
    assert!(matches!(
        summarize(&zero_ts),
        Err(E::NotPositive { field: "ts", .. })
    ));
    assert!(matches!(
        log_likelihood(Observer::Bls, 0.1, 0.1, &zero_ts, &prior, Rounding::None),
        Err(E::NotPositive { field: "ts", .. })
    ));
    let frac = [Record { ts: 10.0, tp: 10.5 }];
    assert!(matches!(
        fit_observers(&frac, &prior, Rounding::WholeSteps),
        Err(E::NotWholeSteps { .. })
    ));
    // Summaries need ≥ 2 trials at every ts and ≥ 2 distinct ts.
    assert!(matches!(
        summarize(&ok),
        Err(E::TooFewTrials { got: 1, min: 2, .. })
    ));
    let one_ts = [Record { ts: 10.0, tp: 9.0 }, Record { ts: 10.0, tp: 12.0 }];
    assert!(matches!(
        summarize(&one_ts),
        Err(E::TooFew {
            field: "distinct ts values",
            ..
        })
    ));
}
