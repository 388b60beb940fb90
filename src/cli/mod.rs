//! The `vrep-maze` command line: a thin layer over the library. One file per command.

mod apply;
mod batch;
mod clear;
mod completions;
mod connect;
mod demo;
mod generate;
mod output;
mod render;
mod serve;
mod validate;
mod values;

use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

/// Seeded, reproducible grid mazes for CoppeliaSim (V-REP): generate, validate, render.
#[derive(Debug, Parser)]
#[command(name = "vrep-maze", version, about, long_about = None)]
#[command(
    after_help = "Example:\n  vrep-maze generate --seed 42 --algo prim -o maze.json\n  vrep-maze validate maze.json\n  vrep-maze render maze.json --solution\n  vrep-maze apply maze.json          # into a running CoppeliaSim (stopped simulation)\n  vrep-maze demo                     # all of it on the course default, no simulator needed"
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Generate a maze and write its layout JSON.
    Generate(generate::GenerateArgs),
    /// Check a layout file and print its metrics.
    Validate(validate::ValidateArgs),
    /// Draw a layout as ASCII (terminal), SVG or PNG (the floor as the camera sees it).
    Render(render::RenderArgs),
    /// Generate a dataset: one layout per seed plus a manifest, on all cores.
    Batch(batch::BatchArgs),
    /// Print a shell completion script (bash, zsh, fish, ...).
    Completions(completions::CompletionsArgs),
    /// The whole job on the course default: generate, validate, show, and draw into an emulated simulator.
    Demo(demo::DemoArgs),
    /// Draw a layout into CoppeliaSim over the legacy (19997) or ZeroMQ (23000) remote API.
    Apply(apply::ApplyArgs),
    /// Remove a drawn maze from CoppeliaSim (the templates stay).
    Clear(clear::ClearArgs),
    /// Emulate CoppeliaSim's legacy and/or ZeroMQ remote API over an in-memory scene.
    Serve(serve::ServeArgs),
}

/// Parses the command line and runs it; errors become one line on standard error.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(error) => {
            eprintln!("error: {}", one_line(&error));
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Generate(args) => generate::run(args),
        Command::Validate(args) => validate::run(args),
        Command::Render(args) => render::run(args),
        Command::Batch(args) => batch::run(args),
        Command::Completions(args) => completions::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Apply(args) => apply::run(args),
        Command::Clear(args) => clear::run(args),
        Command::Serve(args) => serve::run(args),
    }
}

/// The error and its causes on one line.
pub(crate) fn one_line(error: &anyhow::Error) -> String {
    format!("{error:#}").replace('\n', " ")
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        super::Cli::command().debug_assert();
    }
}
