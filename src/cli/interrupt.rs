//! Ctrl-C, SIGTERM and SIGHUP for commands that must stop cleanly (`batch`, `apply`, `inspect`,
//! `clear`): the first
//! signal asks the running command to finish what is in flight and stop; a second one ends
//! the process at once with exit code 130.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};

/// Exit code of a run ended by an interrupt (128 + SIGINT, as shells report it).
pub const INTERRUPTED_EXIT_CODE: u8 = 130;

/// A run stopped by an interrupt before it changed anything (while it waited for a
/// connection): the command line prints it as one line and exits with
/// [`INTERRUPTED_EXIT_CODE`].
#[derive(Debug, thiserror::Error)]
#[error("interrupted {0}")]
pub struct Interrupted(pub String);

/// Set once the user has asked to stop.
#[derive(Debug, Clone)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// Installs the handler for this process (once per process).
    pub fn install() -> Result<Interrupt> {
        let flag = Arc::new(AtomicBool::new(false));
        let seen = flag.clone();
        ctrlc::set_handler(move || {
            if seen.swap(true, Ordering::SeqCst) {
                eprintln!("\ninterrupted again: stopping at once");
                std::process::exit(i32::from(INTERRUPTED_EXIT_CODE));
            }
            eprintln!(
                "\ninterrupted: finishing what is in flight (press Ctrl-C again to stop at once)"
            );
        })
        .context("cannot install the Ctrl-C handler")?;
        Ok(Interrupt(flag))
    }

    /// The flag the library polls.
    pub fn flag(&self) -> &AtomicBool {
        &self.0
    }

    /// The flag, shared, for options that own it.
    pub fn shared(&self) -> Arc<AtomicBool> {
        self.0.clone()
    }

    /// `true` once a signal has arrived.
    pub fn requested(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}
