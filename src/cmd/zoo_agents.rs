//! The trained agents of the zoo on the command line: listed by `zoo list`, added by
//! `zoo add` (from a finished sweep job), and accepted as `--run zoo:<model>/<task>` by
//! `eval`, `record`, `export` and `adapt` ([`resolve_run`]).

use anyhow::{Context, Result, bail};
use chronocooked_analysis::behaviour::metrics::Metrics;
use chronocooked_analysis::columns::headline;
use chronocooked_analysis::job_folder;
use chronocooked_env::integrity;
use chronocooked_models::run_folder;
use chronocooked_training::agent_zoo::{
    self, AGENT_FILES, INDEX, Provenance, ZooAgent, ZooEvaluation, ZooIndex,
};
use clap::Args;
use std::path::{Path, PathBuf};

/// A `--run` argument: `zoo:<model>/<task>` becomes the zoo agent's checked folder.
pub fn resolve_run(arg: &Path) -> Result<PathBuf> {
    Ok(agent_zoo::resolve_run(arg)?)
}

/// One agent as a line of `zoo list`: its task's headline success (FI: full-reward
/// deliveries at the trained TD; bisection: correct counter at the anchors) as recorded
/// when it was added.
fn agent_line(a: &ZooAgent) -> String {
    let p = &a.provenance;
    let h = &p.evaluation.headline;
    let success = match (h.get("fi_success"), h.get("bisection_accuracy")) {
        (Some(s), _) => format!("FI success {s:.2}"),
        (None, Some(s)) => format!("anchor accuracy {s:.2}"),
        (None, None) => format!("success {:.2}", p.evaluation.success_rate),
    };
    format!(
        "  zoo:{:<36} seed {}  {} env steps  {success:<21} ({} episodes)  {:.0} kB",
        p.name,
        p.seed,
        p.env_steps,
        p.evaluation.episodes,
        a.bytes as f64 / 1024.0
    )
}

/// The trained agents for `zoo list` (text lines) and `zoo list --json` (values).
pub fn agents_listing() -> Result<(Vec<String>, serde_json::Value)> {
    let root = agent_zoo::zoo_root()?;
    let agents = agent_zoo::list_agents(&root)?;
    let total: u64 = agents.iter().map(|a| a.bytes).sum();
    let mut lines = vec![format!(
        "Trained agents ({} in {}, {:.2} MB; `--run zoo:NAME` in eval, record, export, adapt):",
        agents.len(),
        root.display(),
        total as f64 / 1e6
    )];
    lines.extend(agents.iter().map(agent_line));
    let json = serde_json::json!({
        "root": root,
        "bytes": total,
        "agents": agents.iter().map(agent_zoo::ZooAgent::listing_json).collect::<Vec<_>>(),
    });
    Ok((lines, json))
}

/// Arguments of `zoo add`.
#[derive(Args, Debug)]
pub struct ZooAddArgs {
    /// A finished sweep job folder (`job.json`, `run/` with `model.bpk`, `eval/`).
    pub job: PathBuf,
    /// The sweep file the job belongs to (recorded in the provenance).
    #[arg(long)]
    pub sweep: PathBuf,
    /// The sweep output folder the job was run into (for the recorded command).
    #[arg(long)]
    pub sweep_out: PathBuf,
    /// Git commit of the code that trained the job.
    #[arg(long)]
    pub commit: String,
    /// Compact results of the same study (`results/<study>`): the job of the same id is
    /// compared with this one.
    #[arg(long)]
    pub study: Option<PathBuf>,
    /// The zoo folder (its `index.json` gains the agent).
    #[arg(long, default_value = "zoo")]
    pub zoo: PathBuf,
}

/// The evaluation record of a metrics file.
pub fn evaluation(metrics: &Metrics) -> ZooEvaluation {
    ZooEvaluation {
        episodes: metrics.episodes,
        success_rate: metrics.success_rate,
        headline: headline(metrics)
            .into_iter()
            .filter(|(_, v)| v.is_finite())
            .collect(),
        conditions: metrics
            .conditions
            .iter()
            .map(|c| {
                let kind = serde_json::to_value(c.kind)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default();
                (kind, c.td, c.episodes, c.success_rate)
            })
            .collect(),
    }
}

