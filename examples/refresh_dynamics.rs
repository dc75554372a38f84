//! Recomputes the dynamics signature in every `activity.summary.json` under the given
//! folders from the `activity.json` beside it (`neural::probe::refresh_dynamics`), for
//! recordings summarised before the dynamics view (or by an older version of it); the
//! other fields of the summaries are kept. Job folders of a sweep's output keep both files.
//!
//!     cargo run --release --example refresh_dynamics -- lab-out/mechanisms-reference
//!
//! Prints the number of summaries refreshed and every one that failed.

use std::path::{Path, PathBuf};

fn main() {
    let mut done = 0;
    let mut failed = 0;
    for root in std::env::args().skip(1) {
        for dir in folders_with_summaries(Path::new(&root)) {
            match chronocooked_analysis::neural::probe::refresh_dynamics(&dir) {
                Ok(_) => done += 1,
                Err(e) => {
                    failed += 1;
                    eprintln!("{}: {e}", dir.display());
                }
            }
        }
    }
    println!("{done} summaries refreshed, {failed} failed");
    if failed > 0 {
        std::process::exit(1);
    }
}

/// Every folder under `root` (itself included) holding both `activity.json` and
/// `activity.summary.json`; symbolic links are not followed.
fn folders_with_summaries(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        if dir.join("activity.json").is_file() && dir.join("activity.summary.json").is_file() {
            out.push(dir.clone());
        }
        stack.extend(chronocooked_env::fs::real_subdirs(&dir));
    }
    out.sort();
    out
}
