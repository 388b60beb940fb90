//! Where a command's words go: `-q` keeps everything but errors (and a `--json` document)
//! quiet; `--json` keeps standard output for the one JSON document, so the lines a person
//! reads move to standard error.

use std::sync::atomic::{AtomicBool, Ordering};

use serde::Serialize;

static QUIET: AtomicBool = AtomicBool::new(false);
static JSON: AtomicBool = AtomicBool::new(false);

/// Sets the run's modes: `quiet` (`-q`) and `json` (the command's `--json`).
pub fn set_modes(quiet: bool, json: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
    JSON.store(json, Ordering::Relaxed);
}

/// Sets `--json` for this run (the command knows it once its options are parsed).
pub fn set_json(json: bool) {
    JSON.store(json, Ordering::Relaxed);
}

/// `true` under `-q`.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// `true` under `--json`.
pub fn json() -> bool {
    JSON.load(Ordering::Relaxed)
}

/// A result line for a person: standard output, standard error under `--json`, nothing
/// under `-q`. A write error is the run's error ([`super::stdout`]), never a panic.
/// A line holds names from files, options and scenes: each control character in it is
/// escaped ([`super::escape`]), so no name can split it, forge another or move the cursor.
pub fn say(line: impl std::fmt::Display) -> anyhow::Result<()> {
    if quiet() {
        return Ok(());
    }
    let line = line.to_string();
    let line = super::escape::escaped(&line);
    if json() {
        eprintln!("{line}");
        Ok(())
    } else {
        super::stdout::line(format_args!("{line}"))
    }
}

/// A note on what is going on ("connecting to ..."): standard error, nothing under `-q`;
/// escaped as [`say`] is.
pub fn note(line: impl std::fmt::Display) {
    if !quiet() {
        eprintln!("{}", super::escape::escaped(&line.to_string()));
    }
}

/// The run's JSON document, on one line of standard output (also under `-q`).
pub fn document(report: &impl Serialize) -> anyhow::Result<()> {
    let text = serde_json::to_string(report)?;
    super::stdout::write_stdout(|w| writeln!(w, "{text}"))
}
