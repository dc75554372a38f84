//! Evaluation protocols end to end: the oracle gives the ideal answers, a random agent gives
//! failed fits reported as such, and metrics recomputed from saved records are identical.

use chronocooked_analysis::{
    ConditionKind, Mode, compute_metrics, reference_conditions, run_protocol,
};
use chronocooked_env::{ChronoEnv, TaskParams, make_config};
use chronocooked_models::agent::{OracleAgent, RandomAgent};

#[test]
fn oracle_gives_the_ideal_bisection_and_fi_answers() {
    let env = ChronoEnv::from_id("Bisection-v0", &["short=4", "long=12"]).unwrap();
    let conds = reference_conditions(
        &chronocooked_env::Task::parse(
            "Bisection-v0",
            &["short=4".into(), "long=12".into()] as &[String],
        )
        .unwrap(),
    )
    .unwrap();
    assert_eq!(conds.len(), 16, "probes 1..L+4");
    let mut oracle = OracleAgent::new(&env);
    let recs = run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap();
    assert_eq!(recs.len(), 16 * 8);
    let m = compute_metrics("oracle", &recs, 0);
    let b = m.bisection.unwrap();
    for (p, pl) in b.probes.iter().zip(&b.p_long) {
        if p.t < 4.0 {
            assert_eq!(*pl, 0.0, "probe {}", p.t);
        }
        if p.t > 12.0 {
            assert_eq!(*pl, 1.0, "probe {}", p.t);
        }
    }
    assert_eq!(b.anchor_accuracy, 1.0);
    let fit = b.fit.unwrap();
    assert!(fit.separated && fit.bp > 6.0 && fit.bp < 7.5, "{fit:?}");

    // FI: the oracle's first oven check is exactly the TD.
    let env = ChronoEnv::from_id("FixedInterval-v0", &["td=9"]).unwrap();
    let conds = reference_conditions(
        &chronocooked_env::Task::parse("FixedInterval-v0", &["td=9".into()] as &[String]).unwrap(),
    )
    .unwrap();
    assert_eq!(
        conds.iter().filter(|c| c.kind == ConditionKind::Pi).count(),
        2
    );
    let mut oracle = OracleAgent::new(&env);
    let recs = run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap();
    let m = compute_metrics("oracle", &recs, 0);
    let fi = m.fi.unwrap();
    assert_eq!(fi.foc.len(), 1);
    assert_eq!(fi.foc[0].mean, 9.0);
    assert_eq!(fi.foc[0].sd, 0.0);
    assert_eq!(m.conditions[0].success_rate, 1.0);
    // PI: the ideal timer starts checking at TD.
    let pi = &m.pi[0];
    // (Oven time 0 has no action: the onion goes in and the timer reads 1 at the next one.)
    assert!(pi.rate[0].is_nan());
    assert!(
        pi.rate[1..9].iter().all(|&r| r == 0.0) && pi.rate[9] == 1.0,
        "{:?}",
        pi.rate
    );
}

#[test]
fn random_agent_gives_failed_fits_not_crashes_and_metrics_recompute_identically() {
    let conds =
        reference_conditions(&chronocooked_env::Task::new("Bisection-v0").unwrap()).unwrap();
    let mut random = RandomAgent::default();
    let recs = run_protocol(&mut random, &conds, Mode::Stochastic { episodes: 5 }, 3).unwrap();
    assert_eq!(recs.len(), 16 * 5);
    let m = compute_metrics("random", &recs, 0);
    let b = m.bisection.as_ref().unwrap();
    assert!(b.fit.is_none() && b.fit_error.is_some(), "{b:?}");
    assert!(
        b.fit_error.as_ref().unwrap().contains("no reliable"),
        "{b:?}"
    );
    assert!(
        b.p_long.iter().any(|p| p.is_nan()),
        "probes with >50% failures are NaN"
    );
    let json = serde_json::to_string(&m).unwrap();
    // Records → JSON lines → records → the same metrics JSON.
    let lines: Vec<String> = recs
        .iter()
        .map(|r| serde_json::to_string(r).unwrap())
        .collect();
    let back: Vec<chronocooked_analysis::EvalRecord> = lines
        .iter()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(back, recs);
    assert_eq!(
        serde_json::to_string(&compute_metrics("random", &back, 0)).unwrap(),
        json
    );
    // Same seed → same stochastic evaluation.
    let again = run_protocol(
        &mut RandomAgent::default(),
        &conds,
        Mode::Stochastic { episodes: 5 },
        3,
    )
    .unwrap();
    assert_eq!(again, recs);
}

