//! Chronocooked Lab pipeline: the stages of a study job as library calls, above the
//! training and analysis crates (the `chronocooked` CLI and sweep workers call these; so can
//! any other front end).
//!
//! * [`stages`] — one function per stage, each writing its own folder:
//!   [`stages::train`] (PPO or timing model → run folder), [`stages::evaluate`] (the task's
//!   reference protocol → `eval/`), [`stages::adapt`] (uncertainty adaptation → `adapt/`),
//!   [`stages::record`] (neural activity → `activity.json`, summary, figures),
//!   [`stages::export`] (NPZ + CSV + JSON metadata → `export/`);
//! * [`job`] — [`run_job`]: the unfinished stages of one sweep job, in order, resumable
//!   (finished stages are skipped, a PPO run continues from its newest checkpoint);
//! * [`sweep`] — sweep files, typed job stages, job progress, Slurm emission, cost estimates;
//! * [`error`] — [`PipelineError`], naming the file or the setting at fault.

#![warn(missing_docs)]

pub mod error;
pub mod job;
pub mod stages;
pub mod sweep;

pub use error::PipelineError;
pub use job::{JobObserver, LogObserver, find_job, run_job};
