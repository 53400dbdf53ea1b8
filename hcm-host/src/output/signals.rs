//! Interrupted runs leave nothing behind: on SIGINT (Ctrl-C), SIGTERM or SIGHUP every
//! temporary file and directory of the process is removed before it exits.
//!
//! SIGKILL (and a machine that stops) cannot be caught: the temporaries stay, named
//! `.hcm-tmp-<process id>-…` beside the destination, and the next hcm run that writes into
//! the same directory removes them (it checks that their process no longer exists).
//! Finished outputs are never touched: they appear by rename, whole.

use super::registry;
use std::io;

/// Starts a thread that waits for SIGINT, SIGTERM or SIGHUP, then removes every live
/// temporary and exits with status 128 + the signal's number (130, 143, 129), as a shell
/// reports a process the signal ended. Call once, first thing in `main`. A no-op where
/// signals are not Unix's.
pub fn remove_temporaries_on_signals() -> io::Result<()> {
    #[cfg(unix)]
    {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
        std::thread::Builder::new()
            .name("hcm-signals".into())
            .spawn(move || {
                if let Some(signal) = signals.forever().next() {
                    registry::remove_all_and_exit(128 + signal);
                }
            })?;
    }
    Ok(())
}
