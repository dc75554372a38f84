//! The Bayesian observer as an agent of `Reproduction-v0`: played through the evaluation
//! protocol (cues seen in the observation, productions rounded to whole steps), its
//! per-prior slope and BIAS equal the observer's analytic values, and fitting its records
//! recovers its noise and picks its observer.

use chronocooked_analysis::reproduction::{
    Observer, ObserverAgent, Prior, Rounding, predicted_summary,
};
use chronocooked_analysis::{Mode, compute_metrics, reference_conditions, run_protocol};
use chronocooked_env::ChronoEnv;

#[test]
fn an_observer_agent_reproduces_its_analytic_slope_and_bias_and_is_recovered() {
    // A prior pair and noise levels unlike the task's defaults.
    let sets = vec!["priors=10-18,15-23".to_string()];
    let (wm, wp) = (0.13, 0.07);
    let env = ChronoEnv::from_id("Reproduction-v0", &sets).unwrap();
    let conds =
        reference_conditions(&chronocooked_env::Task::parse("Reproduction-v0", &sets).unwrap())
            .unwrap();
    for observer in [Observer::Bls, Observer::Ml] {
        let mut agent = ObserverAgent::new(&env, observer, wm, wp).unwrap();
        let recs = run_protocol(&mut agent, &conds, Mode::Reference, 17).unwrap();
        let m = compute_metrics("observer", &recs, 0).reproduction.unwrap();
        for (c, (lo, hi)) in m.contexts.iter().zip([(10u32, 18u32), (15, 23)]) {
            assert_eq!(c.failures, 0, "every episode produces");
            let values: Vec<f64> = (lo..=hi).map(f64::from).collect();
            let prior = Prior::new(&values).unwrap();
            let want = predicted_summary(observer, wm, wp, &prior, Rounding::WholeSteps).unwrap();
            let slope = c.slope.unwrap();
            let bias = c.bias.unwrap();
            assert!(
                (slope - want.slope).abs() < 0.05,
                "{observer:?} {lo}-{hi}: slope {slope} vs {}",
                want.slope
            );
            assert!(
                (bias - want.bias).abs() < 0.5,
                "{observer:?} {lo}-{hi}: BIAS {bias} vs {}",
                want.bias
            );
            if observer == Observer::Bls {
                // ML's (wm, wp) are weakly identified at these trial counts (module doc);
                // BLS's are recovered.
                let fit = c.observer.as_ref().unwrap();
                assert_eq!(fit.best, "BLS", "{lo}-{hi}: {:?}", fit.log_likelihoods);
                assert!((fit.wm - wm).abs() / wm < 0.1, "wm {}", fit.wm);
                assert!((fit.wp - wp).abs() / wp < 0.1, "wp {}", fit.wp);
            }
        }
    }
}

#[test]
fn an_observer_agent_needs_the_reproduction_task_and_valid_noise() {
    let fi = ChronoEnv::from_id("FixedInterval-v0", &[] as &[&str]).unwrap();
    let err = ObserverAgent::new(&fi, Observer::Bls, 0.1, 0.06)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("reproduction"), "{err}");
    let env = ChronoEnv::from_id("Reproduction-v0", &[] as &[&str]).unwrap();
    let err = ObserverAgent::new(&env, Observer::Bls, 0.0, 0.06)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("wm"), "{err}");
}
