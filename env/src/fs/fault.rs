//! Fault injection for the lab's fault-tolerance tests: a full disk or a sudden death at a
//! chosen write, without root, a size-limited tmpfs or a debugger.
//!
//! Every write of the lab (atomic writes and appends) passes [`before_commit`] just before
//! it becomes visible (the rename of an atomic write, the append of a line). When the
//! environment variable [`FAULT_ENV`] is set, the write numbered `N` (1-based, counted per
//! process) and every later one fail or end the process:
//!
//! * `enospc@N` — the write fails with `ENOSPC` ("No space left on device"), as on a full
//!   disk (which stays full: every later write fails too);
//! * `kill@N` — the process ends at once by `abort()`, with no destructor, flush or
//!   clean-up run: on disk, the same as `kill -9` at that point.
//!
//! Unset (always, outside tests), the check is one relaxed atomic load.

use std::path::Path;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

/// The environment variable that asks for a fault (`enospc@N` or `kill@N`).
pub const FAULT_ENV: &str = "CHRONOCOOKED_FAULT";

/// The `ENOSPC` error number on Linux and the BSDs.
const ENOSPC: i32 = 28;

/// A fault asked for through [`FAULT_ENV`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fault {
    /// Writes from the `n`-th on fail with `ENOSPC`.
    DiskFull(u64),
    /// The process aborts at the `n`-th write.
    Kill(u64),
}

impl Fault {
    /// Parses `enospc@N` / `kill@N` (N ≥ 1).
    pub fn parse(text: &str) -> Option<Fault> {
        let (kind, n) = text.trim().split_once('@')?;
        let n: u64 = n.parse().ok().filter(|&n| n >= 1)?;
        match kind {
            "enospc" => Some(Fault::DiskFull(n)),
            "kill" => Some(Fault::Kill(n)),
            _ => None,
        }
    }
}

static WRITES: AtomicU64 = AtomicU64::new(0);

fn planned() -> Option<Fault> {
    static PLAN: OnceLock<Option<Fault>> = OnceLock::new();
    *PLAN.get_or_init(|| std::env::var(FAULT_ENV).ok().and_then(|v| Fault::parse(&v)))
}

/// Called just before a write to `path` becomes visible: counts it and, when a fault is
/// planned for it, fails with `ENOSPC` or aborts the process.
pub fn before_commit(path: &Path) -> std::io::Result<()> {
    let Some(fault) = planned() else {
        return Ok(());
    };
    let n = WRITES.fetch_add(1, Ordering::SeqCst) + 1;
    match fault {
        Fault::DiskFull(at) if n >= at => Err(std::io::Error::from_raw_os_error(ENOSPC)),
        Fault::Kill(at) if n >= at => {
            eprintln!("fault injection: abort before writing {}", path.display());
            std::process::abort()
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fault_plans_parse_and_bad_ones_are_ignored() {
        assert_eq!(Fault::parse("enospc@3"), Some(Fault::DiskFull(3)));
        assert_eq!(Fault::parse(" kill@1 "), Some(Fault::Kill(1)));
        for bad in ["enospc@0", "kill", "kill@x", "full@2", ""] {
            assert_eq!(Fault::parse(bad), None, "{bad}");
        }
        let e = std::io::Error::from_raw_os_error(ENOSPC);
        assert!(e.to_string().contains("No space left"), "{e}");
    }
}
