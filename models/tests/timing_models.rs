//! Oracle tests of the timing models: analytic results, not examples.

use chronocooked_models::timing::timecells::laplace_peak_times;
use chronocooked_models::timing::timers::Timer;
use chronocooked_models::timing::{
    BeatFrequency, Ctrnn, DriftDiffusion, FrequencyLayout, LinearTd, Representation, TimeCells,
    microstimulus, microstimulus_peak,
};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// Mean, SD, skewness of a sample.
fn moments(x: &[f64]) -> (f64, f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let m3 = x.iter().map(|v| (v - mean).powi(3)).sum::<f64>() / n;
    (mean, var.sqrt(), m3 / var.powf(1.5))
}

#[test]
fn ddm_first_passage_is_inverse_gaussian_with_scalar_cv() {
    // Simulated diffusion (step 0.005, bridge-corrected) vs the inverse-Gaussian moments:
    // mean z/A, CV m/√z independent of A, skewness 3·CV.
    let (z, m) = (1.0, 0.3);
    let cv_theory = m / f64::sqrt(z);
    let mut cvs = Vec::new();
    for (k, drift) in [0.5, 2.0].into_iter().enumerate() {
        let mut ddm = DriftDiffusion::new(drift, z, m);
        let mut r = rng(11 + k as u64);
        let n = 20_000;
        let times: Vec<f64> = (0..n)
            .map(|_| {
                ddm.simulate_first_passage(0.005 / drift, 100.0, &mut r)
                    .expect("crosses")
            })
            .collect();
        let (mean, sd, skew) = moments(&times);
        let mean_theory = z / drift;
        let se_mean = mean_theory * cv_theory / (n as f64).sqrt();
        assert!(
            (mean - mean_theory).abs() < 4.0 * se_mean,
            "A={drift}: mean {mean} vs {mean_theory} (SE {se_mean})"
        );
        let cv = sd / mean;
        assert!(
            (cv - cv_theory).abs() < 0.03 * cv_theory,
            "A={drift}: CV {cv} vs {cv_theory}"
        );
        assert!(
            (skew - 3.0 * cv_theory).abs() < 0.15 * 3.0 * cv_theory,
            "A={drift}: skewness {skew} vs {}",
            3.0 * cv_theory
        );
        cvs.push(cv);
        // The exact sampler has the same law.
        let exact: Vec<f64> = (0..n).map(|_| ddm.sample_first_passage(&mut r)).collect();
        let (me, sde, _) = moments(&exact);
        assert!((me - mean_theory).abs() < 4.0 * se_mean);
        assert!((sde / me - cv_theory).abs() < 0.03 * cv_theory);
    }
    assert!(
        (cvs[0] - cvs[1]).abs() < 0.05 * cv_theory,
        "CV depends on A: {cvs:?}"
    );
}

#[test]
fn ddm_one_trial_drift_learning_hits_z_over_t() {
    for (a0, t) in [(0.05, 12.0), (0.4, 12.0), (1.0, 3.0), (0.01, 40.0)] {
        // Noise-free accumulator run to the reward at T, then the α = 1 rule.
        let mut ddm = DriftDiffusion::new(a0, 1.0, 0.0);
        let mut r = rng(1);
        ddm.reset();
        let steps = (t / 0.01_f64).round() as usize;
        for _ in 0..steps {
            ddm.step(0.01, &mut r);
        }
        let x_t = ddm.x;
        assert!((x_t - a0 * t).abs() < 1e-9);
        ddm.learn(x_t, 1.0);
        assert!(
            (ddm.drift - 1.0 / t).abs() < 1e-9,
            "A0={a0}, T={t}: learned {} (late trial: {})",
            ddm.drift,
            x_t < 1.0
        );
    }
    // Learning-rate form moves part of the way, in the right direction.
    let mut ddm = DriftDiffusion::new(0.05, 1.0, 0.0);
    ddm.learn_interval(10.0, 0.5);
    assert!((ddm.drift - 0.05 * (1.0 + 0.5 * (1.0 - 0.5) / 0.5)).abs() < 1e-12);
}

fn argmax(v: &[f64]) -> usize {
    v.iter()
        .enumerate()
        .fold(
            (0, f64::NEG_INFINITY),
            |b, (i, &x)| if x > b.1 { (i, x) } else { b },
        )
        .0
}

