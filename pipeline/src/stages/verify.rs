//! `verify`: re-derives what a folder claims from what determines it, and names every
//! difference (file, field, recorded value against recomputed value).
//!
//! Hashes (`SHA256SUMS`) catch corruption, not forgery: whoever edits a file can recompute
//! its hash. What the lab can re-derive is its determinism: the same configuration and
//! seed give the same learned state, and an evaluation is a pure function of the learned
//! state, the protocol and the seed. So:
//!
//! * an **evaluation folder**: its metrics again from its records; with the run (a sweep
//!   job's `run/`, or `--run`) or the reference agent it names, the whole protocol played
//!   again and compared record for record (an evaluation of another agent, or with another
//!   seed or task, differs);
//! * a **run folder**: a timing model trained again from its `config.json` (seconds) and
//!   compared with `agent.json`; a PPO run only with `retrain` (the whole budget);
//! * a **sweep job folder**: its run and its evaluation, played again from that run;
//! * a **compact results folder** (`paper collect`, the committed baselines): every job's
//!   `metrics.json` against its `episodes.csv` (per condition: episodes, success, mean
//!   reward and oven-off time). Compact jobs keep no learned state and not every training
//!   setting of their sweep, so their episodes are re-derived by rerunning the sweep job,
//!   not here.
//!
//! A zoo agent (evaluation against its `provenance.json`) is verified by the CLI, which
//! owns the zoo's records.

use crate::PipelineError;
use crate::stages::evaluate::{EvalSubject, subject_agent};
use chronocooked_analysis::behaviour::metrics::compute_metrics;
use chronocooked_analysis::collect::EpisodeRow;
use chronocooked_analysis::records::{check_complete_eval, read_eval_info, read_records};
use chronocooked_analysis::{job_folder, reference_conditions, run_protocol_recorded};
use chronocooked_models::run_folder;
use chronocooked_present::eval_folder::{EVAL_INFO, METRICS, RECORDS};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Relative tolerance for recomputed numbers (the same code on the same records gives the
/// same bits; the margin only absorbs a JSON round trip).
const REL_TOL: f64 = 1e-9;

/// One value a folder claims that its re-derivation contradicts.
#[derive(Debug, Clone, PartialEq)]
pub struct Difference {
    /// The file that claims it.
    pub file: PathBuf,
    /// The field (a JSON path such as `conditions[2].success_rate`, or `line 14`).
    pub field: String,
    /// What the file says.
    pub recorded: String,
    /// What the re-derivation gives.
    pub recomputed: String,
}

/// What `verify` checked and found.
#[derive(Debug, Clone, Default)]
pub struct Verification {
    /// Each check made, as a line (`metrics.json from records.jsonl (576 episodes)`).
    pub checked: Vec<String>,
    /// Every contradiction found.
    pub differences: Vec<Difference>,
    /// What could not be re-derived, and why (a PPO run without `retrain`).
    pub not_rederived: Vec<String>,
}

impl Verification {
    /// Whether nothing contradicted the folder's claims.
    pub fn ok(&self) -> bool {
        self.differences.is_empty()
    }
}

/// Options of [`verify`].
#[derive(Debug, Clone, Default)]
pub struct VerifyRequest {
    /// The folder: a run, an evaluation, a sweep job, a sweep output or compact results.
    pub dir: PathBuf,
    /// The run an evaluation folder evaluated (sweep jobs name their own).
    pub run: Option<PathBuf>,
    /// Also train what training gives again: PPO runs (their whole budget) and the
    /// timing-model jobs of compact results.
    pub retrain: bool,
}

/// Verifies `req.dir` (see the module documentation).
pub fn verify(req: &VerifyRequest) -> Result<Verification, PipelineError> {
    let dir = &req.dir;
    chronocooked_env::fs::ensure_not_being_written(dir)?;
    let mut v = Verification::default();
    if dir.join(job_folder::JOB).is_file() && dir.join(job_folder::EVAL).is_dir() {
        let run = dir.join(job_folder::RUN);
        let subject = if run.is_dir() {
            verify_run(&run, req.retrain, &mut v)?;
            EvalSubject::Run(run)
        } else {
            EvalSubject::Reference(job_model(dir)?)
        };
        verify_eval(&dir.join(job_folder::EVAL), Some(&subject), &mut v)?;
    } else if dir.join(EVAL_INFO).is_file() || dir.join(METRICS).is_file() {
        let subject = req.run.clone().map(EvalSubject::Run);
        verify_eval(dir, subject.as_ref(), &mut v)?;
    } else if dir.join(run_folder::CONFIG).is_file() {
        verify_run(dir, req.retrain, &mut v)?;
    } else if dir.join("jobs").is_dir() {
        chronocooked_analysis::collect::check_complete(dir)
            .map_err(|e| PipelineError::Analysis(e.to_string()))?;
        for job in chronocooked_analysis::collect::job_folders(&dir.join("jobs")) {
            verify_compact_job(&job, &mut v)?;
        }
        v.not_rederived.push(format!(
            "{}: the episodes (compact jobs keep no learned state; rerun a job with \
             `chronocooked sweep-job SWEEP --id JOB` to play it again)",
            dir.display()
        ));
    } else {
        let jobs = sweep_job_dirs(dir);
        if jobs.is_empty() {
            return Err(PipelineError::Invalid(format!(
                "{}: nothing to verify (allowed: a run folder, an `eval` folder, a sweep job \
                 or a sweep's output, compact results of `paper collect`)",
                dir.display()
            )));
        }
        for job in jobs {
            let sub = verify(&VerifyRequest {
                dir: job,
                run: None,
                retrain: req.retrain,
            })?;
            v.checked.extend(sub.checked);
            v.differences.extend(sub.differences);
            v.not_rederived.extend(sub.not_rederived);
        }
    }
    Ok(v)
}

/// The sweep job folders below a sweep's output (`job.json` beside an `eval/`), sorted.
fn sweep_job_dirs(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        if d.join(job_folder::JOB).is_file() && d.join(job_folder::EVAL).is_dir() {
            out.push(d);
            continue;
        }
        stack.extend(chronocooked_env::fs::real_subdirs(&d));
    }
    out.sort();
    out
}

