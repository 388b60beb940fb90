//! Standard output that can fail. Every line a command prints goes through [`outln!`], so a
//! full disk (`> /dev/full`), a closed stream (`>&-`) or any other write error ends the run
//! with one error line and exit code 1 instead of a panic; a reader that closes a pipe
//! early (`| head`) ends it quietly with success ([`PipeClosed`]).

use std::fmt;
use std::io::{self, Write};
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::Result;

/// Set when the process started with its standard output closed (`>&-`).
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// The reader of standard output closed it (`vrep-maze validate *.json | head -1`): the
/// run stops and exits 0, as `rg | head` does.
#[derive(Debug, thiserror::Error)]
#[error("the reader closed standard output")]
pub(crate) struct PipeClosed;

/// Notes whether the process started with its standard output closed (`>&-`). Rust's
/// runtime opens `/dev/null` on a closed standard stream before `main` (so no file this run
/// opens takes its number), which makes writes to it vanish; the binary calls this from
/// a constructor that runs before that, so that writing to a closed standard output fails
/// instead. Linux only (it reads `/proc/self/fd`); elsewhere it notes nothing.
pub fn note_closed_stdout() {
    if cfg!(target_os = "linux")
        && std::path::Path::new("/proc/self/fd").is_dir()
        && std::fs::read_link("/proc/self/fd/1").is_err()
    {
        STDOUT_CLOSED.store(true, Ordering::SeqCst);
    }
}

/// Writes what `write` produces to standard output and flushes it; the error names
/// standard output ([`PipeClosed`] for a closed pipe).
pub(crate) fn write_stdout(write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    if STDOUT_CLOSED.load(Ordering::SeqCst) {
        anyhow::bail!("cannot write to standard output: it is closed (nothing was written)");
    }
    let stdout = io::stdout();
    let mut lock = stdout.lock();
    match write(&mut lock).and_then(|()| lock.flush()) {
        Ok(()) => Ok(()),
        Err(e) if is_broken_pipe(&e) => Err(anyhow::Error::new(PipeClosed)),
        Err(e) => Err(anyhow::Error::new(e).context("cannot write to standard output")),
    }
}

/// One line on standard output: what [`outln!`] calls.
pub(crate) fn line(text: fmt::Arguments<'_>) -> Result<()> {
    write_stdout(|w| writeln!(w, "{text}"))
}

/// `println!` that returns an error instead of panicking: `outln!("OK {name}")?`.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::stdout::line(format_args!($($arg)*))
    };
}
pub(crate) use outln;

/// True if `e`, or an error it wraps (the JSON writer's), is a closed pipe.
pub(crate) fn is_broken_pipe(e: &io::Error) -> bool {
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
