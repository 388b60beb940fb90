//! The `vrep-maze` command line: a thin layer over the library. One file per command.

mod apply;
mod batch;
mod clear;
mod completions;
mod connect;
mod demo;
mod drive;
mod escape;
mod export;
mod generate;
mod hinted;
mod import;
mod input;
pub mod inspect;
mod interrupt;
mod listed;
mod output;
mod progress;
pub mod remedies;
mod render;
pub mod reports;
mod say;
mod score;
mod serve;
mod session_marker;
mod solve;
mod stdout;
pub mod summary;
pub mod usage;
mod validate;
mod values;
mod wheels;
pub mod wording;

pub use clear::ClearArgs;
pub use connect::RawClient;
pub use interrupt::Interrupted;
pub use stdout::note_closed_stdout;

use std::ffi::OsString;
use std::io::Write;
use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

use usage::{USAGE_EXIT_CODE, UsageError, details, hints, one_line, report_usage, shorten};

/// Seeded, reproducible grid mazes for CoppeliaSim (V-REP): generate, validate, render.
#[derive(Debug, Parser)]
#[command(name = "vrep-maze", version, about, long_about = None)]
#[command(
    after_help = "Example:\n  vrep-maze generate --seed 42 --algo prim -o maze.json\n  vrep-maze validate maze.json\n  vrep-maze render maze.json --solution\n  vrep-maze apply maze.json          # into a running CoppeliaSim (stopped simulation)\n  vrep-maze demo                     # all of it on the course default, no simulator needed"
)]
pub struct Cli {
    /// No progress bars (they show on a terminal only, for steps of over a second).
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Generate a maze and write its layout JSON.
    Generate(generate::GenerateArgs),
    /// Read a maze drawn as text (micromouse drawings, our ASCII render) into a layout.
    Import(import::ImportArgs),
    /// Check a layout file and print its metrics.
    Validate(validate::ValidateArgs),
    /// Draw a layout as ASCII (terminal), SVG or PNG (the floor as the camera sees it).
    Render(render::RenderArgs),
    /// Write a layout as a file a simulator loads: CoppeliaSim XML model or scene, MuJoCo,
    /// Gazebo (SDF), URDF, Webots, Gymnasium-Robotics PointMaze arguments, or a ROS
    /// map_server occupancy map (.yaml + .pgm).
    Export(export::ExportArgs),
    /// The solution as data: its cells and floor waypoints (JSON), or a timed path (CSV).
    Solve(solve::SolveArgs),
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
    /// Show what a CoppeliaSim scene holds now (and whether it matches a layout), changing nothing.
    Inspect(inspect::InspectArgs),
    /// Follow a robot while the simulation runs and grade its run against the maze.
    Score(score::ScoreArgs),
    /// A robot to score at once: add a dummy `Robot` at Start (if none) and move it along
    /// the solution while the simulation runs (ZeroMQ API).
    Drive(drive::DriveArgs),
    /// Emulate CoppeliaSim's legacy and/or ZeroMQ remote API over an in-memory scene.
    Serve(serve::ServeArgs),
}

/// Parses the command line and runs it; errors become one line on standard error (then
/// one line per hint), with exit code 2 for usage errors and 1 for other failures.
pub fn main() -> ExitCode {
    main_with_args(std::env::args_os())
}

/// [`main`] for the command line `args` (the program name first): the `vrep-maze` binary's
/// code for programs that embed it (the Python package's `vrep-maze` command).
pub fn main_with_args(args: impl IntoIterator<Item = OsString>) -> ExitCode {
    end_quietly_on_broken_pipe();
    let args: Vec<OsString> = args.into_iter().collect();
    let cli = match Cli::try_parse_from(&args) {
        Ok(cli) => cli,
        Err(e) => return report_usage::<Cli>(&e, &args),
    };
    match run(cli) {
        Ok(code) => code,
        Err(error) if error.chain().any(|cause| cause.is::<stdout::PipeClosed>()) => {
            ExitCode::SUCCESS
        }
        Err(error)
            if error
                .chain()
                .any(|cause| cause.is::<interrupt::Interrupted>()) =>
        {
            eprintln!("{}", one_line(&error));
            ExitCode::from(interrupt::INTERRUPTED_EXIT_CODE)
        }
        Err(error) => {
            eprintln!("error: {}", one_line(&error));
            for detail in details(&error) {
                eprintln!("  {detail}");
            }
            for hint in hints(&error) {
                eprintln!("  hint: {}", shorten(&escape::escaped(&hint)));
            }
            // a usage error can be the context of another (which keeps that one's hints)
            if error.downcast_ref::<UsageError>().is_some()
                || error.chain().any(|cause| cause.is::<UsageError>())
            {
                ExitCode::from(USAGE_EXIT_CODE)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// A reader that closes our output early (`vrep-maze validate *.json | head -1`) ends the run
/// quietly with success, as `rg | head` does. Commands print through [`stdout::outln!`],
/// which returns errors; should a Rust print macro still fail somewhere (a progress line on
/// a full standard error), this panic hook exits 0 for a closed pipe and 1 for any other
/// write error, with one line instead of a backtrace. Every other panic goes to the
/// default hook.
fn end_quietly_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.contains("Broken pipe") || message.contains("BrokenPipe") {
            std::process::exit(0);
        }
        if let Some(why) = message.strip_prefix("failed printing to ") {
            let _ = writeln!(std::io::stderr(), "error: cannot write to {why}");
            std::process::exit(1);
        }
        default(info);
    }));
}

fn run(cli: Cli) -> Result<ExitCode> {
    let progress = progress::Progress::new(cli.quiet);
    say::set_modes(cli.quiet, false);
    match cli.command {
        Command::Generate(args) => generate::run(args, progress),
        Command::Import(args) => import::run(args),
        Command::Validate(args) => validate::run(args, progress),
        Command::Render(args) => render::run(args, progress),
        Command::Export(args) => export::run(args),
        Command::Solve(args) => solve::run(args, progress),
        Command::Batch(args) => batch::run(args, progress),
        Command::Completions(args) => completions::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Apply(args) => apply::run(args, progress),
        Command::Clear(args) => clear::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::Score(args) => score::run(args),
        Command::Drive(args) if args.wheels => wheels::run(args),
        Command::Drive(args) => drive::run(args),
        Command::Serve(args) => serve::run(args),
    }
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    #[test]
    fn the_command_line_definition_is_consistent() {
        super::Cli::command().debug_assert();
    }
}
