//! Ready-Set-Go mechanics composed by a family defined outside the env crate
//! ([`RuleSet::ready_set_go`]): the kitchen runs it, the oracle is paid at `g · ts`, and the
//! agents that read the mechanics — the Bayesian observer and the timing agents — play it
//! from the environment without knowing its family. The family is registered for the whole
//! test process (no other test of this crate lists the registered tasks).

use chronocooked_env::error::EnvError;
use chronocooked_env::layout::{Layout, ObjectKind};
use chronocooked_env::settings::Spec;
use chronocooked_env::task::ExternalParams;
use chronocooked_env::task::condition::{Condition, ConditionKind};
use chronocooked_env::task::family::{
    Family, ResponseKind, RuleSet, TaskSpec, condition, register,
};
use chronocooked_env::{
    ChronoEnv, Oracle, ReadySetGo, ResetOption, ResetOptions, Task, TaskConfig, TaskFamily,
    TaskParams,
};
use chronocooked_models::agent::run_episode;
use chronocooked_models::bayes::{Observer, ObserverAgent};
use chronocooked_models::timing::zoo::make_timing_agent;

const ID: &str = "ScaledReproduction-v0";
/// Delivery counter at (0,2), oven at (2,0); no onion (the oven is loaded).
const LAYOUT: &str = "..D/.../V../.../...";
/// One prior of sample intervals (steps) and one gain unlike the built-in task's (1, 1.5).
const PRIOR: (u32, u32) = (6, 10);
const GAIN: f32 = 2.0;

/// Reproduce twice the interval between Ready and Set: `tp = 2 · ts`, uncued.
struct ScaledReproduction;

fn mechanics(layout: &Layout) -> ReadySetGo {
    ReadySetGo {
        priors: vec![PRIOR],
        gains: vec![GAIN],
        tolerance: 0.1,
        tolerance_steps: 1.0,
        foreperiod: (2, 4),
        prior_cue: false,
        counter: layout.cells_of(ObjectKind::DeliveryCounter)[0],
    }
}

impl Family for ScaledReproduction {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: ID,
            family: TaskFamily::External,
            tags: &["test"],
            summary: "Ready-Set-Go with gain 2, defined outside the env crate",
            description: "",
            source: "test family",
        }
    }

    fn params(&self) -> &'static [Spec] {
        &[]
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        let params = TaskParams::External(ExternalParams {
            task: ID.into(),
            values: Default::default(),
        });
        (LAYOUT, params)
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        vec![ObjectKind::DeliveryCounter, ObjectKind::Oven]
    }

    fn rules(&self, _config: &TaskConfig, layout: &Layout) -> Result<RuleSet, EnvError> {
        RuleSet::ready_set_go(mechanics(layout))
    }

    fn evaluation_tds(&self, _params: &TaskParams) -> Vec<u32> {
        (PRIOR.0..=PRIOR.1).collect()
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Reproduction
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Reproduce)
    }

    fn reset_options(&self) -> &'static [ResetOption] {
        &[
            ResetOption::Start,
            ResetOption::Td,
            ResetOption::Prior,
            ResetOption::Gain,
        ]
    }

    fn conditions(&self, task: &Task, _config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        Ok((PRIOR.0..=PRIOR.1)
            .map(|ts| condition(ConditionKind::Reproduction, task, ts))
            .collect())
    }

    fn demo_conditions(&self, _params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        vec![(PRIOR.0, None), (PRIOR.1, None)]
    }
}

fn env() -> ChronoEnv {
    static DONE: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    DONE.get_or_init(|| register(&ScaledReproduction).unwrap());
    ChronoEnv::from_id(ID, &[] as &[&str]).unwrap()
}

/// The production `tp` of an episode: steps from Set to the pickup (the pickup's
/// `oven_off_time`).
fn production(infos: &[chronocooked_env::Info]) -> Option<i32> {
    infos
        .iter()
        .find(|i| i.events.has(chronocooked_env::Events::PICKUP))
        .map(|i| i.oven_off_time)
}

