//! Maximal straight runs: of a line maze's passages (one green rectangle each) and of a wall
//! maze's closed sides (one wall bar each), computed from the passages in one pass. The
//! pictures (`render`), the meshes drawn into a simulator and the exported models all draw
//! these runs, so they show the same maze.

use crate::layout::Opening;
use crate::layout::walls::{WallAxis, lattice, opening_side};
use crate::maze::{Direction, Maze};

/// Which way a run goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Along a row (the maze's x): open east passages.
    Row,
    /// Along a column (the maze's y): open north passages.
    Column,
}

/// A run: a maximal chain of open east passages along a row, or of open north passages
/// up a column, from cell `first` to cell `last` on grid line `line`.
///
/// Its picture is one rectangle ([`Run::rect`]) from `width / 2` before the first cell's
/// centre to `width / 2` past the last one's, `width` across. That is exactly the
/// picture of the layout's segments: a renderer is only given layouts that passed
/// [`crate::validate::checked`], which proves that on every grid line the union of the
/// segments equals the union of the passage intervals `[k c - w/2, (k + 1) c + w/2]`
/// (within 10 um), and a run is a maximal union of touching passage intervals. A cell with
/// no passage (a 1 x 1 maze) lies in no run and draws nothing, as it has no segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Run {
    /// Row or column.
    pub axis: Axis,
    /// The row's y or the column's x, in cells.
    pub line: u32,
    /// The first cell along the line.
    pub first: u32,
    /// The last cell along the line (after `first`).
    pub last: u32,
}

impl Run {
    /// Its rectangle in the maze frame, `[x0, y0, x1, y1]`, for cells of side `cell` and
    /// lines `width` wide.
    pub fn rect(&self, cell: f64, width: f64) -> [f64; 4] {
        let half = width / 2.0;
        let across = f64::from(self.line) * cell;
        let lo = f64::from(self.first) * cell - half;
        let hi = f64::from(self.last) * cell + half;
        match self.axis {
            Axis::Row => [lo, across - half, hi, across + half],
            Axis::Column => [across - half, lo, across + half, hi],
        }
    }
}

/// Calls `emit` for every run of `maze` and `row_done` after each row, in one pass over the
/// cells, south row first: row `y` yields its east runs and the north runs that end on it.
/// Stops at the first error `emit` returns.
pub fn for_each_run<E>(
    maze: &Maze,
    mut emit: impl FnMut(Run) -> Result<(), E>,
    mut row_done: impl FnMut(u32),
) -> Result<(), E> {
    const NONE: u32 = u32::MAX;
    let (east, north) = (Direction::East.bit(), Direction::North.bit());
    let width = maze.grid().width() as usize;
    // The row each column's open run started on, NONE when no run is open.
    let mut column_starts = vec![NONE; width];
    for (y, masks) in (0u32..).zip(maze.masks().chunks_exact(width)) {
        let mut row_start = NONE;
        for ((x, &mask), column_start) in (0u32..).zip(masks).zip(&mut column_starts) {
            if mask & east != 0 {
                if row_start == NONE {
                    row_start = x;
                }
            } else if row_start != NONE {
                emit(Run {
                    axis: Axis::Row,
                    line: y,
                    first: row_start,
                    last: x,
                })?;
                row_start = NONE;
            }
            if mask & north != 0 {
                if *column_start == NONE {
                    *column_start = y;
                }
            } else if *column_start != NONE {
                emit(Run {
                    axis: Axis::Column,
                    line: x,
                    first: *column_start,
                    last: y,
                })?;
                *column_start = NONE;
            }
        }
        row_done(y);
    }
    Ok(())
}

