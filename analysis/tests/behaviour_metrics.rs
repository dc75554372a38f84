//! Behavioural metrics with known answers: logistic-fit recovery and interval coverage,
//! separated and degenerate data, first oven check on hand-built episodes, FOC statistics.

use chronocooked_analysis::behaviour::foc::linear_fit;
use chronocooked_analysis::behaviour::psychometric::bp_relative;
use chronocooked_analysis::{
    FitError, FocConvention, ProbeCounts, first_oven_check, first_oven_check_with, fit_logistic,
    fit_with_ci, foc_stats, scalar_property,
};
use chronocooked_env::{Events, Info};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn simulate(bp: f64, s: f64, n: u32, rng: &mut Xoshiro256PlusPlus) -> Vec<ProbeCounts> {
    (1..=16)
        .map(|t| {
            let p = 1.0 / (1.0 + (-(t as f64 - bp) / s).exp());
            let long = (0..n).filter(|_| rng.random::<f64>() < p).count() as u32;
            ProbeCounts {
                t: t as f64,
                valid: n,
                long,
                failed: 0,
            }
        })
        .collect()
}

#[test]
fn logistic_fit_recovers_known_parameters_and_its_interval_covers() {
    let (bp, s) = (7.3, 1.6);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let fit = fit_logistic(&simulate(bp, s, 2000, &mut rng)).unwrap();
    assert!((fit.bp - bp).abs() < 0.1, "BP {}", fit.bp);
    assert!((fit.scale - s).abs() < 0.1, "s {}", fit.scale);
    assert!((fit.dl - s * 3f64.ln()).abs() < 0.15);
    assert!((fit.t75 - fit.t25 - 2.0 * fit.dl).abs() < 1e-9);
    assert!((fit.wf - fit.dl / fit.bp).abs() < 1e-12);
    // Coverage of the 90% bootstrap interval of BP over repetitions (small samples).
    let reps = 120;
    let mut covered = 0;
    for r in 0..reps {
        let data = simulate(bp, s, 20, &mut rng);
        let f = fit_with_ci(&data, 0.9, 200, r).unwrap();
        let (lo, hi) = f.bp_ci.unwrap();
        assert!(lo <= f.bp && f.bp <= hi);
        if lo <= bp && bp <= hi {
            covered += 1;
        }
    }
    let rate = covered as f64 / reps as f64;
    assert!((0.82..=0.97).contains(&rate), "coverage {rate}");
    // A real transition is significant; flat random choices are not.
    let strong = simulate(bp, s, 20, &mut rng);
    let f = fit_logistic(&strong).unwrap();
    assert!(chronocooked_analysis::behaviour::psychometric::transition_p_value(&strong, &f) < 1e-6);
    let flat = simulate(bp, 1e6, 20, &mut rng);
    if let Ok(f) = fit_logistic(&flat) {
        assert!(
            chronocooked_analysis::behaviour::psychometric::transition_p_value(&flat, &f) > 0.001
        );
    }
    let (am, gm) = bp_relative(8.0, 4.0, 16.0);
    assert!((am - 0.8).abs() < 1e-12 && (gm - 1.0).abs() < 1e-12);
}

