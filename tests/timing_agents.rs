//! Timing-model agents on the Chronocooked tasks: they learn FI and bisection through the
//! project's own training path, their first oven checks show timing, and every model's
//! recorded activity (timing models and PPO networks) comes out in one dataset type.

use chronocooked_analysis::{
    Mode, compute_metrics, episode_foc, reference_conditions, run_protocol,
};
use chronocooked_env::make_config;
use chronocooked_models::activity::{ActivityMeta, Marker, TrialRecorder};
use chronocooked_models::{Agent, PolicyConfig, evaluate_agent};
use chronocooked_training::timing_run::load_agent;
use chronocooked_training::{ObsEncoding, PpoAgent, TimingRunConfig, run_timing_training};

const MODELS: [&str; 5] = [
    "ddm",
    "sbf",
    "timecells-csc",
    "timecells-ms",
    "timecells-laplace",
];

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-timing-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn timing_agents_solve_fi12_and_bisection_4_12() {
    for task in ["FixedInterval-v0", "Bisection-v0"] {
        for model in MODELS {
            let cfg = TimingRunConfig::new(&chronocooked_env::Task::new(task).unwrap(), model, 0);
            let dir = temp_dir(&format!("{task}-{model}"));
            let summary = run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
            assert!(
                summary.eval_success >= 0.95,
                "{model} on {task}: {summary:?}"
            );
            // The saved agent plays the same.
            let mut agent = load_agent(&dir, None).unwrap();
            let config = cfg.task.config().unwrap();
            let tds = chronocooked_training::eval_tds(&config);
            let records = evaluate_agent(agent.as_mut(), &config, &tds, 1, None).unwrap();
            let rate = chronocooked_models::agent::success_rate(records.iter().map(|r| r.success))
                .expect("evaluation episodes");
            assert!(rate >= 0.95, "{model} on {task} reloaded: {rate}");
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
}

/// Trains the timing run `cfg` through the project's training path (in a temporary run
/// folder named after `label`; unique across the `timing_*` tests) and loads the saved
/// agent.
pub(crate) fn trained_agent(
    cfg: &TimingRunConfig,
    label: &str,
) -> Box<dyn chronocooked_models::Agent> {
    let dir = temp_dir(label);
    run_timing_training(cfg, &dir, "test", |_| {}).unwrap();
    let agent = load_agent(&dir, None).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    agent
}

/// Anchors, largest fall of P(long) between consecutive valid probes, BP/GM, P(long).
fn judged_curve(
    model: &str,
    short: u32,
    long: u32,
    seed: u64,
    sets: &[&str],
) -> (f64, f64, f64, Vec<f64>) {
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("Bisection-v0").unwrap(),
        model,
        seed,
    );
    for s in sets {
        cfg.set(s).unwrap();
    }
    cfg.set(&format!("env.short={short}")).unwrap();
    cfg.set(&format!("env.long={long}")).unwrap();
    let label = format!("judge-{model}-{short}-{long}-{seed}-{}", sets.len());
    let mut agent = trained_agent(&cfg, &label);
    let conds = reference_conditions(&cfg.task).unwrap();
    let records = run_protocol(agent.as_mut(), &conds, Mode::Reference, 7).unwrap();
    let b = compute_metrics(model, &records, 0).bisection.unwrap();
    let valid: Vec<f64> = b.p_long.iter().copied().filter(|p| p.is_finite()).collect();
    assert_eq!(valid.len(), b.p_long.len(), "{model}: every probe answered");
    let drop = valid.windows(2).map(|w| w[0] - w[1]).fold(0.0, f64::max);
    let fit = b
        .fit
        .unwrap_or_else(|| panic!("{model}: {:?}", b.fit_error));
    let gm = f64::from(short * long).sqrt();
    (b.anchor_accuracy, drop, fit.bp / gm, b.p_long)
}

#[test]
fn timing_models_judge_bisection_against_their_anchor_memories() {
    // Each model compares its own timing state with its memories of the anchors; the
    // criterion sits at their geometric mean, so the curve is monotone, probes far below
    // the short anchor are "short", and BP ≈ GM (issue 17's criteria, on two pairs). The
    // mechanism is checked with the models' near-deterministic settings (even 6 vs 8 is
    // then judged right); with the default noise a 6-8 judgment errs as often as its
    // log-SD says (RESULTS.md), and a 1:3 pair is still judged right (below).
    let quiet = |model: &str| -> &'static [&'static str] {
        match model {
            "ddm" => &["noise=0.06", "memory_noise=0"],
            "sbf" => &["memory_noise=0.05", "clock_noise=0"],
            _ => &["clock_noise=0", "memory_noise=0"],
        }
    };
    for model in MODELS[..2].iter().chain(&MODELS[3..]) {
        for (short, long) in [(4, 12), (6, 8)] {
            let (anchors, drop, bp_gm, p) = judged_curve(model, short, long, 3, quiet(model));
            assert!(
                anchors >= 0.95,
                "{model} {short}-{long}: anchors {anchors} {p:?}"
            );
            assert!(drop <= 0.25, "{model} {short}-{long}: drop {drop} {p:?}");
            assert!(
                (0.8..=1.3).contains(&bp_gm),
                "{model} {short}-{long}: BP/GM {bp_gm} {p:?}"
            );
            assert_eq!(
                p[0], 0.0,
                "{model}: probe 1 is far shorter than the short anchor"
            );
            assert_eq!(
                *p.last().unwrap(),
                1.0,
                "{model}: the longest probe is long"
            );
        }
        // Default noise, anchors 1:3 (half-gap ln 3 / 2 = 0.55 against a log-SD ≈ 0.2).
        let (anchors, _, bp_gm, p) = judged_curve(model, 4, 12, 3, &[]);
        assert!(anchors >= 0.9, "{model} 4-12 default: {anchors} {p:?}");
        assert!(
            (0.85..=1.25).contains(&bp_gm),
            "{model} 4-12 default: {bp_gm}"
        );
    }
}

