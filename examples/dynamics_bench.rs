//! Time of the dynamics signature (`neural::dynamics::dynamics`) of a 1,000-unit population
//! (phase-reset cosines of 1,000 frequencies, the size of the lab's SBF), at TD 6, 12 and
//! 24 (windows of 2 × TD steps plus the window after it), and of the summary's share: the
//! dynamics of every population of a recorded `activity.json` when given.
//!
//!     cargo run --release --example dynamics_bench [-- ACTIVITY_FOLDER …]
//!
//! Prints the median of 21 runs per case (ms).

use chronocooked_analysis::neural::dynamics::dynamics;
use std::time::Instant;

fn median_ms(mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..21)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[10]
}

fn main() {
    let units = 1000;
    for td in [6u32, 12, 24] {
        let window = 2 * td as usize;
        let rows = 2 * window;
        let traj: Vec<f64> = (0..rows)
            .flat_map(|r| (0..units).map(move |i| (0.05 + 0.002 * i as f64) * (r as f64 + 1.0)))
            .map(f64::cos)
            .collect();
        let ms = median_ms(|| {
            std::hint::black_box(dynamics(&traj, units, window, td));
        });
        println!("synthetic {units} units, TD {td} ({rows} steps): {ms:.2} ms");
    }
    for dir in std::env::args().skip(1) {
        let path = std::path::Path::new(&dir).join("activity.json");
        let bytes = std::fs::read(&path).expect("activity.json");
        let ds = chronocooked_models::ActivityDataset::from_json(&bytes).expect("dataset");
        let opts = chronocooked_analysis::neural::summary::SummaryOptions::default();
        let tds = chronocooked_analysis::neural::summary::recorded_tds(&ds);
        let ms = median_ms(|| {
            for p in &ds.meta.populations {
                for &td in &tds {
                    let _ = std::hint::black_box(
                        chronocooked_analysis::neural::summary::population_dynamics(
                            &ds,
                            Some(&p.name),
                            td,
                            &opts,
                        ),
                    );
                }
            }
        });
        println!(
            "{dir}: {} units, dynamics of every population: {ms:.2} ms",
            ds.meta.n_units()
        );
    }
}