#[test]
fn separated_failed_and_one_sided_data_are_reported_not_crashed() {
    // Oracle-like: all short up to 6, all long from 7.
    let data: Vec<ProbeCounts> = (1..=16)
        .map(|t| ProbeCounts {
            t: t as f64,
            valid: 8,
            long: if t >= 7 { 8 } else { 0 },
            failed: 0,
        })
        .collect();
    let f = fit_logistic(&data).unwrap();
    assert!(f.separated);
    assert_eq!(f.bp, 6.5);
    // A step has no measurable slope: DL and WF are undefined, not 0.
    assert!(f.wf.is_nan() && f.dl.is_nan() && f.scale.is_nan(), "{f:?}");
    // Quasi-separation: one mixed probe (3 of 8 long at 7) between all-short and
    // all-long. The likelihood keeps rising with the slope, so WF is undefined too, and
    // BP is where the empirical curve crosses 0.5: 7 + (0.5 − 0.375)/(1 − 0.375) = 7.2.
    let quasi: Vec<ProbeCounts> = (1..=16)
        .map(|t| ProbeCounts {
            t: t as f64,
            valid: 8,
            long: match t {
                ..=6 => 0,
                7 => 3,
                _ => 8,
            },
            failed: 0,
        })
        .collect();
    let q = fit_logistic(&quasi).unwrap();
    assert!(q.separated && q.wf.is_nan(), "{q:?}");
    assert!((q.bp - 7.2).abs() < 1e-12, "BP {}", q.bp);
    // Serialised, the undefined statistics are null and read back as NaN.
    let json = serde_json::to_string(&q).unwrap();
    assert!(json.contains("\"wf\":null"), "{json}");
    let back: chronocooked_analysis::behaviour::psychometric::LogisticFit =
        serde_json::from_str(&json).unwrap();
    assert!(back.wf.is_nan() && (back.bp - 7.2).abs() < 1e-12);
    // Two mixed probes identify the slope: a finite WF.
    let mut two = quasi.clone();
    two[7].long = 6;
    let t = fit_logistic(&two).unwrap();
    assert!(!t.separated && t.wf.is_finite() && t.wf > 0.0, "{t:?}");
    // A random agent that always goes long: no bisection point.
    let all_long: Vec<ProbeCounts> = (1..=16)
        .map(|t| ProbeCounts {
            t: t as f64,
            valid: 8,
            long: 8,
            failed: 0,
        })
        .collect();
    assert_eq!(fit_logistic(&all_long), Err(FitError::NoTransition));
    // More than half failed → NaN probe, excluded; too few probes left.
    let failing: Vec<ProbeCounts> = (1..=16)
        .map(|t| ProbeCounts {
            t: t as f64,
            valid: 3,
            long: 1,
            failed: if t == 3 { 1 } else { 5 },
        })
        .collect();
    assert!(failing[0].p_long().is_nan());
    assert!((failing[2].p_long() - 1.0 / 3.0).abs() < 1e-12);
    assert_eq!(fit_logistic(&failing), Err(FitError::TooFewProbes(1)));
}

fn step(timer: i32, events: u16) -> Info {
    Info {
        timer_at_action: timer,
        events: Events(events),
        ..Info::default()
    }
}

#[test]
fn first_oven_check_follows_the_paper_definition() {
    let check = Events::OVEN_CHECK;
    let pickup = Events::OVEN_CHECK | Events::PICKUP;
    // check at 3, wait (breaks the run), checks at 5, 6 and pickup at 7.
    let actions = [1u8, 5, 0, 5, 5, 5, 4];
    let infos = [
        step(1, 0),
        step(3, check),
        step(4, 0),
        step(5, check),
        step(6, check),
        step(7, pickup),
        step(-1, 0),
    ];
    assert_eq!(first_oven_check(&actions, &infos), Some(5));
    // A pickup on the first check: FOC = its timer.
    assert_eq!(first_oven_check(&[5], &[step(12, pickup)]), Some(12));
    // The paper's code walks back over any interact: an interact without effect does not
    // break the run; the lab's `Checks` convention stops there.
    let actions = [5u8, 5, 5];
    let infos = [step(4, check), step(5, Events::NO_EFFECT), step(6, pickup)];
    assert_eq!(first_oven_check(&actions, &infos), Some(4));
    assert_eq!(
        first_oven_check_with(&actions, &infos, FocConvention::Checks),
        Some(6)
    );
    // No pickup: no FOC.
    assert_eq!(
        first_oven_check(&[5, 5], &[step(1, check), step(2, check)]),
        None
    );
}

