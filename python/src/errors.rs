//! Python exceptions for the library's errors, worded as the command line words them.
//!
//! A usage error (an option out of range, options that conflict) is a `ValueError`; an
//! invalid layout a `ValidationError` (a `ValueError`) listing its problems; a simulator
//! that does not answer or refuses a `SimulatorError` carrying the remedies the command line
//! prints as `hint:` lines; an interrupted drawing an `Interrupted` (a `KeyboardInterrupt`).
//! A drawing error's roles and remedies come as data and are worded with Python's keywords
//! (`remedies`), as are the options the library's messages name (`wording`); only text the
//! command line's own code words (clap's errors, its usage errors and connection hints) has
//! its options rewritten as keywords ([`python_names`]).

use std::io;

use pyo3::create_exception;
use pyo3::exceptions::{PyBaseException, PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use vrep_maze::cli::{UsageError, cause_hints, details_with, one_line_with};
use vrep_maze::draw::DrawError;
use vrep_maze::layout::json::ReadError;
use vrep_maze::validate::Invalid;
use vrep_maze::wording::Message;

use crate::wording::{Keywords, OverCommandLine};

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

/// `text` with the command line's option names as the keywords Python takes:
/// `invalid value 'prims' for '--algo <ALGO>'` becomes `invalid value algo='prims'`,
/// `'--size <SIZE>'` becomes `size`, and a bare `--connect-timeout` `connect_timeout`
/// (`--create-missing`, a flag, `create_missing=True`).
///
/// Only for the text that comes in the command line's words, written by the command line's
/// own code: clap's parse errors, connection failures and their hints, its usage errors. The
/// library's messages carry their options as data (`wording`), a drawing error's roles and
/// remedies too (`remedies`).
pub fn python_names(text: &str) -> String {
    let keyword = |option: &str| option.trim_start_matches("--").replace('-', "_");
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("'--") {
        let Some(len) = rest[at + 1..].find('\'') else {
            break;
        };
        let quoted = &rest[at + 1..at + 1 + len];
        let name = keyword(quoted.split_whitespace().next().unwrap_or(quoted));
        let before = &rest[..at];
        // "invalid value 'X' for '--opt <V>'" reads "invalid value opt='X'"
        match before
            .strip_suffix(" for ")
            .and_then(|b| b.rsplit_once("invalid value "))
        {
            Some((head, value)) => out.push_str(&format!("{head}invalid value {name}={value}")),
            None => {
                out.push_str(before);
                out.push_str(&name);
            }
        }
        rest = &rest[at + 1 + len + 1..];
    }
    out.push_str(rest);
    bare_options(&out)
}

/// Bare `--option` words as Python keyword arguments: `option=True` for a flag,
/// `option=VALUE` with the value that follows (`--api legacy --connect-timeout 75` reads
/// `api="legacy", connect_timeout=75`), `option` alone when no value follows.
fn bare_options(text: &str) -> String {
    use clap::CommandFactory;
    let cli = vrep_maze::cli::Cli::command();
    let flag = |long: &str| {
        cli.get_subcommands()
            .flat_map(|s| s.get_arguments())
            .chain(cli.get_arguments())
            .find(|a| a.get_long() == Some(long))
            .is_some_and(|a| !a.get_action().takes_values())
    };
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    // the end of the keyword argument just written: another that follows joins with ", "
    let mut after_keyword = false;
    while let Some(at) = rest.find("--") {
        let starts_word = at == 0 || !rest[..at].ends_with(|c: char| c.is_alphanumeric());
        let name_len = rest[at + 2..]
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(rest.len() - at - 2);
        let long = &rest[at + 2..at + 2 + name_len];
        let between = &rest[..at];
        let keyword =
            starts_word && !long.is_empty() && long.starts_with(|c: char| c.is_ascii_alphabetic());
        if keyword && after_keyword && between == " " {
            out.push_str(", ");
        } else {
            out.push_str(between);
        }
        after_keyword = false;
        rest = &rest[at + 2 + name_len..];
        if !keyword {
            out.push_str("--");
            out.push_str(long);
            continue;
        }
        out.push_str(&long.replace('-', "_"));
        if flag(long) {
            out.push_str("=True");
            after_keyword = true;
        } else if let Some((value, left)) = option_value(rest) {
            out.push('=');
            out.push_str(&python_value(value));
            rest = left;
            after_keyword = true;
        }
    }
    out.push_str(rest);
    out
}

/// The value word that follows an option in `rest` (` 75`, ` legacy,`), without trailing
/// punctuation, and what follows it; `None` when no value follows (an option named alone).
fn option_value(rest: &str) -> Option<(&str, &str)> {
    let word_start = rest.strip_prefix(' ')?;
    let len = word_start
        .find(char::is_whitespace)
        .unwrap_or(word_start.len());
    let word = word_start[..len].trim_end_matches([',', ';', ')', ':']);
    let plain = |c: char| c.is_ascii_alphanumeric() || "._-/".contains(c);
    if word.is_empty() || word.starts_with("--") || !word.chars().all(plain) {
        return None;
    }
    // an English word after an option name ("--port: CoppeliaSim ...") is no value
    let lower_word = word.chars().all(|c| c.is_ascii_lowercase());
    let values = [
        "legacy", "zmq", "auto", "both", "mesh", "copies", "stop", "end",
    ];
    if lower_word && !values.contains(&word) {
        return None;
    }
    Some((word, &word_start[word.len()..]))
}

/// `value` as Python writes it: a number or a placeholder (`NAME`) as is, a word quoted.
fn python_value(value: &str) -> String {
    let number = value.parse::<f64>().is_ok();
    let placeholder = value.chars().any(|c| c.is_ascii_uppercase())
        && !value.chars().any(|c| c.is_ascii_lowercase());
    if number || placeholder {
        value.to_string()
    } else {
        format!("\"{value}\"")
    }
}

#[cfg(test)]
mod tests {
    use super::python_names;

    #[test]
    fn hints_name_keyword_arguments_with_their_values() {
        assert_eq!(
            python_names("pass --api legacy --connect-timeout 75 to wait it out"),
            "pass api=\"legacy\", connect_timeout=75 to wait it out"
        );
        assert_eq!(
            python_names(
                "the ZeroMQ remote API answers on 127.0.0.1:23000: try --api zmq --port 23000"
            ),
            "the ZeroMQ remote API answers on 127.0.0.1:23000: try api=\"zmq\", port=23000"
        );
        assert_eq!(
            python_names("pass --robot NAME with the name"),
            "pass robot=NAME with the name"
        );
        assert_eq!(
            python_names("check --port: CoppeliaSim serves"),
            "check port: CoppeliaSim serves"
        );
        assert_eq!(
            python_names("pass --create-missing to create them"),
            "pass create_missing=True to create them"
        );
    }
}