#[test]
fn every_task_has_reference_conditions_the_oracle_plays() {
    let mut paying = 0;
    for spec in chronocooked_env::all_tasks() {
        let conds = reference_conditions(&chronocooked_env::Task::new(spec.id).unwrap()).unwrap();
        assert!(!conds.is_empty(), "{}", spec.id);
        let env = ChronoEnv::from_id(spec.id, &[] as &[&str]).unwrap();
        let mut oracle = OracleAgent::new(&env);
        let mut recs = run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap();
        // Reference protocol: one greedy episode per free start cell per condition, in
        // condition order and row-major start order, each played at its condition's TD —
        // except reproduction, which plays each context's sample intervals in a random
        // order (Jazayeri & Shadlen 2010): there the same episodes, mixed.
        if spec.id == "Reproduction-v0" {
            let played: Vec<u32> = recs.iter().map(|r| r.condition.td).collect();
            assert!(
                played.windows(2).any(|w| w[0] > w[1]),
                "sample intervals mixed"
            );
            let index =
                |c: &chronocooked_analysis::Condition| conds.iter().position(|x| x == c).unwrap();
            recs.sort_by_key(|r| (index(&r.condition), r.episode.start));
        }
        let mut k = 0;
        for c in &conds {
            let cenv = ChronoEnv::new(&c.task.config().unwrap()).unwrap();
            let layout = cenv.layout();
            for &cell in layout.free_cells() {
                let r = &recs[k];
                assert_eq!(r.condition, *c, "{}", spec.id);
                assert_eq!(r.episode.start, layout.coords(cell as usize), "{}", spec.id);
                assert_eq!(r.episode.td, c.td, "{}", spec.id);
                k += 1;
            }
        }
        assert_eq!(k, recs.len(), "{}: no extra episodes", spec.id);
        // The oracle earns the full reward in every condition that pays it: the trained
        // FI interval, the bisection anchors, every trained multi-timer TD, the normal
        // uncertainty episodes.
        let m = compute_metrics("oracle", &recs, 0);
        assert_eq!(m.episodes, recs.len());
        let config = make_config(spec.id, &[] as &[&str]).unwrap();
        for c in &m.conditions {
            let pays = match c.kind.as_str() {
                "fi" => true,
                "bisection" => match config.params {
                    TaskParams::Bisection { short, long } => c.td == short || c.td == long,
                    _ => false,
                },
                "multi_timer" => match &config.params {
                    TaskParams::MultiTimer { tds, .. } => tds.contains(&c.td),
                    _ => false,
                },
                "uncertainty" => c.never_ready == Some(false),
                "reproduction" => true,
                "multi_anchor" => config
                    .params
                    .active_anchors()
                    .is_some_and(|a| a.contains(&c.td)),
                "multi_oven" => match config.params {
                    TaskParams::MultiOven { short, long, .. } => c.td == short || c.td == long,
                    _ => false,
                },
                _ => false,
            };
            if pays {
                assert_eq!(c.success_rate, 1.0, "{}: {:?}", spec.id, c);
                paying += 1;
            }
        }
    }
    // FI 1, bisection 2 anchors, multi-timer ≥ 1 trained TD, uncertainty 1, multi-anchor
    // 3 anchors, multi-oven 2 anchors, reproduction 2 priors × 7 intervals.
    assert!(paying >= 24, "{paying} paying conditions checked");
}

