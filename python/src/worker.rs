//! Long work on a worker thread while the calling thread, without the GIL, watches Python's
//! signals: Ctrl-C reaches Python's handler (as `KeyboardInterrupt`) during a long
//! generation or drawing instead of after it.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the waiting thread runs Python's signal handlers.
const POLL: Duration = Duration::from_millis(20);

/// What to do when a Python signal handler raised (Ctrl-C: `KeyboardInterrupt`).
pub enum OnSignal {
    /// Raise it now; the worker thread finishes on its own and its result is dropped.
    Raise(PyErr),
    /// Keep waiting for the worker (it was asked to stop and will return soon).
    Wait,
}

/// Runs `work` on its own thread and returns its result. The calling thread holds the GIL
/// only to run Python's signal handlers every [`POLL`]; when one raises, `on_signal`
/// decides whether to raise at once or to keep waiting.
pub fn run<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send + 'static,
    mut on_signal: impl FnMut(PyErr) -> OnSignal,
) -> PyResult<T> {
    let (sender, mut receiver) = mpsc::channel();
    std::thread::Builder::new()
        .name("vrep-maze".into())
        .spawn(move || {
            // the receiver is gone only when the caller raised and left
            let _ = sender.send(work());
        })?;
    loop {
        // the receiver goes along and comes back: it may be sent, not shared
        let (back, received) = py.detach(move || {
            let received = receiver.recv_timeout(POLL);
            (receiver, received)
        });
        receiver = back;
        match received {
            Ok(result) => return Ok(result),
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the vrep-maze worker thread panicked (its message is on standard error)",
                ));
            }
            Err(RecvTimeoutError::Timeout) => {}
        }
        if let Err(raised) = py.check_signals()
            && let OnSignal::Raise(err) = on_signal(raised)
        {
            return Err(err);
        }
    }
}
