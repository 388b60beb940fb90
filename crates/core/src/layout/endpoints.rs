//! `--start` and `--end`: which cells the robot starts from and must reach.

use std::fmt;
use std::str::FromStr;

use crate::maze::analysis::{Distances, diameter_ends};
use crate::maze::{Cell, Grid, Maze};
use crate::wording::{Message, Opt, Value};

/// A grid corner, by compass name (north is +y).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// Lowest x, lowest y.
    SouthWest,
    /// Highest x, lowest y.
    SouthEast,
    /// Lowest x, highest y.
    NorthWest,
    /// Highest x, highest y.
    NorthEast,
}

impl Corner {
    /// The corner cell of `grid`.
    pub fn cell(self, grid: Grid) -> Cell {
        let (max_x, max_y) = (grid.width() - 1, grid.height() - 1);
        match self {
            Corner::SouthWest => Cell::new(0, 0),
            Corner::SouthEast => Cell::new(max_x, 0),
            Corner::NorthWest => Cell::new(0, max_y),
            Corner::NorthEast => Cell::new(max_x, max_y),
        }
    }
}

/// How a start or end cell is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndpointSpec {
    /// This cell (`x,y`).
    Cell(Cell),
    /// This corner (`sw`, `se`, `nw`, `ne`).
    Corner(Corner),
    /// End only: the cell farthest from the start along the maze.
    Farthest,
    /// Start only: both ends of the maze's diameter (the end spec is then ignored).
    FarthestPair,
}

/// The `--start` words, `x,y` standing for a cell: for completions.
pub const START_WORDS: [&str; 6] = ["sw", "se", "nw", "ne", "farthest-pair", "x,y"];

/// The `--end` words, `x,y` standing for a cell: for completions.
pub const END_WORDS: [&str; 6] = ["sw", "se", "nw", "ne", "farthest", "x,y"];

/// The accepted words, for help and error texts.
pub const ENDPOINT_HELP: &str = "a cell 'x,y' (column,row from 0), a corner 'sw|se|nw|ne', 'farthest' (end only) or 'farthest-pair' (start only)";

impl FromStr for EndpointSpec {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let word = s.trim().to_ascii_lowercase();
        let corner = match word.as_str() {
            "sw" | "south-west" | "southwest" => Some(Corner::SouthWest),
            "se" | "south-east" | "southeast" => Some(Corner::SouthEast),
            "nw" | "north-west" | "northwest" => Some(Corner::NorthWest),
            "ne" | "north-east" | "northeast" => Some(Corner::NorthEast),
            _ => None,
        };
        if let Some(corner) = corner {
            return Ok(EndpointSpec::Corner(corner));
        }
        match word.as_str() {
            "farthest" => return Ok(EndpointSpec::Farthest),
            "farthest-pair" => return Ok(EndpointSpec::FarthestPair),
            _ => {}
        }
        let (x, y) = word
            .split_once(',')
            .ok_or_else(|| format!("'{s}' is not {ENDPOINT_HELP}"))?;
        let parse = |v: &str| {
            v.trim()
                .parse::<u32>()
                .map_err(|_| format!("'{s}' is not {ENDPOINT_HELP}"))
        };
        Ok(EndpointSpec::Cell(Cell::new(parse(x)?, parse(y)?)))
    }
}

impl fmt::Display for EndpointSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EndpointSpec::Cell(c) => write!(f, "{},{}", c.x, c.y),
            EndpointSpec::Corner(Corner::SouthWest) => f.write_str("sw"),
            EndpointSpec::Corner(Corner::SouthEast) => f.write_str("se"),
            EndpointSpec::Corner(Corner::NorthWest) => f.write_str("nw"),
            EndpointSpec::Corner(Corner::NorthEast) => f.write_str("ne"),
            EndpointSpec::Farthest => f.write_str("farthest"),
            EndpointSpec::FarthestPair => f.write_str("farthest-pair"),
        }
    }
}

/// Checks the start and end specs against `grid` before any maze exists: cells on the
/// grid, `farthest` only for the end, `farthest-pair` only for the start and then with
/// no other end (it picks both).
pub fn check(grid: Grid, start: EndpointSpec, end: EndpointSpec) -> Result<(), Message> {
    match (start, end) {
        (EndpointSpec::Farthest, _) => return Err(farthest_start()),
        (_, EndpointSpec::FarthestPair) => return Err(farthest_pair_end()),
        (EndpointSpec::FarthestPair, EndpointSpec::Farthest) => return Ok(()),
        (EndpointSpec::FarthestPair, end) => {
            return Err(Message::setting(Opt::End, Value::word(end))
                .and(" conflicts with ")
                .and_message(farthest_pair())
                .and(", which picks both ends: drop ")
                .and_opt(Opt::End));
        }
        _ => {}
    }
    for (spec, which) in [(start, Opt::Start), (end, Opt::End)] {
        if let EndpointSpec::Cell(cell) = spec
            && !grid.contains(cell)
        {
            return Err(off_grid(grid, cell, which));
        }
    }
    Ok(())
}

/// `--start farthest-pair`.
fn farthest_pair() -> Message {
    Message::setting(Opt::Start, Value::word(EndpointSpec::FarthestPair))
}

/// Why the start cannot be `farthest`.
fn farthest_start() -> Message {
    Message::setting(Opt::Start, Value::word(EndpointSpec::Farthest))
        .and(" needs a reference: use ")
        .and_message(farthest_pair())
}