/// Output `Σ wᵢ xᵢ(t)` on a grid `t = i·dt`, `i < n`.
fn sbf_output(sbf: &BeatFrequency, w: &[f64], dt: f64, n: usize) -> Vec<f64> {
    let mut x = Vec::new();
    (0..n)
        .map(|i| {
            sbf.oscillators_into(i as f64 * dt, &mut x);
            sbf.output(w, &x)
        })
        .collect()
}

#[test]
fn sbf_peaks_at_t_with_sinc_envelope_and_manipulations_move_it() {
    let t_star = 2.0; // s
    let dt = 0.001;
    let mut r = rng(3);
    let sbf = BeatFrequency::new(1000, 5.0, 15.0, FrequencyLayout::Even, &mut r);
    let mut w = Vec::new();
    sbf.reinforce(&mut w, t_star, &mut r);
    let out = sbf_output(&sbf, &w, dt, 4000);
    let peak = argmax(&out) as f64 * dt;
    assert!((peak - t_star).abs() < 1.5 * dt, "peak at {peak}");

    // Envelope FWHM ≈ 1.207/Δf (Δf = 10 Hz).
    let env: Vec<f64> = (0..4000)
        .map(|i| sbf.envelope(i as f64 * dt, t_star))
        .collect();
    let above: Vec<usize> = (0..env.len()).filter(|&i| env[i] >= 0.5).collect();
    let fwhm = (above.last().unwrap() - above.first().unwrap()) as f64 * dt;
    assert!(
        (fwhm - 1.207 / 10.0).abs() < 0.004,
        "FWHM {fwhm} vs {}",
        1.207 / 10.0
    );
    // The output's local maxima follow the envelope: away from T they stay below it.
    for (i, &o) in out.iter().enumerate() {
        let t = i as f64 * dt;
        if (t - t_star).abs() > 0.3 {
            assert!(o.abs() < 0.2 * out[argmax(&out)], "side lobe at {t}: {o}");
        }
    }

    // Evenly spaced frequencies alias: the envelope returns to ~1 at T + 1/δf.
    let df = 10.0 / 999.0;
    assert!(sbf.envelope(t_star + 1.0 / df, t_star) > 0.99);

    // Clock speed k·f: peak at T/k. Memory scale k·T: peak at kT.
    let mut fast = sbf.clone();
    fast.clock_speed = 1.25;
    let peak_fast = argmax(&sbf_output(&fast, &w, dt, 4000)) as f64 * dt;
    assert!((peak_fast - t_star / 1.25).abs() < 1.5 * dt, "{peak_fast}");
    let mut long_memory = sbf.clone();
    long_memory.memory_scale = 1.2;
    let mut w2 = Vec::new();
    long_memory.reinforce(&mut w2, t_star, &mut r);
    let peak_mem = argmax(&sbf_output(&long_memory, &w2, dt, 4000)) as f64 * dt;
    assert!((peak_mem - 1.2 * t_star).abs() < 1.5 * dt, "{peak_mem}");
}

#[test]
fn sbf_memory_noise_gives_scalar_peak_times() {
    // Peak-time CV = κ from trial-to-trial noise in the stored time, at two intervals.
    let mut r = rng(5);
    let mut sbf = BeatFrequency::new(400, 5.0, 15.0, FrequencyLayout::Random, &mut r);
    sbf.memory_noise = 0.1;
    for t_star in [1.0, 3.0] {
        let peaks: Vec<f64> = (0..400)
            .map(|_| {
                let mut w = Vec::new();
                sbf.reinforce(&mut w, t_star, &mut r);
                argmax(&sbf_output(
                    &sbf,
                    &w,
                    0.002,
                    (t_star * 2.0 / 0.002) as usize,
                )) as f64
                    * 0.002
            })
            .collect();
        let (mean, sd, _) = moments(&peaks);
        assert!((mean - t_star).abs() < 0.03 * t_star, "mean {mean}");
        assert!((sd / mean - 0.1).abs() < 0.015, "CV {}", sd / mean);
    }
}

