//! Known answers for the multi-anchor and multi-oven metrics: scripted categorizers with a
//! known boundary rule and known noise (log-normal perceived durations, as a scalar timer
//! has), their records built directly, and the metrics compared with the closed forms.

use chronocooked_analysis::behaviour::categorization::{accepted, multi_anchor_metrics};
use chronocooked_analysis::behaviour::concurrent::{delivery_order, multi_oven_metrics};
use chronocooked_analysis::records::{Condition, ConditionKind, EvalRecord};
use chronocooked_env::{Counter, Events, Info, OvenSet};
use chronocooked_models::EpisodeRecord;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

fn record(
    kind: ConditionKind,
    task: &str,
    env: &[String],
    td: u32,
    infos: Vec<Info>,
) -> EvalRecord {
    EvalRecord {
        condition: Condition {
            kind,
            task: chronocooked_env::Task::parse(task, env).unwrap(),
            td,
            never_ready: None,
            factor: None,
            context: None,
        },
        episode: EpisodeRecord {
            td,
            start: (1, 1),
            seed: 0,
            reward: 0.0,
            success: false,
            actions: vec![5; infos.len()],
            infos,
            ovens: Vec::new(),
        },
    }
}

fn delivery(counter: Counter) -> Info {
    Info {
        timestep: 1,
        counter: Some(counter),
        events: Events(Events::DELIVERY),
        ..Info::default()
    }
}

/// A categorizer that perceives `ln t + σ z` and picks the counter of the category whose
/// boundaries (`rule(a_i, a_{i+1})`) enclose it.
fn categorize(
    anchors: &[u32],
    sigma: &[f64],
    rule: fn(f64, f64) -> f64,
    per_probe: usize,
    seed: u64,
) -> Vec<EvalRecord> {
    let env = vec![format!(
        "anchors={}",
        anchors
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(",")
    )];
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let last = *anchors.last().unwrap();
    let mut out = Vec::new();
    for t in 1..=last + 4 {
        for _ in 0..per_probe {
            let z: f64 = StandardNormal.sample(&mut rng);
            // The noise of the boundary nearest t in log time (each boundary its own σ).
            let b = anchors
                .windows(2)
                .map(|w| (f64::from(t).ln() - rule(f64::from(w[0]), f64::from(w[1])).ln()).abs())
                .enumerate()
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .map_or(0, |(i, _)| i);
            let perceived = (f64::from(t).ln() + sigma[b.min(sigma.len() - 1)] * z).exp();
            let c = 1 + anchors
                .windows(2)
                .filter(|w| perceived >= rule(f64::from(w[0]), f64::from(w[1])))
                .count();
            out.push(record(
                ConditionKind::MultiAnchor,
                "MultiAnchor-v0",
                &env,
                t,
                vec![delivery(Counter::Anchor(c as u8))],
            ));
        }
    }
    out
}

fn gm(a: f64, b: f64) -> f64 {
    (a * b).sqrt()
}
fn am(a: f64, b: f64) -> f64 {
    0.5 * (a + b)
}

/// Closed form: a log-normal judgment `Φ((ln t − ln B)/σ)` has T75/T25 = B·e^{±0.6745σ},
/// so DL / BP = sinh(0.6745 σ) (the logistic fit approximates the probit within a few %).
fn wf_of(sigma: f64) -> f64 {
    (0.674_49 * sigma).sinh()
}

#[test]
fn boundaries_sit_where_the_rule_puts_them_with_the_known_weber_fraction() {
    for (anchors, rule, name) in [
        (vec![4u32, 16, 40], gm as fn(f64, f64) -> f64, "geometric"),
        (vec![4u32, 16, 40], am as fn(f64, f64) -> f64, "arithmetic"),
        (
            vec![3u32, 7, 13, 29],
            gm as fn(f64, f64) -> f64,
            "geometric",
        ),
    ] {
        let sigma = [0.12];
        let recs = categorize(&anchors, &sigma, rule, 300, 11);
        let m = multi_anchor_metrics(&recs, 5).expect("multi-anchor metrics");
        assert_eq!(m.anchors, anchors);
        assert_eq!(m.boundaries.len(), anchors.len() - 1);
        for b in &m.boundaries {
            let fit = b
                .fit
                .as_ref()
                .unwrap_or_else(|| panic!("{name}: {:?}", b.fit_error));
            let want = rule(f64::from(b.lower), f64::from(b.upper));
            let (lo, hi) = fit.bp_ci.expect("bootstrap interval");
            assert!(
                (fit.bp - want).abs() / want < 0.03 || (lo..=hi).contains(&want),
                "{name} {}-{}: BP {} vs {want} [{lo}, {hi}]",
                b.lower,
                b.upper,
                fit.bp
            );
            // GM and AM differ by ≥ 10% on these pairs, so the nearer mean is decidable.
            assert_eq!(b.nearer.as_deref(), Some(name), "{}-{}", b.lower, b.upper);
            let wf = wf_of(sigma[0]);
            assert!(
                (fit.wf - wf).abs() / wf < 0.2,
                "{name}: WF {} vs {wf}",
                fit.wf
            );
        }
        let c = m.wf_constancy.as_ref().expect("≥ 2 boundaries");
        assert_eq!(c.constant, Some(true), "{name}: one σ, one WF: {c:?}");
        assert!(m.anchor_accuracy > 0.9);
    }
}