#[test]
fn multi_timer_dual_and_uncertainty_metrics_on_the_oracle() {
    use chronocooked_analysis::behaviour::metrics::count_plateaus;
    let pts = [
        (1, 2.1),
        (2, 2.0),
        (3, 2.2),
        (4, 4.0),
        (5, 4.1),
        (6, 4.0),
        (7, 4.2),
    ];
    assert_eq!(count_plateaus(&pts, &[2, 4]), 2);
    assert_eq!(count_plateaus(&[(1, 1.0), (2, 2.0), (3, 3.0)], &[]), 0);

    let env = [
        "tds=2,4".to_string(),
        "num_timers=2".into(),
        "mode=lower_bounded".into(),
    ];
    let conds =
        reference_conditions(&chronocooked_env::Task::parse("MultiTimer-v0", &env).unwrap())
            .unwrap();
    let mut oracle = OracleAgent::new(&ChronoEnv::from_id("MultiTimer-v0", &env).unwrap());
    let m = compute_metrics(
        "oracle",
        &run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap(),
        0,
    );
    let mt = m.multi_timer.unwrap();
    assert_eq!(mt.by_td.len(), 7, "TDs 1..=4+3");
    for (td, reward, off) in &mt.by_td {
        assert_eq!(*reward, 1.0, "TD {td}");
        assert_eq!(*off, f64::from(*td), "the oracle takes the soup at TD");
    }
    assert_eq!(mt.by_buffer.len(), 8, "2 TDs x 4 buffers");
    assert!(mt.by_buffer.iter().all(|b| b.2 == 1.0));

    let conds =
        reference_conditions(&chronocooked_env::Task::new("Uncertainty-v0").unwrap()).unwrap();
    let mut oracle =
        OracleAgent::new(&ChronoEnv::from_id("Uncertainty-v0", &[] as &[&str]).unwrap());
    let m = compute_metrics(
        "oracle",
        &run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap(),
        0,
    );
    let u = m.uncertainty.unwrap();
    assert_eq!(u.success_normal, 1.0);
    assert_eq!(u.button_use, 1.0);
    let td = f64::from(conds[0].td);
    // The oracle waits at the oven until TD, then walks to the button.
    assert!(
        u.press_time >= td && u.press_time <= td + 4.0,
        "{}",
        u.press_time
    );

    let conds = reference_conditions(&chronocooked_env::Task::new("DualTask-v0").unwrap()).unwrap();
    let mut oracle = OracleAgent::new(&ChronoEnv::from_id("DualTask-v0", &[] as &[&str]).unwrap());
    let m = compute_metrics(
        "oracle",
        &run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap(),
        0,
    );
    let d = m.dual.unwrap();
    assert_eq!(d.by_td.len(), 1);
    assert!(
        (d.by_td[0].1 - (1.0 + 0.01 * d.by_td[0].2)).abs() < 1e-5,
        "soup + sink rewards"
    );
    assert!(d.by_td[0].2 > 0.0 && d.by_td[0].3 > 0.0);
}

/// Episodes played by the oracle on `env`, one per `(seed, reset options)`, written exactly
/// as `env play --record` writes them (each reset line with its key, then one line per step).
fn oracle_recording(
    env: &mut ChronoEnv,
    episodes: &[(u64, chronocooked_env::ResetOptions)],
) -> String {
    use chronocooked_env::Oracle;
    use chronocooked_env::trace::TraceLine;
    let oracle = Oracle::new(env);
    let mut text = String::new();
    for (seed, opts) in episodes {
        let info = env.reset(Some(*seed), opts).unwrap();
        text += &TraceLine::reset(env, info)
            .with_reset_key(Some(*seed), *opts)
            .to_json();
        text.push('\n');
        loop {
            let a = oracle.act(&env.state());
            let t = env.step(a).unwrap();
            text += &TraceLine::step(env, a, &t).to_json();
            text.push('\n');
            if t.done() {
                break;
            }
        }
    }
    text
}

