//! The full check of a sweep file at load: every job's settings resolved exactly as its
//! run will resolve them (PPO configs through [`crate::resolve`] and
//! [`crate::TrainConfig::validate`], timing models through [`TimingRunConfig::set`] and
//! [`TimingRunConfig::validate`], every job's task through the env's task checks), so
//! `sweep --dry-run` refuses everything a run would refuse, before anything starts.

use crate::error::TrainError;
use crate::sweep::file::{Job, SweepFile, applies};
use crate::timing_run::TimingRunConfig;
use crate::zoo::{Family, family_of};

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
    chronocooked_env::make_config(&job.task, &job.env)?;
    match job.family {
        Family::DeepRl => {
            let arch = job
                .model
                .parse()
                .map_err(|e: String| TrainError::param("model", &job.model, &e))?;
            crate::resolve(&job.task, arch, &sweep.preset, job.seed, &job.sets)?;
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

/// Why no model of `sweep` accepts the setting `kv` of `field` (`set` or `variants`): the
/// range error of a model that knows the key, or else "unknown setting".
pub(crate) fn refusal(sweep: &SweepFile, field: &str, kv: &str) -> TrainError {
    let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
    let (k, v) = (k.trim(), v.trim());
    for task in &sweep.tasks {
        for m in sweep.expanded_models() {
            let family = family_of(&m);
            if field == "set" && !matches!(family, Ok(Family::DeepRl)) {
                continue;
            }
            let err = match family {
                Ok(Family::DeepRl) => m
                    .parse()
                    .ok()
                    .and_then(|arch| crate::TrainConfig::base(task, arch).set(k, v).err()),
                Ok(Family::Timing) => TimingRunConfig::new(task, &m, 0).set(kv).err(),
                _ => None,
            };
            if let Some(TrainError::InvalidParam { field: f, .. }) = &err
                && f == k
            {
                return err.unwrap_or(TrainError::BadOverride(kv.into()));
            }
        }
    }
    let allowed = if field == "set" {
        "PPO settings some PPO model of the sweep accepts, or env.<task parameter> (`set` reaches PPO runs only; timing models take `episodes` and `variants`)"
    } else {
        "settings some model of the sweep accepts (PPO or timing-model settings, or env.<task parameter>)"
    };
    TrainError::InvalidParam {
        field: field.into(),
        value: kv.into(),
        allowed: allowed.into(),
    }
}
