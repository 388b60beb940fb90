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
    let mut script = String::from_utf8(script)?;
    if args.shell == Shell::Bash {
        script = bash_fixed(&script);
    }
    write_stdout(|out| out.write_all(script.as_bytes()))?;
    Ok(ExitCode::SUCCESS)
}

/// clap_complete 4.6 names the subcommands' `case` labels `vrep__subcmd__maze__subcmd__X`
/// for a binary whose name has a hyphen, while its dispatcher sets `vrep__maze__subcmd__X`
/// (clap issue 6421), so no option ever completed: the labels are given the dispatcher's
/// spelling.
fn bash_fixed(script: &str) -> String {
    script.replace("vrep__subcmd__maze", "vrep__maze")
}
