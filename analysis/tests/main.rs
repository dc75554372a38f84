//! Every integration test of `chronocooked-analysis`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-analysis <file>` runs one of them.

mod synthetic;

mod behaviour_metrics;
mod dynamics_known_answers;
mod eval_protocol;
mod extension_metrics;
mod fingerprint_reference;
mod neural_categories;
mod neural_categories_edges;
mod neural_known_answers;
mod neural_metrics;
mod production_speed;
mod reproduction_agent;
mod reproduction_known_answers;
mod reproduction_protocol;
mod reproduction_recovery;
mod robust_statistics;
mod speed_known_answers;
mod speed_timing_models;