/// The model a sweep job names (`job.json`'s `model`).
fn job_model(dir: &Path) -> Result<String, PipelineError> {
    #[derive(serde::Deserialize)]
    struct ModelOnly {
        model: String,
    }
    let path = dir.join(job_folder::JOB);
    let text = std::fs::read_to_string(&path).map_err(|e| PipelineError::read(&path, e))?;
    serde_json::from_str::<ModelOnly>(&text)
        .map(|m| m.model)
        .map_err(|e| PipelineError::NotA {
            path,
            what: "a sweep job's job.json",
            message: e.to_string(),
        })
}

fn analysis(e: impl ToString) -> PipelineError {
    PipelineError::Analysis(e.to_string())
}

/// The metrics again from the records; with `subject`, the protocol played again.
fn verify_eval(
    dir: &Path,
    subject: Option<&EvalSubject>,
    v: &mut Verification,
) -> Result<(), PipelineError> {
    check_complete_eval(dir).map_err(analysis)?;
    let info = read_eval_info(dir).map_err(analysis)?;
    let records = read_records(dir).map_err(analysis)?;
    let recomputed = compute_metrics(&info.model, &records, info.seed);
    let claimed = read_value(&dir.join(METRICS))?;
    let again = serde_json::to_value(&recomputed).map_err(analysis)?;
    diff_values(
        &dir.join(METRICS),
        "",
        &claimed,
        &again,
        REL_TOL,
        &mut v.differences,
    );
    v.checked.push(format!(
        "{}: metrics from {RECORDS} ({} episodes)",
        dir.display(),
        records.len()
    ));
    let Some(subject) = subject else {
        v.not_rederived.push(format!(
            "{}: the episodes themselves (give the evaluated run with --run to play them again)",
            dir.display()
        ));
        return Ok(());
    };
    let config = info.task.config()?;
    let mut agent = subject_agent(subject, &config)?;
    if agent.name() != info.model {
        v.differences.push(Difference {
            file: dir.join(EVAL_INFO),
            field: "model".into(),
            recorded: info.model.clone(),
            recomputed: agent.name(),
        });
    }
    let conditions = reference_conditions(&info.task)?;
    let played = run_protocol_recorded(agent.as_mut(), &conditions, info.mode, info.seed, None)?;
    if played.len() != records.len() {
        v.differences.push(Difference {
            file: dir.join(RECORDS),
            field: "episodes".into(),
            recorded: records.len().to_string(),
            recomputed: played.len().to_string(),
        });
    }
    let mut shown = 0;
    for (i, (a, b)) in records.iter().zip(&played).enumerate() {
        if a != b {
            shown += 1;
            if shown <= 5 {
                let (ra, rb) = (EpisodeRow::of(a), EpisodeRow::of(b));
                v.differences.push(Difference {
                    file: dir.join(RECORDS),
                    field: format!("line {}", i + 1),
                    recorded: row_text(&ra),
                    recomputed: row_text(&rb),
                });
            }
        }
    }
    if shown > 5 {
        v.differences.push(Difference {
            file: dir.join(RECORDS),
            field: "lines".into(),
            recorded: format!("{shown} episodes differ"),
            recomputed: "(the first 5 are listed)".into(),
        });
    }
    v.checked.push(format!(
        "{}: {} episodes played again by {} (seed {})",
        dir.display(),
        played.len(),
        match subject {
            EvalSubject::Run(r) => r.display().to_string(),
            EvalSubject::Reference(n) => n.clone(),
        },
        info.seed
    ));
    Ok(())
}

