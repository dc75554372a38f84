//! Every integration test of `chronocooked-present`, compiled into one test binary. Each file
//! below is one topic; `cargo test --release -p chronocooked-present <file>` runs one of them.

mod figures;
mod leaderboard_robust;
