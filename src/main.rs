//! The `chronocooked` binary: the command line of [`chronocooked_lab::run`].

use std::process::ExitCode;

fn main() -> ExitCode {
    chronocooked_lab::run()
}
