//! Compact study results: from a sweep's output folder (run folders with checkpoints,
//! per-step evaluation records) to what the paper's analysis needs and what a repository
//! can keep — per job a summary (`job.json`), one line per evaluation episode
//! (`episodes.csv`), a thinned learning curve (`curve.csv`), the lab's metrics
//! (`metrics.json`) and, for recorded jobs, the neural summary (`activity.summary.json`).

use crate::behaviour::foc::{FocConvention, first_oven_check_with};
use crate::job_folder;
use crate::records::{ConditionKind, EvalRecord, read_records};
use crate::records::{METRICS, RECORDS};
use chronocooked_env::{Counter, Task};
use chronocooked_models::run_folder;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What one finished job reports (its `job.json` in the compact results).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobSummary {
    /// Sweep job id (`task/model~variant/seedN`), also its folder.
    pub id: String,
    /// The task, with the job's parameters (serialised as `task` and `env`: `td=12`).
    #[serde(flatten)]
    pub task: Task,
    /// Zoo model name.
    pub model: String,
    /// The sweep's row label: the model plus its variant's non-task settings
    /// (`lstm125~recurrent_batches-chunks`); absent in results collected before it existed
    /// (then the model name). Analyses group runs by it ([`JobSummary::label`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub row: Option<String>,
    /// Training seed.
    pub seed: u64,
    /// Preset the run used.
    pub preset: String,
    /// Env-step budget.
    pub total_steps: u64,
    /// Env steps done.
    pub steps_done: u64,
    /// Training wall-clock seconds (one core; NaN — `null` in the file — for jobs without
    /// PPO training: timing models, oracle, random).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub wall_s: f64,
    /// Mean episode length of the last 100 training episodes at the end (the paper's
    /// `rollout/ep_len_mean`, used to exclude bisection runs).
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub final_ep_len_mean: f64,
    /// Mean return of the last 100 training episodes at the end.
    #[serde(deserialize_with = "crate::stats::nan_if_null")]
    pub final_ep_return_mean: f64,
    /// Multi-timer curriculum: env steps at which each level was entered (level 0 at 0).
    pub level_steps: Vec<u64>,
    /// The run's PPO settings (`config.json`'s `ppo`).
    pub ppo: serde_json::Value,
}

impl JobSummary {
    /// The group this run belongs to in the analysis: the sweep row (model plus non-task
    /// settings, so a faithfulness switch is its own group), else the model.
    pub fn label(&self) -> &str {
        self.row.as_deref().unwrap_or(&self.model)
    }
}

/// One evaluation episode (a line of `episodes.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRow {
    /// Condition kind.
    pub kind: ConditionKind,
    /// Target / probe duration (steps).
    pub td: u32,
    /// PI release factor or multi-timer buffer fraction.
    pub factor: Option<f64>,
    /// Condition task settings, space-separated.
    pub env: String,
    /// Start cell row.
    pub row: usize,
    /// Start cell column.
    pub col: usize,
    /// Steps played.
    pub steps: usize,
    /// Total reward.
    pub reward: f32,
    /// Full-reward delivery.
    pub success: bool,
    /// First oven check, paper convention (empty without pickup).
    pub foc: Option<i32>,
    /// First oven check counting oven checks only (the lab's earlier convention).
    pub foc_checks: Option<i32>,
    /// Delivery counter: 0 main, 1 short, 2 long (multi-anchor: 1…4), −1 none (the paper's code).
    pub counter: i8,
    /// Steps from the onion put to the soup pickup (−1: never taken).
    pub oven_off_time: i32,
}