#[test]
fn microstimuli_peak_times_and_heights_match_closed_form() {
    let (d, sigma, m) = (0.985, 0.08, 10);
    for i in 1..=m {
        let (t_star, h_star) = microstimulus_peak(i, m, sigma, d);
        // Dense search over continuous time.
        let grid: Vec<f64> = (0..400_000)
            .map(|k| microstimulus(d.powf(k as f64 * 0.001), i, m, sigma))
            .collect();
        let k = argmax(&grid);
        assert!(
            (k as f64 * 0.001 - t_star).abs() < 0.002,
            "microstimulus {i}: peak {} vs {t_star}",
            k as f64 * 0.001
        );
        assert!((grid[k] - h_star).abs() < 1e-6 * h_star.max(1.0));
        // The running representation (integer steps) peaks at the nearest step.
        let mut tc = TimeCells::new(Representation::Microstimulus {
            decay: d,
            sigma,
            count: m,
        });
        tc.onset();
        let mut series = Vec::new();
        let mut units = Vec::new();
        for _ in 0..400 {
            tc.units_into(&mut units);
            series.push(units[i - 1]);
            tc.tick();
        }
        assert!((argmax(&series) as f64 - t_star).abs() <= 0.5 + 1e-9);
    }
    // Ludvig, Sutton & Kehoe (2008): x = y·exp(−(y − i/m)²/(2σ²))/√(2π), by hand.
    let root_2pi = (2.0 * std::f64::consts::PI).sqrt();
    assert!((microstimulus(1.0, 10, 10, 0.08) - 1.0 / root_2pi).abs() < 1e-15);
    assert!((microstimulus(0.5, 5, 10, 0.08) - 0.5 / root_2pi).abs() < 1e-15);
    let by_hand = 0.42 * (-(0.42f64 - 0.3).powi(2) / (2.0 * 0.08 * 0.08)).exp() / root_2pi;
    assert!((microstimulus(0.42, 3, 10, 0.08) - by_hand).abs() < 1e-15);
    // Peak of unit i = m = 10 (μ = 1 ≥ y* boundary: y* = (1 + √(1 + 4σ²))/2 > 1) is at onset.
    let (t10, h10) = microstimulus_peak(10, 10, 0.08, 0.985);
    assert_eq!(t10, 0.0);
    assert!((h10 - 1.0 / root_2pi).abs() < 1e-15);
    // Unit 5: y* = (0.5 + √(0.25 + 0.0256))/2, t* = ln y*/ln 0.985, height y*·e^{−(y*−0.5)²/(2σ²)}/√(2π).
    let y5 = 0.5 * (0.5 + (0.25f64 + 4.0 * 0.0064).sqrt());
    let (t5, h5) = microstimulus_peak(5, 10, 0.08, 0.985);
    assert!((t5 - y5.ln() / 0.985f64.ln()).abs() < 1e-12);
    assert!((h5 - y5 * (-(y5 - 0.5).powi(2) / 0.0128).exp() / root_2pi).abs() < 1e-15);
    // Later microstimuli peak later and lower (the trace decays).
    let peaks: Vec<(f64, f64)> = (1..=m)
        .map(|i| microstimulus_peak(i, m, sigma, d))
        .collect();
    assert!(peaks.windows(2).all(|p| p[0].0 > p[1].0));
}

#[test]
fn laplace_time_cells_on_a_fast_or_slow_clock_are_the_same_cells_at_the_scaled_time() {
    // A per-trial clock-speed factor r runs the representation at represented time u = r t:
    // every cell must equal the analytic Laplace cell s^{k+1} u^k e^{−s u}/k! there — the
    // same shape and the same peak height, only earlier or later (not r^{−k} × as high).
    let (cells, tau_min, tau_max, k) = (10, 1.0, 64.0, 8);
    let fact: f64 = (1..=k).map(|v| v as f64).product();
    let taus = laplace_peak_times(cells, tau_min, tau_max);
    for r in [0.8, 0.95, 1.1, 1.3] {
        let mut tc = TimeCells::new(Representation::Laplace {
            cells,
            tau_min,
            tau_max,
            order: k,
        });
        tc.onset_with_speed(r);
        let mut units = Vec::new();
        for t in 1..=60u32 {
            tc.tick();
            tc.units_into(&mut units);
            let u = r * t as f64;
            for (j, &tau) in taus.iter().enumerate() {
                let s = k as f64 / tau;
                let exact = s.powi(k as i32 + 1) * u.powi(k as i32) * (-s * u).exp() / fact;
                assert!(
                    (units[j] - exact).abs() <= 1e-9 * exact.max(1e-6),
                    "r {r} t {t} cell {j}: {} vs {exact}",
                    units[j]
                );
            }
        }
    }
}