#[test]
fn a_weber_fraction_that_grows_across_boundaries_is_not_constant() {
    // Anchors far enough apart that each boundary's DL spans ≥ 1 probe step (a DL below a
    // step cannot be resolved on whole-step probes).
    let anchors = [10u32, 30, 90];
    let recs = categorize(&anchors, &[0.1, 0.3], gm, 400, 3);
    let m = multi_anchor_metrics(&recs, 9).unwrap();
    let c = m.wf_constancy.unwrap();
    assert_eq!(c.constant, Some(false), "{c:?}");
    assert!(c.wfs[1] > 2.0 * c.wfs[0], "{c:?}");
    for (b, s) in m.boundaries.iter().zip([0.1, 0.3]) {
        let wf = b.fit.as_ref().unwrap().wf;
        assert!((wf - wf_of(s)).abs() / wf_of(s) < 0.25, "σ {s}: WF {wf}");
    }
}

#[test]
fn category_error_rates_match_a_table_counted_by_hand() {
    // Anchors 4, 8, 12; categories: t<4 → {1}; 4≤t<8 → {1,2}; 8≤t<12 → {2,3}; t≥12 → {3}.
    assert_eq!(accepted(0, 3), vec![1]);
    assert_eq!(accepted(1, 3), vec![1, 2]);
    assert_eq!(accepted(2, 3), vec![2, 3]);
    assert_eq!(accepted(3, 3), vec![3]);
    let env = vec!["anchors=4,8,12".to_string()];
    let mk = |t: u32, c: Option<u8>| {
        let infos = match c {
            Some(c) => vec![delivery(Counter::Anchor(c))],
            None => vec![Info::default()],
        };
        record(ConditionKind::MultiAnchor, "MultiAnchor-v0", &env, t, infos)
    };
    let recs = vec![
        mk(2, Some(1)),
        mk(2, Some(2)), // category 0: 1 error of 2
        mk(4, Some(2)), // an anchor falls in the category above: counter 2 is right
        mk(6, Some(3)), // category 1: 1 error of 2
        mk(9, Some(1)),
        mk(9, Some(3)),
        mk(9, None), // category 2: the failure is not a choice: 1 of 2
        mk(15, Some(3)),
        mk(16, Some(3)), // category 3: 0 of 2
    ];
    let m = multi_anchor_metrics(&recs, 0).unwrap();
    let rates: Vec<(u32, u32)> = m
        .category_errors
        .iter()
        .map(|c| (c.errors, c.choices))
        .collect();
    assert_eq!(rates, vec![(1, 2), (1, 2), (1, 2), (0, 2)]);
    assert_eq!(m.category_errors[1].rate, 0.5);
    // Proportions at probe 9 count the failure in the denominator.
    let p9 = m.probes.iter().find(|p| p.t == 9).unwrap();
    assert_eq!(p9.proportions(), vec![1.0 / 3.0, 0.0, 1.0 / 3.0]);
    // Anchor accuracy: probe 4 chose counter 2 (anchor 4 is counter 1) → 0 of 1.
    assert_eq!(m.anchor_accuracy, 0.0);
}

/// One multi-oven episode's record: every oven at duration `t`, oven `o` judged long with
/// the given choices, delivered in `order`, oven 0 started at the put on step `put`.
fn oven_record(
    env: &[String],
    t: u32,
    n: usize,
    choices: &[u8],
    order: &[usize],
    on_time: [i32; 3],
    put: u32,
) -> EvalRecord {
    let mut ovens = OvenSet {
        n: n as u8,
        td: [t; 3],
        timer: [-1; 3],
        on_time,
        off_time: [-1; 3],
        delivered: [0; 3],
        paid: 0,
    };
    // A whole episode: steps 1 … put−1 at the oven, the put, one delivery per step.
    let at = |timestep: u32, events: u16| Info {
        timestep,
        td: t,
        agent: (1, 1),
        events: Events(events),
        ..Info::default()
    };
    let mut infos: Vec<Info> = (1..put).map(|k| at(k, 0)).collect();
    infos.push(at(put, Events::ONION_IN));
    let mut states = vec![ovens; infos.len()];
    for (k, &o) in order.iter().enumerate() {
        ovens.delivered[o] = choices[o];
        infos.push(Info {
            counter: Some(if choices[o] == 2 {
                Counter::Long
            } else {
                Counter::Short
            }),
            ..at(put + 1 + k as u32, Events::DELIVERY)
        });
        states.push(ovens);
    }
    let mut r = record(ConditionKind::MultiOven, "MultiOven-v0", env, t, infos);
    r.episode.ovens = states;
    r.validate().expect("a consistent multi-oven record");
    r
}