#[test]
fn foc_is_zero_for_an_interact_run_from_the_put() {
    // Walk to the oven, put the onion (timer -1 before the put step), then interact without
    // a break until the pickup at timer 4: the paper's code reports FOC 0, the lab's
    // earlier convention 1.
    let check = Events::OVEN_CHECK;
    let pickup = Events::OVEN_CHECK | Events::PICKUP;
    let actions = [1u8, 5, 5, 5, 5, 5, 2];
    let infos = [
        step(-1, 0),
        step(-1, Events::ONION_IN),
        step(1, check),
        step(2, check),
        step(3, check),
        step(4, pickup),
        step(-1, 0),
    ];
    assert_eq!(first_oven_check(&actions, &infos), Some(0));
    assert_eq!(
        first_oven_check_with(&actions, &infos, FocConvention::Checks),
        Some(1)
    );
    // The same agent with one wait after the put: the run starts at timer 2.
    let actions = [1u8, 5, 0, 5, 5, 2];
    let infos = [
        step(-1, 0),
        step(-1, Events::ONION_IN),
        step(1, 0),
        step(2, check),
        step(3, pickup),
        step(-1, 0),
    ];
    assert_eq!(first_oven_check(&actions, &infos), Some(2));
}

#[test]
fn foc_counts_only_the_final_streak_and_needs_a_pickup() {
    let check = Events::OVEN_CHECK;
    let pickup = Events::OVEN_CHECK | Events::PICKUP;
    // An interrupted streak: checks at timer 1 and 2, a wait at 3, then checks from 4 to the
    // pickup at 5. Only the final streak defines FOC (the earlier checks are not counted),
    // under both conventions.
    let actions = [1u8, 5, 5, 5, 0, 5, 5, 2];
    let infos = [
        step(-1, 0),
        step(-1, Events::ONION_IN),
        step(1, check),
        step(2, check),
        step(3, 0),
        step(4, check),
        step(5, pickup),
        step(-1, 0),
    ];
    assert_eq!(first_oven_check(&actions, &infos), Some(4));
    assert_eq!(
        first_oven_check_with(&actions, &infos, FocConvention::Checks),
        Some(4)
    );
    // The same checks without a pickup (the episode timed out): no FOC.
    let infos_no_pickup: Vec<_> = infos
        .iter()
        .map(|i| {
            if i.events.has(Events::PICKUP) {
                step(5, check)
            } else {
                *i
            }
        })
        .collect();
    assert_eq!(first_oven_check(&actions, &infos_no_pickup), None);
    assert_eq!(
        first_oven_check_with(&actions, &infos_no_pickup, FocConvention::Checks),
        None
    );
}

#[test]
fn foc_statistics_show_the_scalar_property_on_scalar_data() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let groups: Vec<(u32, Vec<f64>)> = [4u32, 6, 9, 12, 18, 24]
        .iter()
        .map(|&td| {
            let v = (0..4000)
                .map(|_| {
                    let z: f64 = (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0;
                    td as f64 * (1.0 + 0.2 * z)
                })
                .collect();
            (td, v)
        })
        .collect();
    let stats = foc_stats(&groups);
    for s in &stats {
        assert!((s.mean - s.td as f64).abs() < 0.05 * s.td as f64);
        assert!((s.cv - 0.2).abs() < 0.01, "CV {}", s.cv);
    }
    let sp = scalar_property(&stats);
    assert!(sp.r2_mean_vs_td > 0.999 && (sp.mean_slope - 1.0).abs() < 0.02);
    assert!(sp.r2_sd_vs_mean > 0.99 && (sp.sd_slope - 0.2).abs() < 0.01);
    let (m, b, r2) = linear_fit(&[1.0, 2.0, 3.0], &[3.0, 5.0, 7.0]);
    assert!((m - 2.0).abs() < 1e-12 && (b - 1.0).abs() < 1e-12 && (r2 - 1.0).abs() < 1e-12);
    assert!(foc_stats(&[(4, vec![])])[0].mean.is_nan());
    // A deterministic model: every SD 0. SD~mean has nothing to explain — R² undefined
    // (NaN), never the "perfect" 1 a degenerate fit used to report.
    let exact = foc_stats(&[(6, vec![6.0; 8]), (12, vec![12.0; 8]), (18, vec![18.0; 8])]);
    let sp = scalar_property(&exact);
    assert!(sp.r2_sd_vs_mean.is_nan(), "{sp:?}");
    assert!((sp.r2_mean_vs_td - 1.0).abs() < 1e-12);
    let json = serde_json::to_string(&sp).unwrap();
    let back: chronocooked_analysis::behaviour::foc::ScalarProperty =
        serde_json::from_str(&json).unwrap();
    assert!(back.r2_sd_vs_mean.is_nan());
}

