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
    after_help = "Examples:\n  vrep-maze render maze.json --solution\n  vrep-maze render maze.json --format svg -o maze.svg\n  vrep-maze render maze.json --solution -o maze.png"
)]
pub struct RenderArgs {
    /// The layout file (`-` reads standard input).
    pub file: PathBuf,
    /// ascii (terminal), svg or png [default: from the -o extension, else ascii].
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
    if let Some(scene) = scene_dump(&args)? {
        let svg = crate::sim::svg::scene_svg(&scene, 800.0);
        write_output(args.output.as_deref(), |w| w.write_all(svg.as_bytes()))?;
        return Ok(ExitCode::SUCCESS);
    }
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

/// A `vrep-maze serve --dump` scene file (drawn as SVG seen from above), else `None`.
fn scene_dump(args: &RenderArgs) -> Result<Option<crate::sim::Scene>> {
    if args.file.as_os_str() == "-" {
        return Ok(None);
    }
    let Ok(text) = std::fs::read_to_string(&args.file) else {
        return Ok(None);
    };
    if !text.contains("\"vrep-maze scene\"") {
        return Ok(None);
    }
    anyhow::ensure!(
        args.format.is_none_or(|f| f == Format::Svg),
        "{}: a scene dump renders as SVG only (use --format svg or -o FILE.svg)",
        args.file.display()
    );
    let scene =
        crate::sim::Scene::from_json(&text).with_context(|| format!("{}", args.file.display()))?;
    Ok(Some(scene))
}
