//! The oracle reaches the maximum reward from every free start cell, for every task,
//! at several TDs — checked against analytic maxima and a brute-force optimum.

use chronocooked_env::{ChronoEnv, Oracle, ResetOptions, optimal_return};

/// Runs the oracle from every free start cell; returns the returns.
fn oracle_returns(
    env: &mut ChronoEnv,
    td: u32,
    never_ready: Option<bool>,
) -> Vec<(usize, usize, f64)> {
    let starts: Vec<_> = env.layout().free_coords();
    let oracle = Oracle::new(env);
    starts
        .into_iter()
        .map(|start| {
            let opts = ResetOptions {
                start: Some(start),
                td: Some(td),
                never_ready,
                ..ResetOptions::default()
            };
            env.reset(Some(1), &opts).unwrap();
            let mut total = 0.0;
            while !env.is_done() {
                total += env.step(oracle.act(&env.state())).unwrap().reward as f64;
            }
            (start.0, start.1, total)
        })
        .collect()
}

fn assert_all(env: &mut ChronoEnv, td: u32, never_ready: Option<bool>, expected: f64, what: &str) {
    for (r, c, ret) in oracle_returns(env, td, never_ready) {
        assert!(
            (ret - expected).abs() < 1e-5,
            "{what} td={td} start=({r},{c}): oracle return {ret}, expected {expected}"
        );
    }
}

#[test]
fn fixed_interval_oracle_gets_one_from_every_start() {
    for td in [1, 4, 6, 9, 12, 18, 24] {
        let mut env = ChronoEnv::from_id("FixedInterval-v0", &[format!("td={td}")]).unwrap();
        assert_all(&mut env, td, None, 1.0, "FI");
    }
}

#[test]
fn peak_interval_oracle_takes_the_released_soup_and_gets_nothing_on_pure_probes() {
    for (k, expected) in [(2, 1.0), (5, 1.0), (0, 0.0)] {
        for td in [4, 12] {
            let mut env = ChronoEnv::from_id(
                "PeakInterval-v0",
                &[format!("td={td}"), format!("probe_factor={k}")],
            )
            .unwrap();
            assert_all(&mut env, td, None, expected, &format!("PI k={k}"));
        }
    }
}

#[test]
fn bisection_oracle_is_right_on_both_anchors_of_every_paper_pair() {
    for (s, l) in [(6, 8), (4, 8), (6, 12), (4, 12), (6, 18), (4, 18), (1, 2)] {
        let mut env =
            ChronoEnv::from_id("Bisection-v0", &[format!("short={s}"), format!("long={l}")])
                .unwrap();
        assert_all(&mut env, s, None, 1.0, "bisection short");
        assert_all(&mut env, l, None, 1.0, "bisection long");
        // Probes pay nothing whatever the counter (reference rule).
        let probe = (s + l) / 2;
        if probe != s && probe != l {
            assert_all(&mut env, probe, None, 0.0, "bisection probe");
        }
    }
}

#[test]
fn multi_timer_oracle_hits_the_window_in_both_modes() {
    for mode in ["exact", "lower_bounded"] {
        for (under, over) in [(0, 0), (2, 0), (0, 3), (5, 5)] {
            let sets = [
                "tds=2,4,9,15,24".to_string(),
                "num_timers=5".into(),
                format!("mode={mode}"),
                format!("under_buffer={under}"),
                format!("over_buffer={over}"),
            ];
            let mut env = ChronoEnv::from_id("MultiTimer-v0", &sets).unwrap();
            for td in [2, 4, 9, 15, 24, 1, 30] {
                assert_all(
                    &mut env,
                    td,
                    None,
                    1.0,
                    &format!("multi {mode} {under}/{over}"),
                );
            }
        }
    }
}

#[test]
fn uncertainty_oracle_gets_one_normally_and_the_manual_reward_when_never_ready() {
    for td in [3, 9, 15] {
        let mut env = ChronoEnv::from_id("Uncertainty-v0", &[format!("td={td}")]).unwrap();
        assert_all(&mut env, td, Some(false), 1.0, "uncertainty normal");
        assert_all(&mut env, td, Some(true), 0.1, "uncertainty never-ready");
    }
}

#[test]
fn oracle_equals_the_brute_force_optimum_on_small_horizons() {
    // Exhaustive search over all action sequences (memoised on the hidden state).
    /// (task id, overrides, TDs, never-ready flag)
    type Case<'a> = (&'a str, &'a [&'a str], &'a [u32], Option<bool>);
    let cases: &[Case] = &[
        ("FixedInterval-v0", &["max_timesteps=20"], &[1, 3, 6], None),
        (
            "Bisection-v0",
            &["max_timesteps=24", "short=2", "long=5"],
            &[2, 5],
            None,
        ),
        (
            "MultiTimer-v0",
            &[
                "max_timesteps=20",
                "tds=2,5",
                "num_timers=2",
                "under_buffer=1",
            ],
            &[2, 5],
            None,
        ),
        (
            "DualTask-v0",
            &["max_timesteps=26", "td=12"],
            &[6, 12],
            None,
        ),
        (
            "DualTask-v0",
            &[
                "max_timesteps=26",
                "td=12",
                "under_buffer=2",
                "sink_reward=0.05",
            ],
            &[12],
            None,
        ),
        (
            "Uncertainty-v0",
            &["max_timesteps=24", "td=5"],
            &[5],
            Some(true),
        ),
        (
            "Uncertainty-v0",
            &["max_timesteps=24", "td=5"],
            &[5],
            Some(false),
        ),
    ];
    for (id, sets, tds, never) in cases {
        let mut env = ChronoEnv::from_id(id, sets).unwrap();
        for &td in *tds {
            for (r, c, ret) in oracle_returns(&mut env, td, *never) {
                let opts = ResetOptions {
                    start: Some((r, c)),
                    td: Some(td),
                    never_ready: *never,
                    ..ResetOptions::default()
                };
                env.reset(Some(1), &opts).unwrap();
                let best = optimal_return(&env);
                assert!(
                    (ret - best).abs() < 1e-5,
                    "{id} {sets:?} td={td} start=({r},{c}): oracle {ret} < optimum {best}"
                );
            }
        }
    }
}

#[test]
fn dual_task_oracle_collects_sink_rewards_and_the_full_soup_reward() {
    let mut env = ChronoEnv::from_id("DualTask-v0", &["td=18"]).unwrap();
    for (r, c, ret) in oracle_returns(&mut env, 18, None) {
        assert!(ret > 1.05 && ret < 1.2, "start ({r},{c}): return {ret}");
    }
}
