//! Golden traces produced by the original Python implementation (reference-compatible
//! mode): 631 cases over FI, bisection and multi-timer, including time-limit edges,
//! early checks, overcooked pickups, wrong counters, window edges and the
//! second-onion deadlock. Every step must agree on obs, reward and terminated.

use chronocooked_env::{Action, ChronoEnv, PerOven, ResetOptions};
use serde::Deserialize;

#[derive(Deserialize)]
struct Case {
    case: String,
    task: String,
    set: Vec<String>,
    td: u32,
    start: (usize, usize),
    actions: Vec<i64>,
    /// Hex-encoded codes observation per step (reset first), `[R, C, 6]` row-major.
    obs: Vec<String>,
    reward: Vec<f32>,
    terminated: Vec<bool>,
}

fn hex(obs: &[u8]) -> String {
    obs.iter().map(|b| format!("{b:02x}")).collect()
}

/// Steps `env` through `actions` and checks every step's observation (`obs[i + 1]`), reward
/// and termination against the reference's; returns the steps replayed.
fn replay(
    env: &mut ChronoEnv,
    case: &str,
    actions: &[i64],
    obs: &[String],
    reward: &[f32],
    terminated: &[bool],
) -> usize {
    for (i, &a) in actions.iter().enumerate() {
        let t = env.step(Action::from_code(a).unwrap()).unwrap();
        let step = i + 1;
        assert_eq!(
            hex(env.obs_codes()),
            obs[step],
            "{case}: obs at step {step}"
        );
        assert!(
            (t.reward - reward[i]).abs() < 1e-6,
            "{case}: reward at step {step}: {} vs {}",
            t.reward,
            reward[i]
        );
        assert_eq!(
            t.terminated, terminated[i],
            "{case}: terminated at step {step}"
        );
        assert!(!t.truncated, "{case}: reference mode never truncates");
    }
    actions.len()
}

#[test]
fn replay_matches_reference_step_for_step() {
    let text = include_str!("golden/reference_traces.jsonl");
    let mut cases = 0;
    let mut steps = 0;
    for line in text.lines() {
        let c: Case = serde_json::from_str(line).expect("valid golden line");
        let mut env = ChronoEnv::from_id(&c.task, &c.set)
            .unwrap_or_else(|e| panic!("{}: config rejected: {e}", c.case));
        let options = ResetOptions {
            start: Some(c.start),
            td: Some(c.td),
            never_ready: None,
            ..ResetOptions::default()
        };
        env.reset(Some(0), &options).unwrap();
        assert_eq!(hex(env.obs_codes()), c.obs[0], "{}: reset obs", c.case);
        assert_eq!(c.actions.len(), c.reward.len(), "{}: fixture shape", c.case);
        steps += replay(
            &mut env,
            &c.case,
            &c.actions,
            &c.obs,
            &c.reward,
            &c.terminated,
        );
        assert!(
            env.is_done() == *c.terminated.last().unwrap_or(&false),
            "{}",
            c.case
        );
        cases += 1;
    }
    assert!(cases >= 600, "only {cases} cases");
    assert!(steps >= 10_000, "only {steps} steps");
}

#[derive(Deserialize)]
struct ExtensionCase {
    case: String,
    task: String,
    set: Vec<String>,
    /// Duration per oven (multi-anchor: the one oven's).
    tds: Vec<u32>,
    /// Asynchronous multi-oven: on-times of ovens 2…n.
    on_times: Option<Vec<u32>>,
    start: (usize, usize),
    actions: Vec<i64>,
    obs: Vec<String>,
    reward: Vec<f32>,
    terminated: Vec<bool>,
}

/// Golden traces of the reference's multi-anchor and multi-oven classes (593 cases:
/// anchors 2–4 of five sets, 1–3 ovens synchronous and asynchronous with recorded on-times,
/// wrong counters, probes, early interactions, second-onion deadlocks, TD 0, time-outs;
/// generator and coverage in `golden/EXTENSIONS.md`). Every step must agree on obs,
/// reward and terminated.
#[test]
fn extension_replay_matches_reference_step_for_step() {
    let text = include_str!("golden/extension_traces.jsonl");
    let (mut cases, mut steps, mut anchors, mut ovens) = (0, 0, 0, 0);
    for line in text.lines() {
        let c: ExtensionCase = serde_json::from_str(line).expect("valid golden line");
        let mut env = ChronoEnv::from_id(&c.task, &c.set)
            .unwrap_or_else(|e| panic!("{}: config rejected: {e}", c.case));
        let multi_oven = c.task.starts_with("MultiOven");
        let options = ResetOptions {
            start: Some(c.start),
            td: (!multi_oven).then(|| c.tds[0]),
            oven_tds: multi_oven.then(|| PerOven::new("oven_tds", &c.tds).unwrap()),
            on_times: c
                .on_times
                .as_ref()
                .map(|t| PerOven::new("on_times", t).unwrap()),
            ..ResetOptions::default()
        };
        env.reset(Some(0), &options)
            .unwrap_or_else(|e| panic!("{}: reset rejected: {e}", c.case));
        assert_eq!(hex(env.obs_codes()), c.obs[0], "{}: reset obs", c.case);
        steps += replay(
            &mut env,
            &c.case,
            &c.actions,
            &c.obs,
            &c.reward,
            &c.terminated,
        );
        cases += 1;
        if multi_oven {
            ovens += 1;
        } else {
            anchors += 1;
        }
    }
    assert!(anchors >= 250 && ovens >= 250, "{anchors} / {ovens} cases");
    assert!(cases >= 500, "only {cases} cases");
    assert!(steps >= 10_000, "only {steps} steps");
}
