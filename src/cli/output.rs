//! Writing results: to standard output, or to a file replaced atomically so an
//! interrupted run never leaves half a file (or destroys the old one).

use std::io::{self, Write};
use std::path::Path;

use anyhow::{Context, Result};

use crate::atomic_file::write_atomically;

/// Writes what `write` produces to `path`, or to standard output when `path` is `None`
/// or `-`. Files are written to a temporary sibling, then renamed over the target.
pub fn write_output(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<()> {
    match path {
        None => write_stdout(write),
        Some(p) if p.as_os_str() == "-" => write_stdout(write),
        Some(p) => write_file(p, write),
    }
}

fn write_stdout(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    let stdout = io::stdout();
    let mut lock = stdout.lock();
    match write(&mut lock).and_then(|()| lock.flush()) {
        // A closed pipe (`| head`) is the reader's choice, not our failure.
        Err(e) if is_broken_pipe(&e) => Ok(()),
        other => other.context("writing to standard output"),
    }
}

/// True if `e`, or an error it wraps (the JSON writer's), is a closed pipe.
fn is_broken_pipe(e: &io::Error) -> bool {
    if e.kind() == io::ErrorKind::BrokenPipe {
        return true;
    }
    let mut inner: Option<&(dyn std::error::Error + 'static)> = e.get_ref().map(|r| r as _);
    while let Some(cause) = inner {
        let kind = cause
            .downcast_ref::<io::Error>()
            .map(io::Error::kind)
            .or_else(|| cause.downcast_ref::<serde_json::Error>()?.io_error_kind());
        if kind == Some(io::ErrorKind::BrokenPipe) {
            return true;
        }
        inner = cause.source();
    }
    false
}

fn write_file(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    write_atomically(path, write).with_context(|| format!("{}: cannot write", path.display()))
}