impl EpisodeRow {
    /// The compact line of one evaluation record.
    pub fn of(r: &EvalRecord) -> Self {
        let e = &r.episode;
        let last = e.infos.last();
        let counter = match last.and_then(|i| i.counter) {
            Some(Counter::Main) => 0,
            Some(Counter::Short) => 1,
            Some(Counter::Long) => 2,
            Some(Counter::Anchor(i)) => i as i8,
            None => -1,
        };
        EpisodeRow {
            kind: r.condition.kind,
            td: r.condition.td,
            factor: r.condition.factor,
            env: r.condition.task.overrides().join(" "),
            row: e.start.0,
            col: e.start.1,
            steps: e.actions.len(),
            reward: e.reward,
            success: e.success,
            foc: first_oven_check_with(&e.actions, &e.infos, FocConvention::Paper),
            foc_checks: first_oven_check_with(&e.actions, &e.infos, FocConvention::Checks),
            counter,
            oven_off_time: e
                .infos
                .iter()
                .rev()
                .map(|i| i.oven_off_time)
                .find(|&t| t >= 0)
                .unwrap_or(-1),
        }
    }
}

/// File of a job's evaluation folder (and of its compact results) with the multi-timer
/// curriculum's per-level evaluation: one [`LevelEpisode`] per line.
pub const LEVELS_CSV: &str = "levels.csv";

/// One evaluation episode of a curriculum level's policy in that level's test setting (a
/// line of `levels.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LevelEpisode {
    /// Curriculum level whose policy played (0 warm-up, then the number of timers).
    pub level: usize,
    /// Target duration of the episode (steps).
    pub td: u32,
    /// Start cell row.
    pub row: usize,
    /// Start cell column.
    pub col: usize,
    /// Steps played.
    pub steps: usize,
    /// Reward of the episode (the notebook's final-step reward: the pickup is the only
    /// reward).
    pub reward: f32,
    /// Full-reward delivery.
    pub success: bool,
    /// Steps from the onion put to the soup pickup (−1: never taken).
    pub oven_off_time: i32,
    /// The protocol condition the episode played (absent in files written before it was
    /// kept; multi-timer levels play only multi-timer conditions).
    #[serde(default)]
    pub kind: Option<ConditionKind>,
}

impl LevelEpisode {
    /// The line of one record played by the policy of `level`.
    pub fn of(level: usize, r: &EvalRecord) -> Self {
        let e = EpisodeRow::of(r);
        LevelEpisode {
            level,
            td: e.td,
            row: e.row,
            col: e.col,
            steps: e.steps,
            reward: e.reward,
            success: e.success,
            oven_off_time: e.oven_off_time,
            kind: Some(e.kind),
        }
    }
}

/// Writes `rows` as the CSV `path` (atomically).
pub fn write_level_episodes(path: &Path, rows: &[LevelEpisode]) -> Result<(), CollectError> {
    write_csv(path, rows)
}

/// Reads a `levels.csv` (no file: no rows).
pub fn read_level_episodes(path: &Path) -> Result<Vec<LevelEpisode>, CollectError> {
    if !path.is_file() {
        return Ok(Vec::new());
    }
    read_rows(path)
}

/// Every row of the CSV file `path`; errors name the file.
fn read_rows<T: serde::de::DeserializeOwned>(path: &Path) -> Result<Vec<T>, CollectError> {
    csv::Reader::from_path(path)
        .map_err(|e| err(path, e))?
        .deserialize()
        .collect::<Result<Vec<T>, _>>()
        .map_err(|e| err(path, e))
}

/// One thinned learning-curve row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurveRow {
    /// Env steps done.
    pub env_steps: u64,
    /// Wall-clock seconds.
    pub wall_s: f64,
    /// Mean return of the last 100 episodes.
    pub ep_return_mean: f64,
    /// Mean length of the last 100 episodes.
    pub ep_len_mean: f64,
    /// Success rate of the last 100 episodes.
    pub success_rate: f64,
    /// Multi-timer curriculum level.
    pub curriculum_level: usize,
}

/// Errors of the compact-results reader and writer (each names the file).
#[derive(Debug, thiserror::Error)]
pub enum CollectError {
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
}

