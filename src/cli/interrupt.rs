//! Ctrl-C, SIGTERM and SIGHUP for commands that must stop cleanly (`batch`, `apply`, `inspect`,
//! `clear`): the first
//! signal asks the running command to finish what is in flight and stop; a second one ends
//! the process at once with exit code 130 (once a legacy request in flight is answered, for at
//! most [`REPLY_WAIT`]: a real CoppeliaSim quits when its legacy client leaves mid-request).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, Result};

/// Exit code of a run ended by an interrupt (128 + SIGINT, as shells report it).
pub const INTERRUPTED_EXIT_CODE: u8 = 130;

/// A run stopped by an interrupt before it changed anything (while it waited for a
/// connection): the command line prints it as one line and exits with 130
/// (`INTERRUPTED_EXIT_CODE`).
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
        let signals = AtomicU8::new(0);
        ctrlc::set_handler(move || {
            seen.store(true, Ordering::SeqCst);
            match signals.fetch_add(1, Ordering::SeqCst) {
                0 => eprintln!(
                    "\ninterrupted: finishing what is in flight (press Ctrl-C again to stop at once)"
                ),
                1 if crate::legacy::client::exchange_in_flight() => {
                    eprintln!(
                        "\ninterrupted again: stopping as soon as CoppeliaSim has answered the request in flight (a legacy client that leaves mid-request makes it quit); Ctrl-C once more to stop anyway"
                    );
                    std::thread::spawn(stop_after_the_reply);
                }
                _ => {
                    eprintln!("\ninterrupted again: stopping at once");
                    std::process::exit(i32::from(INTERRUPTED_EXIT_CODE));
                }
            }
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

/// The longest a second interrupt waits for a legacy reply in flight.
pub const REPLY_WAIT: Duration = Duration::from_secs(10);

/// Exits with [`INTERRUPTED_EXIT_CODE`] once no legacy exchange is in flight, or after
/// [`REPLY_WAIT`].
fn stop_after_the_reply() {
    let began = Instant::now();
    while crate::legacy::client::exchange_in_flight() && began.elapsed() < REPLY_WAIT {
        std::thread::sleep(Duration::from_millis(1));
    }
    std::process::exit(i32::from(INTERRUPTED_EXIT_CODE));
}
