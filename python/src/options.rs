//! Keyword arguments as a `vrep-maze` command line, parsed by the command line's own parser.
//!
//! `cell_size=0.5` becomes `--cell-size=0.5`, `size=(20, 15)` `--size=20x15`, `start=(0, 3)`
//! `--start=0,3`, `dry_run=True` `--dry-run`; `None` leaves the option at its default. The
//! keywords a function takes are the options of its command (read from the command line's
//! definition, so a new option is a new keyword at once), and clap and the commands' own
//! checks refuse a value with the message `vrep-maze` prints.

use std::ffi::OsString;

use clap::{CommandFactory, Parser};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use vrep_maze::cli::Cli;
use vrep_maze::cli::usage::rendered_escaped;

/// The program name the parsed command lines start with.
const PROGRAM: &str = "vrep-maze";

/// Options that no function takes as a keyword: clap's own, and those a function replaces
/// (files written or read by the command, which the Python API passes as objects).
const NOT_KEYWORDS: &[&str] = &["help", "version", "output", "out-dir", "seeds"];

/// The command line `vrep-maze <command> <fixed...> --option=value...` for the keyword
/// arguments `options` of the Python function of the same name. An unknown keyword is a
/// `TypeError`, as Python raises for any function.
pub fn command_line(
    command: &str,
    fixed: &[&str],
    options: &Bound<'_, PyDict>,
) -> PyResult<Vec<OsString>> {
    let cli = Cli::command();
    let sub = cli
        .find_subcommand(command)
        .ok_or_else(|| PyValueError::new_err(format!("no vrep-maze command {command}")))?;
    let mut argv: Vec<OsString> = [PROGRAM, command].iter().map(OsString::from).collect();
    argv.extend(fixed.iter().map(OsString::from));
    for (key, value) in options.iter() {
        let key: String = key.extract()?;
        // a trailing underscore is Python's way round its own keywords: `where_` is `--where`
        let long = key.trim_end_matches('_').replace('_', "-");
        let arg = sub
            .get_arguments()
            .find(|a| a.get_long() == Some(long.as_str()) && !NOT_KEYWORDS.contains(&long.as_str()))
            .ok_or_else(|| {
                PyTypeError::new_err(format!(
                    "{command}() got an unexpected keyword argument '{key}'"
                ))
            })?;
        if value.is_none() {
            continue;
        }
        if arg.get_action().takes_values() {
            argv.push(format!("--{long}={}", value_text(&key, &long, &value)?).into());
        } else if value
            .extract::<bool>()
            .map_err(|_| PyTypeError::new_err(format!("{key} takes True or False")))?
        {
            argv.push(format!("--{long}").into());
        }
    }
    Ok(argv)
}

/// A keyword argument's value as the command line writes it: text as given, a number in its
/// shortest exact form, a pair joined the way the option writes pairs (`20x15` for sizes,
/// `0,3` for cells and points).
fn value_text(key: &str, long: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if value.is_instance_of::<PyBool>() {
        return Err(PyTypeError::new_err(format!(
            "{key} takes a number, text or a pair, not a bool"
        )));
    }
    if let Ok(text) = value.cast::<PyString>() {
        return text.extract::<String>();
    }
    if value.is_instance_of::<PyInt>() {
        return value.str()?.extract::<String>();
    }
    if let Ok(number) = value.cast::<PyFloat>() {
        // Rust's shortest form reads back as the same f64, as Python's repr does
        return Ok(format!("{}", number.value()));
    }
    if value.is_instance_of::<PyTuple>() || value.is_instance_of::<PyList>() {
        let parts: Vec<Bound<'_, PyAny>> = value.try_iter()?.collect::<PyResult<_>>()?;
        if parts.len() == 2 {
            let separator = if matches!(long, "size" | "floor-size") {
                "x"
            } else {
                ","
            };
            let a = value_text(key, long, &parts[0])?;
            let b = value_text(key, long, &parts[1])?;
            return Ok(format!("{a}{separator}{b}"));
        }
    }
    Err(PyTypeError::new_err(format!(
        "{key} takes a number, text or a pair, not {}",
        value.repr()?
    )))
}

/// Parses `argv` as `vrep-maze` does; a refused command line is a `ValueError` with the
/// command line's error line (what follows `error: `).
pub fn parse(argv: Vec<OsString>) -> PyResult<vrep_maze::cli::Command> {
    Cli::try_parse_from(&argv)
        .map(|cli| cli.command)
        .map_err(|e| PyValueError::new_err(clap_message(&e, &argv)))
}

/// `clear`'s options from Python keywords (the connection's and the object names): what
/// `vrep_maze.clear`, `vrep_maze.connect` and a session's `clear` take.
pub fn clear_args(options: &Bound<'_, PyDict>) -> PyResult<vrep_maze::cli::ClearArgs> {
    match parse(command_line("clear", &[], options)?)? {
        vrep_maze::cli::Command::Clear(args) => Ok(args),
        _ => Err(PyRuntimeError::new_err("clear parsed as another command")),
    }
}

/// The line `vrep-maze` prints for a usage error clap found in `argv`, without its
/// `error: `: the values clap echoes with their control characters escaped, as the command
/// line shows them ([`rendered_escaped`]).
fn clap_message(error: &clap::Error, argv: &[OsString]) -> String {
    let text = rendered_escaped::<Cli>(error, argv);
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .unwrap_or_default();
    crate::wording::python_names(first.strip_prefix("error: ").unwrap_or(first))
}

/// `options` with `name=value` added unless `value` is `None` (the named parameters a
/// function spells out in its signature, e.g. `seed`, join its `**options`).
pub fn with<'py>(
    options: Option<&Bound<'py, PyDict>>,
    py: Python<'py>,
    named: &[(&str, Option<Bound<'py, PyAny>>)],
) -> PyResult<Bound<'py, PyDict>> {
    let all = match options {
        Some(options) => options.copy()?,
        None => PyDict::new(py),
    };
    for (name, value) in named {
        if let Some(value) = value {
            all.set_item(name, value)?;
        }
    }
    Ok(all)
}
