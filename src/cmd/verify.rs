//! `verify DIR`: what a run, an evaluation, a sweep's results or a zoo agent claims,
//! re-derived from what determines it (`chronocooked_pipeline::stages::verify`); every
//! difference is named with its file, field, recorded and recomputed value.

use anyhow::{Context, Result, bail};
use chronocooked_analysis::behaviour::metrics::compute_metrics;
use chronocooked_pipeline::stages::verify::diff_values;
use chronocooked_pipeline::stages::{self, Verification, VerifyRequest};
use chronocooked_training::agent_zoo::Provenance;
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `verify`.
#[derive(Args, Debug)]
pub struct VerifyArgs {
    /// What to verify: a run folder, an `eval` folder, a sweep job or a sweep's output,
    /// compact results (`results/<study>`), or a zoo agent (`zoo:<model>/<task>` or its
    /// folder).
    pub dir: PathBuf,
    /// The run an `eval` folder evaluated: its episodes are played again from it.
    #[arg(long)]
    pub run: Option<PathBuf>,
    /// Also train PPO runs again (their whole budget) and compare the learned parameters.
    #[arg(long)]
    pub retrain: bool,
}

/// Prints what was checked and every difference; an error when any was found.
pub fn run(args: VerifyArgs) -> Result<()> {
    let v = verify_any(&args.dir, args.run.as_deref(), args.retrain)?;
    print(&v);
    if !v.ok() {
        bail!(
            "{}: {} difference(s) between what it records and what it re-derives",
            args.dir.display(),
            v.differences.len()
        );
    }
    Ok(())
}

/// Verifies `dir` (a zoo agent here, anything else in the pipeline).
pub fn verify_any(dir: &Path, run: Option<&Path>, retrain: bool) -> Result<Verification> {
    let dir = crate::cmd::zoo_agents::resolve_run(dir)?;
    if dir
        .join(chronocooked_training::agent_zoo::PROVENANCE)
        .is_file()
    {
        return verify_zoo_agent(&dir);
    }
    Ok(stages::verify(&VerifyRequest {
        dir,
        run: run.map(Path::to_path_buf),
        retrain,
    })?)
}

fn print(v: &Verification) {
    for line in &v.checked {
        println!("checked  {line}");
    }
    for line in &v.not_rederived {
        println!("not re-derived  {line}");
    }
    for d in &v.differences {
        println!(
            "DIFFERS  {} field `{}`: recorded {}, re-derived {}",
            d.file.display(),
            d.field,
            d.recorded,
            d.recomputed
        );
    }
    if v.ok() {
        println!("verified: {} checks, no difference", v.checked.len());
    }
}

/// A zoo agent: its recorded evaluation against the protocol played again by its policy.
fn verify_zoo_agent(dir: &Path) -> Result<Verification> {
    let path = dir.join(chronocooked_training::agent_zoo::PROVENANCE);
    let bytes = chronocooked_env::integrity::read_checked(&path)?;
    let prov: Provenance = serde_json::from_slice(&bytes)
        .with_context(|| format!("{}: not a zoo agent's provenance", path.display()))?;
    let config = prov.task.config()?;
    let mut agent = chronocooked_training::timing_run::load_agent(dir, Some(&config))?;
    let conditions = chronocooked_analysis::reference_conditions(&prov.task)?;
    let records = chronocooked_analysis::run_protocol_recorded(
        agent.as_mut(),
        &conditions,
        chronocooked_analysis::Mode::Reference,
        prov.seed,
        None,
    )?;
    let metrics = compute_metrics(&prov.model, &records, prov.seed);
    let again = crate::cmd::zoo_agents::evaluation(&metrics);
    let mut v = Verification::default();
    // What the episodes fix exactly: their number, success overall and per condition.
    let exact = |e: &chronocooked_training::agent_zoo::ZooEvaluation| {
        serde_json::json!({
            "episodes": e.episodes,
            "success_rate": e.success_rate,
            "conditions": e.conditions,
        })
    };
    diff_values(
        &path,
        "evaluation",
        &exact(&prov.evaluation),
        &exact(&again),
        1e-12,
        &mut v.differences,
    );
    // The headline numbers include fitted ones (PI peak and spread by Levenberg–Marquardt):
    // compared to the fit's own precision, and a fit that converges on one side only (a
    // flat PI curve) is reported, not counted as a forgery.
    for (key, &recorded) in &prov.evaluation.headline {
        match again.headline.get(key) {
            Some(&x) => diff_values(
                &path,
                &format!("evaluation.headline.{key}"),
                &serde_json::json!(recorded),
                &serde_json::json!(x),
                HEADLINE_TOL,
                &mut v.differences,
            ),
            None => v.not_rederived.push(format!(
                "{}: evaluation.headline.{key} = {recorded}: today's fit gives no value",
                path.display()
            )),
        }
    }
    for key in again.headline.keys() {
        if !prov.evaluation.headline.contains_key(key) {
            v.not_rederived.push(format!(
                "{}: evaluation.headline.{key} = {}: not recorded",
                path.display(),
                again.headline[key]
            ));
        }
    }
    v.checked.push(format!(
        "{}: its evaluation played again ({} episodes, seed {})",
        dir.display(),
        records.len(),
        prov.seed
    ));
    Ok(v)
}

/// Relative precision of a fitted headline number (the fits stop at a relative change of
/// about 1e-8; the zoo's agents reproduce theirs to 3e-8).
const HEADLINE_TOL: f64 = 1e-6;