#[test]
fn the_kitchen_runs_an_external_ready_set_go_and_pays_the_oracle_at_g_times_ts() {
    let mut env = env();
    let rsg = env
        .ready_set_go()
        .expect("the family declared Ready-Set-Go")
        .clone();
    assert_eq!(rsg.priors, vec![PRIOR]);
    assert_eq!(rsg.gains, vec![GAIN]);
    assert_eq!(env.config().ready_set_go().unwrap(), Some(rsg));
    let oracle = Oracle::new(&env);
    for ts in PRIOR.0..=PRIOR.1 {
        let options = ResetOptions {
            td: Some(ts),
            ..ResetOptions::default()
        };
        env.reset(Some(u64::from(ts)), &options).unwrap();
        let mut total = 0.0;
        let mut tp = None;
        while !env.is_done() {
            let t = env.step(oracle.act(&env.state())).unwrap();
            total += t.reward;
            if t.info.events.has(chronocooked_env::Events::PICKUP) {
                tp = Some(t.info.oven_off_time);
            }
        }
        assert_eq!(tp, Some(2 * ts as i32), "ts {ts}: the oracle produces g·ts");
        assert!((total - 1.0).abs() < 1e-6, "ts {ts}: reward {total}");
    }
}

#[test]
fn the_bayesian_observer_plays_it_from_the_environment_with_its_gain_and_prior() {
    let mut env = env();
    let mut agent = ObserverAgent::new(&env, Observer::Bls, 0.1, 0.06).unwrap();
    let mean_tp = |ts: u32, env: &mut ChronoEnv, agent: &mut ObserverAgent| -> f64 {
        let seeds = 40;
        let mut sum = 0.0;
        for seed in 0..seeds {
            let options = ResetOptions {
                td: Some(ts),
                ..ResetOptions::default()
            };
            let rec = run_episode(env, agent, 1000 * u64::from(ts) + seed, &options, None).unwrap();
            let tp = production(&rec.infos).expect("every episode produces");
            sum += f64::from(tp);
        }
        sum / seeds as f64
    };
    let (short, mid, long) = (
        mean_tp(PRIOR.0, &mut env, &mut agent),
        mean_tp(8, &mut env, &mut agent),
        mean_tp(PRIOR.1, &mut env, &mut agent),
    );
    // At the prior's mean the BLS estimate is unbiased: tp ≈ g · 8 = 16 (a gain of 1 or 1.5,
    // the built-in task's, would give 8 or 12).
    assert!((mid - 16.0).abs() < 1.5, "tp at ts 8: {mid}");
    // Regression to the mean: the productions span less than g · (10 − 6) = 8 steps, and
    // still grow with ts.
    assert!(
        long > short + 2.0 && long - short < 8.0,
        "{short} .. {long}"
    );
}

#[test]
fn the_timing_agents_read_its_cues_and_defaults_from_the_environment() {
    let env = env();
    let counter = env.layout().cells_of(ObjectKind::DeliveryCounter)[0];
    for model in ["ddm", "sbf", "timecells-csc"] {
        let agent = make_timing_agent(model, &env, 3).unwrap();
        let cues = agent.reproduction.as_ref().expect("Ready-Set-Go cues");
        assert_eq!(cues.cue_cell, counter, "{model}");
        assert_eq!(cues.gains, vec![2.0], "{model}");
        assert_eq!(cues.gain(0), 2.0, "{model}: no cue, the only gain");
    }
}

/// A change that makes valid mechanics invalid.
type Spoil = Box<dyn Fn(&mut ReadySetGo)>;

#[test]
fn ready_set_go_mechanics_are_checked_and_each_error_names_its_field() {
    let layout = Layout::parse(LAYOUT).unwrap();
    let good = mechanics(&layout);
    let cases: [(&str, Spoil); 6] = [
        ("priors", Box::new(|m| m.priors.clear())),
        ("priors", Box::new(|m| m.priors = vec![(9, 9)])),
        ("gains", Box::new(|m| m.gains = vec![0.0])),
        ("tolerance", Box::new(|m| m.tolerance = f64::NAN)),
        ("tolerance_steps", Box::new(|m| m.tolerance_steps = -1.0)),
        ("foreperiod", Box::new(|m| m.foreperiod = (5, 4))),
    ];
    for (field, spoil) in cases {
        let mut bad = good.clone();
        spoil(&mut bad);
        let err = RuleSet::ready_set_go(bad).err().expect(field).to_string();
        assert!(err.contains(field), "{field}: {err}");
    }
    assert!(RuleSet::ready_set_go(good).is_ok());
}
