//! The `vrep-maze` binary: all logic lives in the library; see `vrep_maze::cli`.

fn main() -> std::process::ExitCode {
    vrep_maze::cli::main()
}

/// Runs before Rust's runtime opens `/dev/null` on closed standard streams, so that a closed
/// standard output (`>&-`) is told from `> /dev/null` ([`vrep_maze::cli::note_closed_stdout`]).
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static NOTE_CLOSED_STDOUT: extern "C" fn() = {
    extern "C" fn note() {
        vrep_maze::cli::note_closed_stdout();
    }
    note
};