#[test]
fn presence_representation_cannot_do_bisection() {
    // A control: without elapsed-time information the anchors cannot be told apart.
    let cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("Bisection-v0").unwrap(),
        "timecells-presence",
        0,
    );
    let dir = temp_dir("presence");
    let summary = run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
    assert!(summary.eval_success <= 0.6, "{summary:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn first_oven_check_increases_with_td() {
    let tds = [4u32, 6, 9, 12, 18, 24];
    for model in MODELS {
        let mut means = Vec::new();
        for td in tds {
            let mut cfg = TimingRunConfig::new(
                &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
                model,
                0,
            );
            cfg.set(&format!("env.td={td}")).unwrap();
            cfg.set("eval_every=0").unwrap();
            let mut agent = cfg.build_agent().unwrap();
            let config = cfg.task.config().unwrap();
            chronocooked_models::train_timing_agent(
                &mut agent,
                &config,
                &cfg.train,
                &[td],
                0,
                |_| {},
            )
            .unwrap();
            let mut focs = Vec::new();
            for rep in 0..5 {
                let recs = evaluate_agent(&mut agent, &config, &[td], 100 + rep, None).unwrap();
                focs.extend(recs.iter().filter_map(episode_foc));
            }
            assert!(
                focs.len() >= 55,
                "{model} TD {td}: {} pickups of 60",
                focs.len()
            );
            means.push(focs.iter().map(|&f| f as f64).sum::<f64>() / focs.len() as f64);
        }
        assert!(
            means.windows(2).all(|w| w[1] > w[0]),
            "{model}: mean FOC per TD {tds:?} = {means:?}"
        );
        // Roughly on the diagonal: the model times the interval, it does not just wait.
        for (m, td) in means.iter().zip(tds) {
            assert!(
                (m - td as f64).abs() <= 0.35 * td as f64 + 1.5,
                "{model}: {means:?}"
            );
        }
    }
}