/// A wall run: a maximal chain of closed sides on lattice line `line`, from lattice corner
/// `first` to lattice corner `last` (the sides `first..last`).
///
/// Lattice line `j` along x lies at `y = (j - 1/2) cell` (south of row `j`), line `i`
/// along y at `x = (i - 1/2) cell`; corner `k` along a line is at `(k - 1/2) cell`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WallRun {
    /// Which way the lattice line runs.
    pub axis: WallAxis,
    /// The lattice line: 0 to rows (along x) or 0 to columns (along y).
    pub line: u32,
    /// The corner the run starts at.
    pub first: u32,
    /// The corner it ends at (after `first`).
    pub last: u32,
}

impl WallRun {
    /// Its rectangle in the maze frame, `[x0, y0, x1, y1]`, for cells of side `cell` and
    /// walls `thickness` thick: corner to corner along the line, centred on it across.
    pub fn rect(&self, cell: f64, thickness: f64) -> [f64; 4] {
        let half = thickness / 2.0;
        let corner = |k: u32| (f64::from(k) - 0.5) * cell;
        let (across, lo, hi) = (corner(self.line), corner(self.first), corner(self.last));
        match self.axis {
            WallAxis::AlongX => [lo, across - half, hi, across + half],
            WallAxis::AlongY => [across - half, lo, across + half, hi],
        }
    }
}

/// The square of the post at lattice corner `[i, j]` in the maze frame, `[x0, y0, x1, y1]`,
/// for cells of side `cell` and posts `size` wide.
pub fn post_rect([i, j]: [u32; 2], cell: f64, size: f64) -> [f64; 4] {
    let corner = |k: u32| (f64::from(k) - 0.5) * cell;
    let (x, y, half) = (corner(i), corner(j), size / 2.0);
    [x - half, y - half, x + half, y + half]
}

/// The outer sides a wall maze leaves open, as (axis, line, side) in lattice terms,
/// sorted; openings that face no outer side are left out.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct OpenSides(Vec<(WallAxis, u32, u32)>);

impl OpenSides {
    /// The sides `openings` names on `maze`'s grid.
    pub fn of(maze: &Maze, openings: &[Opening]) -> Self {
        let mut sides: Vec<_> = openings
            .iter()
            .filter_map(|o| opening_side(maze.grid(), o))
            .collect();
        sides.sort_unstable();
        Self(sides)
    }

    /// `true` if side `k` of lattice line `line` is one of them.
    fn contains(&self, axis: WallAxis, line: u32, k: u32) -> bool {
        self.0.binary_search(&(axis, line, k)).is_ok()
    }
}

/// The chain of closed sides being followed along one lattice line.
#[derive(Debug, Clone, Copy)]
struct Chain {
    /// The corner the chain started at, if one is being followed.
    start: Option<u32>,
}

impl Chain {
    const NONE: Chain = Chain { start: None };

    /// Side `k` of the line is `closed` or not: the run that ends at corner `k`, if one does.
    fn step(&mut self, k: u32, closed: bool) -> Option<(u32, u32)> {
        match (closed, self.start) {
            (true, None) => {
                self.start = Some(k);
                None
            }
            (false, Some(first)) => {
                self.start = None;
                Some((first, k))
            }
            _ => None,
        }
    }
}

