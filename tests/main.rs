//! Every integration test of `chronocooked-lab`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-lab <file>` runs one of them.

mod common;

mod baselines;
mod cli;
mod cli_runs;
mod corruption_props;
mod faults;
mod mechanisms;
mod reliability;
mod signals;
mod structure;
mod sweep;
mod walks_and_bounds;
mod zoo_agents;
