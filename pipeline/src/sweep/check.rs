//! The full check of a sweep file at load: every job's settings resolved exactly as its
//! run will resolve them (PPO configs through [`chronocooked_training::resolve`] and
//! [`chronocooked_training::TrainConfig::validate`], timing models through [`TimingRunConfig::set`] and
//! [`TimingRunConfig::validate`], every job's task through the env's task checks), so
//! `sweep --dry-run` refuses everything a run would refuse, before anything starts.

use crate::stages::record::MAX_REPEATS as MAX_RECORD_REPEATS;
use crate::sweep::file::{Job, SweepFile, applies, refusal};
use chronocooked_training::TrainError;
use chronocooked_training::timing_run::TimingRunConfig;
use chronocooked_training::zoo::{Family, family_of};
use std::path::Path;

/// Checks the sweep-wide settings (`set`: each must apply to some model of the sweep, so a
/// misspelt key is an error rather than dropped) and then every job's resolved settings.
/// Errors name the job and the setting.
pub fn check_jobs(sweep: &SweepFile) -> Result<(), TrainError> {
    let models = sweep.expanded_models();
    // `set` reaches the PPO runs (its `env.*` entries every model): an entry no PPO model
    // of the sweep accepts would be dropped silently.
    for s in &sweep.set {
        let used = s.starts_with("env.")
            || sweep.tasks.iter().any(|task| {
                models.iter().any(|m| {
                    family_of(m).is_ok_and(|f| f == Family::DeepRl && applies(f, task, m, s))
                })
            });
        if !used {
            return Err(refusal(sweep, "set", s));
        }
    }
    if let Some(r) = sweep.record_repeats
        && !(1..=MAX_RECORD_REPEATS).contains(&r)
    {
        return Err(TrainError::InvalidParam {
            field: "record_repeats".into(),
            value: r.to_string(),
            allowed: format!("1–{MAX_RECORD_REPEATS} repetitions of the recording protocol"),
        });
    }
    for (field, zero) in [
        ("adapt_episodes", sweep.adapt_episodes == Some(0)),
        ("adapt_steps", sweep.adapt_steps == Some(0)),
    ] {
        if zero {
            return Err(TrainError::InvalidParam {
                field: field.into(),
                value: "0".into(),
                allowed: "a positive budget".into(),
            });
        }
    }
    for job in sweep.jobs()? {
        check_job(sweep, &job).map_err(|e| TrainError::Job {
            id: job.id.clone(),
            message: e.to_string(),
        })?;
    }
    Ok(())
}

/// Resolves one job's settings as its train and evaluation stages will.
fn check_job(sweep: &SweepFile, job: &Job) -> Result<(), TrainError> {
    job.task.config()?;
    match job.family {
        Family::DeepRl => {
            let arch = job
                .model
                .parse()
                .map_err(|e: String| TrainError::param("model", &job.model, &e))?;
            chronocooked_training::resolve(
                job.task.id(),
                arch,
                &sweep.preset,
                job.seed,
                &job.sets,
            )?;
        }
        Family::Timing => {
            let mut cfg = TimingRunConfig::new(&job.task, &job.model, job.seed);
            for kv in &job.sets {
                cfg.set(kv)?;
            }
            cfg.validate()?;
            cfg.build_agent()?;
        }
        Family::Baseline => {}
    }
    Ok(())
}

impl SweepFile {
    /// Parses a sweep file's text and checks it fully ([`SweepFile::validate`], then every
    /// job's resolved settings: [`crate::sweep::check::check_jobs`]); `source` names the
    /// file in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self, TrainError> {
        let f: SweepFile = toml::from_str(text).map_err(|e| TrainError::SweepFile {
            file: source.into(),
            message: e.to_string(),
        })?;
        let in_file = |e: TrainError| TrainError::SweepFile {
            file: source.into(),
            message: e.to_string(),
        };
        f.validate().map_err(in_file)?;
        check_jobs(&f).map_err(in_file)?;
        Ok(f)
    }

    /// Reads and parses a sweep file.
    pub fn load(path: &Path) -> Result<Self, TrainError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            if e.kind() == std::io::ErrorKind::NotFound && path.starts_with("sweeps") {
                // The guide's study files are the clone's: say where they are looked for.
                let cwd = std::env::current_dir().unwrap_or_default();
                TrainError::io(
                    &cwd.join(path),
                    std::io::Error::new(
                        e.kind(),
                        "no such file (the lab's study files are in the sweeps/ folder of \
                         its clone: run from the clone's root)",
                    ),
                )
            } else {
                TrainError::io(path, e)
            }
        })?;
        Self::parse(&text, &path.display().to_string())
    }
}