/// One episode as a short text (condition, start cell, steps, reward, first check).
fn row_text(r: &EpisodeRow) -> String {
    format!(
        "{:?} td {} start ({},{}): {} steps, reward {}, foc {:?}, counter {}",
        r.kind, r.td, r.row, r.col, r.steps, r.reward, r.foc, r.counter
    )
}

/// A run's learned state from its configuration: timing models always, PPO with `retrain`.
fn verify_run(run: &Path, retrain: bool, v: &mut Verification) -> Result<(), PipelineError> {
    if chronocooked_training::timing_run::is_timing_run(run) {
        let (cfg, agent) = chronocooked_training::timing_run::load_timing_agent(run)?;
        let task = cfg.task.config()?;
        let mut again = cfg.build_agent()?;
        let tds = chronocooked_training::evaluate::eval_tds(&task);
        chronocooked_models::timing::train::train_timing_agent(
            &mut again,
            &task,
            &cfg.train,
            &tds,
            cfg.seed,
            |_| {},
        )?;
        let claimed = serde_json::to_value(&agent).map_err(analysis)?;
        let derived = serde_json::to_value(&again).map_err(analysis)?;
        diff_values(
            &run.join(run_folder::AGENT),
            "",
            &claimed,
            &derived,
            REL_TOL,
            &mut v.differences,
        );
        v.checked.push(format!(
            "{}: agent.json trained again from config.json (seed {})",
            run.display(),
            cfg.seed
        ));
        return Ok(());
    }
    if !retrain {
        v.not_rederived.push(format!(
            "{}: the PPO learned state (train it again with --retrain: the whole budget)",
            run.display()
        ));
        return Ok(());
    }
    let (policy, _, cfg) = chronocooked_training::ppo::run_dir::load_policy(run)?;
    let mut trainer = chronocooked_training::Trainer::new(
        chronocooked_training::checked::Check::check(cfg.clone())?,
    )?;
    while !trainer.finished() {
        trainer.update()?;
    }
    let claimed = chronocooked_training::ppo::params::flat_params(&policy);
    let derived = chronocooked_training::ppo::params::flat_params(&trainer.policy());
    let differ = claimed
        .iter()
        .zip(&derived)
        .filter(|(a, b)| a.to_bits() != b.to_bits())
        .count()
        + claimed.len().abs_diff(derived.len());
    if differ > 0 {
        v.differences.push(Difference {
            file: run.join(run_folder::MODEL),
            field: "parameters".into(),
            recorded: format!("{} values", claimed.len()),
            recomputed: format!("{differ} of them differ after training again"),
        });
    }
    v.checked.push(format!(
        "{}: model.bpk trained again from config.json ({} env steps, seed {})",
        run.display(),
        cfg.total_steps,
        cfg.seed
    ));
    Ok(())
}

