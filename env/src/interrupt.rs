//! Stop requests from SIGINT / SIGTERM, for the loops that can stop cleanly (PPO training
//! saves a checkpoint and ends; a sweep stops its workers and waits for them).
//!
//! The binary installs a signal handler that calls [`deliver`]. While some loop
//! [`listen`]s, a signal is recorded and the loop sees it through [`requested`]; while none
//! does, [`deliver`] answers `false` and the handler restores the signal's default action
//! (the process ends as it would without a handler). Everything here is lock-free atomics,
//! so [`deliver`] is safe to call from a signal handler.

use std::sync::atomic::{AtomicI32, AtomicUsize, Ordering};

/// Loops listening now.
static LISTENERS: AtomicUsize = AtomicUsize::new(0);
/// The signal number of the first stop request (0: none).
static REQUESTED: AtomicI32 = AtomicI32::new(0);

/// SIGINT's number on Unix (what Ctrl-C sends).
pub const SIGINT: i32 = 2;
/// SIGTERM's number on Unix (what `kill` and schedulers send).
pub const SIGTERM: i32 = 15;

/// While alive, stop requests are recorded instead of ending the process.
#[derive(Debug)]
pub struct Listening(());

impl Drop for Listening {
    fn drop(&mut self) {
        LISTENERS.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Starts listening for stop requests (until the guard is dropped).
pub fn listen() -> Listening {
    LISTENERS.fetch_add(1, Ordering::SeqCst);
    Listening(())
}

/// Called by the signal handler with the signal's number: records the request and returns
/// `true` while a loop listens; returns `false` (record nothing) otherwise, so the handler
/// falls back to the default action. A second signal while a stop is pending also returns
/// `false`: pressing Ctrl-C twice ends the process at once.
pub fn deliver(signal: i32) -> bool {
    if LISTENERS.load(Ordering::SeqCst) == 0 {
        return false;
    }
    REQUESTED
        .compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst)
        .is_ok()
}

/// The signal of a pending stop request, if any.
pub fn requested() -> Option<i32> {
    match REQUESTED.load(Ordering::SeqCst) {
        0 => None,
        s => Some(s),
    }
}

/// The conventional exit status of a process stopped by `signal` (128 + its number: 130
/// for SIGINT, 143 for SIGTERM).
pub fn exit_status(signal: i32) -> u8 {
    u8::try_from(128 + signal.clamp(0, 127)).unwrap_or(255)
}

/// Name of a stop signal for messages.
pub fn signal_name(signal: i32) -> String {
    match signal {
        SIGINT => "SIGINT".into(),
        SIGTERM => "SIGTERM".into(),
        s => format!("signal {s}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_recorded_only_while_listening_and_the_first_one_wins() {
        // One test touches the process-global state, so no other test races with it.
        assert!(!deliver(SIGTERM), "recorded with nobody listening");
        assert_eq!(requested(), None);
        let guard = listen();
        assert!(deliver(SIGTERM));
        assert!(!deliver(SIGINT), "a second signal must fall through");
        assert_eq!(requested(), Some(SIGTERM));
        drop(guard);
        assert!(!deliver(SIGINT));
        assert_eq!(exit_status(SIGINT), 130);
        assert_eq!(exit_status(SIGTERM), 143);
        assert_eq!(signal_name(SIGTERM), "SIGTERM");
    }
}
