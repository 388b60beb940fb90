//! Writing results: to standard output, or to a file replaced atomically so an
//! interrupted run never leaves half a file (or destroys the old one).

use std::io::{self, Write};
use std::path::Path;

use anyhow::{Context, Result};

use super::stdout::write_stdout;
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

fn write_file(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    write_atomically(path, write).with_context(|| format!("{}: cannot write", path.display()))
}