/// A compact job: its metrics against its episode lines.
fn verify_compact_job(job: &Path, v: &mut Verification) -> Result<(), PipelineError> {
    let metrics_path = job.join(METRICS);
    let metrics: MetricsCounts =
        serde_json::from_value(read_value(&metrics_path)?).map_err(|e| PipelineError::NotA {
            path: metrics_path.clone(),
            what: "a metrics file",
            message: e.to_string(),
        })?;
    let episodes_path = job.join("episodes.csv");
    let rows: Vec<EpisodeRow> = csv::Reader::from_path(&episodes_path)
        .and_then(|mut r| r.deserialize().collect::<Result<_, _>>())
        .map_err(|e| PipelineError::NotA {
            path: episodes_path.clone(),
            what: "a job's episode lines",
            message: e.to_string(),
        })?;
    rows_against_metrics(&metrics_path, &metrics, &rows, &mut v.differences);
    v.checked.push(format!(
        "{}: metrics against {} episode lines",
        job.display(),
        rows.len()
    ));
    Ok(())
}

/// What a job's episode lines fix of its `metrics.json`, typed: the totals and, per
/// condition in protocol order, its counts and means (a `null`, how JSON writes NaN, or a
/// field an older file lacks reads as NaN).
#[derive(Debug, Default, serde::Deserialize)]
pub struct MetricsCounts {
    /// Episodes evaluated.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub episodes: f64,
    /// Share of successful episodes.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub success_rate: f64,
    /// Per condition, in protocol order.
    #[serde(default)]
    pub conditions: Vec<ConditionCounts>,
}

/// One condition's counts in a `metrics.json` ([`MetricsCounts`]).
#[derive(Debug, Default, serde::Deserialize)]
pub struct ConditionCounts {
    /// Episodes of the condition.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub episodes: f64,
    /// Share of successful episodes.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub success_rate: f64,
    /// Mean reward.
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub mean_reward: f64,
    /// Mean oven-off time (steps).
    #[serde(default = "nan", deserialize_with = "nan_if_null")]
    pub mean_oven_off: f64,
}

/// A missing number: NaN.
fn nan() -> f64 {
    f64::NAN
}

