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
mod validate;
mod values;
mod wheels;
pub mod wording;

pub use clear::ClearArgs;
pub use interrupt::Interrupted;
pub use stdout::note_closed_stdout;

use std::ffi::OsString;
use std::io::Write;
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
    /// Gazebo (SDF), URDF, Webots, or a ROS map_server occupancy map (.yaml + .pgm).
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

/// Exit code of a command line that asks for something impossible (clap uses it too).
const USAGE_EXIT_CODE: u8 = 2;

/// A command line that asks for something impossible (a value out of range, options that
/// conflict): reported like clap's own usage errors, with exit code 2. Any other failure
/// exits with 1. Public so that programs embedding the command line (the Python package)
/// tell usage errors from failures as the exit code does.
/// Its message is the command line's text, or a library's message naming options, which
/// [`wording::Flags`] words (an embedding program words it its own way).
#[derive(Debug, thiserror::Error)]
#[error("{}", wording::worded(.0))]
pub struct UsageError(pub crate::wording::Message);

/// `message` as a [`UsageError`].
pub(crate) fn usage(message: impl Into<crate::wording::Message>) -> anyhow::Error {
    anyhow::Error::new(UsageError(message.into()))
}

/// Fails with a [`UsageError`] unless `condition` holds.
macro_rules! ensure_usage {
    ($condition:expr, $($message:tt)+) => {
        if !$condition {
            return Err(anyhow::Error::new($crate::cli::UsageError(format!($($message)+).into())));
        }
    };
}
pub(crate) use ensure_usage;

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
        Err(e) => return report_usage(&e, &args),
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

/// Help and version go to standard output as clap prints them (a write error is one
/// `error:` line and exit code 1, a closed pipe exit 0); a usage error becomes one `error:`
/// line (clap's first), its tips `hint:` lines, and exit code 2. The command line's
/// arguments (`args`) that clap echoes are shown with their control characters escaped.
fn report_usage(error: &clap::Error, args: &[OsString]) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let printed = if error.use_stderr() {
            error.print().map_err(anyhow::Error::new)
        } else {
            stdout::write_stdout(|_| error.print())
        };
        match printed {
            Ok(()) => {}
            Err(e) if e.is::<stdout::PipeClosed>() => return ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {}", one_line(&e));
                return ExitCode::FAILURE;
            }
        }
        return if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(USAGE_EXIT_CODE)
        } else {
            ExitCode::SUCCESS
        };
    }
    // clap echoes arguments with their control characters, or some of them: the same
    // command line with them escaped fails the same way and echoes them as escapes
    let escaped: Vec<String> = args
        .iter()
        .map(|arg| escape::escaped(&arg.to_string_lossy()).into_owned())
        .collect();
    let again = Cli::try_parse_from(&escaped)
        .err()
        .filter(|again| again.kind() == error.kind());
    let shown = again.as_ref().unwrap_or(error);
    let text = shown.render().to_string();
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    if let Some(first) = lines.next() {
        eprintln!("{}{}", shorten(first), missing_arguments(error));
    }
    // clap's tips, and the values an option takes when the one given is not among them
    for line in lines {
        if let Some(tip) = line.strip_prefix("tip:") {
            eprintln!("  hint:{}", shorten(tip));
        } else if let Some(values) = line.strip_prefix("[possible values: ") {
            eprintln!("  hint: one of {}", shorten(values.trim_end_matches(']')));
        }
    }
    eprintln!("  hint: `--help` lists every option, with examples");
    ExitCode::from(USAGE_EXIT_CODE)
}

/// The arguments a `MissingRequiredArgument` error names (" <FILE>, --seeds <SEEDS>"), to
/// follow clap's first line ("... were not provided:"), which names none; empty otherwise.
fn missing_arguments(error: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if error.kind() != ErrorKind::MissingRequiredArgument {
        return String::new();
    }
    match error.get(ContextKind::InvalidArg) {
        Some(ContextValue::Strings(names)) => format!(" {}", names.join(", ")),
        Some(ContextValue::String(name)) => format!(" {name}"),
        _ => String::new(),
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
        Command::Drive(args) => drive::run(args),
        Command::Serve(args) => serve::run(args),
    }
}

/// Longest text of one cause in an error line; longer ones (e.g. an echoed 100 KB argument)
/// are cut, saying how long they were.
const MAX_CAUSE_CHARS: usize = 400;

/// The error and its causes on one line, each cause once: a cause whose text the line
/// already holds (an inner error that its context also printed) is not repeated.
pub fn one_line(error: &anyhow::Error) -> String {
    one_line_with(error, cause_text)
}

