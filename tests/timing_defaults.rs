//! The timing models' literature-calibrated defaults, checked through the project's own
//! training and evaluation path: scalar first-check variability on fixed interval, an
//! animal-like Weber fraction on bisection, the reference protocol sampling a noisy model's
//! noise, and each bisection decision rule putting the bisection point at its own mean.

use chronocooked_analysis::{Mode, compute_metrics, reference_conditions, run_protocol};
use chronocooked_training::timing_run::load_agent;
use chronocooked_training::{TimingRunConfig, run_timing_training};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-defaults-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Trains `model` on `task` with `sets` and evaluates it with the reference protocol.
fn trained_metrics(
    model: &str,
    task: &str,
    sets: &[&str],
    seed: u64,
) -> (chronocooked_analysis::Metrics, usize) {
    let mut cfg = TimingRunConfig::new(&chronocooked_env::Task::new(task).unwrap(), model, seed);
    for s in sets {
        cfg.set(s).unwrap();
    }
    let dir = temp_dir(&format!("{model}-{task}-{}-{seed}", sets.join("-")));
    run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
    let mut agent = load_agent(&dir, None).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let conds = reference_conditions(&cfg.task).unwrap();
    let records = run_protocol(agent.as_mut(), &conds, Mode::Reference, seed).unwrap();
    (compute_metrics(model, &records, 0), records.len())
}

#[test]
fn default_drift_diffusion_and_delay_line_time_with_scalar_variability() {
    // Drift-diffusion: first-passage CV = m/√z = 0.15 at every TD (Simen et al. 2011). Time
    // cells: a per-trial clock-speed factor with log-SD 0.15 moves every response in
    // proportion to TD. With 4 noise draws × 12 start cells = 48 episodes per TD, a CV's
    // sampling error is ≈ 10% of it; the bands allow that and the one-step quantisation.
    // Laplace time cells share the clock noise since their speed factor scales only time
    // (session 15: it had scaled every cell's amplitude by r^{−k} as well).
    for (model, lo, hi) in [
        ("ddm", 0.09, 0.25),
        ("timecells-csc", 0.09, 0.25),
        ("timecells-laplace", 0.09, 0.25),
    ] {
        let mut cvs = Vec::new();
        for td in [6u32, 18] {
            let (m, n) = trained_metrics(model, "FixedInterval-v0", &[&format!("env.td={td}")], 0);
            let foc = m.fi.unwrap().foc;
            let f = foc.iter().find(|f| f.td == td).unwrap();
            assert!(f.n >= 40, "{model} TD {td}: {n} episodes, FOC n {}", f.n);
            let ratio = f.mean / f64::from(td);
            assert!(
                (0.8..=1.2).contains(&ratio),
                "{model} TD {td}: FOC/TD {ratio}"
            );
            assert!((lo..=hi).contains(&f.cv), "{model} TD {td}: CV {}", f.cv);
            cvs.push(f.cv);
        }
        let spread = cvs[0].max(cvs[1]) / cvs[0].min(cvs[1]);
        assert!(spread <= 1.5, "{model}: CV at TD 6 and 18 {cvs:?}");
    }
}

#[test]
fn default_bisection_has_an_animal_like_weber_fraction() {
    // Clock and memory noise together give the judgment a log-SD of ≈ 0.18, so WF ≈
    // 0.67 × 0.18 ≈ 0.12 (animals: 0.1–0.3) while the anchors of a 1:2 pair stay ≥ 90%
    // right (error ≈ Φ(−ln 2 / 2 / 0.18) ≈ 3%). The curve is a real transition: WF defined.
    let (m, _) = trained_metrics("ddm", "Bisection-v0", &["env.short=5", "env.long=10"], 0);
    let b = m.bisection.unwrap();
    let fit = b.fit.unwrap();
    assert!(!fit.separated, "{fit:?}");
    assert!(
        (0.05..=0.3).contains(&fit.wf),
        "WF {} {:?}",
        fit.wf,
        b.p_long
    );
    assert!(b.anchor_accuracy >= 0.9, "anchors {}", b.anchor_accuracy);
    let gm = 50f64.sqrt();
    assert!((0.85..=1.25).contains(&(fit.bp / gm)), "BP {}", fit.bp);
}

