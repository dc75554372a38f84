//! `env`: list the tasks, replay action lists, render episodes, play in the terminal, and
//! the oracle-vs-random tour (`env demo`).

use anyhow::{Context, Result, bail};
use chronocooked_env::{
    Action, ChronoEnv, Oracle, PerOven, ResetOptions, all_tasks, parse_action_list, render,
    task::common_params, trace,
};
use clap::{Args, Subcommand, ValueEnum};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::io::Write;
use std::path::PathBuf;

mod demo;
mod play;

/// Task, overrides and reset options shared by replay, render and play.
#[derive(Args, Debug, Clone)]
pub struct TaskArgs {
    /// Task id (see `env list`), e.g. FixedInterval-v0, Bisection-v0, MultiTimer-v0.
    pub task: String,
    /// Parameter override `key=value` (repeatable); reference names are accepted as aliases
    /// (e.g. oven_duration, max_timesteps, overcooked_buffer, undercooked_possible).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Reference-compatible mode: the time-limit stop is reported as `terminated`.
    #[arg(long)]
    pub reference: bool,
    /// Start cell `row,col` (must be free); drawn uniformly if omitted.
    #[arg(long, value_name = "ROW,COL")]
    pub start: Option<String>,
    /// Target duration of the episode (steps; reproduction: the sample interval ts); drawn
    /// by the task if omitted. Multi-oven: one value for every oven, or one per oven (`6,12`).
    #[arg(long, value_name = "STEPS[,STEPS…]")]
    pub td: Option<String>,
    /// Asynchronous multi-oven: the on-time of each oven after the first (steps, `3,7`).
    #[arg(long, value_name = "STEPS[,STEPS…]")]
    pub on_times: Option<String>,
    /// Ready-Set-Go tasks: the index of the episode's prior (in `priors`); drawn if omitted.
    #[arg(long)]
    pub prior: Option<u8>,
    /// Ready-Set-Go tasks: the index of the episode's gain (in `gains`); drawn if omitted.
    #[arg(long)]
    pub gain: Option<u8>,
    /// Uncertainty task: force a never-ready (true) or normal (false) episode.
    #[arg(long)]
    pub never_ready: Option<bool>,
    /// RNG seed for what is not fixed by the options.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

impl TaskArgs {
    /// Builds the env and the reset options.
    pub fn build(&self) -> Result<(ChronoEnv, ResetOptions)> {
        // Two spellings of one setting that disagree are refused, never resolved silently.
        let set_value = |key: &str| {
            self.set.iter().find_map(|kv| {
                let (k, v) = kv.split_once('=')?;
                (k.trim().eq_ignore_ascii_case(key)).then(|| v.trim().to_string())
            })
        };
        if self.reference
            && let Some(v) = set_value("reference_compat")
            && v != "true"
        {
            anyhow::bail!(
                "--reference and --set reference_compat={v} disagree (--reference means reference_compat=true): drop one"
            );
        }
        if let (Some(td), Some(v)) = (&self.td, set_value("td"))
            && td.trim() != v
        {
            anyhow::bail!(
                "--td {td} and --set td={v} disagree (--td sets this episode's target duration): drop one"
            );
        }
        let mut overrides = self.set.clone();
        if self.reference {
            overrides.push("reference_compat=true".into());
        }
        let env = ChronoEnv::from_id(&self.task, &overrides)?;
        let start = match &self.start {
            None => None,
            Some(text) => {
                let parts: Vec<&str> = text.split(',').map(str::trim).collect();
                let parsed: Option<(usize, usize)> = match parts.as_slice() {
                    [r, c] => r.parse().ok().zip(c.parse().ok()),
                    _ => None,
                };
                Some(parsed.with_context(|| {
                    format!(
                        "--start `{text}`: expected ROW,COL with non-negative integers, e.g. 1,1"
                    )
                })?)
            }
        };
        let td = self
            .td
            .as_deref()
            .map(|t| steps_list("--td", t))
            .transpose()?;
        let on_times = self
            .on_times
            .as_deref()
            .map(|t| steps_list("--on-times", t))
            .transpose()?;
        let (td, oven_tds) = match td {
            Some(v) if v.len() == 1 => (Some(v[0]), None),
            Some(v) => (None, Some(PerOven::new("oven_tds", &v)?)),
            None => (None, None),
        };
        Ok((
            env,
            ResetOptions {
                start,
                td,
                never_ready: self.never_ready,
                oven_tds,
                on_times: on_times.map(|v| PerOven::new("on_times", &v)).transpose()?,
                prior: self.prior,
                gain: self.gain,
            },
        ))
    }
}

/// A comma-separated list of whole steps (`6,12`).
fn steps_list(flag: &str, text: &str) -> Result<Vec<u32>> {
    text.split(',')
        .map(|x| x.trim().parse::<u32>())
        .collect::<std::result::Result<Vec<_>, _>>()
        .ok()
        .filter(|v| !v.is_empty())
        .with_context(|| {
            format!("{flag} `{text}`: expected comma-separated whole steps, e.g. 6,12")
        })
}

/// Which policy drives a rendered episode.
#[derive(ValueEnum, Clone, Copy, Debug)]
pub enum RenderPolicy {
    /// The optimal scripted policy.
    Oracle,
    /// Uniformly random actions.
    Random,
}

/// `env` subcommands.
#[derive(Subcommand, Debug)]
pub enum EnvCommand {
    /// List registered tasks with tags, defaults and parameters.
    List {
        /// Only tasks with this tag.
        #[arg(long)]
        tag: Option<String>,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Print the Markdown table of every task parameter (the one in docs/tasks.md).
        #[arg(long, conflicts_with = "json")]
        markdown: bool,
    },
    /// Replay a comma-separated action list; prints JSON lines (reset, then one per step).
    Replay {
        #[command(flatten)]
        task: TaskArgs,
        /// Action codes, e.g. 3,5,1,5 (0 wait, 1 down, 2 up, 3 right, 4 left, 5 interact).
        #[arg(long, allow_hyphen_values = true)]
        actions: String,
    },
    /// Oracle vs random policy on every task from every start cell: GIFs and a summary.
    Demo(demo::DemoArgs),
    /// Render an oracle or random episode as an animated GIF (and optional PNG frames / ASCII).
    Render {
        #[command(flatten)]
        task: TaskArgs,
        /// Policy that plays the episode.
        #[arg(long, value_enum, default_value_t = RenderPolicy::Oracle)]
        policy: RenderPolicy,
        /// Output GIF path.
        #[arg(long, default_value = "episode.gif")]
        out: PathBuf,
        /// Also write every frame as PNG into this folder.
        #[arg(long)]
        png_dir: Option<PathBuf>,
        /// Print every frame as ASCII.
        #[arg(long)]
        ascii: bool,
        /// Hundredths of a second per GIF frame.
        #[arg(long, default_value_t = 25)]
        delay: u16,
    },
    /// Play a task in the terminal (arrows/WASD move, space/E interact, . wait, q quit);
    /// every step is recorded as JSON lines in the same shape as `env replay`.
    Play {
        #[command(flatten)]
        task: TaskArgs,
        /// JSON-lines file that receives the recording (appended, flushed every step).
        #[arg(long, default_value = "play.jsonl")]
        record: PathBuf,
        /// Number of episodes to play (0 = until q).
        #[arg(long, default_value_t = 1)]
        episodes: u32,
    },
}

/// Runs an `env` subcommand.
pub fn run(cmd: EnvCommand) -> Result<()> {
    match cmd {
        EnvCommand::List { markdown: true, .. } => {
            print!("{}", chronocooked_env::registry::parameters_markdown());
            Ok(())
        }
        EnvCommand::List { tag, json, .. } => list(tag.as_deref(), json),
        EnvCommand::Replay { task, actions } => {
            let (mut env, options) = task.build()?;
            let actions = parse_action_list(&actions)?;
            let lines = trace::replay(&mut env, Some(task.seed), &options, &actions)?;
            let mut out = std::io::stdout().lock();
            for line in lines {
                writeln!(out, "{}", line.to_json())?;
            }
            Ok(())
        }
        EnvCommand::Demo(args) => demo::run(args),
        EnvCommand::Render {
            task,
            policy,
            out,
            png_dir,
            ascii,
            delay,
        } => render_episode(&task, policy, &out, png_dir.as_deref(), ascii, delay),
        EnvCommand::Play {
            task,
            record,
            episodes,
        } => play::run(&task, &record, episodes),
    }
}

fn list(tag: Option<&str>, json: bool) -> Result<()> {
    let tasks: Vec<_> = all_tasks()
        .iter()
        .filter(|t| tag.is_none_or(|tag| t.tags.contains(&tag)))
        .collect();
    if tasks.is_empty() {
        bail!(
            "no task has tag `{}` (tags in use: {})",
            tag.unwrap_or_default(),
            all_tags().join(", ")
        );
    }
    if json {
        for t in tasks {
            let value = serde_json::json!({
                "id": t.id,
                "family": t.family,
                "tags": t.tags,
                "summary": t.summary,
                "description": t.description,
                "source": t.source,
                "defaults": t.default_config(),
                "params": chronocooked_env::task::params::rows(&t.default_config()),
            });
            println!("{value}");
        }
        return Ok(());
    }
    for t in &tasks {
        let cfg = t.default_config();
        println!("{}  [{}]", t.id, t.tags.join(", "));
        println!("  {}", t.summary);
        println!("  source: {}", t.source);
        println!("  defaults: {}", serde_json::to_string(&cfg.params)?);
        println!(
            "  layout: {}  max_timesteps: {}",
            cfg.layout, cfg.max_timesteps
        );
        let rows = chronocooked_env::task::params::rows(&cfg);
        let common: Vec<&str> = common_params().iter().map(|p| p.key).collect();
        for r in rows.iter().filter(|r| !common.contains(&r.key.as_str())) {
            print_param(r);
        }
        println!();
    }
    println!("Parameters of every task (defaults of the first task listed):");
    let cfg = tasks[0].default_config();
    for r in chronocooked_env::task::params::rows(&cfg)
        .iter()
        .filter(|r| common_params().iter().any(|p| p.key == r.key))
    {
        print_param(r);
    }
    Ok(())
}

fn print_param(r: &chronocooked_env::task::params::ParamRow) {
    let aliases = if r.aliases.is_empty() {
        String::new()
    } else {
        format!(" (alias {})", r.aliases.join(", "))
    };
    println!(
        "    {}{}: {} [default {}] — {}",
        r.key, aliases, r.allowed, r.default, r.doc
    );
}

fn all_tags() -> Vec<&'static str> {
    let mut tags: Vec<&str> = all_tasks()
        .iter()
        .flat_map(|t| t.tags.iter().copied())
        .collect();
    tags.sort_unstable();
    tags.dedup();
    tags
}

