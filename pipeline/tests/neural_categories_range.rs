//! The timing models' known signatures in the unit categories at every fixed-interval TD
//! of the paper (4, 6, 9, 12, 18, 24) and on two seeds, with default settings: each model
//! is trained through the project's training path and recorded by the record stage on
//! peak-interval probe trials (`record --probe --summary`, one repeat: 12 trials).
//!
//! * SBF: ≥ 90% of the oscillators oscillating and none untuned; the striatal detector a
//!   time field;
//! * drift-diffusion: the accumulator a ramp, scaling ≈ 2 between TD 8 and 16;
//! * the delay line, microstimuli and Laplace cells: ≥ 80% of the units whose peak lies
//!   inside the window (trial-average maximum at steps 1 … W − 2, not counted beyond the
//!   window) are time fields.

use chronocooked_analysis::neural::categories::{Category, UnitTests};
use chronocooked_analysis::neural::summary::{NeuralSummary, SummaryOptions, classify_td};
use chronocooked_models::ActivityDataset;
use chronocooked_pipeline::stages::{RecordRequest, record};
use chronocooked_training::{TimingRunConfig, run_timing_training};
use std::path::PathBuf;

const TDS: [u32; 6] = [4, 6, 9, 12, 18, 24];
const SEEDS: [u64; 2] = [8, 9];

/// A temporary folder under the target dir, removed on drop.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Trains `model` at each of `tds` (seed `seed`), records the runs together on probe
/// trials with the summary, and returns the dataset and the summaries.
fn recorded(model: &str, tds: &[u32], seed: u64) -> (ActivityDataset, Vec<NeuralSummary>) {
    let root = Scratch(
        std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
            "cc-range-{}-{model}-{seed}-{}",
            std::process::id(),
            tds[0]
        )),
    );
    let _ = std::fs::remove_dir_all(&root.0);
    let runs: Vec<PathBuf> = tds
        .iter()
        .map(|td| {
            let mut cfg = TimingRunConfig::new(
                &chronocooked_env::Task::new("FixedInterval-v0").unwrap(),
                model,
                seed,
            );
            cfg.set(&format!("env.td={td}")).unwrap();
            let dir = root.0.join(format!("td{td}"));
            run_timing_training(&cfg, &dir, "test", |_| {}).unwrap();
            dir
        })
        .collect();
    let out = root.0.join("activity.json");
    record(&RecordRequest {
        run: runs[0].clone(),
        more_runs: runs[1..].to_vec(),
        task: None,
        tds: vec![],
        probe: true,
        repeats: 1,
        seed,
        out: out.clone(),
        summary: true,
        figures: None,
    })
    .unwrap();
    let read = |p: PathBuf| std::fs::read_to_string(p).unwrap();
    (
        serde_json::from_str(&read(out.clone())).unwrap(),
        serde_json::from_str(&read(out.with_extension("summary.json"))).unwrap(),
    )
}

fn tests_of(ds: &ActivityDataset, population: &str, td: u32) -> Vec<UnitTests> {
    classify_td(ds, Some(population), td, &SummaryOptions::default())
        .unwrap()
        .tests
        .unwrap()
}

#[test]
fn sbf_oscillates_and_its_detector_is_a_time_field_at_every_td() {
    for seed in SEEDS {
        for td in TDS {
            let (ds, summaries) = recorded("sbf", &[td], seed);
            let osc = summaries
                .iter()
                .find(|s| s.population == "oscillators")
                .unwrap();
            let c = osc.categories.as_ref().unwrap();
            println!("SBF seed {seed} TD {td}: {:?}", c.counts);
            assert!(
                c.counts.oscillating as f64 >= 0.9 * osc.units as f64,
                "seed {seed} TD {td}: {:?}",
                c.counts
            );
            assert_eq!(c.counts.untuned, 0, "seed {seed} TD {td}");
            let det = tests_of(&ds, "striatum", td);
            assert_eq!(
                det[0].category,
                Category::TimeField,
                "seed {seed} TD {td}: {det:?}"
            );
        }
    }
}

#[test]
fn the_ddm_accumulator_is_a_ramp_at_every_td_and_scales_by_two_from_8_to_16() {
    for seed in SEEDS {
        for td in TDS {
            let (ds, _) = recorded("ddm", &[td], seed);
            let acc = tests_of(&ds, "accumulator", td);
            assert_eq!(
                acc[0].category,
                Category::Ramp,
                "seed {seed} TD {td}: {acc:?}"
            );
        }
        let (_, summaries) = recorded("ddm", &[8, 16], seed);
        let s = summaries
            .iter()
            .find(|s| s.population == "accumulator")
            .unwrap();
        let m = s.scaling.as_ref().and_then(|x| x.median).unwrap();
        println!("DDM seed {seed}: scaling 8 → 16 {m:.3}");
        assert!((m - 2.0).abs() <= 0.4, "seed {seed}: {m}");
    }
}

/// ≥ 80% of the in-window units of `model`'s time cells are time fields at every TD.
fn time_cells_are_fields_inside_the_window(model: &str) {
    for seed in SEEDS {
        for td in TDS {
            let (ds, _) = recorded(model, &[td], seed);
            let w = 2 * td as usize;
            let tests = tests_of(&ds, "time_cells", td);
            let inside: Vec<&UnitTests> = tests
                .iter()
                .filter(|u| {
                    u.category != Category::BeyondWindow && u.peak_time >= 1 && u.peak_time + 2 <= w
                })
                .collect();
            let fields = inside
                .iter()
                .filter(|u| u.category == Category::TimeField)
                .count();
            let beyond = tests
                .iter()
                .filter(|u| u.category == Category::BeyondWindow)
                .count();
            println!(
                "{model} seed {seed} TD {td}: {fields} of {} in-window units are time fields; {beyond} beyond the window; {} units",
                inside.len(),
                tests.len()
            );
            assert!(!inside.is_empty(), "{model} seed {seed} TD {td}");
            assert!(
                fields as f64 >= 0.8 * inside.len() as f64,
                "{model} seed {seed} TD {td}: {fields} of {}: {inside:?}",
                inside.len()
            );
        }
    }
}

#[test]
fn the_delay_line_is_made_of_time_fields_at_every_td() {
    time_cells_are_fields_inside_the_window("timecells-csc");
}

#[test]
fn microstimuli_are_time_fields_at_every_td() {
    time_cells_are_fields_inside_the_window("timecells-ms");
}

#[test]
fn laplace_cells_are_time_fields_at_every_td() {
    time_cells_are_fields_inside_the_window("timecells-laplace");
}