#[test]
fn multi_oven_curves_interference_offsets_and_orders_match_the_generator() {
    let (short, long) = (4u32, 16u32);
    let sig = [0.1, 0.1, 0.35]; // oven 3 interfered with
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(21);
    let three: Vec<String> = ["short=4", "long=16", "ovens=3", "asynchronous=true"]
        .map(String::from)
        .to_vec();
    let mut one = three.clone();
    one.push("ovens=1".into());
    let mut recs = Vec::new();
    let gmv = gm(4.0, 16.0);
    let mut judge = |t: u32, s: f64| -> u8 {
        let z: f64 = StandardNormal.sample(&mut rng);
        if f64::from(t).ln() + s * z >= gmv.ln() {
            2
        } else {
            1
        }
    };
    for t in 1..=20u32 {
        for e in 0..250 {
            let choices = [judge(t, sig[0]), judge(t, sig[1]), judge(t, sig[2])];
            // Orders alternate 0-1-2 / 2-0-1; on-times 3 and 9, the put on step 5.
            let order: &[usize] = if e % 2 == 0 { &[0, 1, 2] } else { &[2, 0, 1] };
            recs.push(oven_record(&three, t, 3, &choices, order, [-1, 3, 9], 5));
            let c = [judge(t, 0.1), 0, 0];
            recs.push(oven_record(&one, t, 1, &c, &[0], [-1, -1, -1], 5));
        }
    }
    let m = multi_oven_metrics(&recs, 1).expect("multi-oven metrics");
    assert_eq!(
        (m.short, m.long, m.ovens, m.asynchronous),
        (short, long, 3, true)
    );
    for (c, s) in m.per_oven.iter().zip(sig) {
        let f = c.fit.as_ref().unwrap();
        // The logistic in linear time fits a log-normal judgment less well as σ grows.
        let tol = if s > 0.2 { 0.3 } else { 0.2 };
        assert!(
            (f.bp - gmv).abs() / gmv < tol / 2.0,
            "oven {}: BP {}",
            c.oven,
            f.bp
        );
        assert!(
            (f.wf - wf_of(s)).abs() / wf_of(s) < tol,
            "oven {}: WF {} vs {}",
            c.oven,
            f.wf,
            wf_of(s)
        );
    }
    let single = m.single.as_ref().expect("the one-oven curve");
    assert!((single.fit.as_ref().unwrap().wf - wf_of(0.1)).abs() / wf_of(0.1) < 0.2);
    // Interference: ovens 1-2 like the single oven, oven 3 a larger WF.
    assert_eq!(m.interference.len(), 3);
    assert!(
        m.interference[0].d_wf.abs() < 0.3 * wf_of(0.1),
        "{:?}",
        m.interference
    );
    assert!(
        m.interference[2].d_wf > 0.5 * (wf_of(0.35) - wf_of(0.1)),
        "{:?}",
        m.interference
    );
    // Offsets: oven 2 at on-time 3 → 3 − 5 = −2, oven 3 at 9 → +4.
    let offsets: Vec<i32> = m.by_offset.iter().map(|o| o.offset).collect();
    assert_eq!(offsets, vec![-2, 4]);
    assert!(
        m.by_offset[0].accuracy > m.by_offset[1].accuracy,
        "{:?}",
        m.by_offset
    );
    // Orders: half each.
    assert_eq!(
        m.orders,
        vec![("0-1-2".to_string(), 2500), ("2-0-1".to_string(), 2500)]
    );
    // The leaderboard's columns: the mean accuracy and WF over the ovens, and the mean
    // interference, which oven 3's wider judgment makes positive.
    let h = chronocooked_analysis::columns::headline(
        &chronocooked_analysis::behaviour::metrics::compute_metrics("scripted", &recs, 1),
    );
    let mean = |v: Vec<f64>| v.iter().sum::<f64>() / v.len() as f64;
    let d_wf = mean(m.interference.iter().map(|i| i.d_wf).collect());
    assert!((h["mo_d_wf"] - d_wf).abs() < 1e-12 && d_wf > 0.0, "{h:?}");
    let accuracy = mean(m.per_oven.iter().map(|c| c.accuracy).collect());
    assert!((h["mo_accuracy"] - accuracy).abs() < 1e-12, "{h:?}");
    // Records alternate three-oven and one-oven episodes: the second three-oven one (e = 1).
    assert_eq!(delivery_order(&recs[2].episode.ovens), vec![2, 0, 1]);
    // A multi-oven record without the ovens' states is refused, not scored without them.
    let mut bare = recs[2].clone();
    bare.episode.ovens.clear();
    let err = bare.validate().unwrap_err();
    assert!(err.contains("`ovens`"), "{err}");
}