#[test]
fn gaussian_peak_fit_recovers_known_curve() {
    use chronocooked_analysis::behaviour::peak::fit_gaussian;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    let (a, mu, sigma, b) = (0.8, 18.0, 4.5, 0.05);
    let rate: Vec<f64> = (0..60)
        .map(|t| {
            let z = (t as f64 - mu) / sigma;
            a * (-0.5 * z * z).exp() + b + 0.01 * (rng.random::<f64>() - 0.5)
        })
        .collect();
    let f = fit_gaussian(&rate).unwrap();
    assert!((f.peak - mu).abs() < 0.1, "{f:?}");
    assert!((f.spread - sigma).abs() < 0.1, "{f:?}");
    assert!(
        (f.amplitude - a).abs() < 0.02 && (f.baseline - b).abs() < 0.01,
        "{f:?}"
    );
    assert!((f.cv - sigma / mu).abs() < 0.01);
    assert!(fit_gaussian(&[0.0; 20]).is_none());
}

#[test]
fn start_stop_on_a_hand_computed_trial() {
    use chronocooked_analysis::behaviour::peak::start_stop;
    // Responses at steps 5..10 (and a stray one at 2): low–high–low with start 5, stop 10.
    let mut r = vec![0.0; 20];
    for v in &mut r[5..10] {
        *v = 1.0;
    }
    r[2] = 1.0;
    let s = start_stop(&r).unwrap();
    assert_eq!((s.start, s.stop, s.spread), (5, 10, 5));
    assert_eq!(s.middle, 7.5);
    assert!(start_stop(&[0.0; 10]).is_none());
}

#[test]
fn itpc_of_frequency_jittered_oscillators_decays_as_predicted() {
    use chronocooked_analysis::neural::oscillation::{itpc, welch};
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    let (f0, sf, dt, n) = (10.0, 0.5, 1.0 / 400.0, 400);
    let trials: Vec<Vec<f64>> = (0..400)
        .map(|_| {
            let z: f64 = (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0;
            let f = f0 + sf * z;
            (0..n)
                .map(|k| (2.0 * std::f64::consts::PI * f * k as f64 * dt).cos())
                .collect()
        })
        .collect();
    let c = itpc(&trials);
    for k in (80..320).step_by(40) {
        let t = k as f64 * dt;
        let expected = (-2.0 * std::f64::consts::PI.powi(2) * sf * sf * t * t).exp();
        assert!(
            (c[k] - expected).abs() < 0.08,
            "t={t}: {} vs {expected}",
            c[k]
        );
    }
    // Welch: the spectrum peaks at the oscillation frequency.
    let x: Vec<f64> = (0..2000)
        .map(|k| {
            (2.0 * std::f64::consts::PI * 7.0 * k as f64 * 0.01).sin()
                + 0.5 * (rng.random::<f64>() - 0.5)
        })
        .collect();
    let s = welch(&x, 200, 0.01);
    assert!((s.peak - 7.0).abs() <= 0.5, "peak {}", s.peak);
}

#[test]
fn aggregation_has_known_answers() {
    use chronocooked_analysis::behaviour::aggregate::Spread;
    let s = Spread::of([1.0, 2.0, 3.0, f64::NAN]);
    assert_eq!((s.mean, s.n), (2.0, 3));
    assert!((s.sd - 1.0).abs() < 1e-12);
    assert!(Spread::of([]).mean.is_nan());
}
