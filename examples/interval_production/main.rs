//! A task family defined outside the lab's crates: registers `IntervalProduction-v0`
//! ([`family`]) and runs the lab's command line with it known.
//!
//! ```bash
//! cargo run --release --example interval_production -- env list
//! cargo run --release --example interval_production -- train --task IntervalProduction-v0 \
//!     --model cnn-mlp --preset fast --out lab-out/interval-production
//! ```

mod family;

use std::process::ExitCode;

fn main() -> ExitCode {
    if let Err(e) = family::register_once() {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    chronocooked_lab::run()
}