/// [`one_line`] with each cause's text from `text`: a program that embeds the command line
/// (the Python package) says the drawing errors in its own words.
pub fn one_line_with(
    error: &anyhow::Error,
    text: impl Fn(&(dyn std::error::Error + 'static)) -> String,
) -> String {
    let mut line = String::new();
    for cause in error.chain() {
        let text = shorten(&escape::escaped(&text(cause)));
        if line.contains(&text) {
            continue;
        }
        if !line.is_empty() {
            line.push_str(": ");
        }
        line.push_str(&text);
    }
    line
}

/// `text`, or its start and a note of its length when it is longer than [`MAX_CAUSE_CHARS`].
fn shorten(text: &str) -> String {
    let chars = text.chars().count();
    if chars <= MAX_CAUSE_CHARS {
        return text.to_string();
    }
    let head: String = text.chars().take(MAX_CAUSE_CHARS).collect();
    format!("{head}... ({chars} characters in all)")
}

/// What the error's causes list beyond their one line (an invalid layout's problems).
pub fn details(error: &anyhow::Error) -> Vec<String> {
    details_with(error, &wording::Flags)
}

/// [`details`] with the options the problems name in `wording`'s words: a program that
/// embeds the command line (the Python package) says them in its own.
pub fn details_with(error: &anyhow::Error, wording: &dyn crate::wording::Wording) -> Vec<String> {
    error
        .chain()
        .filter_map(|cause| cause.downcast_ref::<crate::validate::Invalid>())
        .flat_map(|invalid| invalid.shown(wording))
        .map(|line| shorten(&escape::escaped(&line)))
        .collect()
}

/// One cause's text in the command line's words: a drawing error's roles with their options
/// ([`remedies::message`]), a library message's options as flags ([`wording::Flags`]), any
/// other cause as it displays itself.
fn cause_text(cause: &(dyn std::error::Error + 'static)) -> String {
    if let Some(draw) = cause.downcast_ref::<crate::draw::DrawError>() {
        return remedies::message(draw);
    }
    match cause.downcast_ref::<crate::wording::Message>() {
        Some(message) => wording::worded(message),
        None => cause.to_string(),
    }
}

/// The remedies the error's causes know of, one per line, printed after the error line.
pub fn hints(error: &anyhow::Error) -> Vec<String> {
    error.chain().flat_map(cause_hints).collect()
}

/// The remedies one cause knows of, in the command line's words (a drawing error's from
/// [`remedies::hints`]).
pub fn cause_hints(cause: &(dyn std::error::Error + 'static)) -> Vec<String> {
    let draw = cause.downcast_ref::<crate::draw::DrawError>();
    let connect = cause.downcast_ref::<connect::ConnectError>();
    let hinted = cause.downcast_ref::<hinted::Hinted>();
    draw.map(remedies::hints)
        .into_iter()
        .chain(connect.map(|e| e.hints()))
        .chain(hinted.map(|e| e.hints()))
        .flatten()
        .collect()
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    use super::*;
    use crate::draw::{DrawError, Role};

    #[test]
    fn a_cause_that_its_context_already_printed_is_not_repeated() {
        let os = std::io::Error::new(std::io::ErrorKind::NotFound, "No such file (os error 2)");
        let error = anyhow::Error::new(os).context("m.json: No such file (os error 2)");
        let line = one_line(&error);
        assert_eq!(line.matches("No such file").count(), 1, "{line}");
        let error = anyhow::anyhow!("inner").context("outer");
        assert_eq!(one_line(&error), "outer: inner");
    }

    #[test]
    fn a_huge_cause_is_cut_and_says_its_length() {
        let error = anyhow::anyhow!("{}", "x".repeat(100_000)).context("no object `...`");
        let line = one_line(&error);
        assert!(line.len() < 1000, "{} bytes", line.len());
        assert!(line.contains("100000 characters in all"), "{line}");
    }

    #[test]
    fn remedies_are_hints_on_their_own_lines_not_in_the_error_line() {
        let error = anyhow::Error::new(DrawError::Missing {
            objects: vec![(Role::Floor, "Floor".into()), (Role::Line, "Line".into())],
            sizes: None,
        })
        .context("drawing m.json");
        assert_eq!(
            one_line(&error),
            "drawing m.json: missing in the scene: Floor, Line"
        );
        let hints = hints(&error);
        assert_eq!(hints.len(), 3, "{hints:?}");
        assert!(hints[0].contains("--floor"), "{hints:?}");
        assert!(hints.iter().all(|h| !h.contains('\n')), "{hints:?}");
        let running = anyhow::Error::new(DrawError::SimulationRunning);
        assert!(super::hints(&running)[0].contains("--stop-simulation"));
    }

    #[test]
    fn the_command_line_definition_is_consistent() {
        super::Cli::command().debug_assert();
    }
}
