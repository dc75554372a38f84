//! KiNeT timing-by-speed analysis (`analysis/src/neural/speed.rs`) on the timing models'
//! own trajectories after Set in the reproduction task, driven directly without noise
//! (Ready, `ts` steps, Set, then the production up to its target). Known answers from the
//! mechanisms:
//! * drift-diffusion ramps from 0 at Set on the drift `z/ts` it learned from the
//!   measurement, `x_i(t) = t/ts_i`: time-stretched copies of one trajectory, so its
//!   scaling index is 1 (relative speed ∝ 1/`ts`) — it times by speed;
//! * SBF restarts its oscillators at Set at their nominal frequencies whatever `ts`, and the
//!   time cells restart their population: one trajectory cut at different lengths, a
//!   fixed-speed clock, scaling index 0 — they time by where the trajectory is, not how
//!   fast it runs;
//! * a gain slows SBF's oscillators: at one `ts`, the gain-1.5 trajectory runs at 1/1.5 of
//!   the gain-1 one (Remington et al. 2018's speed account of the gain).

use chronocooked_analysis::neural::speed::{
    ConditionTrajectory, ReferenceChoice, SpeedOptions, kinet_speed,
};
use chronocooked_env::{ChronoEnv, make_config};
use chronocooked_models::activity::StepRecorder;
use chronocooked_models::timing::timers::Timer;
use chronocooked_models::timing::zoo::make_timing_agent;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

fn noise_free_timer(model: &str) -> Timer {
    let config = make_config("Reproduction-v0", &[] as &[&str]).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    make_timing_agent(model, &env, 11)
        .unwrap()
        .timer
        .noise_free()
}

/// The model's population state: drift-diffusion's accumulator, SBF's oscillators, the
/// time cells' units.
fn state(timer: &Timer) -> Vec<f64> {
    match timer {
        Timer::Ddm(d) => vec![d.acc.x],
        Timer::TimeCells(tc) => {
            let mut v = Vec::new();
            tc.cells.units_into(&mut v);
            v
        }
        Timer::Sbf(_) => {
            let mut rec = StepRecorder::default();
            timer.record(&mut rec);
            rec.population("oscillators")
                .unwrap()
                .iter()
                .map(|&x| f64::from(x))
                .collect()
        }
    }
}

/// The trajectory from Set to the target `g·ts` (one state per step).
fn trajectory(timer: &mut Timer, ts: u32, gain: f64) -> ConditionTrajectory {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    timer.clear();
    timer.begin_measurement(0, &mut rng);
    for t in 1..=ts {
        timer.tick(t, &mut rng);
    }
    timer.begin_production(0, f64::from(ts), gain, &mut rng);
    let steps = (gain * f64::from(ts)).round() as u32;
    let mut states = Vec::new();
    let mut dims = 0;
    for c in 1..=steps {
        timer.tick(c, &mut rng);
        let s = state(timer);
        dims = s.len();
        states.extend(s);
    }
    ConditionTrajectory {
        ts: f64::from(ts),
        time: steps as usize,
        dims,
        states,
    }
}

fn scaling_index(model: &str) -> f64 {
    let mut timer = noise_free_timer(model);
    let conditions: Vec<ConditionTrajectory> = [8u32, 10, 12, 14, 16, 18, 20]
        .iter()
        .map(|&ts| trajectory(&mut timer, ts, 1.0))
        .collect();
    kinet_speed(&conditions, SpeedOptions::default())
        .unwrap()
        .scaling_index
        .unwrap()
}

#[test]
fn drift_diffusion_times_the_production_by_speed() {
    let index = scaling_index("ddm");
    assert!((index - 1.0).abs() < 0.05, "scaling index {index:.3}");
}

#[test]
fn sbf_and_time_cells_run_a_fixed_speed_clock_after_set() {
    for model in ["sbf", "timecells-ms", "timecells-csc"] {
        let index = scaling_index(model);
        assert!(index.abs() < 0.05, "{model}: scaling index {index:.3}");
    }
}

#[test]
fn a_gain_slows_sbfs_oscillators() {
    let mut timer = noise_free_timer("sbf");
    let conditions = vec![
        trajectory(&mut timer, 12, 1.0),
        trajectory(&mut timer, 12, 1.5),
    ];
    let options = SpeedOptions {
        reference: ReferenceChoice::Condition(0),
        ..SpeedOptions::default()
    };
    let a = kinet_speed(&conditions, options).unwrap();
    let speed = a.conditions[1].relative_speed.unwrap();
    assert!(
        (speed - 1.0 / 1.5).abs() < 0.03,
        "relative speed {speed:.3}"
    );
}