/// Whether the evaluation episodes of `eval` (its records) equal the lines of a committed
/// job's `episodes.csv` (`None` when there is no such file): the same behaviour, episode
/// for episode, whatever the metrics code computed from them then and now.
fn same_episodes(eval: &Path, committed: &Path) -> Result<Option<bool>> {
    use chronocooked_analysis::collect::EpisodeRow;
    if !committed.is_file() {
        return Ok(None);
    }
    let records = chronocooked_analysis::evaluation::protocol::read_records(eval)
        .map_err(|e| anyhow::anyhow!("{}: {e}", eval.display()))?;
    let mine: Vec<EpisodeRow> = records.iter().map(EpisodeRow::of).collect();
    let theirs = csv::Reader::from_path(committed)
        .and_then(|mut r| r.deserialize().collect::<Result<Vec<EpisodeRow>, _>>())
        .with_context(|| committed.display().to_string())?;
    Ok(Some(mine == theirs))
}

/// Runs `zoo add`: copies the job's final model, configuration and summary into
/// `zoo/<model>/<task>/`, writes its provenance, records every file in `SHA256SUMS` and
/// adds the agent to the index.
pub fn add(args: ZooAddArgs) -> Result<()> {
    let job = job_folder::read_job(&args.job).map_err(anyhow::Error::msg)?;
    if job.id.is_empty() {
        bail!(
            "{}: field `id` missing (a sweep job's job.json)",
            args.job.join(job_folder::JOB).display()
        );
    }
    let (id, task, model) = (job.id.clone(), job.task.id().to_string(), job.model.clone());
    let run = args.job.join(job_folder::RUN);
    let eval = args.job.join(job_folder::EVAL);
    // The model must load intact before it is copied.
    let (_, _, cfg) = chronocooked_training::load_policy(&run)?;
    let metrics_path = eval.join(chronocooked_present::eval_folder::METRICS);
    let metrics_text = std::fs::read_to_string(&metrics_path)
        .with_context(|| metrics_path.display().to_string())?;
    let metrics: Metrics = chronocooked_analysis::stats::nan_json::from_str_nan(&metrics_text)
        .with_context(|| format!("{}: not a metrics file", metrics_path.display()))?;
    let summary_path = run.join(run_folder::SUMMARY);
    let summary: chronocooked_training::RunSummary = serde_json::from_str(
        &std::fs::read_to_string(&summary_path)
            .with_context(|| summary_path.display().to_string())?,
    )
    .with_context(|| format!("{}: not a run summary", summary_path.display()))?;
    let name = format!("{model}/{task}");
    let (study_job, reproduces) = match &args.study {
        Some(study) => {
            let other = study.join("jobs").join(&id);
            let same = same_episodes(&eval, &other.join("episodes.csv"))?;
            (same.map(|_| other.display().to_string()), same)
        }
        None => (None, None),
    };
    let provenance = Provenance {
        name: name.clone(),
        model: model.clone(),
        task: cfg.task.clone(),
        seed: cfg.seed,
        preset: cfg.preset.clone(),
        env_steps: summary.env_steps,
        sweep: args.sweep.display().to_string(),
        job: id.clone(),
        command: format!(
            "chronocooked sweep-job {} --out {} --id '{id}'",
            args.sweep.display(),
            args.sweep_out.display()
        ),
        commit: args.commit.clone(),
        train_wall_s: summary.wall_s,
        evaluation: evaluation(&metrics),
        study_job,
        reproduces_study_job: reproduces,
    };
    let dir = args.zoo.join(&name);
    if dir.exists() {
        bail!(
            "{}: already in the zoo (remove the folder to replace it)",
            dir.display()
        );
    }
    std::fs::create_dir_all(&dir).with_context(|| dir.display().to_string())?;
    for file in AGENT_FILES {
        let bytes = if file == "provenance.json" {
            let mut t = serde_json::to_string_pretty(&provenance)?;
            t.push('\n');
            t.into_bytes()
        } else if file == run_folder::MODEL || file == run_folder::POLICY {
            integrity::read_verified(&run.join(file))?
        } else {
            std::fs::read(run.join(file)).with_context(|| run.join(file).display().to_string())?
        };
        integrity::write_recorded(&dir.join(file), &bytes)?;
    }
    agent_zoo::verify_agent(&dir)?;
    let index_path = args.zoo.join(INDEX);
    let mut index = if index_path.is_file() {
        agent_zoo::read_index(&args.zoo)?
    } else {
        ZooIndex {
            format: 1,
            agents: vec![],
        }
    };
    if !index.agents.contains(&name) {
        index.agents.push(name.clone());
    }
    let mut text = serde_json::to_string_pretty(&index)?;
    text.push('\n');
    chronocooked_env::fs::write_atomic(&index_path, text.as_bytes())?;
    println!(
        "zoo:{name} ← {} (success {:.2}; reproduces {}: {:?})",
        args.job.display(),
        metrics.success_rate,
        id,
        reproduces
    );
    Ok(())
}
