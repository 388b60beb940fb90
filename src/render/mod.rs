//! Pictures of a layout: one file per output format, all behind [`Renderer`].

mod ascii;
mod png;
mod svg;

use std::fmt;
use std::str::FromStr;

use anyhow::{Result, anyhow};

use crate::layout::{Layout, passages};
use crate::maze::analysis::shortest_path;
use crate::maze::{Cell, Grid, Maze};

pub use ascii::Ascii;
pub use png::Png;
pub use svg::Svg;

/// What to draw besides the maze.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RenderOptions {
    /// Overlay the shortest path from start to end.
    pub solution: bool,
}

/// Turns a layout into the bytes of one picture format.
pub trait Renderer {
    /// Renders `layout`.
    fn render(&self, layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>>;
}

/// The formats `render --format` accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Walls drawn with `+`, `-` and `|`, for a terminal.
    Ascii,
    /// The floor as the robot's camera sees it: green lines, blue start, red end.
    Svg,
    /// The SVG picture as pixels.
    Png,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 3] = [Format::Ascii, Format::Svg, Format::Png];

    /// Its name on the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Format::Ascii => "ascii",
            Format::Svg => "svg",
            Format::Png => "png",
        }
    }

    /// The format a file name's extension implies, if any.
    pub fn from_extension(path: &std::path::Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "svg" => Some(Format::Svg),
            "png" => Some(Format::Png),
            "txt" => Some(Format::Ascii),
            _ => None,
        }
    }

    /// The renderer for this format.
    pub fn renderer(self) -> Box<dyn Renderer> {
        match self {
            Format::Ascii => Box::new(Ascii),
            Format::Svg => Box::new(Svg),
            Format::Png => Box::new(Png),
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Format {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown format '{s}' (known: ascii, svg, png)"))
    }
}

/// The maze of a layout, with its start, end and (if asked) solution cells.
struct MazeView {
    maze: Maze,
    start: Cell,
    end: Cell,
    solution: Vec<Cell>,
}

impl MazeView {
    fn of(layout: &Layout, options: &RenderOptions) -> Result<Self> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())?;
        let maze = passages::decode(grid, &layout.passages).map_err(|e| anyhow!(e))?;
        let start = Cell::new(layout.start.cell[0], layout.start.cell[1]);
        let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
        for (which, cell) in [("start", start), ("end", end)] {
            if !grid.contains(cell) {
                return Err(anyhow!("{which}.cell {cell} is off the {grid} grid"));
            }
        }
        let solution = if options.solution {
            shortest_path(&maze, grid.index(start), grid.index(end))
                .ok_or_else(|| {
                    anyhow!("end {end} cannot be reached from start {start}: no solution to draw")
                })?
                .into_iter()
                .map(|i| grid.cell(i))
                .collect()
        } else {
            Vec::new()
        };
        Ok(Self {
            maze,
            start,
            end,
            solution,
        })
    }
}
