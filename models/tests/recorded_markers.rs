//! The event markers of recorded trials, from the env's info alone (the oracle plays):
//! where each oven of the multi-oven task turns on and every oven's duration; where the
//! reproduction task's Ready and Set flash. Expected values come from the task rules.

use chronocooked_env::{ChronoEnv, PerOven, ResetOptions, make_config};
use chronocooked_models::activity::Marker;
use chronocooked_models::agent::{OracleAgent, run_episode};
use chronocooked_models::{ActivityMeta, TrialRecorder};

/// Recorded multi-oven trials carry every oven's duration and a marker where each oven
/// turned on: oven 2 (3) on the step at whose end it starts in asynchronous mode (the env
/// starts an oven at the end of step `on_time`, counting the first action as step 1 — so
/// an on-time of 0 never fires in the reference), with the put in synchronous mode. The oracle plays; the markers come from the env's info alone.
#[test]
fn recorded_trials_mark_each_ovens_onset_and_duration() {
    for (sets, tds, on_times) in [
        (
            vec!["ovens=3", "asynchronous=true"],
            vec![7u32, 13, 7],
            vec![4u32, 9],
        ),
        (vec!["ovens=2", "asynchronous=true"], vec![13, 7], vec![2]),
        (vec!["ovens=2", "asynchronous=false"], vec![7, 13], vec![]),
    ] {
        // Anchors S 7 / L 13 (a set-up no doc uses); every oven holds one of them.
        let sets: Vec<String> = sets
            .iter()
            .chain(&["short=7", "long=13"])
            .map(|s| s.to_string())
            .collect();
        let config = make_config("MultiOven-v0", &sets).unwrap();
        let mut env = ChronoEnv::new(&config).unwrap();
        let mut agent = OracleAgent::new(&env);
        let mut recorder = TrialRecorder::new(ActivityMeta::new(
            "oracle",
            &chronocooked_env::Task::parse("MultiOven-v0", &sets).unwrap(),
            0,
        ));
        let options = ResetOptions {
            oven_tds: Some(PerOven::new("oven_tds", &tds).unwrap()),
            on_times: (!on_times.is_empty()).then(|| PerOven::new("on_times", &on_times).unwrap()),
            ..Default::default()
        };
        let rec = run_episode(&mut env, &mut agent, 5, &options, Some(&mut recorder)).unwrap();
        assert!(rec.success, "{sets:?}: the oracle delivers every soup");
        let trial = &recorder.finish().trials[0];
        assert_eq!(trial.oven_tds, tds, "{sets:?}");
        assert_eq!(trial.oven_td(2), Some(tds[1]));
        let put = trial
            .first(Marker::OvenOn)
            .expect("the put turns oven 1 on");
        for oven in 2..=tds.len() {
            // The env's timestep counts the first action as step 1, a trial's step index
            // as step 0: on-time t is step index t − 1.
            let want = match on_times.get(oven - 2) {
                Some(&t) => t - 1,
                None => put,
            };
            assert_eq!(
                trial.first(Marker::oven_on(oven)),
                Some(want),
                "{sets:?}: oven {oven}"
            );
            let n = trial
                .events
                .iter()
                .filter(|e| e.marker == Marker::oven_on(oven))
                .count();
            assert_eq!(n, 1, "{sets:?}: oven {oven} turns on once");
        }
    }
}

/// Reproduction: Set flashes `ts` steps after Ready (Ready at the end of the foreperiod's
/// step, Set at the end of step foreperiod + ts), and the oracle takes the soup out `ts`
/// steps after Set (`tp` counts the steps from the Set step to the response's).
#[test]
fn ready_and_set_are_marked_ts_steps_apart_and_the_oracle_produces_ts() {
    let sets: Vec<String> = vec!["priors=6-12".into()];
    let config = make_config("Reproduction-v0", &sets).unwrap();
    let mut env = ChronoEnv::new(&config).unwrap();
    let mut agent = OracleAgent::new(&env);
    let mut recorder = TrialRecorder::new(ActivityMeta::new(
        "oracle",
        &chronocooked_env::Task::parse("Reproduction-v0", &sets).unwrap(),
        0,
    ));
    for ts in 6..=12u32 {
        let options = ResetOptions {
            td: Some(ts),
            ..Default::default()
        };
        let rec = run_episode(
            &mut env,
            &mut agent,
            u64::from(ts),
            &options,
            Some(&mut recorder),
        )
        .unwrap();
        assert!(rec.success, "ts {ts}");
    }
    for trial in &recorder.finish().trials {
        let ready = trial.first(Marker::Ready).expect("Ready flashes");
        let set = trial.first(Marker::Set).expect("Set flashes");
        assert_eq!(set - ready, trial.td, "{:?}", trial.events);
        assert_eq!(trial.first(Marker::Pickup), Some(set + trial.td));
        for m in [Marker::Ready, Marker::Set] {
            assert_eq!(trial.events.iter().filter(|e| e.marker == m).count(), 1);
        }
    }
}

/// A recording of the reproduction task plays each `ts` in every context that can hold it:
/// under each prior whose range contains it (the default priors, short 8–14 and long
/// 14–20, share 14) and at each gain; every trial carries its context.
#[test]
fn a_reproduction_recording_plays_every_ts_under_each_prior_holding_it_and_each_gain() {
    use chronocooked_models::agent::record_dataset;
    let sets: Vec<String> = vec!["gains=1,1.5".into()];
    let config = make_config("Reproduction-v0", &sets).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    let cells = env.layout().free_cells().len();
    let mut agent = OracleAgent::new(&env);
    let tds: Vec<u32> = (8..=20).collect();
    let ds = record_dataset(
        &mut agent,
        &config,
        &chronocooked_env::Task::parse("Reproduction-v0", &sets).unwrap(),
        &tds,
        1,
        3,
    )
    .unwrap();
    // 13 ts, 14 of them under both priors, × 2 gains × every start cell.
    assert_eq!(ds.trials.len(), (13 + 1) * 2 * cells);
    let mut seen = std::collections::BTreeSet::new();
    for t in &ds.trials {
        let ctx = t.reproduction.expect("every trial carries its context");
        let (lo, hi) = [(8, 14), (14, 20)][ctx.prior as usize];
        assert!(
            (lo..=hi).contains(&t.td),
            "ts {} under prior {}",
            t.td,
            ctx.prior
        );
        assert!(t.first(Marker::Set).is_some());
        seen.insert((t.td, ctx.prior, ctx.gain));
    }
    assert_eq!(seen.len(), (13 + 1) * 2);
    assert!(seen.contains(&(14, 0, 1)) && seen.contains(&(14, 1, 0)));
}
