//! The `vrep-maze` command of the Python package: the binary's code, run in-process.

use std::ffi::OsString;
use std::io::Write;
use std::process::ExitCode;

use pyo3::prelude::*;

/// Runs the `vrep-maze` command line `argv` (the program name first) exactly as the
/// `vrep-maze` binary does, without the GIL, and returns its exit status (0, 1, 2 or 130).
/// The package's `vrep-maze` command calls it with `sys.argv` after giving Ctrl-C back its
/// default action, so that it behaves as the binary. Like the binary, `apply`, `clear`,
/// `batch` and `serve` install their own Ctrl-C handler, for the rest of the process: this is
/// the command's entry point, not a function for scripts (they call `apply` and the rest).
#[pyfunction]
pub fn main(py: Python<'_>, argv: Vec<OsString>) -> u8 {
    let code = py.detach(|| vrep_maze::cli::main_with_args(argv));
    // what a program prints is out when it exits; Python exits next
    let _ = std::io::stdout().flush();
    exit_status(code)
}

/// The number of an exit code (`ExitCode` compares but does not tell its number).
fn exit_status(code: ExitCode) -> u8 {
    (0..=u8::MAX)
        .find(|&n| ExitCode::from(n) == code)
        .unwrap_or(1)
}
