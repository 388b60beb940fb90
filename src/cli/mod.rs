//! Command-line interface (temporary skeleton on branch `legacy`; the lead's `Command` enum
//! on main replaces it at merge).

pub mod serve;

/// vrep-maze: seeded grid mazes for CoppeliaSim.
#[derive(Debug, clap::Parser)]
#[command(version)]
pub struct Cli {
    /// Subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Emulate CoppeliaSim's legacy remote API over an in-memory scene.
    Serve(serve::ServeArgs),
}

/// Dispatches a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Serve(a) => serve::run(a),
    }
}