/// A [`CollectError::File`] for `path`.
pub fn err(path: &Path, e: impl std::fmt::Display) -> CollectError {
    CollectError::File {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Reads a run's `curves.csv` (by column name).
pub fn read_curve(path: &Path) -> Result<Vec<CurveRow>, CollectError> {
    let mut rd = csv::Reader::from_path(path).map_err(|e| err(path, e))?;
    let header = rd.headers().map_err(|e| err(path, e))?.clone();
    let col = |name: &str| header.iter().position(|h| h == name);
    let idx = |name: &str| col(name).ok_or_else(|| err(path, format!("no column `{name}`")));
    let (steps, wall, ret, len, succ) = (
        idx("env_steps")?,
        idx("wall_s")?,
        idx("ep_return_mean")?,
        idx("ep_len_mean")?,
        idx("success_rate")?,
    );
    let level = col("curriculum_level");
    let num = |s: &str| s.parse::<f64>().unwrap_or(f64::NAN);
    let mut out = Vec::new();
    for rec in rd.records() {
        let rec = rec.map_err(|e| err(path, e))?;
        let get = |i: usize| rec.get(i).unwrap_or("");
        out.push(CurveRow {
            env_steps: get(steps).parse().map_err(|e| err(path, e))?,
            wall_s: num(get(wall)),
            ep_return_mean: num(get(ret)),
            ep_len_mean: num(get(len)),
            success_rate: num(get(succ)),
            curriculum_level: level.and_then(|i| get(i).parse().ok()).unwrap_or(0),
        });
    }
    Ok(out)
}

/// Job folders (those with a `job.json`) under a sweep output folder, sorted; symbolic links
/// are not followed, so each real job folder counts once.
pub fn job_folders(root: &Path) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(rd) = std::fs::read_dir(dir) else {
            return;
        };
        for e in rd.flatten() {
            let p = e.path();
            // Real folders only: symbolic links (self-links, loops) are not followed.
            if e.file_type().is_ok_and(|t| t.is_dir()) {
                if p.join(job_folder::JOB).is_file() {
                    out.push(p);
                } else {
                    walk(&p, out);
                }
            }
        }
    }
    let mut out = Vec::new();
    walk(root, &mut out);
    out.sort();
    out
}

/// The compact results of one finished job folder (`None` while its evaluation is missing).
pub fn summarise_job(dir: &Path) -> Result<Option<CompactJob>, CollectError> {
    let eval = dir.join(job_folder::EVAL);
    if !eval.join(METRICS).is_file() || !eval.join(RECORDS).is_file() {
        return Ok(None);
    }
    let job = job_folder::read_job(dir).map_err(|e| err(&dir.join(job_folder::JOB), e))?;
    // A reference agent's job (oracle, random) trains nothing: no run folder, no curve.
    let run = dir.join(job_folder::RUN);
    let trained = run.is_dir();
    let cfg = if trained {
        run_folder::read_config_header(&run).map_err(|e| err(&run.join(run_folder::CONFIG), e))?
    } else {
        run_folder::ConfigHeader::default()
    };
    // A multi-timer curriculum run that kept its levels' policies is evaluated once they are
    // too (the levels stage). The multi-anchor/multi-oven curricula's levels are copied when
    // evaluated (jobs evaluated before that stage covered them have none).
    let kept_levels = run.join(run_folder::LEVELS).is_dir();
    let multi_timer = cfg.curriculum_kind() == Some("multi_timer");
    if kept_levels && multi_timer && !eval.join(LEVELS_CSV).is_file() {
        return Ok(None);
    }
    // A timing-model run's curves.csv has its own columns (episodes, not PPO updates): its
    // compact result keeps the evaluation, metrics and neural summary, no PPO curve.
    let curve = if !trained || cfg.is_timing() {
        Vec::new()
    } else {
        read_curve(&run.join(run_folder::CURVES))?
    };
    let records = read_records(&eval).map_err(|e| err(&eval.join(RECORDS), e))?;
    let mut level_steps = vec![0];
    let mut prev = curve.first().map_or(0, |r| r.curriculum_level);
    for w in &curve {
        if w.curriculum_level > prev {
            level_steps.push(w.env_steps);
            prev = w.curriculum_level;
        }
    }
    let last = curve.last();
    let summary = JobSummary {
        id: job.id,
        task: job.task,
        model: job.model,
        row: job.row,
        seed: job.seed,
        preset: cfg.preset,
        total_steps: cfg.total_steps,
        steps_done: last.map_or(0, |r| r.env_steps),
        wall_s: last.map_or(f64::NAN, |r| r.wall_s),
        final_ep_len_mean: last.map_or(f64::NAN, |r| r.ep_len_mean),
        final_ep_return_mean: last.map_or(f64::NAN, |r| r.ep_return_mean),
        level_steps,
        ppo: cfg.ppo,
    };
    let episodes = records.iter().map(EpisodeRow::of).collect();
    // Every 10th update, level changes and the last row.
    let thinned = curve
        .iter()
        .enumerate()
        .filter(|(i, r)| {
            i % 10 == 9
                || *i + 1 == curve.len()
                || (*i > 0 && curve[i - 1].curriculum_level != r.curriculum_level)
        })
        .map(|(_, r)| r.clone())
        .collect();
    let levels = read_level_episodes(&eval.join(LEVELS_CSV))?;
    Ok(Some(CompactJob {
        job: summary,
        episodes,
        curve: thinned,
        levels,
    }))
}

