//! `vrep-maze completions`: shell completion scripts.

use std::process::ExitCode;

use anyhow::Result;
use clap::{Args, CommandFactory};
use clap_complete::Shell;

use super::Cli;
use super::stdout::write_stdout;

/// Options of `completions`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze completions bash > ~/.local/share/bash-completion/completions/vrep-maze\n  vrep-maze completions zsh > ~/.zfunc/_vrep-maze\n  vrep-maze completions fish > ~/.config/fish/completions/vrep-maze.fish"
)]
pub struct CompletionsArgs {
    /// The shell: bash, zsh, fish, elvish or powershell.
    pub shell: Shell,
}

/// Runs `completions`: prints the script for the shell.
pub fn run(args: CompletionsArgs) -> Result<ExitCode> {
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command(), "vrep-maze", &mut script);
    write_stdout(|out| out.write_all(&script))?;
    Ok(ExitCode::SUCCESS)
}
