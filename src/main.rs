//! The `vrep-maze` binary: all logic lives in the library; see `vrep_maze::cli`.

fn main() -> std::process::ExitCode {
    vrep_maze::cli::main()
}
