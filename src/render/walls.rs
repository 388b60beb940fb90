//! What a wall maze's SVG and PNG pictures show besides the floor: its walls as dark bars,
//! merged into runs along the lattice lines, and its goal region.
//!
//! The walls are drawn from the passages and the wall template, never from the layout's
//! `walls`: a renderer is only given layouts that passed [`crate::validate::checked`],
//! which proves that the walls on every lattice line cover exactly its closed sides
//! ([`crate::layout::walls::is_closed`]), corner to corner, the template's thickness across.
//! So a run of closed sides is one bar from its first lattice corner to its last: where
//! two runs meet at a right angle, the picture (like the cuboids) leaves a notch
//! `thickness / 2` square at the outer corner. A maze with posts has one more square, the
//! post's, at every lattice corner (validation proves one stands at each), drawn with the
//! bars: walls and posts together cover each closed side corner to corner.

use anyhow::{Result, anyhow};

use crate::layout::walls::{WallAxis, lattice, opening_side};
use crate::layout::{Layout, Opening};
use crate::maze::{Cell, Direction, Maze};

/// A wall run: a maximal chain of closed sides on lattice line `line`, from lattice corner
/// `first` to lattice corner `last` (the sides `first..last`).
///
/// Lattice line `j` along x lies at `y = (j - 1/2) cell` (south of row `j`), line `i`
/// along y at `x = (i - 1/2) cell`; corner `k` along a line is at `(k - 1/2) cell`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct WallRun {
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
pub(super) fn post_rect([i, j]: [u32; 2], cell: f64, size: f64) -> [f64; 4] {
    let corner = |k: u32| (f64::from(k) - 0.5) * cell;
    let (x, y, half) = (corner(i), corner(j), size / 2.0);
    [x - half, y - half, x + half, y + half]
}

/// The outer sides a wall maze leaves open, as (axis, line, side) in lattice terms,
/// sorted; openings that face no outer side are left out.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(super) struct OpenSides(Vec<(WallAxis, u32, u32)>);

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
pub(super) fn for_each_wall_run<E>(
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

/// What a wall maze draws besides the floor and the markers.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Walls {
    /// The wall template's thickness, metres.
    pub thickness: f64,
    /// The outer sides left open.
    pub open: OpenSides,
    /// The goal region's cells but the start and end (their markers cover them), tinted.
    pub goal: Vec<Cell>,
    /// The side of the post at every lattice corner, if the maze has posts.
    pub post: Option<f64>,
}

impl Walls {
    /// The walls of `layout`, whose passages are `maze`; `None` for a line maze.
    pub fn of(layout: &Layout, maze: &Maze, start: Cell, end: Cell) -> Result<Option<Self>> {
        if layout.style.is_lines() {
            return Ok(None);
        }
        let spec = layout
            .wall
            .as_ref()
            .ok_or_else(|| anyhow!("a layout with style \"walls\" needs its wall template"))?;
        let goal = layout
            .end
            .region
            .iter()
            .map(|&[x, y]| Cell::new(x, y))
            .filter(|&c| c != start && c != end && maze.grid().contains(c))
            .collect();
        Ok(Some(Self {
            thickness: spec.thickness,
            open: OpenSides::of(maze, &spec.openings),
            goal,
            post: layout.post.as_ref().map(|post| post.size),
        }))
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::walls::is_closed;
    use crate::layout::{GenerateSpec, Layout, Side, build_layout, passages};
    use crate::maze::Grid;

    /// A `columns` x `rows` course maze of `seed` (Prim) with walls, turned `degrees`,
    /// opened as `openings` asks ("none", "start", "start,end", ...).
    pub(in crate::render) fn wall_layout(
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
    pub(in crate::render) fn count_wall_runs(maze: &Maze, openings: &[Opening]) -> usize {
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

    #[test]
    fn the_goal_tint_leaves_the_markers_cells_out() {
        let mut layout = wall_layout(3, 2, 1, 0.0, "none");
        layout.start.cell = [0, 0];
        layout.end.cell = [2, 1];
        layout.end.region = vec![[2, 1], [1, 1], [2, 0]];
        let maze = passages::decode(Grid::new(3, 2).unwrap(), &layout.passages).unwrap();
        let walls = Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1))
            .unwrap()
            .unwrap();
        assert_eq!(walls.goal, [Cell::new(1, 1), Cell::new(2, 0)]);
        assert_eq!(walls.thickness, 0.05);
        layout.wall = None;
        assert!(Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1)).is_err());
        layout.style = crate::layout::Style::Lines;
        assert_eq!(
            Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1)).unwrap(),
            None
        );
    }
}