/// A number, `null` read as NaN.
fn nan_if_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(<Option<f64> as serde::Deserialize>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// What a job's episode lines fix of its metrics (`metrics.json` as JSON): episodes,
/// overall success, and per condition (in protocol order) episodes, success, mean reward
/// and mean oven-off time.
pub fn rows_against_metrics(
    file: &Path,
    metrics: &MetricsCounts,
    rows: &[EpisodeRow],
    out: &mut Vec<Difference>,
) {
    let conditions = &metrics.conditions;
    let mut push = |field: String, recorded: String, recomputed: String| {
        out.push(Difference {
            file: file.to_path_buf(),
            field,
            recorded,
            recomputed,
        })
    };
    if metrics.episodes != rows.len() as f64 {
        push(
            "episodes".into(),
            metrics.episodes.to_string(),
            rows.len().to_string(),
        );
    }
    let rate = |rs: &[&EpisodeRow]| {
        rs.iter().filter(|r| r.success).count() as f64 / rs.len().max(1) as f64
    };
    let all: Vec<&EpisodeRow> = rows.iter().collect();
    if !close(metrics.success_rate, rate(&all)) {
        push(
            "success_rate".into(),
            metrics.success_rate.to_string(),
            rate(&all).to_string(),
        );
    }
    // Consecutive lines of one condition, in protocol order.
    let mut groups: Vec<Vec<&EpisodeRow>> = Vec::new();
    for r in rows {
        let same = groups.last().and_then(|g| g.last()).is_some_and(|l| {
            l.kind == r.kind && l.td == r.td && l.factor == r.factor && l.env == r.env
        });
        if same {
            groups.last_mut().expect("a group").push(r);
        } else {
            groups.push(vec![r]);
        }
    }
    if groups.len() != conditions.len() {
        // Conditions of the same (kind, TD) that the lines cannot tell apart (uncertainty's
        // never-ready split): only the totals above are compared.
        return;
    }
    for (i, (c, g)) in conditions.iter().zip(&groups).enumerate() {
        let n = g.len();
        let reward = g.iter().map(|r| r.reward as f64).sum::<f64>() / n as f64;
        let offs: Vec<f64> = g
            .iter()
            .filter(|r| r.oven_off_time >= 0)
            .map(|r| r.oven_off_time as f64)
            .collect();
        let off = if offs.is_empty() {
            f64::NAN
        } else {
            offs.iter().sum::<f64>() / offs.len() as f64
        };
        // A multi-oven episode has one oven-off time per oven; its line keeps one of them.
        let one_oven = g[0].kind != chronocooked_analysis::ConditionKind::MultiOven;
        for (field, claimed, derived) in [
            ("episodes", c.episodes, n as f64),
            ("success_rate", c.success_rate, rate(g)),
            ("mean_reward", c.mean_reward, reward),
            (
                "mean_oven_off",
                c.mean_oven_off,
                if one_oven { off } else { c.mean_oven_off },
            ),
        ] {
            if !(close(claimed, derived) || claimed.is_nan() && derived.is_nan()) {
                push(
                    format!("conditions[{i}].{field}"),
                    claimed.to_string(),
                    derived.to_string(),
                );
            }
        }
    }
}

/// Equal up to [`REL_TOL`] (and a 1e-6 absolute floor for f32 rewards summed in f64).
fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= REL_TOL * a.abs().max(b.abs()).max(1.0) + 1e-6
}

fn read_value(path: &Path) -> Result<Value, PipelineError> {
    let bytes =
        chronocooked_env::integrity::read_checked(path).map_err(|e| analysis(e.to_string()))?;
    serde_json::from_slice(&bytes).map_err(|e| PipelineError::NotA {
        path: path.to_path_buf(),
        what: "a JSON file",
        message: e.to_string(),
    })
}

/// Every leaf where `claimed` and `derived` differ, by JSON path (`at` the path so far),
/// numbers equal to the relative tolerance `tol`.
pub fn diff_values(
    file: &Path,
    at: &str,
    claimed: &Value,
    derived: &Value,
    tol: f64,
    out: &mut Vec<Difference>,
) {
    let here = |k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    match (claimed, derived) {
        (Value::Object(a), Value::Object(b)) => {
            let keys: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
            for k in keys {
                diff_values(
                    file,
                    &here(k),
                    a.get(k).unwrap_or(&Value::Null),
                    b.get(k).unwrap_or(&Value::Null),
                    tol,
                    out,
                );
            }
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                diff_values(file, &format!("{at}[{i}]"), x, y, tol, out);
            }
        }
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            if !(x == y || (x - y).abs() <= tol * x.abs().max(y.abs()).max(1.0)) {
                out.push(Difference {
                    file: file.to_path_buf(),
                    field: at.to_string(),
                    recorded: x.to_string(),
                    recomputed: y.to_string(),
                });
            }
        }
        (a, b) if a != b => out.push(Difference {
            file: file.to_path_buf(),
            field: at.to_string(),
            recorded: short(a),
            recomputed: short(b),
        }),
        _ => {}
    }
}

/// A JSON value in at most 120 characters.
fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() > 120 {
        format!("{}…", s.chars().take(120).collect::<String>())
    } else {
        s
    }
}
