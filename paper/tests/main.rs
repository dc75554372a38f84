//! Every integration test of `chronocooked-paper`, compiled into one test binary: one link
//! instead of one per file, and the tests of all files share the test threads. Each file
//! below is one topic; `cargo test --release -p chronocooked-paper --test integration
//! <file>` runs one of them.

mod common;

mod paper_analysis;
mod paper_claims;
mod paper_claims_multitimer;
mod paper_heldout;
mod paper_levels_spreads;
mod paper_power;
