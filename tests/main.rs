//! Every integration test of `chronocooked-lab`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-lab <file>` runs one of them.
//!
//! These are the lab's cross-crate behaviour tests: through the binary (CLI, faults,
//! sweeps), and through the libraries where a behaviour needs several crates at once
//! (`timing_*`: a timing model trained by `chronocooked-training` and scored by the
//! evaluation protocol of `chronocooked-analysis`). Tests of one crate live with it.

mod common;

mod baselines;
mod cli;
mod cli_runs;
mod corruption_props;
mod doc_commands;
mod docs;
mod dynamics_view;
mod eval_folders;
mod external_task;
mod faults;
mod mechanisms;
mod reliability;
mod signals;
mod structure;
mod studies;
mod sweep;
mod timing_agents;
mod timing_defaults;
mod timing_tasks;
mod verify;
mod walks_and_bounds;
mod zoo_agents;