#[test]
fn recorded_play_goes_through_the_same_metrics() {
    use chronocooked_env::ResetOptions;
    // Two FI episodes "played" by the oracle, written exactly like `env play --record`.
    let mut env = ChronoEnv::from_id("FixedInterval-v0", &["td=6"]).unwrap();
    let episodes = [(1, (1, 1)), (2, (4, 2))].map(|(seed, start)| {
        let opts = ResetOptions {
            start: Some(start),
            ..Default::default()
        };
        (seed, opts)
    });
    let text = oracle_recording(&mut env, &episodes);
    let recs = chronocooked_analysis::behaviour::human::records_from_trace(&text).unwrap();
    assert_eq!(recs.len(), 2);
    assert!(
        recs.iter()
            .all(|r| r.episode.success && r.condition.kind == ConditionKind::Fi)
    );
    assert_eq!(recs[1].episode.start, (4, 2));
    let m = compute_metrics("human", &recs, 0);
    assert_eq!(m.fi.unwrap().foc[0].mean, 6.0);
    assert!(chronocooked_analysis::behaviour::human::records_from_trace("{not json").is_err());
    assert!(
        chronocooked_analysis::behaviour::human::records_from_trace(
            &text.lines().skip(1).collect::<Vec<_>>().join("\n")
        )
        .is_err()
    );
}

/// Two episodes recorded as `env play` records them: the first reset seeded, the next
/// continuing the generator (start cells drawn), every reset line with its key.
fn play_recording() -> Vec<String> {
    use chronocooked_env::trace::TraceLine;
    use chronocooked_env::{Oracle, ResetOptions};
    let mut env = ChronoEnv::from_id("FixedInterval-v0", &["td=5"]).unwrap();
    let oracle = Oracle::new(&env);
    let opts = ResetOptions::default();
    let mut lines = Vec::new();
    for seed in [Some(11), None] {
        let info = env.reset(seed, &opts).unwrap();
        lines.push(
            TraceLine::reset(&env, info)
                .with_reset_key(seed, opts)
                .to_json(),
        );
        loop {
            let a = oracle.act(&env.state());
            let t = env.step(a).unwrap();
            lines.push(TraceLine::step(&env, a, &t).to_json());
            if t.done() {
                break;
            }
        }
    }
    lines
}

#[test]
fn an_edited_play_recording_is_refused_naming_the_line_and_the_field() {
    use chronocooked_analysis::behaviour::human::records_from_trace;
    let lines = play_recording();
    let recs = records_from_trace(&lines.join("\n")).unwrap();
    assert_eq!(recs.len(), 2);
    assert!(recs.iter().all(|r| r.episode.success));
    let first_end = lines
        .iter()
        .position(|l| l.contains("\"terminated\":true"))
        .unwrap();
    let edit = |k: usize, from: &str, to: &str| {
        let mut edited = lines.clone();
        assert!(edited[k].contains(from), "{from} in line {}", k + 1);
        edited[k] = edited[k].replacen(from, to, 1);
        records_from_trace(&edited.join("\n")).unwrap_err()
    };
    // The paid delivery made unpaid: the replay pays it.
    let e = edit(first_end, "\"reward\":1.0", "\"reward\":0.0");
    assert!(
        e.contains(&format!("line {}", first_end + 1)) && e.contains("`reward`"),
        "{e}"
    );
    // Another TD in one step's info.
    let e = edit(2, "\"td\":5", "\"td\":7");
    assert!(e.contains("line 3") && e.contains("`info.td`"), "{e}");
    // The second episode's start cell moved: its reset is not the generator's.
    let second = first_end + 1;
    let e = edit(second, "\"agent\":[", "\"agent\":[1");
    assert!(e.contains(&format!("line {}", second + 1)), "{e}");
    // A step appended after the last episode ended.
    let mut extra = lines.clone();
    extra.push(lines[lines.len() - 1].clone());
    let e = records_from_trace(&extra.join("\n")).unwrap_err();
    assert!(e.contains("after the episode ended"), "{e}");
    // Recordings made before reset lines carried their key are read unchecked.
    let unkeyed: Vec<String> = lines
        .iter()
        .map(|l| {
            let mut v: serde_json::Value = serde_json::from_str(l).unwrap();
            v.as_object_mut().unwrap().remove("reset");
            v.to_string()
        })
        .collect();
    assert_eq!(records_from_trace(&unkeyed.join("\n")).unwrap().len(), 2);
}

