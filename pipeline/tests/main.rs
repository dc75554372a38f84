//! Every integration test of `chronocooked-pipeline`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-pipeline <file>` runs one of them.

mod corrupt_files;
mod curriculum_levels;
mod neural_categories_range;
mod neural_model_signatures;
mod run_job;
