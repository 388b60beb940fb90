//! `vrep-maze import`: a maze drawn as text (micromouse drawings, our ASCII render) to a
//! layout.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

use super::input::read_text;
use super::output::write_output;
use super::values::parse_metres;
use crate::layout::import::{ImportOptions, import};
use crate::layout::{Style, write_layout};

/// Options of `import`.
#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze import apec2009.txt -o apec2009.json\n  vrep-maze render maze.json > maze.txt && vrep-maze import maze.txt --cell-size 1 --lines -o again.json"
)]
pub struct ImportArgs {
    /// The drawing: posts 'o' or '+', walls '---' and '|', one text row per row of cells
    /// (north at the top), optional marks S (start), G (goal cells), E (end).
    pub file: PathBuf,
    /// Side of a cell, metres; walls are one cell long, cell/15 thick and 5/18 of a cell
    /// high (0.012 m and 0.05 m at the default, the micromouse's 0.18 m).
    #[arg(long, default_value_t = 0.18, value_parser = parse_metres)]
    pub cell_size: f64,
    /// Make a line layout (the passages drawn as Line copies) instead of a wall layout.
    #[arg(long)]
    pub lines: bool,
    /// Write the layout here (atomically) instead of standard output.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// The most bytes of a drawing: twice what our ASCII render of the largest grid
/// (4096x4096: 8193 lines of 16386 characters) takes.
const MAX_DRAWING_BYTES: usize = 256 << 20;

/// Runs `import`.
pub fn run(args: ImportArgs) -> Result<ExitCode> {
    let name = args.file.display().to_string();
    let text = read_text(
        &args.file,
        MAX_DRAWING_BYTES,
        "a text drawing of a maze",
        "our drawing of the largest grid, 4096x4096, takes about 134 MB",
    )?;
    anyhow::ensure!(
        !(text.trim_start().starts_with('{') && text.contains(crate::layout::FORMAT)),
        "{name} is a layout (JSON) already, not a maze drawn as text: use it as it is (vrep-maze render {} draws it as text)",
        super::escape::shell_word(&name)
    );
    let options = ImportOptions {
        cell_size: args.cell_size,
        style: if args.lines {
            Style::Lines
        } else {
            Style::Walls
        },
    };
    let layout = import(&text, &name, &options).map_err(anyhow::Error::msg)?;
    write_output(args.output.as_deref(), |w| write_layout(&layout, w))?;
    if let Some(path) = &args.output {
        eprintln!(
            "wrote {}: {}x{} imported from {}, solution {} cells",
            super::escape::escaped(&path.display().to_string()),
            layout.grid.columns,
            layout.grid.rows,
            super::escape::escaped(&name),
            layout.metrics.solution_cells
        );
    }
    Ok(ExitCode::SUCCESS)
}
