//! `sweep`: run a sweep file's jobs in parallel on this machine (bounded worker processes,
//! finished jobs skipped, interrupted jobs continued), or emit a Slurm job array for them;
//! `sweep-job`: run one job's stages in this process (what workers and Slurm tasks call).

use anyhow::{Context, Result, bail};
use chronocooked_env::fs::write_atomic;
use chronocooked_pipeline::LogObserver;
use chronocooked_pipeline::sweep::{
    Job, SweepFile, finished_stages, job_dir, job_done, slurm_script,
};
use chronocooked_training::zoo::Family;
use clap::Args;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// Arguments of `sweep`.
#[derive(Args, Debug)]
pub struct SweepArgs {
    /// Sweep file (TOML: tasks, models, sizes, seeds, preset, steps, episodes, set, variants,
    /// record, export, stochastic). See `sweeps/demo.toml`.
    pub file: PathBuf,
    /// Output folder (default `lab-out/<sweep name>`); job folders are `<task>/<model>/seed<N>`.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker processes at once (default: the number of cores).
    #[arg(long)]
    pub workers: Option<usize>,
    /// Instead of running, write a cluster submission: `slurm` (job array + commands).
    #[arg(long, value_name = "SCHEDULER")]
    pub emit: Option<String>,
    /// Slurm: array tasks running at once.
    #[arg(long, default_value_t = 64)]
    pub max_parallel: usize,
    /// Slurm: wall-time limit per job (HH:MM:SS).
    #[arg(long, default_value = "04:00:00")]
    pub time: String,
    /// List the jobs and whether each is finished, run nothing.
    #[arg(long)]
    pub dry_run: bool,
    /// Do not write the leaderboard after the jobs.
    #[arg(long)]
    pub no_report: bool,
}

/// Arguments of `sweep-job` (one job of a sweep, run in this process).
#[derive(Args, Debug)]
pub struct SweepJobArgs {
    /// Sweep file.
    pub file: PathBuf,
    /// Sweep output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Job id (`<task>/<model>/seed<N>`, as listed by `sweep --dry-run`).
    #[arg(long)]
    pub id: String,
}

/// Worker processes when none is asked for: one per core.
pub fn default_workers() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

/// `--dry-run`: every job of `sweep` with whether it is finished under `out`, then the
/// count and the estimated PPO core-hours with `workers` workers.
pub fn print_dry_run(sweep: &SweepFile, jobs: &[Job], out: &Path, workers: usize) {
    let (mut all_s, mut todo_s, mut todo, mut unknown) = (0.0, 0.0, 0, 0);
    for j in jobs {
        let done = job_done(&job_dir(out, &j.id));
        println!("{}  {}", if done { "done" } else { "todo" }, j.id);
        let est = chronocooked_pipeline::sweep::estimate_seconds(sweep, j);
        unknown += usize::from(est.is_none() && j.family == Family::DeepRl);
        let s = est.unwrap_or(0.0);
        all_s += s;
        if !done {
            todo += 1;
            todo_s += s;
        }
    }
    println!(
        "{} jobs ({todo} to do); estimated {:.1} core-hours of PPO training ({:.1} to do; \
         ≈ {:.1} h with {workers} workers) at the {} preset's measured throughput \
         on the lab's 2-core machine (BENCHMARKS.md){}",
        jobs.len(),
        all_s / 3600.0,
        todo_s / 3600.0,
        todo_s / 3600.0 / workers as f64,
        sweep.preset,
        if unknown > 0 {
            format!("; {unknown} jobs of models unmeasured at this preset not counted")
        } else {
            String::new()
        }
    );
}

/// Runs `sweep`.
pub fn run(args: SweepArgs) -> Result<()> {
    let sweep = SweepFile::load(&args.file)?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("lab-out").join(&sweep.name));
    let file = std::path::absolute(&args.file)?;
    let jobs = sweep.jobs()?;
    if args.dry_run {
        let workers = args.workers.unwrap_or_else(default_workers);
        print_dry_run(&sweep, &jobs, &out, workers);
        return Ok(());
    }
    if let Some(kind) = &args.emit {
        if kind != "slurm" {
            bail!("unknown scheduler `{kind}` for --emit (allowed: slurm)");
        }
        return emit_slurm(&sweep, &file, &std::path::absolute(&out)?, &jobs, &args);
    }
    let workers = args.workers.unwrap_or_else(default_workers);
    run_sweep(&sweep, &file, &out, workers, !args.no_report)
}