/// Plays one episode with `policy`, returning the codes observations (reset first) and the return.
pub fn play_episode(
    env: &mut ChronoEnv,
    seed: u64,
    options: &ResetOptions,
    policy: RenderPolicy,
) -> Result<(Vec<Vec<u8>>, f64, u32)> {
    env.reset(Some(seed), options)?;
    let oracle = Oracle::new(env);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ 0x5eed);
    let mut frames = vec![env.obs_codes().to_vec()];
    let mut total = 0.0;
    let mut steps = 0;
    while !env.is_done() {
        let action = match policy {
            RenderPolicy::Oracle => oracle.act(&env.state()),
            RenderPolicy::Random => Action::ALL[rng.random_range(0..Action::COUNT)],
        };
        let t = env.step(action)?;
        total += t.reward as f64;
        steps += 1;
        frames.push(env.obs_codes().to_vec());
    }
    Ok((frames, total, steps))
}

fn render_episode(
    task: &TaskArgs,
    policy: RenderPolicy,
    out: &std::path::Path,
    png_dir: Option<&std::path::Path>,
    ascii: bool,
    delay: u16,
) -> Result<()> {
    let (mut env, options) = task.build()?;
    let (frames, total, steps) = play_episode(&mut env, task.seed, &options, policy)?;
    let layout = env.layout().clone();
    let family = env.family();
    let images: Vec<_> = frames
        .iter()
        .map(|f| render::frame(&layout, family, f))
        .collect();
    chronocooked_env::fs::write_atomic(out, &render::gif_bytes(&images, delay)?)?;
    if let Some(dir) = png_dir {
        for (i, img) in images.iter().enumerate() {
            chronocooked_env::fs::write_atomic(
                &dir.join(format!("frame_{i:04}.png")),
                &render::png_bytes(img)?,
            )?;
        }
    }
    if ascii {
        for (i, f) in frames.iter().enumerate() {
            println!("step {i}\n{}", render::ascii(&layout, family, f));
        }
    }
    println!(
        "{}: {:?} policy, {} steps, return {:.3} -> {}",
        env.config().id,
        policy,
        steps,
        total,
        out.display()
    );
    Ok(())
}