#[test]
fn every_model_records_into_the_same_dataset_type() {
    let config = make_config("FixedInterval-v0", &["td=6"]).unwrap();
    let meta = |model: &str| ActivityMeta {
        model: model.into(),
        task: chronocooked_env::Task::parse("FixedInterval-v0", &["td=6"]).unwrap(),
        seed: 0,
        dt: 1.0,
        populations: Vec::new(),
    };
    let env = chronocooked_env::ChronoEnv::new(&config).unwrap();
    let mut agents: Vec<(Box<dyn Agent>, Vec<&str>)> = Vec::new();
    for (name, pops) in [
        ("ddm", vec!["accumulator", "drift", "value", "rpe"]),
        ("sbf", vec!["oscillators", "striatum", "value", "rpe"]),
        (
            "timecells-laplace",
            vec!["time_cells", "laplace", "value", "rpe"],
        ),
    ] {
        let mut a = chronocooked_models::timing::zoo::make_timing_agent(name, &env, 0).unwrap();
        let train = chronocooked_models::TimingTrainConfig {
            episodes: 2000,
            eval_every: 0,
            ..Default::default()
        };
        chronocooked_models::train_timing_agent(&mut a, &config, &train, &[6], 0, |_| {}).unwrap();
        agents.push((Box::new(a), pops));
    }
    for arch in ["lstm8", "ctrnn8", "cnn-mlp"] {
        let pcfg = PolicyConfig::new(arch.parse().unwrap(), 15, 6, 6);
        let policy = pcfg.init(0, &chronocooked_models::cpu());
        let agent = PpoAgent::new(arch, policy, &config, ObsEncoding::Codes).unwrap();
        let pops = if arch == "lstm8" {
            vec!["latent", "cell", "value"]
        } else {
            vec!["latent", "value"]
        };
        agents.push((Box::new(agent), pops));
    }
    for (mut agent, pops) in agents {
        let name = agent.name();
        let mut rec = TrialRecorder::new(meta(&name));
        let records = evaluate_agent(agent.as_mut(), &config, &[6], 0, Some(&mut rec)).unwrap();
        let ds = rec.finish();
        let names: Vec<&str> = ds
            .meta
            .populations
            .iter()
            .map(|p| p.name.as_str())
            .collect();
        assert_eq!(names, pops, "{name}");
        assert_eq!(ds.trials.len(), records.len(), "{name}");
        let n = ds.meta.n_units();
        assert_eq!(ds.meta.unit_names().len(), n);
        for (trial, r) in ds.trials.iter().zip(&records) {
            assert_eq!(trial.steps, r.actions.len(), "{name}");
            assert_eq!(trial.activity.len(), trial.steps * n, "{name}");
            assert_eq!(trial.success, r.success);
            // Markers match the env's events step by step.
            for e in &trial.events {
                let step = e.step as usize;
                let expected = Marker::of_step(&r.infos[step], r.ovens.get(step), 0.0);
                assert!(
                    expected.contains(&e.marker) || e.marker == Marker::Reward,
                    "{name}: {e:?}"
                );
            }
        }
        // Aligned to oven-on: [trials, window, N], NaN past a trial's end.
        let (aligned, used) = ds.aligned(Marker::OvenOn, 8);
        assert_eq!(aligned.len(), used.len() * 9 * n, "{name}");
        if name.starts_with("timecells") || name == "ddm" || name == "sbf" {
            assert_eq!(
                used.len(),
                ds.trials.len(),
                "{name}: every trained trial turns the oven on"
            );
        }
        // The dataset round-trips through JSON.
        let back: chronocooked_models::ActivityDataset =
            serde_json::from_str(&serde_json::to_string(&ds).unwrap()).unwrap();
        assert_eq!(back.meta, ds.meta);
        assert_eq!(back.trials.len(), ds.trials.len());
    }
}