/// Calls `emit` for every wall run of `maze` (whose outer sides `open` are left open) and
/// `row_done` after each row, in one pass over the cells, south row first: row `y` yields
/// the runs along lattice line `y` (its south sides) and the runs along y that end at its
/// south edge; the last row also yields those that end at its north edge and the north
/// boundary. Stops at the first error `emit` returns.
pub fn for_each_wall_run<E>(
    maze: &Maze,
    open: &OpenSides,
    mut emit: impl FnMut(WallRun) -> Result<(), E>,
    mut row_done: impl FnMut(u32),
) -> Result<(), E> {
    let grid = maze.grid();
    let (columns, rows) = (grid.width(), grid.height());
    let (south, west) = (Direction::South.bit(), Direction::West.bit());
    let (lines_along_y, _) = lattice(grid, WallAxis::AlongY);
    let mut along_y = vec![Chain::NONE; lines_along_y as usize];
    for (y, masks) in (0u32..).zip(maze.masks().chunks_exact(columns as usize)) {
        let south_closed = |x: u32| {
            masks[x as usize] & south == 0 && !(y == 0 && open.contains(WallAxis::AlongX, 0, x))
        };
        along_x(y, columns, south_closed, &mut emit)?;
        for (x, run) in (0u32..).zip(&mut along_y) {
            let closed = match masks.get(x as usize) {
                Some(mask) => {
                    mask & west == 0 && !(x == 0 && open.contains(WallAxis::AlongY, 0, y))
                }
                None => !open.contains(WallAxis::AlongY, x, y),
            };
            let ended = run.step(y, closed);
            let at_top = if y + 1 == rows {
                run.step(rows, false)
            } else {
                None
            };
            for (first, last) in ended.into_iter().chain(at_top) {
                emit(WallRun {
                    axis: WallAxis::AlongY,
                    line: x,
                    first,
                    last,
                })?;
            }
        }
        if y + 1 == rows {
            along_x(
                rows,
                columns,
                |x| !open.contains(WallAxis::AlongX, rows, x),
                &mut emit,
            )?;
        }
        row_done(y);
    }
    Ok(())
}