fn emit_slurm(
    sweep: &SweepFile,
    file: &Path,
    out: &Path,
    jobs: &[Job],
    args: &SweepArgs,
) -> Result<()> {
    let t = &args.time;
    let ok = t.split(':').count() == 3 && t.split(':').all(|p| p.parse::<u32>().is_ok());
    if !ok {
        bail!("invalid --time `{t}` (allowed: HH:MM:SS, e.g. 04:00:00)");
    }
    if args.max_parallel == 0 {
        bail!("--max-parallel must be at least 1");
    }
    let bin = std::env::current_exe()?.display().to_string();
    let files = slurm_script(
        &sweep.name,
        &bin,
        file,
        out,
        jobs,
        args.max_parallel,
        &args.time,
    );
    let dir = out.join("slurm");
    std::fs::create_dir_all(dir.join("logs"))
        .with_context(|| format!("creating {}", dir.display()))?;
    for (name, text) in [
        ("commands.txt", &files.commands),
        ("sweep.sbatch", &files.array_script),
        ("report.sbatch", &files.report_script),
    ] {
        write_atomic(&dir.join(name), text.as_bytes())?;
    }
    println!(
        "{} jobs → {}\nsubmit:  jobid=$(sbatch --parsable {})\nmerge:   sbatch --dependency=afterok:$jobid {}",
        jobs.len(),
        dir.join("commands.txt").display(),
        dir.join("sweep.sbatch").display(),
        dir.join("report.sbatch").display()
    );
    Ok(())
}

/// Runs every unfinished job of `sweep` with at most `workers` worker processes, then (if
/// `report`) writes the leaderboard to `out/report`. Fails, after every job had its turn,
/// if any job failed (their logs are named).
pub fn run_sweep(
    sweep: &SweepFile,
    file: &Path,
    out: &Path,
    workers: usize,
    report: bool,
) -> Result<()> {
    let workers = workers.max(1);
    // One sweep per output folder: a second one is refused naming this one.
    let _lock = chronocooked_env::fs::FolderLock::acquire_shared_folder(out)?;
    // SIGINT / SIGTERM: stop starting jobs, stop the workers (a training worker saves a
    // checkpoint first), wait for them, then end with the signal's exit status.
    let _listening = chronocooked_env::interrupt::listen();
    let jobs = sweep.jobs()?;
    let pending: Vec<&Job> = jobs
        .iter()
        .filter(|j| !job_done(&job_dir(out, &j.id)))
        .collect();
    eprintln!(
        "sweep `{}`: {} jobs, {} already finished, running {} with {workers} workers → {}",
        sweep.name,
        jobs.len(),
        jobs.len() - pending.len(),
        pending.len(),
        out.display()
    );
    let exe = std::env::current_exe()?;
    let multi = MultiProgress::new();
    let total = multi.add(ProgressBar::new(jobs.len() as u64));
    total.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} jobs {msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    total.set_position((jobs.len() - pending.len()) as u64);
    let spinner =
        ProgressStyle::with_template("  {spinner} {elapsed:>4} {msg}").expect("valid template");
    let mut queue = pending.into_iter();
    let mut running: Vec<(&Job, Child, ProgressBar)> = Vec::new();
    let mut failed: Vec<String> = Vec::new();
    let mut stopping = false;
    loop {
        if !stopping && let Some(signal) = chronocooked_env::interrupt::requested() {
            stopping = true;
            total.println(format!(
                "{}: stopping {} running jobs (rerun the sweep to continue them)",
                chronocooked_env::interrupt::signal_name(signal),
                running.len()
            ));
            for (_, child, _) in &running {
                stop_worker(child);
            }
        }
        while !stopping && running.len() < workers {
            let Some(job) = queue.next() else { break };
            // A job whose folder or log cannot be made fails alone, naming the path; the
            // other jobs still run.
            let child = match start_worker(&exe, file, out, &job.id) {
                Ok(child) => child,
                Err(e) => {
                    failed.push(format!("{} ({e:#})", job.id));
                    total.set_message(format!("{} failed", failed.len()));
                    total.inc(1);
                    continue;
                }
            };
            let bar = multi.add(ProgressBar::new_spinner());
            bar.set_style(spinner.clone());
            bar.set_message(job.id.clone());
            running.push((job, child, bar));
        }
        if running.is_empty() {
            break;
        }
        std::thread::sleep(Duration::from_millis(200));
        let mut i = 0;
        while i < running.len() {
            let (job, child, bar) = &mut running[i];
            match child.try_wait()? {
                None => {
                    let stages = finished_stages(&job_dir(out, &job.id));
                    let names: Vec<&str> = stages.iter().map(|s| s.name()).collect();
                    bar.set_message(format!("{}  [{}]", job.id, names.join(" ")));
                    bar.tick();
                    i += 1;
                }
                Some(status) => {
                    if !status.success() {
                        let log = job_dir(out, &job.id).join("log.txt");
                        failed.push(format!("{} ({status}; log {})", job.id, log.display()));
                        total.set_message(format!("{} failed", failed.len()));
                    }
                    bar.finish_and_clear();
                    multi.remove(bar);
                    total.inc(1);
                    running.swap_remove(i);
                }
            }
        }
    }
    total.finish();
    if let Some(signal) = chronocooked_env::interrupt::requested() {
        bail!(
            "sweep stopped by {} ({} jobs did not finish; training jobs saved a checkpoint); rerun the same command to continue",
            chronocooked_env::interrupt::signal_name(signal),
            failed.len() + queue.len()
        );
    }
    // The report's failure never hides the jobs' (a full disk often fails both).
    let report_error = if report {
        write_sweep_report(out).err()
    } else {
        None
    };
    let jobs_failed = (!failed.is_empty()).then(|| {
        format!(
            "{} of {} jobs failed (rerun the sweep to retry them):\n  {}",
            failed.len(),
            jobs.len(),
            failed.join("\n  ")
        )
    });
    match (jobs_failed, report_error) {
        (None, None) => Ok(()),
        (Some(jobs), None) => bail!("{jobs}"),
        (None, Some(report)) => bail!("the report: {report}"),
        (Some(jobs), Some(report)) => bail!("{jobs}\nand the report: {report}"),
    }
}

