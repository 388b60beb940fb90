//! Python exceptions for the library's errors, worded as the command line words them.
//!
//! A usage error (an option out of range, options that conflict) is a `ValueError`; an
//! invalid layout a `ValidationError` (a `ValueError`) listing its problems; a simulator
//! that does not answer or refuses a `SimulatorError` carrying the remedies the command line
//! prints as `hint:` lines; an interrupted drawing an `Interrupted` (a `KeyboardInterrupt`).

use std::io;

use pyo3::create_exception;
use pyo3::exceptions::{PyBaseException, PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use vrep_maze::cli::{UsageError, details, hints, one_line};
use vrep_maze::layout::json::ReadError;
use vrep_maze::validate::Invalid;

create_exception!(
    vrep_maze,
    ValidationError,
    PyValueError,
    "A layout that `vrep-maze validate` rejects. `problems` lists every problem as `field: what is wrong` (the message shows the first 20)."
);
create_exception!(
    vrep_maze,
    SimulatorError,
    PyRuntimeError,
    "A simulator that did not answer, refused, or did not end up holding the maze. `hints` lists what you can do about it (the command line's `hint:` lines)."
);
create_exception!(
    vrep_maze,
    Interrupted,
    PyKeyboardInterrupt,
    "Ctrl-C stopped `apply` or `clear` between two requests, as the command line does: the idle rate is restored and the connection closed. `placed` and `total` count the lines drawn (`apply`); running the same call again finishes the job."
);

/// The command line's text for `error` (what follows `error: `, then its detail and `hint:`
/// lines) as the Python exception its kind calls for.
pub fn from_anyhow(py: Python<'_>, error: &anyhow::Error) -> PyErr {
    if let Some(invalid) = error.chain().find_map(|c| c.downcast_ref::<Invalid>()) {
        return invalid_error(py, &one_line(error), invalid);
    }
    let hints = hints(error);
    let mut text = one_line(error);
    for detail in details(error) {
        text.push_str("\n  ");
        text.push_str(&detail);
    }
    for hint in &hints {
        text.push_str("\n  hint: ");
        text.push_str(hint);
    }
    if error.chain().any(|cause| cause.is::<UsageError>()) {
        return PyValueError::new_err(text);
    }
    with_attributes(py, SimulatorError::new_err(text), |e| {
        e.setattr("hints", hints)
    })
}

/// A [`ValidationError`] whose message is `headline` and the problems as the command line
/// shows them, with every problem in `problems`.
pub fn invalid_error(py: Python<'_>, headline: &str, invalid: &Invalid) -> PyErr {
    let mut text = headline.to_string();
    for line in invalid.shown() {
        text.push_str("\n  ");
        text.push_str(&line);
    }
    let problems: Vec<String> = invalid.problems.iter().map(ToString::to_string).collect();
    with_attributes(py, ValidationError::new_err(text), |e| {
        e.setattr("problems", problems)
    })
}

/// A layout file or text that could not be read: an `OSError` of the matching kind (e.g.
/// `FileNotFoundError`) or a `ValueError`, with the command line's message.
pub fn read_error(error: ReadError) -> PyErr {
    match error {
        ReadError::Io { path, source } => {
            io::Error::new(source.kind(), format!("{path}: {source}")).into()
        }
        other => PyValueError::new_err(other.to_string()),
    }
}

/// An [`Interrupted`] saying `message`, with `placed` and `total` (lines drawn, lines in the
/// drawing; `None` for `clear`).
pub fn interrupted(py: Python<'_>, message: String, counts: Option<(usize, usize)>) -> PyErr {
    let (placed, total) = counts.unzip();
    with_attributes(py, Interrupted::new_err(message), |e| {
        e.setattr("placed", placed)?;
        e.setattr("total", total)
    })
}

/// `err` with the attributes `set` gives its value (or the error setting them).
fn with_attributes(
    py: Python<'_>,
    err: PyErr,
    set: impl FnOnce(&Bound<'_, PyBaseException>) -> PyResult<()>,
) -> PyErr {
    match set(err.value(py)) {
        Ok(()) => err,
        Err(e) => e,
    }
}
