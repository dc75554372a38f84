//! Sweeps: a TOML file naming models × sizes × tasks × seeds × override variants expands into
//! jobs; each job trains (unless a baseline), evaluates, records activity and exports, in its
//! own folder `OUT/<task>/<model>[~<variant>]/seed<N>/`.
//!
//! * [`file`] — the sweep file and its jobs; [`check`] — every job's settings checked at load;
//! * [`stage`] — the typed stages of a job and which ones it needs;
//! * [`progress`] — finished stages per job folder (`progress.json`), so an interrupted sweep
//!   rerun redoes nothing that finished;
//! * [`slurm`] — the same plan as a Slurm job array;
//! * [`cost`] — measured throughput and the estimated time of a job.
//!
//! The stages themselves run in this crate ([`crate::run_job`]):
//! evaluation, recording and export need the analysis crate, a sibling of this one.

pub mod check;
pub mod cost;
pub mod file;
pub mod progress;
pub mod slurm;
pub mod stage;

pub use cost::{FAST_THROUGHPUT, REFERENCE_THROUGHPUT, estimate_seconds, throughput};
pub use file::{Job, SweepFile, applies, variant_label};
pub use progress::{JobProgress, finished_stages, job_dir, job_done, mark_stage};
pub use slurm::{SlurmFiles, job_command, shell_quote, slurm_script};
pub use stage::Stage;