#[test]
fn laplace_time_cells_peak_at_tau_star_with_cv_one_over_sqrt_k_plus_one() {
    let (cells, tau_min, tau_max, k) = (12, 4.0, 80.0, 8);
    let mut tc = TimeCells::new(Representation::Laplace {
        cells,
        tau_min,
        tau_max,
        order: k,
    });
    tc.onset();
    let horizon = 2000;
    let mut series = vec![Vec::new(); cells];
    let mut units = Vec::new();
    for _ in 0..horizon {
        tc.units_into(&mut units);
        for (j, u) in units.iter().enumerate() {
            series[j].push(*u);
        }
        tc.tick();
    }
    let fact: f64 = (1..=k).map(|v| v as f64).product();
    for (j, tau) in laplace_peak_times(cells, tau_min, tau_max)
        .into_iter()
        .enumerate()
    {
        // Exact propagation: equals s^{k+1} t^k e^{−st} / k! at every step.
        let s = k as f64 / tau;
        for (t, &v) in series[j].iter().enumerate().step_by(7) {
            let exact =
                s.powi(k as i32 + 1) * (t as f64).powi(k as i32) * (-s * t as f64).exp() / fact;
            assert!((v - exact).abs() < 1e-9 * exact.max(1e-3), "cell {j} t {t}");
        }
        let peak = argmax(&series[j]) as f64;
        assert!(
            (peak - tau).abs() <= 1.0,
            "cell {j}: peak {peak} vs τ* {tau}"
        );
        // As a distribution over time: CV 1/√(k+1).
        let total: f64 = series[j].iter().sum();
        let mean: f64 = series[j]
            .iter()
            .enumerate()
            .map(|(t, v)| t as f64 * v)
            .sum::<f64>()
            / total;
        let var: f64 = series[j]
            .iter()
            .enumerate()
            .map(|(t, v)| (t as f64 - mean).powi(2) * v)
            .sum::<f64>()
            / total;
        let cv = var.sqrt() / mean;
        let expected = 1.0 / ((k + 1) as f64).sqrt();
        assert!(
            (cv - expected).abs() < 0.01,
            "cell {j}: CV {cv} vs {expected}"
        );
    }
}

/// CSC features of time `t` (`units` units).
fn csc(t: usize, units: usize) -> Vec<f64> {
    let mut v = vec![0.0; units];
    v[t.min(units - 1)] = 1.0;
    v
}

#[test]
fn csc_td_learns_the_discounted_ramp_and_omission_gives_negative_rpe() {
    // Pavlovian trial: CS at t = 0, US (reward 1) on the transition T−1 → T, trial ends.
    let (t_us, units) = (15, 32);
    let mut td = LinearTd::new(units);
    for _ in 0..3000 {
        td.clear_traces();
        for t in 0..t_us {
            let r = if t + 1 == t_us { 1.0 } else { 0.0 };
            td.update(&csc(t, units), r, &csc(t + 1, units), t + 1 == t_us);
        }
    }
    for t in 0..t_us {
        let v = td.value(&csc(t, units));
        let expected = td.gamma.powi((t_us - 1 - t) as i32);
        assert!(
            (v - expected).abs() < 0.01,
            "V({t}) = {v}, expected {expected}"
        );
    }
    // Omission: no US, the trial goes on; the RPE dips by ≈ −1 at the expected time only.
    let mut probe = td.clone();
    probe.alpha = 0.0;
    probe.clear_traces();
    for t in 0..t_us + 5 {
        let delta = probe.update(&csc(t, units), 0.0, &csc(t + 1, units), false);
        if t + 1 == t_us {
            assert!(delta < -0.95, "omission RPE at T: {delta}");
        } else {
            assert!(delta.abs() < 0.02, "RPE at t={t}: {delta}");
        }
    }
}

#[test]
fn standalone_ctrnn_with_zero_weights_follows_exact_euler_decay() {
    let net = Ctrnn::zeros(6, 3);
    let alpha = 0.1 / (1.0f32.exp().ln_1p());
    assert!((net.alpha()[0] - alpha).abs() < 1e-7);
    let h0 = [0.9f32, -0.5, 0.3, 0.0, 1.0, -1.0];
    let mut h = h0;
    let mut r = rng(0);
    for n in 1..=50 {
        net.step(&mut h, &[0.7, -0.2, 0.4], &mut r);
        for (hi, h0i) in h.iter().zip(h0) {
            let exact = (1.0 - alpha).powi(n) * h0i;
            assert!((hi - exact).abs() < 1e-5, "step {n}: {hi} vs {exact}");
        }
    }
    // Recurrent noise perturbs the trajectory, reproducibly from the seed.
    let mut noisy = net.clone();
    noisy.noise = 0.1;
    let run = |seed| {
        let mut h = h0;
        let mut r = rng(seed);
        for _ in 0..10 {
            noisy.step(&mut h, &[0.0; 3], &mut r);
        }
        h
    };
    assert_eq!(run(4), run(4));
    assert_ne!(run(4), run(5));
}