/// Writes `rows` as CSV (a header from the first row's fields) to `path`, atomically.
pub fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> Result<(), CollectError> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r).map_err(|e| err(path, e))?;
    }
    let bytes = w.into_inner().map_err(|e| err(path, e))?;
    chronocooked_env::fs::write_atomic(path, &bytes).map_err(|e| err(path, e.error))
}

pub use crate::results_folder::{UNFINISHED_MARKER, check_complete as check_complete_folder};

/// Refuses a results folder that a `paper collect` is still writing or left unfinished
/// ([`crate::results_folder::check_complete`]), as a [`CollectError`].
pub fn check_complete(root: &Path) -> Result<(), CollectError> {
    check_complete_folder(root).map_err(|e| err(root, e))
}

/// Whether the sweep job in `dir` finished every stage it needs (its `progress.json` says
/// `done`) and no process is writing it now. A job whose record or export stage failed is
/// not finished, and neither is one a sweep worker is still running.
pub fn job_finished(dir: &Path) -> bool {
    job_folder::job_done(dir) && chronocooked_env::fs::ensure_not_being_written(dir).is_ok()
}

/// Writes the compact results of every finished job under `sweep_out` ([`job_finished`];
/// safe while the sweep still runs) into `to/jobs/<job id>/`; returns `(written,
/// unfinished)` job counts. Holds `to`'s lock while it writes and marks the folder
/// unfinished ([`UNFINISHED_MARKER`]) until the last job is written, so a collect that is
/// killed or runs out of disk leaves a folder every reader refuses, and its rerun completes
/// it.
pub fn collect(sweep_out: &Path, to: &Path) -> Result<(usize, usize), CollectError> {
    if !sweep_out.is_dir() {
        return Err(err(sweep_out, "no such sweep output folder"));
    }
    let _lock = chronocooked_env::fs::FolderLock::acquire(to).map_err(|e| err(to, e))?;
    let marker = to.join(UNFINISHED_MARKER);
    let note = crate::results_folder::UnfinishedCollect {
        sweep_out: sweep_out.display().to_string(),
    };
    let note = serde_json::to_string(&note).map_err(|e| err(&marker, e))?;
    chronocooked_env::fs::write_atomic(&marker, note.as_bytes())
        .map_err(|e| err(&marker, e.error))?;
    let (mut written, mut pending) = (0, 0);
    for dir in job_folders(sweep_out) {
        if !job_finished(&dir) {
            pending += 1;
            continue;
        }
        let Some(CompactJob {
            job: summary,
            episodes,
            curve,
            ..
        }) = summarise_job(&dir)?
        else {
            pending += 1;
            continue;
        };
        let out = to.join("jobs").join(&summary.id);
        std::fs::create_dir_all(&out).map_err(|e| err(&out, e))?;
        chronocooked_env::fs::remove_temp_files(&out);
        let json = serde_json::to_string_pretty(&summary).map_err(|e| err(&out, e))?;
        let job_path = out.join(job_folder::JOB);
        chronocooked_env::fs::write_atomic(&job_path, json.as_bytes())
            .map_err(|e| err(&job_path, e.error))?;
        write_csv(&out.join("episodes.csv"), &episodes)?;
        write_csv(&out.join("curve.csv"), &curve)?;
        let metrics = dir.join(job_folder::EVAL).join(METRICS);
        let text = std::fs::read(&metrics).map_err(|e| err(&metrics, e))?;
        // Copied as written, but only once it is a metrics object (never a corrupt file).
        #[derive(serde::Deserialize)]
        struct MetricsShape {
            #[allow(dead_code)]
            conditions: Vec<serde::de::IgnoredAny>,
        }
        serde_json::from_slice::<MetricsShape>(&text).map_err(|e| {
            err(
                &metrics,
                format!("not a metrics file (a `conditions` list): {e}"),
            )
        })?;
        let m_path = out.join(METRICS);
        chronocooked_env::fs::write_atomic(&m_path, &text).map_err(|e| err(&m_path, e.error))?;
        // The curriculum levels' evaluation, copied once it parses as one.
        let levels = dir.join(job_folder::EVAL).join(LEVELS_CSV);
        if levels.is_file() {
            let rows = read_level_episodes(&levels)?;
            write_level_episodes(&out.join(LEVELS_CSV), &rows)?;
        }
        // The neural summary of a recorded job (a few kB; the activity itself stays behind),
        // copied only when it is a list of population summaries.
        let neural = dir.join(job_folder::ACTIVITY_SUMMARY);
        if neural.is_file() {
            let text = std::fs::read(&neural).map_err(|e| err(&neural, e))?;
            serde_json::from_slice::<Vec<serde::de::IgnoredAny>>(&text).map_err(|e| {
                err(
                    &neural,
                    format!("not a neural summary (a list of populations): {e}"),
                )
            })?;
            let n_path = out.join(job_folder::ACTIVITY_SUMMARY);
            chronocooked_env::fs::write_atomic(&n_path, &text)
                .map_err(|e| err(&n_path, e.error))?;
        }
        written += 1;
    }
    std::fs::remove_file(&marker).map_err(|e| err(&marker, e))?;
    Ok((written, pending))
}

