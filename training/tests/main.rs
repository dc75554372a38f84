//! Every integration test of `chronocooked-training`, compiled into one test binary: one link instead of
//! one per file, and the tests of all files share the test threads. Each file below is
//! one topic; `cargo test --release -p chronocooked-training <file>` runs one of them.

mod adaptation;
mod faithful;
mod native_engine;
mod presets;
mod reproduction_agents;
mod run_folder;
mod settings;
mod task_curricula;
mod tolerance_curriculum;
mod training;