/// Starts the worker process of job `id` (`sweep-job`), its output appended to the job's
/// `log.txt`; errors name the folder or file that could not be made.
fn start_worker(exe: &Path, file: &Path, out: &Path, id: &str) -> Result<Child> {
    let dir = job_dir(out, id);
    std::fs::create_dir_all(&dir).with_context(|| format!("{}: job folder", dir.display()))?;
    let log_path = dir.join("log.txt");
    let log = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&log_path)
        .with_context(|| log_path.display().to_string())?;
    let mut command = Command::new(exe);
    stop_with_parent(&mut command);
    command
        .arg("sweep-job")
        .arg(file)
        .arg("--out")
        .arg(out)
        .arg("--id")
        .arg(id)
        .env("RAYON_NUM_THREADS", "1")
        .stdin(Stdio::null())
        .stdout(
            log.try_clone()
                .with_context(|| log_path.display().to_string())?,
        )
        .stderr(log)
        .spawn()
        .with_context(|| format!("starting a worker for {id}"))
}

/// Writes the sweep's leaderboard to `out/report` from its finished evaluations.
fn write_sweep_report(out: &Path) -> Result<()> {
    let report_dir = out.join("report");
    let rows = chronocooked_present::report::load_rows_from_runs(&[out.to_path_buf()])
        .map_err(anyhow::Error::msg)?;
    if rows.is_empty() {
        eprintln!("no finished evaluation to report");
        return Ok(());
    }
    for f in chronocooked_present::report::write_report(&rows, &report_dir)
        .map_err(anyhow::Error::msg)?
    {
        println!("{}", f.display());
    }
    Ok(())
}

/// Sends SIGTERM to a worker: a training worker saves a checkpoint and ends; any other
/// stage ends at once (its outputs are atomic and its stage is not marked finished).
fn stop_worker(child: &Child) {
    #[cfg(unix)]
    if let Ok(pid) = libc::pid_t::try_from(child.id()) {
        // SAFETY: `kill` only sends a signal to our own child process.
        unsafe {
            libc::kill(pid, libc::SIGTERM);
        }
    }
    #[cfg(not(unix))]
    let _ = child;
}

/// A worker gets SIGTERM when the sweep process dies, even by `kill -9` (Linux), so no
/// worker keeps writing beside a rerun of the sweep.
fn stop_with_parent(command: &mut Command) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: runs in the child between fork and exec; `prctl` is async-signal-safe.
        unsafe {
            command.pre_exec(|| {
                libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGTERM);
                Ok(())
            });
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = command;
}

/// How long a job waits for a worker of an earlier run of the sweep (killed with its
/// sweep, saving its checkpoint) to leave the job's folder (seconds).
const JOB_LOCK_WAIT_S: u64 = 120;

/// Runs `sweep-job`: one job's unfinished stages, in this process, logged to stderr.
pub fn run_job_cmd(args: SweepJobArgs) -> Result<()> {
    let sweep = SweepFile::load(&args.file)?;
    let job = chronocooked_pipeline::find_job(&sweep, &args.file, &args.id)?;
    let _lock = chronocooked_env::fs::FolderLock::acquire_waiting(
        &job_dir(&args.out, &job.id),
        Duration::from_secs(JOB_LOCK_WAIT_S),
    )?;
    chronocooked_pipeline::run_job(&sweep, &job, &args.out, &mut LogObserver)?;
    Ok(())
}
