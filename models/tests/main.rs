//! Every integration test of `chronocooked-models`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-models <file>` runs one of them.

mod categories;
mod external_ready_set_go;
mod multi_oven_agents;
mod recorded_markers;
mod reproduction_timers;
mod timing_models;