/// One job of the compact results, read back.
#[derive(Debug, Clone)]
pub struct CompactJob {
    /// Summary.
    pub job: JobSummary,
    /// Evaluation episodes.
    pub episodes: Vec<EpisodeRow>,
    /// Thinned learning curve.
    pub curve: Vec<CurveRow>,
    /// Multi-timer: every curriculum level's policy in its test setting (empty when the
    /// run kept no per-level policies).
    pub levels: Vec<LevelEpisode>,
}

impl CompactJob {
    /// The integer value of task setting `key` (e.g. `td`, steps), if the job sets it.
    pub fn env_int(&self, key: &str) -> Option<u32> {
        let v = self.job.task.value_set(key)?.as_u64()?;
        u32::try_from(v).ok()
    }

    /// The integer list of task setting `key` (e.g. `tds`), if the job sets it.
    pub fn env_ints(&self, key: &str) -> Option<Vec<u32>> {
        let items = self.job.task.value_set(key)?.as_array()?;
        items
            .iter()
            .map(|x| x.as_u64().and_then(|v| u32::try_from(v).ok()))
            .collect()
    }
}

/// Reads every job of a compact results folder (`to/jobs/...`).
pub fn read_compact(root: &Path) -> Result<Vec<CompactJob>, CollectError> {
    check_complete(root)?;
    let mut out = Vec::new();
    for dir in job_folders(&root.join("jobs")) {
        let job: JobSummary = {
            let p = dir.join(job_folder::JOB);
            let text = std::fs::read_to_string(&p).map_err(|e| err(&p, e))?;
            serde_json::from_str(&text).map_err(|e| err(&p, e))?
        };
        let episodes: Vec<EpisodeRow> = read_rows(&dir.join("episodes.csv"))?;
        let curve: Vec<CurveRow> = read_rows(&dir.join("curve.csv"))?;
        let levels = read_level_episodes(&dir.join(LEVELS_CSV))?;
        out.push(CompactJob {
            job,
            episodes,
            curve,
            levels,
        });
    }
    Ok(out)
}