#[test]
fn the_leaderboard_columns_of_a_categorizer_are_its_known_boundary_and_weber_fraction() {
    // A geometric-mean categorizer with σ 0.1 on anchors 5, 11, 23 (no doc uses them):
    // boundary / GM ≈ 1, WF ≈ sinh(0.6745 σ), and an accuracy the headline copies.
    let sigma = [0.1];
    let recs = categorize(&[5, 11, 23], &sigma, gm, 300, 21);
    let m = chronocooked_analysis::behaviour::metrics::compute_metrics("scripted", &recs, 3);
    let h = chronocooked_analysis::columns::headline(&m);
    let ma = m.multi_anchor.as_ref().expect("multi-anchor metrics");
    assert_eq!(h["ma_accuracy"], ma.anchor_accuracy);
    assert!(
        (h["ma_bp_over_gm"] - 1.0).abs() < 0.03,
        "{}",
        h["ma_bp_over_gm"]
    );
    let wf = wf_of(sigma[0]);
    assert!((h["ma_wf"] - wf).abs() / wf < 0.2, "{} vs {wf}", h["ma_wf"]);
    for key in ["mo_accuracy", "rp_slope", "fi_success"] {
        assert!(!h.contains_key(key), "{key} without its task");
    }
}

#[test]
fn a_drift_diffusion_timers_simulated_boundaries_equal_its_closed_form() {
    // Anchors 5, 11, 23 (no doc uses them) learned by the model's own rule; its judgment
    // simulated on the timer alone and its closed form on the anchors it remembers, both
    // fitted as the lab fits over the probes between the true anchors.
    use chronocooked_analysis::behaviour::predicted::predicted_boundaries;
    use chronocooked_analysis::behaviour::psychometric::{ProbeCounts, fit_logistic};
    use chronocooked_models::timing::judgment::ddm_judgment_p_long;
    use chronocooked_models::timing::timers::Timer;
    let anchors = [5u32, 11, 23];
    let config = chronocooked_env::make_config("MultiAnchor-v0", &["anchors=5,11,23"]).unwrap();
    let env = chronocooked_env::ChronoEnv::new(&config).unwrap();
    let mut timer = chronocooked_models::timing::zoo::make_timing_agent("ddm", &env, 3)
        .unwrap()
        .timer;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(4);
    for _ in 0..40 {
        for (slot, &a) in anchors.iter().enumerate() {
            timer.clear();
            timer.onset(1, anchors.len(), &mut rng);
            for step in 1..=a {
                timer.tick(step, &mut rng);
            }
            timer.reinforce_choice(slot as u8, f64::from(a), &mut rng);
        }
    }
    let Timer::Ddm(d) = &timer else {
        unreachable!()
    };
    let (noise, z) = ((d.acc.noise, d.memory_noise), d.acc.threshold);
    // What it remembers of each anchor: z / its learned drift (learned from noisy trials,
    // so a few percent from the anchor).
    let remembered: Vec<f64> = (0..anchors.len() as u8)
        .map(|slot| z / d.choice_drifts[&slot])
        .collect();
    let simulated = predicted_boundaries(&mut timer, &anchors, 2000, 7).unwrap();
    for (i, pair) in anchors.windows(2).enumerate() {
        let (s, l) = (remembered[i], remembered[i + 1]);
        let probes: Vec<ProbeCounts> = (pair[0]..=pair[1])
            .map(|t| {
                let p = ddm_judgment_p_long(f64::from(t), s, l, (s * l).sqrt(), noise, z);
                ProbeCounts {
                    t: f64::from(t),
                    valid: 1_000_000,
                    long: (p * 1e6).round() as u32,
                    failed: 0,
                }
            })
            .collect();
        let closed = fit_logistic(&probes).unwrap().bp;
        assert!(
            (simulated[i] / closed - 1.0).abs() < 0.01,
            "{s}-{l}: simulated {:.3}, closed form {closed:.3}",
            simulated[i]
        );
        // Both above the GM, as the noise puts them.
        assert!(closed > (s * l).sqrt(), "{s}-{l}: {closed}");
    }
}