/// The first step (1 … `max`) after onset at which `timer` is overdue by 1.5.
fn first_overdue_step(timer: &mut Timer, r: &mut Xoshiro256PlusPlus, max: u32) -> Option<u32> {
    timer.onset(1, 2, r);
    (1..=max).find(|&t| {
        timer.tick(t, r);
        timer.overdue(1.5)
    })
}

#[test]
fn a_noise_free_ramp_is_overdue_from_k_times_its_expected_time() {
    // Untrained drift-diffusion timer: drift z / 8 steps, no noise, so x/z = t / 8 and the
    // interval is overdue (k = 1.5) from step 12 on; a time-cell clock never is.
    let mut r = rng(0);
    assert_eq!(
        first_overdue_step(&mut Timer::ddm(0.0), &mut r, 30),
        Some(12)
    );
    let mut cells = Timer::time_cells(Representation::csc());
    assert_eq!(first_overdue_step(&mut cells, &mut r, 100), None);
}

#[test]
fn an_sbf_clock_is_overdue_from_k_times_its_remembered_time() {
    // One noise-free memory of a 10-step interval (0.25 s at 25 ms per step): overdue
    // (k = 1.5) from step 15; with the clock running twice as fast the remembered time is
    // reached at half the steps, so from step 8 (0.2 s ≥ 1.5 × 0.25 s / 2).
    for (speed, expected) in [(1.0, 15u32), (2.0, 8)] {
        let mut r = rng(1);
        let mut timer = Timer::sbf(200, FrequencyLayout::Even, 0.0, &mut r);
        timer.reinforce(1, 10.0, true, &mut r);
        if let Timer::Sbf(s) = &mut timer {
            s.model.clock_speed = speed;
        }
        let first = first_overdue_step(&mut timer, &mut r, 60);
        assert_eq!(first, Some(expected), "clock speed {speed}");
    }
}

/// Trains `timecells-csc` on fixed interval TD 6 for 300 episodes with `alpha_end`.
fn trained_weights(alpha_end: Option<f64>) -> (f64, String) {
    trained_weights_with(alpha_end, 0.0)
}

/// [`trained_weights`] with the visit-count step floor `visit_power`.
fn trained_weights_with(alpha_end: Option<f64>, visit_power: f64) -> (f64, String) {
    use chronocooked_env::{ChronoEnv, make_config};
    use chronocooked_models::timing::zoo::make_timing_agent;
    use chronocooked_models::{TimingTrainConfig, train_timing_agent};
    let config = make_config("FixedInterval-v0", &["td=6".to_string()]).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    let mut agent = make_timing_agent("timecells-csc", &env, 3).unwrap();
    let train = TimingTrainConfig {
        episodes: 300,
        eval_every: 0,
        alpha_end,
        visit_power,
        ..Default::default()
    };
    train_timing_agent(&mut agent, &config, &train, &[6], 3, |_| {}).unwrap();
    let weights = serde_json::to_string(&agent.learner.weights).unwrap();
    let saved = serde_json::to_value(&agent.learner).unwrap();
    let mut keys: Vec<&String> = saved.as_object().unwrap().keys().collect();
    keys.sort();
    assert_eq!(
        keys,
        ["actions", "config", "features", "q_init", "weights"],
        "the saved learner holds no visit counts"
    );
    (agent.learner.config.alpha, weights)
}

#[test]
fn an_annealed_step_size_changes_learning_and_leaves_the_agents_alpha_as_configured() {
    let (alpha_const, constant) = trained_weights(None);
    // Annealing to the same value is the constant step size, update for update.
    let (alpha_same, same) = trained_weights(Some(alpha_const));
    assert_eq!(same, constant);
    let (alpha_annealed, annealed) = trained_weights(Some(0.005));
    assert_ne!(
        annealed, constant,
        "alpha_end had no effect on the learned weights"
    );
    // The saved agent keeps its configured alpha (the schedule belongs to the run).
    assert_eq!(alpha_const, 0.05);
    assert_eq!(alpha_same, 0.05);
    assert_eq!(alpha_annealed, 0.05);
    // The visit-count floor changes learning too; off (0) it is the plain schedule.
    let (_, floor_off) = trained_weights_with(Some(0.005), 0.0);
    assert_eq!(floor_off, annealed);
    let (alpha_floor, floor) = trained_weights_with(Some(0.005), 0.85);
    assert_ne!(
        floor, annealed,
        "visit_power had no effect on the learned weights"
    );
    assert_eq!(alpha_floor, 0.05);
}
