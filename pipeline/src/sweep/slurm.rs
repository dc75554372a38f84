//! Slurm emission: one job array running `chronocooked sweep-job` per line of
//! `commands.txt`, and a report job to submit after it.

use super::file::Job;
use std::path::Path;

/// Quotes `s` for bash (single quotes).
pub fn shell_quote(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+~@".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// The command line that runs (or finishes) one job: `BIN sweep-job FILE --out OUT --id ID`.
pub fn job_command(bin: &str, sweep_file: &Path, out: &Path, id: &str) -> String {
    [
        shell_quote(bin),
        "sweep-job".into(),
        shell_quote(&sweep_file.display().to_string()),
        "--out".into(),
        shell_quote(&out.display().to_string()),
        "--id".into(),
        shell_quote(id),
    ]
    .join(" ")
}

/// Files of a Slurm submission.
#[derive(Debug, Clone, PartialEq)]
pub struct SlurmFiles {
    /// `commands.txt`: one job command per line (array index i runs line i+1).
    pub commands: String,
    /// `sweep.sbatch`: the job array.
    pub array_script: String,
    /// `report.sbatch`: merges every job into one leaderboard (submit with
    /// `--dependency=afterok:<array job id>`).
    pub report_script: String,
}

/// Slurm job array for `jobs` (`max_parallel` tasks at once, `time` per task as `HH:MM:SS`).
pub fn slurm_script(
    name: &str,
    bin: &str,
    sweep_file: &Path,
    out: &Path,
    jobs: &[Job],
    max_parallel: usize,
    time: &str,
) -> SlurmFiles {
    let slurm_dir = out.join("slurm");
    let commands: String = jobs
        .iter()
        .map(|j| job_command(bin, sweep_file, out, &j.id) + "\n")
        .collect();
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let safe_name: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    let array_script = format!(
        "#!/bin/bash\n\
         #SBATCH --job-name=chronocooked-{safe_name}\n\
         #SBATCH --array=0-{last}%{max_parallel}\n\
         #SBATCH --cpus-per-task=1\n\
         #SBATCH --mem=4G\n\
         #SBATCH --time={time}\n\
         #SBATCH --output={logs}/%A_%a.out\n\
         # One array task per line of commands.txt ({n} jobs). Each command skips stages it\n\
         # already finished, so resubmitting the array after a preemption is safe.\n\
         set -euo pipefail\n\
         export RAYON_NUM_THREADS=1\n\
         COMMANDS={commands_file}\n\
         LINE=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$COMMANDS\")\n\
         if [ -z \"$LINE\" ]; then\n  \
           echo \"no command for array index $SLURM_ARRAY_TASK_ID\" >&2\n  \
           exit 1\n\
         fi\n\
         echo \"$LINE\"\n\
         eval \"$LINE\"\n",
        last = jobs.len().saturating_sub(1),
        logs = q(&slurm_dir.join("logs")),
        n = jobs.len(),
        commands_file = q(&slurm_dir.join("commands.txt")),
    );
    let report_script = format!(
        "#!/bin/bash\n\
         #SBATCH --job-name=chronocooked-{safe_name}-report\n\
         #SBATCH --cpus-per-task=1\n\
         #SBATCH --mem=4G\n\
         #SBATCH --time=00:30:00\n\
         #SBATCH --output={logs}/report.out\n\
         # Submit after the array: sbatch --dependency=afterok:<array job id> report.sbatch\n\
         set -euo pipefail\n\
         {bin} report --runs {out} --out {report}\n",
        logs = q(&slurm_dir.join("logs")),
        bin = shell_quote(bin),
        out = q(out),
        report = q(&out.join("report")),
    );
    SlurmFiles {
        commands,
        array_script,
        report_script,
    }
}