/// Why the end cannot be `farthest-pair`.
fn farthest_pair_end() -> Message {
    Message::setting(Opt::End, Value::word(EndpointSpec::FarthestPair))
        .and(" is not a thing: use ")
        .and_message(farthest_pair())
}

/// Why `cell`, given for `which` end, does not do on `grid`.
fn off_grid(grid: Grid, cell: Cell, which: Opt) -> Message {
    Message::setting(which, Value::word(format!("{},{}", cell.x, cell.y))).and(format!(
        " is off the {grid} grid (columns 0..{}, rows 0..{})",
        grid.width() - 1,
        grid.height() - 1
    ))
}

/// Resolves the start and end specs on `maze` to cells, or says why they don't fit; with
/// the breadth-first distances from the start, which a layout's metrics need too (see
/// [`Metrics::measure_from`](crate::maze::Metrics::measure_from)).
pub fn resolve(
    maze: &Maze,
    start: EndpointSpec,
    end: EndpointSpec,
) -> Result<(Cell, Cell, Distances), Message> {
    let grid = maze.grid();
    check(grid, start, end)?;
    let fixed = |spec: EndpointSpec, which: Opt| -> Result<Option<Cell>, Message> {
        match spec {
            EndpointSpec::Cell(cell) if grid.contains(cell) => Ok(Some(cell)),
            EndpointSpec::Cell(cell) => Err(off_grid(grid, cell, which)),
            EndpointSpec::Corner(corner) => Ok(Some(corner.cell(grid))),
            _ => Ok(None),
        }
    };
    let start_cell = match start {
        EndpointSpec::Farthest => {
            return Err(farthest_start());
        }
        EndpointSpec::FarthestPair => {
            let (a, b, _) = diameter_ends(maze);
            let (start, end) = (a.min(b), a.max(b));
            return Ok((
                grid.cell(start),
                grid.cell(end),
                Distances::from(maze, start),
            ));
        }
        spec => fixed(spec, Opt::Start)?.expect("cell or corner"),
    };
    let from_start = Distances::from(maze, grid.index(start_cell));
    let end_cell = match end {
        EndpointSpec::FarthestPair => {
            return Err(farthest_pair_end());
        }
        EndpointSpec::Farthest => grid.cell(from_start.farthest().0),
        spec => fixed(spec, Opt::End)?.expect("cell or corner"),
    };
    Ok((start_cell, end_cell, from_start))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{Algorithm, generate};
    use crate::maze::analysis::distances_from;
    use crate::wording::testing::dashed;

    #[test]
    fn parses_every_form() {
        assert_eq!("3,4".parse(), Ok(EndpointSpec::Cell(Cell::new(3, 4))));
        assert_eq!("NE".parse(), Ok(EndpointSpec::Corner(Corner::NorthEast)));
        assert_eq!("farthest".parse(), Ok(EndpointSpec::Farthest));
        assert_eq!("farthest-pair".parse(), Ok(EndpointSpec::FarthestPair));
        for bad in ["", "3", "-1,2", "a,b", "middle"] {
            assert!(bad.parse::<EndpointSpec>().is_err(), "{bad}");
        }
    }

    #[test]
    fn farthest_end_is_farthest() {
        let maze = generate(Grid::new(9, 9).unwrap(), Algorithm::Dfs, 42);
        let (s, e, from_s) = resolve(
            &maze,
            EndpointSpec::Corner(Corner::SouthWest),
            EndpointSpec::Farthest,
        )
        .unwrap();
        assert_eq!(from_s, Distances::from(&maze, 0));
        assert_eq!(s, Cell::new(0, 0));
        let dist = distances_from(&maze, 0);
        assert_eq!(dist[maze.grid().index(e)], *dist.iter().max().unwrap());
        let (a, b, from_a) =
            resolve(&maze, EndpointSpec::FarthestPair, EndpointSpec::Farthest).unwrap();
        assert_eq!(from_a, Distances::from(&maze, maze.grid().index(a)));
        let from_a = distances_from(&maze, maze.grid().index(a));
        let diameter = (0..81)
            .map(|i| *distances_from(&maze, i).iter().max().unwrap())
            .max();
        assert_eq!(Some(from_a[maze.grid().index(b)]), diameter);
    }

    #[test]
    fn off_grid_cells_are_named() {
        let maze = generate(Grid::new(3, 3).unwrap(), Algorithm::Dfs, 1);
        let err = resolve(
            &maze,
            EndpointSpec::Cell(Cell::new(3, 0)),
            EndpointSpec::Farthest,
        )
        .unwrap_err();
        let err = dashed(&err);
        assert!(err.contains("--start 3,0 is off the 3x3 grid"), "{err}");
    }

    #[test]
    fn farthest_pair_refuses_an_explicit_end() {
        let grid = Grid::new(3, 3).unwrap();
        let pair = EndpointSpec::FarthestPair;
        assert!(check(grid, pair, EndpointSpec::Farthest).is_ok());
        let err = check(grid, pair, EndpointSpec::Corner(Corner::NorthEast)).unwrap_err();
        assert_eq!(
            dashed(&err),
            "--end ne conflicts with --start farthest-pair, which picks both ends: drop --end"
        );
        assert!(check(grid, pair, EndpointSpec::Cell(Cell::new(1, 1))).is_err());
    }
}