/// Emits the runs of lattice line `line` along x, whose `columns` sides are `closed` or not.
fn along_x<E>(
    line: u32,
    columns: u32,
    closed: impl Fn(u32) -> bool,
    emit: &mut impl FnMut(WallRun) -> Result<(), E>,
) -> Result<(), E> {
    let mut run = Chain::NONE;
    for k in 0..=columns {
        if let Some((first, last)) = run.step(k, k < columns && closed(k)) {
            emit(WallRun {
                axis: WallAxis::AlongX,
                line,
                first,
                last,
            })?;
        }
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::generate::{Algorithm, generate};
    use crate::layout::walls::is_closed;
    use crate::layout::{GenerateSpec, Layout, Side, build_layout, passages};
    use crate::maze::{Cell, Grid};

    /// Runs counted straight from the passages: a run starts at every open passage
    /// whose cell has no open passage behind it.
    pub(crate) fn count_runs(maze: &Maze) -> usize {
        maze.passages()
            .filter(|&(cell, dir)| {
                let behind = match dir {
                    Direction::East if cell.x > 0 => Cell::new(cell.x - 1, cell.y),
                    Direction::North if cell.y > 0 => Cell::new(cell.x, cell.y - 1),
                    _ => return true,
                };
                !maze.is_open(maze.grid().index(behind), dir)
            })
            .count()
    }

    #[test]
    fn runs_cover_every_passage_once_and_are_maximal() {
        for (w, h, algorithm) in [(1, 1, Algorithm::Dfs), (7, 5, Algorithm::Prim)] {
            let maze = generate(Grid::new(w, h).unwrap(), algorithm, 3);
            let mut runs = Vec::new();
            let mut rows = 0;
            let Ok(()) = for_each_run::<std::convert::Infallible>(
                &maze,
                |run| {
                    runs.push(run);
                    Ok(())
                },
                |_| rows += 1,
            );
            assert_eq!(rows, h);
            assert_eq!(runs.len(), count_runs(&maze));
            let covered: u32 = runs.iter().map(|r| r.last - r.first).sum();
            assert_eq!(covered as usize, maze.passage_count());
        }
        let run = Run {
            axis: Axis::Column,
            line: 2,
            first: 1,
            last: 3,
        };
        assert_eq!(run.rect(1.0, 0.1), [1.95, 0.95, 2.05, 3.05]);
    }

    /// A `columns` x `rows` course maze of `seed` (Prim) with walls, turned `degrees`,
    /// opened as `openings` asks ("none", "start", "start,end", ...).
    pub(crate) fn wall_layout(
        columns: u32,
        rows: u32,
        seed: u64,
        degrees: f64,
        openings: &str,
    ) -> Layout {
        let grid = Grid::new(columns.into(), rows.into()).unwrap();
        let mut spec = GenerateSpec::course(grid, Algorithm::Prim, seed);
        spec.geometry.rotation = degrees.to_radians();
        let mut layout = build_layout(&spec).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let options = crate::layout::walls::WallOptions {
            openings: openings.parse().unwrap(),
            ..Default::default()
        };
        crate::layout::walls::into_walls(&mut layout, &maze, &options, true).unwrap();
        layout
    }

    /// Wall runs counted straight from [`is_closed`]: a run starts at every closed side
    /// whose side before it on the same lattice line is open or absent.
    pub(crate) fn count_wall_runs(maze: &Maze, openings: &[Opening]) -> usize {
        let mut count = 0;
        for axis in [WallAxis::AlongX, WallAxis::AlongY] {
            let (lines, sides) = lattice(maze.grid(), axis);
            for line in 0..lines {
                for k in 0..sides {
                    let closed = |k| is_closed(maze, openings, axis, line, k);
                    if closed(k) && (k == 0 || !closed(k - 1)) {
                        count += 1;
                    }
                }
            }
        }
        count
    }

    fn runs_of(maze: &Maze, openings: &[Opening]) -> (Vec<WallRun>, u32) {
        let mut runs = Vec::new();
        let mut rows = 0;
        let Ok(()) = for_each_wall_run::<std::convert::Infallible>(
            maze,
            &OpenSides::of(maze, openings),
            |run| {
                runs.push(run);
                Ok(())
            },
            |_| rows += 1,
        );
        (runs, rows)
    }

    #[test]
    fn runs_cover_every_closed_side_once_and_are_maximal() {
        for (columns, rows, openings) in [(1, 1, "none"), (7, 5, "start"), (4, 6, "none")] {
            let layout = wall_layout(columns, rows, 3, 0.0, openings);
            let grid = Grid::new(columns.into(), rows.into()).unwrap();
            let maze = passages::decode(grid, &layout.passages).unwrap();
            let openings = &layout.wall.as_ref().unwrap().openings;
            let (runs, rows_done) = runs_of(&maze, openings);
            assert_eq!(rows_done, rows);
            assert_eq!(runs.len(), count_wall_runs(&maze, openings));
            // every side of every run is closed, and the run is as long as can be
            let closed = |axis, line, k| is_closed(&maze, openings, axis, line, k);
            let mut sides = 0;
            for run in &runs {
                assert!(run.first < run.last, "{run:?}");
                assert!((run.first..run.last).all(|k| closed(run.axis, run.line, k)));
                assert!(run.first == 0 || !closed(run.axis, run.line, run.first - 1));
                let (_, count) = lattice(grid, run.axis);
                assert!(run.last == count || !closed(run.axis, run.line, run.last));
                sides += run.last - run.first;
            }
            let walls = layout.walls.len() as u32;
            assert_eq!(sides, walls, "one wall a closed side at the course's 1 m");
        }
    }

    #[test]
    fn an_opening_breaks_the_outer_wall() {
        let maze = Maze::closed(Grid::new(3, 2).unwrap());
        let (runs, _) = runs_of(&maze, &[]);
        // every side closed: one run per lattice line
        assert_eq!(runs.len(), 3 + 4);
        let opening = Opening {
            cell: [1, 0],
            side: Side::South,
        };
        let (runs, _) = runs_of(&maze, &[opening]);
        let south: Vec<_> = runs
            .iter()
            .filter(|r| r.axis == WallAxis::AlongX && r.line == 0)
            .map(|r| (r.first, r.last))
            .collect();
        assert_eq!(south, [(0, 1), (2, 3)]);
        let run = WallRun {
            axis: WallAxis::AlongY,
            line: 3,
            first: 0,
            last: 2,
        };
        assert_eq!(run.rect(1.0, 0.1), [2.45, -0.5, 2.55, 1.5]);
    }
}