#[test]
fn reproduction_metrics_of_the_oracle_are_veridical_with_the_gain() {
    let env_sets = vec!["priors=short,9-17".to_string(), "gains=1,1.5".to_string()];
    let conds =
        reference_conditions(&chronocooked_env::Task::parse("Reproduction-v0", &env_sets).unwrap())
            .unwrap();
    // 2 gains × (7 + 9) intervals of the two priors.
    assert_eq!(conds.len(), 2 * (7 + 9));
    let env = ChronoEnv::from_id("Reproduction-v0", &env_sets).unwrap();
    let mut oracle = OracleAgent::new(&env);
    let recs = run_protocol(&mut oracle, &conds, Mode::Reference, 0).unwrap();
    let m = compute_metrics("oracle", &recs, 0);
    let r = m.reproduction.expect("reproduction metrics");
    assert_eq!(r.contexts.len(), 4);
    for c in &r.contexts {
        assert_eq!(c.failures, 0);
        // The oracle produces round(g·ts): the ratio is 1 up to the rounding of g·ts.
        for &(ts, ratio) in &c.ratio {
            let want = (c.gain * f64::from(ts)).round() / (c.gain * f64::from(ts));
            assert!((ratio - want).abs() < 1e-9, "g {} ts {ts}: {ratio}", c.gain);
        }
        let slope = c.slope.unwrap();
        assert!(
            (slope - c.gain).abs() < 0.02,
            "slope {slope} at gain {}",
            c.gain
        );
        if c.gain == 1.0 {
            assert!(c.bias.unwrap().abs() < 1e-9 && c.sqrt_var.unwrap() < 1e-9);
            assert!(c.observer.is_some(), "gain 1 contexts get an observer fit");
        } else {
            assert!(c.observer.is_none());
        }
    }
}

/// Defect (issue #68): human play on a multi-anchor task with non-default anchors was scored
/// against the registered anchors (4, 8, 12), because the condition was rebuilt from the
/// task id alone. The oracle plays anchors 3 and 9 exactly as `env play --record` writes
/// them; the records carry those anchors and every anchor episode counts as right.
#[test]
fn recorded_play_is_scored_against_the_parameters_it_was_played_with() {
    use chronocooked_env::ResetOptions;
    let mut env = ChronoEnv::from_id("MultiAnchor-v0", &["anchors=3,9"]).unwrap();
    let episodes: Vec<(u64, ResetOptions)> = [3u32, 9, 3, 9]
        .iter()
        .enumerate()
        .map(|(i, &td)| {
            let opts = ResetOptions {
                td: Some(td),
                ..Default::default()
            };
            (i as u64 + 1, opts)
        })
        .collect();
    let text = oracle_recording(&mut env, &episodes);
    let recs = chronocooked_analysis::behaviour::human::records_from_trace(&text).unwrap();
    assert_eq!(recs.len(), 4);
    for r in &recs {
        let played = r.condition.task.config().unwrap();
        assert_eq!(played.params.active_anchors(), Some(&[3u32, 9][..]));
        assert_eq!(
            r.condition.task.overrides(),
            vec!["anchors=3,9".to_string()]
        );
    }
    let m = compute_metrics("human", &recs, 0);
    let ma = m.multi_anchor.expect("multi-anchor metrics");
    assert_eq!(ma.anchors, vec![3, 9]);
    assert_eq!(ma.anchor_accuracy, 1.0);
}