#[test]
fn ddm_activity_ramps_to_threshold_at_the_first_check() {
    // The accumulator is a ramping unit aligned to oven-on, and the first check (FOC)
    // comes when it reaches the threshold z = 1 (or one step after).
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        "ddm",
        3,
    );
    cfg.set("env.td=12").unwrap();
    let dir = temp_dir("ddm-ramp");
    run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
    let mut agent = load_agent(&dir, None).unwrap();
    let config = cfg.task.config().unwrap();
    let mut rec = TrialRecorder::new(ActivityMeta {
        model: "ddm".into(),
        task: cfg.task.clone(),
        seed: 0,
        dt: 1.0,
        populations: Vec::new(),
    });
    evaluate_agent(agent.as_mut(), &config, &[12], 9, Some(&mut rec)).unwrap();
    let ds = rec.finish();
    let acc = ds.meta.range("accumulator").unwrap().start;
    let n = ds.meta.n_units();
    for trial in &ds.trials {
        let on = trial.first(Marker::OvenOn).unwrap() as usize;
        let check = trial.first(Marker::OvenCheck).unwrap() as usize;
        let x = |step: usize| trial.activity[step * n + acc];
        // At or just below z: a crossing inside the last step counts (Brownian bridge).
        assert!(
            x(check) >= 0.85,
            "responded far below threshold: {}",
            x(check)
        );
        // The check comes at the crossing or one step later (the TD readout of x/z may
        // wait a step: 7 of the trials on this seed).
        assert!(x(check - 2) < 1.0 || check <= on + 2, "{:?}", x(check - 2));
        // Mean slope positive over the interval.
        assert!(x(check) > x(on + 1));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_timing_model_plays_every_task() {
    for spec in chronocooked_env::all_tasks() {
        let config = spec.default_config();
        let env = chronocooked_env::ChronoEnv::new(&config).unwrap();
        let tds = chronocooked_training::eval_tds(&config);
        for m in chronocooked_models::timing::zoo::TIMING_MODELS {
            let mut agent =
                chronocooked_models::timing::zoo::make_timing_agent(m.name, &env, 1).unwrap();
            let train = chronocooked_models::TimingTrainConfig {
                episodes: 150,
                eval_every: 0,
                ..Default::default()
            };
            let curve = chronocooked_models::train_timing_agent(
                &mut agent,
                &config,
                &train,
                &tds,
                1,
                |_| {},
            )
            .unwrap_or_else(|e| panic!("{} on {}: {e}", m.name, spec.id));
            // 150 episodes per level of the tasks learned in levels (the curricula).
            let levels = chronocooked_models::timing::train::training_levels(&config)
                .unwrap()
                .len();
            assert_eq!(curve.last().unwrap().episode, 150 * levels, "{}", spec.id);
            let records = evaluate_agent(&mut agent, &config, &tds, 2, None).unwrap();
            assert!(
                records
                    .iter()
                    .all(|r| !r.actions.is_empty() && r.actions.len() <= 201)
            );
        }
    }
}

#[test]
fn neural_summaries_tell_ramps_sequences_and_oscillations_apart() {
    use chronocooked_analysis::neural::summary::{SummaryOptions, neural_summary};
    // Fixed-interval trials at TD 18 over the first 16 steps after oven-on (the full
    // probe-trial analysis, 2 x TD windows at two TDs, is pipeline/tests/neural_model_signatures.rs).
    let summarise = |model: &str, population: &str| {
        let mut cfg = TimingRunConfig::new(
            &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
            model,
            0,
        );
        cfg.set("env.td=18").unwrap();
        cfg.set("episodes=2000").unwrap();
        let dir = temp_dir(&format!("summary-{model}"));
        run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
        let mut agent = load_agent(&dir, None).unwrap();
        let config = cfg.task.config().unwrap();
        let mut rec = TrialRecorder::new(ActivityMeta {
            model: model.into(),
            task: cfg.task.clone(),
            seed: 0,
            dt: 1.0,
            populations: Vec::new(),
        });
        for seed in 0..3 {
            evaluate_agent(agent.as_mut(), &config, &[18], seed, Some(&mut rec)).unwrap();
        }
        let _ = std::fs::remove_dir_all(&dir);
        let opts = SummaryOptions {
            window: Some(16),
            ..SummaryOptions::default()
        };
        let s = neural_summary(&rec.finish(), Some(population), &opts).unwrap();
        let c = s.categories.clone().expect("categories defined");
        (s, c)
    };
    let (ddm, c) = summarise("ddm", "accumulator");
    assert_eq!((c.counts.ramp, c.counts.time_field), (1, 0), "{ddm:?}");
    let (tc, c) = summarise("timecells-laplace", "time_cells");
    // Cells whose field does not fall back by half inside the 16 steps are fields beyond
    // the window where the trial shows their fall, ramps where it does not; none
    // oscillates.
    assert!(c.counts.time_field * 3 >= tc.units, "{tc:?}");
    assert_eq!(
        c.counts.time_field + c.counts.ramp + c.counts.beyond_window,
        tc.units,
        "{tc:?}"
    );
    // Cells with τ* beyond the 16-step window peak at its end, so the sequence only
    // partly tiles it.
    assert!(tc.sequentiality.unwrap() > 0.3, "{tc:?}");
    assert!(tc.decode_bayes.unwrap() < 1.0, "{tc:?}");
    let (sbf, c) = summarise("sbf", "oscillators");
    let f = c.fractions.expect("1000 oscillators");
    // 16 steps = 0.4 s: only oscillators of 5 Hz and more show the two cycles the test
    // needs; none of them is a ramp.
    assert!(f.oscillating > 0.8, "{sbf:?}");
    assert!(f.ramp < 0.05, "{sbf:?}");
}

#[test]
fn exported_npz_matches_the_dataset_array_by_array() {
    use chronocooked_present::export::export_activity;
    use chronocooked_present::export::npz::{NpyData, read_npz};
    let config = make_config("FixedInterval-v0", &["td=6"]).unwrap();
    let env = chronocooked_env::ChronoEnv::new(&config).unwrap();
    let mut agent =
        chronocooked_models::timing::zoo::make_timing_agent("timecells-ms", &env, 0).unwrap();
    let train = chronocooked_models::TimingTrainConfig {
        episodes: 1500,
        eval_every: 0,
        ..Default::default()
    };
    chronocooked_models::train_timing_agent(&mut agent, &config, &train, &[6], 0, |_| {}).unwrap();
    let mut rec = TrialRecorder::new(ActivityMeta {
        model: "timecells-ms".into(),
        task: chronocooked_env::Task::parse("FixedInterval-v0", &["td=6"]).unwrap(),
        seed: 0,
        dt: 1.0,
        populations: Vec::new(),
    });
    evaluate_agent(&mut agent, &config, &[6], 0, Some(&mut rec)).unwrap();
    let ds = rec.finish();
    let dir = temp_dir("export");
    export_activity(&ds, &dir, 200).unwrap();
    let arrays = read_npz(&std::fs::read(dir.join("activity.npz")).unwrap()).unwrap();
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("activity.meta.json")).unwrap())
            .unwrap();
    let get = |name: &str| {
        arrays
            .iter()
            .find(|a| a.name == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    let f32s = |name: &str| match &get(name).data {
        NpyData::F32(v) => v.clone(),
        other => panic!("{name}: not float32: {other:?}"),
    };
    let i64s = |name: &str| match &get(name).data {
        NpyData::I64(v) => v.clone(),
        other => panic!("{name}: not int64: {other:?}"),
    };
    let n = ds.meta.n_units();
    // Every array is described, with the right shape.
    for a in &arrays {
        let described: Vec<usize> =
            serde_json::from_value(meta["arrays"][&a.name]["shape"].clone()).unwrap();
        assert_eq!(described, a.shape, "{}", a.name);
    }
    assert_eq!(meta["units"].as_array().unwrap().len(), n);
    // activity: trials concatenated, float32.
    let total: usize = ds.trials.iter().map(|t| t.steps).sum();
    assert_eq!(get("activity").shape, vec![total, n]);
    let expected: Vec<f32> = ds
        .trials
        .iter()
        .flat_map(|t| t.activity.iter().copied())
        .collect();
    assert_eq!(f32s("activity"), expected);
    let offsets = i64s("trial_offsets");
    assert_eq!(offsets.len(), ds.trials.len() + 1);
    assert_eq!(*offsets.last().unwrap() as usize, total);
    assert_eq!(
        i64s("td"),
        ds.trials
            .iter()
            .map(|t| i64::from(t.td))
            .collect::<Vec<_>>()
    );
    let events: usize = ds.trials.iter().map(|t| t.events.len()).sum();
    assert_eq!(i64s("event_step").len(), events);
    let (aligned, used) = ds.aligned(Marker::OvenOn, get("aligned").shape[1] - 1);
    let a = f32s("aligned");
    assert_eq!(a.len(), aligned.len());
    assert!(
        a.iter()
            .zip(&aligned)
            .all(|(x, y)| x == y || (x.is_nan() && y.is_nan()))
    );
    assert_eq!(
        i64s("aligned_trials"),
        used.iter().map(|&u| u as i64).collect::<Vec<_>>()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn zoo_says_which_tasks_each_mechanism_cannot_do() {
    use chronocooked_models::timing::zoo::task_limit;
    // Presence has no elapsed time: no bisection; every model with a clock may do it.
    assert!(task_limit("timecells-presence", "Bisection-v0", false).is_some());
    for model in MODELS {
        assert_eq!(task_limit(model, "Bisection-v0", false), None, "{model}");
        assert_eq!(
            task_limit(model, "FixedInterval-v0", false),
            None,
            "{model}"
        );
        // One-step reward windows: each model names its mechanistic limit (scalar noise,
        // resolution) — the complete serial compound only through its default clock noise
        // (noise-free, one unit per step, it learns them: the dual-task test).
        let limit = task_limit(model, "MultiTimer-v0", true);
        assert!(limit.is_some(), "{model}");
        if model == "timecells-csc" {
            assert!(limit.unwrap().contains("clock_noise=0"), "{limit:?}");
        }
    }
    // Every registered task the timing models can play (its family declares a response
    // kind) is listed: a family added to the registry cannot be left out of `zoo show`. The
    // tasks are read before the zoo, so a family another test registers meanwhile is in the
    // zoo's list if it is in this one.
    let playable: Vec<&str> = chronocooked_env::registry::all_tasks()
        .iter()
        .filter(|spec| {
            chronocooked_env::Task::new(spec.id)
                .and_then(|t| t.config())
                .unwrap()
                .response_kind()
                .is_some()
        })
        .map(|spec| spec.id)
        .collect();
    let entry = chronocooked_training::zoo::zoo()
        .into_iter()
        .find(|e| e.name == "ddm")
        .unwrap();
    for id in &playable {
        assert!(
            entry.tasks.iter().any(|t| t.task.starts_with(id)),
            "{id} missing from {:?}",
            entry.tasks
        );
    }
    assert!(playable.len() >= 9, "{playable:?}");
    assert!(
        entry
            .tasks
            .iter()
            .any(|t| t.task.contains("exact") && t.limit.is_some())
    );
}

/// Trial-averaged activity `[window, units]` of `population` of `model` trained on fixed
/// interval at `td` (greedy episodes from every start cell, three seeds), aligned to oven on.
fn trained_average(model: &str, td: u32, population: &str, window: usize) -> (Vec<f64>, usize) {
    use chronocooked_analysis::neural::Cube;
    let mut cfg = TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
        model,
        0,
    );
    cfg.set(&format!("env.td={td}")).unwrap();
    let mut agent = trained_agent(&cfg, &format!("signature-{model}-{td}"));
    let config = cfg.task.config().unwrap();
    let mut rec = TrialRecorder::new(ActivityMeta::new(model, &cfg.task, 0));
    for seed in 0..3 {
        evaluate_agent(agent.as_mut(), &config, &[td], seed, Some(&mut rec)).unwrap();
    }
    let ds = rec.finish();
    let (aligned, used) = ds.aligned(Marker::OvenOn, window - 1);
    let n = ds.meta.n_units();
    let avg = Cube::from_f32(&aligned, used.len(), window, n).average();
    let r = ds.meta.range(population).unwrap();
    let sub = avg
        .chunks_exact(n)
        .flat_map(|row| row[r.clone()].to_vec())
        .collect();
    (sub, r.len())
}

#[test]
fn recorded_populations_show_each_models_signature() {
    use chronocooked_analysis::neural::oscillation::welch;
    use chronocooked_analysis::neural::scaling_factor;
    // Drift-diffusion: the accumulator ramps to threshold at TD, so its trace at TD 12 is
    // the TD-6 trace stretched by 2 (slope ∝ 1/TD).
    let (a, _) = trained_average("ddm", 6, "accumulator", 6);
    let (b, _) = trained_average("ddm", 12, "accumulator", 12);
    let (s, r2) = scaling_factor(&a, &b);
    assert!((s - 2.0).abs() < 0.3 && r2 > 0.9, "scaling {s}, R² {r2}");

    // SBF: every oscillator's spectrum peaks at its own frequency (Hz × 25 ms per step).
    let config = make_config("FixedInterval-v0", &["td=18"]).unwrap();
    let env = chronocooked_env::ChronoEnv::new(&config).unwrap();
    let sbf = chronocooked_models::timing::zoo::make_timing_agent("sbf", &env, 0).unwrap();
    let chronocooked_models::timing::timers::Timer::Sbf(timer) = &sbf.timer else {
        panic!("sbf")
    };
    let window = 18;
    let (osc, units) = trained_average("sbf", 18, "oscillators", window);
    for (i, f) in timer.model.freqs.iter().enumerate().take(100) {
        let x: Vec<f64> = (0..window).map(|t| osc[t * units + i]).collect();
        let peak = welch(&x, window, 1.0).peak;
        let want = f * timer.seconds_per_step;
        assert!(
            (peak - want).abs() <= 1.0 / window as f64,
            "oscillator {i}: {f} Hz, peak {peak} vs {want} cycles/step"
        );
    }

    // Laplace time cells: each cell's width grows in proportion to its peak time.
    let window = 30;
    let (cells, units) = trained_average("timecells-laplace", 24, "time_cells", window);
    let mut points = Vec::new();
    for i in 0..units {
        let x: Vec<f64> = (0..window).map(|t| cells[t * units + i]).collect();
        let (peak_t, peak) = x
            .iter()
            .enumerate()
            .fold((0, f64::MIN), |b, (t, &v)| if v > b.1 { (t, v) } else { b });
        if !(3..=10).contains(&peak_t) {
            continue;
        }
        let cross = |range: Box<dyn Iterator<Item = usize>>| {
            let mut prev = peak_t;
            for t in range {
                if x[t] < peak / 2.0 {
                    let (a, b) = (x[t], x[prev]);
                    return Some(t as f64 + (prev as f64 - t as f64) * (peak / 2.0 - a) / (b - a));
                }
                prev = t;
            }
            None
        };
        let (Some(lo), Some(hi)) = (
            cross(Box::new((0..peak_t).rev())),
            cross(Box::new(peak_t + 1..window)),
        ) else {
            continue;
        };
        points.push((peak_t as f64, hi - lo));
    }
    assert!(points.len() >= 4, "{points:?}");
    let ratios: Vec<f64> = points.iter().map(|(p, w)| w / p).collect();
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    let sd = (ratios.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / ratios.len() as f64).sqrt();
    assert!(sd / mean < 0.2, "width/peak {ratios:?}");
}
