//! Constructed compact jobs shared by the paper-analysis tests.

use chronocooked_analysis::collect::{EpisodeRow, JobSummary};

/// A constructed `job` for the tests.
pub fn job(task: &str, model: &str, seed: u64, env: &[&str], ep_len: f64) -> JobSummary {
    JobSummary {
        id: format!("{task}/{model}/seed{seed}"),
        task: chronocooked_env::Task::parse(task, env).unwrap(),
        model: model.into(),
        row: None,
        seed,
        preset: "reference".into(),
        total_steps: 1000,
        steps_done: 1000,
        wall_s: 10.0,
        final_ep_len_mean: ep_len,
        final_ep_return_mean: 1.0,
        level_steps: vec![0],
        ppo: serde_json::Value::Null,
    }
}

/// A constructed `ep` for the tests.
pub fn ep(kind: &str, td: u32, cell: (usize, usize), foc: Option<i32>, counter: i8) -> EpisodeRow {
    EpisodeRow {
        kind: kind.parse().unwrap(),
        td,
        factor: None,
        env: String::new(),
        row: cell.0,
        col: cell.1,
        steps: 20,
        reward: 1.0,
        success: foc.is_some() || counter > 0,
        foc,
        foc_checks: foc,
        counter,
        oven_off_time: td as i32,
    }
}

/// A constructed `mt_ep` for the tests.
pub fn mt_ep(td: u32, reward: f32, off: i32) -> EpisodeRow {
    EpisodeRow {
        reward,
        success: reward > 0.0,
        oven_off_time: off,
        foc: None,
        foc_checks: None,
        ..ep("multi_timer", td, (0, 0), None, 0)
    }
}

/// A constructed `curve_at` for the tests.
pub fn curve_at(level: usize, ret: f64) -> chronocooked_analysis::collect::CurveRow {
    chronocooked_analysis::collect::CurveRow {
        env_steps: 1000,
        wall_s: 1.0,
        ep_return_mean: ret,
        ep_len_mean: 20.0,
        success_rate: ret,
        curriculum_level: level,
    }
}

/// A constructed LSTM125 fixed-interval job at `td` with these evaluation episodes.
pub fn lstm_fi_job(
    seed: u64,
    td: u32,
    episodes: Vec<EpisodeRow>,
) -> chronocooked_analysis::collect::CompactJob {
    chronocooked_analysis::collect::CompactJob {
        job: job(
            "FixedInterval-v0",
            "lstm125",
            seed,
            &[&format!("td={td}")],
            20.0,
        ),
        episodes,
        curve: vec![],
        levels: vec![],
    }
}

/// The `claims.csv` row of `claim` in `setting` whose test mentions `test`.
pub fn find_claim<'a>(
    rows: &'a [chronocooked_paper::claims::ClaimRow],
    claim: &str,
    setting: &str,
    test: &str,
) -> &'a chronocooked_paper::claims::ClaimRow {
    rows.iter()
        .find(|r| r.claim == claim && r.setting == setting && r.test.contains(test))
        .unwrap_or_else(|| panic!("no {claim} / {setting} / {test} in {rows:#?}"))
}
