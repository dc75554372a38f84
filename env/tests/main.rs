//! Every integration test of `chronocooked-env`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-env <file>` runs one of them.

mod conformance;
mod extension_tasks;
mod oracle;
mod reference_rules;
mod reference_traces;
mod reproduction_task;
