//! `vrep-maze completions`: shell completion scripts.

use std::process::ExitCode;

use anyhow::Result;
use clap::builder::PossibleValuesParser;
use clap::{Args, Command, CommandFactory};
use clap_complete::Shell;

use super::Cli;
use super::stdout::write_stdout;
use crate::generate::Algorithm;
use crate::render::Format;

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
    clap_complete::generate(args.shell, &mut completed(), "vrep-maze", &mut script);
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

/// The values options take where the parser knows them but clap does not (values parsed
/// from text): listed for the completion scripts only; parsing is unchanged.
fn option_values() -> Vec<(&'static str, Vec<&'static str>)> {
    let corners = ["sw", "se", "nw", "ne"];
    vec![
        ("algo", Algorithm::ALL.map(Algorithm::name).to_vec()),
        ("style", vec!["lines", "walls"]),
        ("preset", vec!["micromouse", "micromouse-half"]),
        ("start", [&corners[..], &["farthest-pair"]].concat()),
        ("end", [&corners[..], &["farthest"]].concat()),
        ("bias", corners.to_vec()),
        ("growing", vec!["newest", "oldest", "random", "middle"]),
        ("openings", vec!["none", "start", "end", "start,end"]),
        ("format", Format::ALL.map(Format::name).to_vec()),
    ]
}

/// The command line with [`option_values`] attached to every subcommand that has them.
fn completed() -> Command {
    let mut cli = Cli::command();
    let names: Vec<String> = cli
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    for name in names {
        cli = cli.mut_subcommand(name, |mut sub| {
            for (id, values) in option_values() {
                let known = sub.get_arguments().any(|a| a.get_id() == id);
                let listed = sub
                    .get_arguments()
                    .find(|a| a.get_id() == id)
                    .is_some_and(|a| !a.get_possible_values().is_empty());
                if known && !listed {
                    sub = sub.mut_arg(id, |a| a.value_parser(PossibleValuesParser::new(values)));
                }
            }
            sub
        });
    }
    cli
}
