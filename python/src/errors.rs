//! Python exceptions for the library's errors, worded as the command line words them.
//!
//! A usage error (an option out of range, options that conflict) is a `ValueError`; an
//! invalid layout a `ValidationError` (a `ValueError`) listing its problems; a simulator
//! that does not answer or refuses a `SimulatorError` carrying the remedies the command line
//! prints as `hint:` lines; an interrupted drawing an `Interrupted` (a `KeyboardInterrupt`).
//! A drawing error's roles and remedies come as data and are worded with Python's keywords
//! (`remedies`), as are the options the library's messages name (`wording`); only text the
//! command line's own code words (clap's errors, its usage errors and connection hints) has
//! its options rewritten as keywords ([`crate::wording::python_names`]).

use std::io;

use pyo3::create_exception;
use pyo3::exceptions::{PyBaseException, PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use vrep_maze::cli::usage::{UsageError, cause_hints, details_with, one_line_with};
use vrep_maze::draw::DrawError;
use vrep_maze::layout::json::ReadError;
use vrep_maze::validate::Invalid;
use vrep_maze::wording::Message;

use crate::wording::{Keywords, OverCommandLine, python_names};

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
    "Ctrl-C stopped `apply` or `clear` between two requests, as the command line does: the idle rate is restored and the connection closed. `placed` and `total` count the lines drawn (`apply`): `placed == total` for a Ctrl-C that came after the last request, the maze drawn; running the same call again finishes the job."
);

/// The command line's text for `error` (what follows `error: `, then its detail and `hint:`
/// lines) as the Python exception its kind calls for.
pub fn from_anyhow(py: Python<'_>, error: &anyhow::Error) -> PyErr {
    if let Some(invalid) = error.chain().find_map(|c| c.downcast_ref::<Invalid>()) {
        return invalid_error(py, &line(error), invalid);
    }
    let hints: Vec<String> = error
        .chain()
        .flat_map(|cause| match cause.downcast_ref::<DrawError>() {
            Some(draw) => crate::remedies::hints(draw),
            None => cause_hints(cause).iter().map(|h| python_names(h)).collect(),
        })
        .collect();
    let mut text = line(error);
    for detail in details_with(error, &Keywords) {
        text.push_str("\n  ");
        text.push_str(&detail);
    }
    for hint in &hints {
        text.push_str("\n  hint: ");
        text.push_str(hint);
    }
    if error.downcast_ref::<UsageError>().is_some()
        || error.chain().any(|cause| cause.is::<UsageError>())
    {
        return PyValueError::new_err(text);
    }
    with_attributes(py, SimulatorError::new_err(text), |e| {
        e.setattr("hints", hints)
    })
}

/// The command line's error line for `error` (what follows `error: `) in Python's words: a
/// drawing error's roles and the options a library message names as keywords, the command
/// line's own text with its options rewritten ([`python_names`]).
pub fn line(error: &anyhow::Error) -> String {
    one_line_with(error, |cause| {
        if let Some(draw) = cause.downcast_ref::<DrawError>() {
            return crate::remedies::message(draw);
        }
        if let Some(message) = cause.downcast_ref::<Message>() {
            return message.worded(&Keywords);
        }
        match cause.downcast_ref::<UsageError>() {
            Some(usage) => usage.0.worded(&OverCommandLine),
            None => python_names(&cause.to_string()),
        }
    })
}

/// A [`ValidationError`] whose message is `headline` and the problems as the command line
/// shows them (options as keywords), with every problem in `problems`.
pub fn invalid_error(py: Python<'_>, headline: &str, invalid: &Invalid) -> PyErr {
    let mut text = headline.to_string();
    for line in invalid.shown(&Keywords) {
        text.push_str("\n  ");
        text.push_str(&line);
    }
    let problems: Vec<String> = invalid
        .problems
        .iter()
        .map(|p| p.worded(&Keywords))
        .collect();
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