#[test]
fn time_cell_bisection_follows_its_noise_model_at_ratio_two() {
    // A time cell's judgment compares this trial's decoded time (clock-speed noise c, log-SD)
    // with the geometric mean of one stored estimate of each anchor (each with its own
    // trial's clock noise and the memory factor m): log-variance c² + (c² + m²)/2. With the
    // defaults c = m = 0.15, σ = 0.212: WF ≈ 0.674 σ = 0.143 and anchors at ratio 2 ≈
    // Φ(ln 2 / (2σ)) = 0.949. Means over four training seeds on 5-10, tolerances for the
    // decoder's step rounding (it lowers the fitted WF, measured 0.12–0.13) and sampling.
    let seeds = 0..4u64;
    let (mut wf, mut anchors) = (0.0, 0.0);
    for seed in seeds.clone() {
        let (m, _) = trained_metrics(
            "timecells-ms",
            "Bisection-v0",
            &["env.short=5", "env.long=10"],
            seed,
        );
        let b = m.bisection.unwrap();
        wf += b
            .fit
            .unwrap_or_else(|| panic!("seed {seed}: {:?}", b.p_long))
            .wf;
        anchors += b.anchor_accuracy;
    }
    let n = seeds.count() as f64;
    let (wf, anchors) = (wf / n, anchors / n);
    let sigma = (0.15f64.powi(2) + (0.15f64.powi(2) + 0.15f64.powi(2)) / 2.0).sqrt();
    let predicted_wf = 0.674 * sigma;
    assert!((predicted_wf - 0.143).abs() < 0.001);
    assert!(
        (predicted_wf - 0.035..=predicted_wf + 0.02).contains(&wf),
        "WF {wf} against {predicted_wf}"
    );
    // Φ(ln 2 / 2σ) = 0.949 (by hand: ln 2 / 0.424 = 1.635).
    assert!((0.925..=0.975).contains(&anchors), "anchors {anchors}");
}

#[test]
fn probes_far_below_the_short_anchor_are_judged_short() {
    // Microstimuli seed 2 on 6-12 is the measured case: walking while the oven ran, it stood
    // at different cells when the short and the long anchor ended, chose the counter by its
    // cell, and sent the 1- and 2-step probes (picked up from the cell where it had put the
    // onion) to the long counter — P(long) 1.00, 1.00, then 0.00: not a psychometric curve.
    // Waiting at the oven, its choice follows its clock's judgment: P(long) rises with the
    // probe (no drop between neighbouring probes beyond sampling noise, 128 episodes each).
    let (m, _) = trained_metrics(
        "timecells-ms",
        "Bisection-v0",
        &["env.short=6", "env.long=12"],
        2,
    );
    let b = m.bisection.unwrap();
    let p: Vec<f64> = b.p_long.iter().copied().filter(|v| v.is_finite()).collect();
    assert!(p.len() >= 10, "{:?}", b.p_long);
    assert!(
        p[0] <= 0.1 && p[1] <= 0.1,
        "short probes judged long: {p:?}"
    );
    let worst_drop = p.windows(2).map(|w| w[0] - w[1]).fold(0.0, f64::max);
    assert!(worst_drop <= 0.25, "non-monotone: {p:?}");
}

#[test]
fn the_reference_protocol_samples_a_noisy_models_noise() {
    // 12 free start cells on fixed interval, 2 PI probes + the FI condition: a noisy model
    // plays each start cell NOISE_DRAWS (16) times, a noise-free one once.
    use chronocooked_models::timing::agent::NOISE_DRAWS;
    let (_, noisy) = trained_metrics("ddm", "FixedInterval-v0", &["env.td=6"], 1);
    let quiet = ["env.td=6", "noise=0", "memory_noise=0"];
    let (_, exact) = trained_metrics("ddm", "FixedInterval-v0", &quiet, 1);
    assert_eq!(exact, 3 * 12, "one episode per start cell and condition");
    assert_eq!(NOISE_DRAWS, 16);
    assert_eq!(noisy, NOISE_DRAWS * exact, "{noisy} vs {exact}");
}

#[test]
fn each_decision_rule_puts_the_bisection_point_at_its_own_mean() {
    // Anchors 4 and 16: geometric mean 8, arithmetic mean 10, harmonic mean 6.4. Without
    // noise the time-cell judgment is exact, so BP lands between the probes around the
    // rule's criterion.
    let bp = |rule: &str| {
        let sets = [
            "env.short=4",
            "env.long=16",
            "clock_noise=0",
            "memory_noise=0",
            &format!("decision_rule={rule}"),
        ];
        let (m, _) = trained_metrics("timecells-csc", "Bisection-v0", &sets, 2);
        let b = m.bisection.unwrap();
        b.fit.unwrap_or_else(|| panic!("{rule}: {:?}", b.p_long)).bp
    };
    let (ratio, difference, likelihood) = (bp("ratio"), bp("difference"), bp("likelihood"));
    assert!((ratio - 8.0).abs() <= 1.0, "ratio rule BP {ratio}");
    assert!(
        (difference - 10.0).abs() <= 1.0,
        "difference rule BP {difference}"
    );
    assert!(
        (likelihood - 6.4).abs() <= 1.0,
        "likelihood rule BP {likelihood}"
    );
    assert!(likelihood < ratio && ratio < difference);
    // The learned criterion starts at the arithmetic mean; noise-free, no error ever moves
    // it, so it stays there — a result of learning, not of construction.
    let learned = bp("learned");
    assert!((learned - 10.0).abs() <= 1.0, "learned BP {learned}");
}
