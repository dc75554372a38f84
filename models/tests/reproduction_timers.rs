//! The timing models' own machinery in the reproduction task (Ready-Set-Go), driven
//! directly: Ready ([`Timer::begin_measurement`]), `ts` steps, Set
//! ([`Timer::begin_production`]), then steps until the model responds. The agent's
//! production clock reads 1 at the Set observation, so a response at clock `c` produces
//! `tp = c`. Known answers:
//! * drift-diffusion without noise, one-shot learning (Simen et al. 2011): the drift at Set
//!   is `z / x(ts) · A = z / ts`, so the ramp reaches `z` at `g · ts`;
//! * with a learning rate `α < 1` the drift is the running average
//!   `A_n = (1 − α) A_{n−1} + α z / ts_n` (computed here by hand), and `tp_n = z / A_n`;
//! * with its default noise the one-shot production is unbiased: `E[x(ts)] = A ts`, and the
//!   production's mean first passage is `x(ts) / A`, so `E[tp] = ts` (+ half a step of
//!   discrete crossing) and the slope of `tp` on `ts` is 1: no regression to the mean;
//! * SBF without noise matches the pattern stored at Set: its envelope
//!   `≈ |sinc(0.25 (t/g − ts))|` passes the response threshold 0.9 about one step (`g`
//!   steps with a gain) before the stored time.

use chronocooked_env::{ChronoEnv, make_config};
use chronocooked_models::timing::timers::Timer;
use chronocooked_models::timing::zoo::make_timing_agent;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// The production of one trial: `ts` steps of measurement, then the first clock at which
/// the model responds (`None` within 10 × the target).
fn produce(timer: &mut Timer, ts: u32, gain: f64, rng: &mut Xoshiro256PlusPlus) -> Option<u32> {
    timer.clear();
    timer.begin_measurement(0, rng);
    for t in 1..=ts {
        timer.tick(t, rng);
    }
    timer.begin_production(0, f64::from(ts), gain, rng);
    let limit = (10.0 * gain * f64::from(ts)).ceil() as u32 + 10;
    for c in 1..=limit {
        timer.tick(c, rng);
        if timer.respond(c, None) {
            return Some(c);
        }
    }
    None
}

fn timer_of_noise_free(model: &str) -> Timer {
    timer_of(model).noise_free()
}

fn timer_of(model: &str) -> Timer {
    let config = make_config("Reproduction-v0", &[] as &[&str]).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    make_timing_agent(model, &env, 7).unwrap().timer
}

#[test]
fn noise_free_drift_diffusion_reproduces_every_interval_and_its_gain() {
    let mut timer = timer_of_noise_free("ddm");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    for gain in [1.0, 1.5, 0.7] {
        for ts in 3..=37u32 {
            let tp = produce(&mut timer, ts, gain, &mut rng).unwrap();
            let target = gain * f64::from(ts);
            // The ramp reaches z at g·ts; the first clock at or past it (a float sum of
            // drifts may land a hair below z at an integer target: one step later).
            assert!(
                f64::from(tp) >= target - 1e-9 && f64::from(tp) < target + 1.0 + 1e-9,
                "ts {ts} gain {gain}: tp {tp}, target {target}"
            );
        }
    }
}

#[test]
fn drift_diffusion_with_a_learning_rate_below_one_averages_its_past_measurements() {
    let mut timer = timer_of_noise_free("ddm");
    let alpha = 0.4;
    let (z, a0) = match &mut timer {
        Timer::Ddm(d) => {
            d.reproduction_rate = alpha;
            (d.acc.threshold, d.acc.threshold / d.initial_interval)
        }
        _ => unreachable!(),
    };
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
    let mut a = a0;
    for ts in [12u32, 12, 20, 20, 20, 9, 15, 15, 30, 10] {
        a = (1.0 - alpha) * a + alpha * z / f64::from(ts);
        let expected = z / a;
        let tp = produce(&mut timer, ts, 1.0, &mut rng).unwrap();
        assert!(
            f64::from(tp) >= expected - 1e-6 && f64::from(tp) < expected + 1.0 + 1e-6,
            "ts {ts}: tp {tp}, running-average prediction {expected:.3}"
        );
    }
}

/// Least-squares slope and intercept of `y` on `x`.
fn line(points: &[(f64, f64)]) -> (f64, f64) {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxy / sxx, my - sxy / sxx * mx)
}

#[test]
fn noisy_one_shot_drift_diffusion_is_unbiased_and_does_not_regress_to_the_mean() {
    let mut timer = timer_of("ddm");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let mut points = Vec::new();
    for ts in [9u32, 13, 17, 21] {
        let n = 3000;
        let mean = (0..n)
            .map(|_| f64::from(produce(&mut timer, ts, 1.0, &mut rng).unwrap()))
            .sum::<f64>()
            / f64::from(n);
        // E[tp] = ts, plus up to one step from reading the crossing at whole steps.
        assert!(
            mean > f64::from(ts) - 0.3 && mean < f64::from(ts) + 1.3,
            "ts {ts}: mean tp {mean:.2}"
        );
        points.push((f64::from(ts), mean));
    }
    let (slope, _) = line(&points);
    assert!((slope - 1.0).abs() < 0.05, "slope {slope:.3}");
}

#[test]
fn noise_free_sbf_matches_the_pattern_stored_at_set() {
    let mut timer = timer_of_noise_free("sbf");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(4);
    for gain in [1.0, 1.5] {
        for ts in 4..=30u32 {
            let tp = f64::from(produce(&mut timer, ts, gain, &mut rng).unwrap());
            let target = gain * f64::from(ts);
            assert!(
                tp <= target + 1e-9 && tp >= target - gain - 1.0,
                "ts {ts} gain {gain}: tp {tp}, target {target}"
            );
        }
    }
}
