//! `vrep-maze render`: draw a layout.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

use super::output::write_output;
use crate::layout::read_layout;
use crate::render::{Format, RenderOptions};

/// Options of `render`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze render maze.json --solution\n  vrep-maze render maze.json --format svg -o maze.svg"
)]
pub struct RenderArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// ascii (terminal) or svg [default: from the -o extension, else ascii].
    #[arg(long, value_parser = clap::value_parser!(Format))]
    pub format: Option<Format>,
    /// Overlay the shortest path from start to end.
    #[arg(long)]
    pub solution: bool,
    /// Write the picture here instead of standard output.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Runs `render`.
pub fn run(args: RenderArgs) -> Result<ExitCode> {
    let layout = read_layout(&args.file)?;
    let format = args
        .format
        .or_else(|| args.output.as_deref().and_then(Format::from_extension))
        .unwrap_or(Format::Ascii);
    let options = RenderOptions {
        solution: args.solution,
    };
    let bytes = format
        .renderer()
        .render(&layout, &options)
        .with_context(|| format!("{}", args.file.display()))?;
    write_output(args.output.as_deref(), |w| w.write_all(&bytes))?;
    Ok(ExitCode::SUCCESS)
}
