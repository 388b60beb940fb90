//! The solution as data: the cells of a shortest path through a layout's maze, and the floor
//! waypoints a robot follows along it (what `vrep-maze solve` writes and `render --solution`
//! draws).

use std::f64::consts::FRAC_PI_2;

use nalgebra::{Isometry2, Point2, Vector2};
use schemars::JsonSchema;
use serde::Serialize;

use super::Layout;
use super::geometry::{normalize_angle, round_um};
use crate::maze::analysis::{distances_from, shortest_path};
use crate::maze::{Cell, Direction, Maze};

/// One point a robot passes on its way, in the layout's floor frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
pub struct Waypoint {
    /// Metres, on the floor.
    pub x: f64,
    /// Metres, on the floor.
    pub y: f64,
    /// Heading about the floor's z axis, radians in (-pi, pi]: the way the robot faces here.
    pub yaw: f64,
    /// Metres travelled from the first waypoint along the path.
    pub distance: f64,
}

/// A shortest path from one cell to the layout's end: the cells and the waypoints.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Solution {
    /// The first cell (x, y): the layout's start unless another was asked for.
    pub from: [u32; 2],
    /// The last cell (x, y): the layout's end (with a goal region, the region cell nearest
    /// `from`).
    pub to: [u32; 2],
    /// Every cell of the path, both ends included, as (x, y).
    pub cells: Vec<[u32; 2]>,
    /// The cell centres in order; a cell where the path turns holds two, the heading on
    /// arrival and the heading on leaving (a turn on the spot).
    pub waypoints: Vec<Waypoint>,
    /// Length of the path, metres (cell centre to cell centre).
    pub length: f64,
    /// Number of turns.
    pub turns: usize,
}

/// The value of a solve report's `format` field.
pub const SOLVE_FORMAT: &str = "vrep-maze/solve";

/// The JSON document `vrep-maze solve` writes (`schema/solve-v1.schema.json`): which
/// layout, then the [`Solution`].
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SolveReport {
    /// Always `"vrep-maze/solve"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// The layout file solved (`-` for standard input).
    pub layout: String,
    /// The path and its waypoints.
    #[serde(flatten)]
    pub solution: Solution,
}

/// The cells of a shortest path from `from` to `to` (breadth-first, so the shortest in a
/// braided maze too), both included; `None` if `to` cannot be reached. The one path
/// `solve` writes and `render --solution` draws.
pub fn path_cells(maze: &Maze, from: Cell, to: Cell) -> Option<Vec<Cell>> {
    let grid = maze.grid();
    let path = shortest_path(maze, grid.index(from), grid.index(to))?;
    Some(path.into_iter().map(|i| grid.cell(i)).collect())
}

/// The cell a robot at `from` heads for: the layout's end, or with a goal region the region
/// cell nearest `from` along the maze (lowest index among equals; the layout's `end.cell`
/// is that cell for the layout's own start).
fn target(layout: &Layout, maze: &Maze, from: Cell) -> Cell {
    let grid = maze.grid();
    let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
    let region: Vec<Cell> = layout
        .end
        .region
        .iter()
        .map(|c| Cell::new(c[0], c[1]))
        .filter(|&c| grid.contains(c))
        .collect();
    let start = Cell::new(layout.start.cell[0], layout.start.cell[1]);
    if region.is_empty() || from == start {
        return end;
    }
    let steps = distances_from(maze, grid.index(from));
    region
        .into_iter()
        .min_by_key(|&c| (steps[grid.index(c)], grid.index(c)))
        .unwrap_or(end)
}

/// The solution of `layout` (whose passages are `maze`) from `from`, or the layout's start;
/// an error names a cell off the grid or an end that cannot be reached.
pub fn solve(layout: &Layout, maze: &Maze, from: Option<Cell>) -> Result<Solution, String> {
    let grid = maze.grid();
    let from = from.unwrap_or(Cell::new(layout.start.cell[0], layout.start.cell[1]));
    let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
    for (which, cell) in [("from", from), ("end", end)] {
        if !grid.contains(cell) {
            return Err(format!("{which} cell {cell} is off the {grid} grid"));
        }
    }
    let to = target(layout, maze, from);
    let cells = path_cells(maze, from, to)
        .ok_or_else(|| format!("end {to} cannot be reached from {from}"))?;
    let headings: Vec<Direction> = cells
        .windows(2)
        .map(|w| step_direction(w[0], w[1]))
        .collect();
    let turns = headings.windows(2).filter(|h| h[0] != h[1]).count();
    let cell_size = layout.grid.cell_size;
    let frame = Isometry2::new(
        Vector2::new(layout.grid.origin[0], layout.grid.origin[1]),
        layout.grid.rotation,
    );
    let yaw = |d: Direction| round_um(normalize_angle(layout.grid.rotation + angle(d)));
    let mut waypoints = Vec::with_capacity(cells.len() + turns);
    for (i, cell) in cells.iter().enumerate() {
        let centre =
            frame * Point2::new(f64::from(cell.x) * cell_size, f64::from(cell.y) * cell_size);
        let arriving = i.checked_sub(1).map(|j| headings[j]);
        let leaving = headings.get(i).copied();
        let point = |d: Option<Direction>| Waypoint {
            x: round_um(centre.x),
            y: round_um(centre.y),
            yaw: d.map_or(round_um(normalize_angle(layout.grid.rotation)), yaw),
            distance: round_um(i as f64 * cell_size),
        };
        match (arriving, leaving) {
            (Some(a), Some(l)) if a != l => waypoints.extend([point(Some(a)), point(Some(l))]),
            (a, l) => waypoints.push(point(l.or(a))),
        }
    }
    Ok(Solution {
        from: [from.x, from.y],
        to: [to.x, to.y],
        cells: cells.iter().map(|c| [c.x, c.y]).collect(),
        waypoints,
        length: round_um((cells.len() - 1) as f64 * cell_size),
        turns,
    })
}

/// The direction of one step between neighbouring cells `a` and `b`.
fn step_direction(a: Cell, b: Cell) -> Direction {
    match (b.x.cmp(&a.x), b.y.cmp(&a.y)) {
        (std::cmp::Ordering::Greater, _) => Direction::East,
        (std::cmp::Ordering::Less, _) => Direction::West,
        (_, std::cmp::Ordering::Greater) => Direction::North,
        _ => Direction::South,
    }
}

/// A direction's angle in the maze frame, radians counter-clockwise from +x.
fn angle(d: Direction) -> f64 {
    match d {
        Direction::East => 0.0,
        Direction::North => FRAC_PI_2,
        Direction::West => std::f64::consts::PI,
        Direction::South => -FRAC_PI_2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout, passages};
    use crate::maze::Grid;

    fn course(algorithm: Algorithm, rotation: f64) -> (Layout, Maze) {
        let grid = Grid::new(5, 4).unwrap();
        let mut spec = GenerateSpec::course(grid, algorithm, 11);
        spec.geometry.rotation = rotation;
        let layout = build_layout(&spec).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        (layout, maze)
    }

    #[test]
    fn the_path_matches_the_layout_metrics_and_its_waypoints_follow_it() {
        let (layout, maze) = course(Algorithm::Prim, 0.0);
        let s = solve(&layout, &maze, None).unwrap();
        assert_eq!(s.cells.len() as u64, layout.metrics.solution_cells);
        assert_eq!(s.turns as u64, layout.metrics.solution_turns);
        assert_eq!(s.from, layout.start.cell);
        assert_eq!(s.to, layout.end.cell);
        assert_eq!(s.waypoints.len(), s.cells.len() + s.turns);
        assert_eq!(s.length, (s.cells.len() - 1) as f64 * layout.grid.cell_size);
        let last = s.waypoints.last().unwrap();
        assert_eq!(last.distance, s.length);
        assert_eq!((last.x, last.y), (layout.end.pose.x, layout.end.pose.y));
        let first = s.waypoints[0];
        assert_eq!(
            (first.x, first.y),
            (layout.start.pose.x, layout.start.pose.y)
        );
        // Each waypoint faces the next distinct point.
        for w in s.waypoints.windows(2) {
            if (w[0].x, w[0].y) != (w[1].x, w[1].y) {
                let heading = (w[1].y - w[0].y).atan2(w[1].x - w[0].x);
                assert!((normalize_angle(heading - w[0].yaw)).abs() < 1e-5, "{w:?}");
                assert!((w[1].distance - w[0].distance - 1.0).abs() < 1e-9);
            } else {
                assert_ne!(w[0].yaw, w[1].yaw, "two waypoints on a cell are a turn");
            }
        }
    }

    #[test]
    fn waypoints_turn_with_the_maze() {
        let (plain, maze) = course(Algorithm::Kruskal, 0.0);
        let (turned, _) = course(Algorithm::Kruskal, FRAC_PI_2);
        let a = solve(&plain, &maze, None).unwrap();
        let b = solve(&turned, &maze, None).unwrap();
        assert_eq!(a.cells, b.cells);
        for (p, q) in a.waypoints.iter().zip(&b.waypoints) {
            assert!((normalize_angle(q.yaw - p.yaw) - FRAC_PI_2).abs() < 1e-5);
        }
    }

    #[test]
    fn another_start_and_bad_cells() {
        let (layout, maze) = course(Algorithm::Dfs, 0.0);
        let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
        let at_end = solve(&layout, &maze, Some(end)).unwrap();
        assert_eq!(at_end.cells.len(), 1);
        assert_eq!(
            (at_end.length, at_end.turns, at_end.waypoints.len()),
            (0.0, 0, 1)
        );
        let off = solve(&layout, &maze, Some(Cell::new(9, 0))).unwrap_err();
        assert!(off.contains("(9,0)") || off.contains("9,0"), "{off}");
        assert!(off.contains("off the"), "{off}");
    }

    #[test]
    fn a_braided_maze_gives_the_shortest_path() {
        let grid = Grid::new(3, 2).unwrap();
        // A loop: 0-1-2 along the south row, 3-4-5 along the north, open at both ends.
        let mut maze = Maze::closed(grid);
        for (i, d) in [
            (0, Direction::East),
            (1, Direction::East),
            (3, Direction::East),
            (4, Direction::East),
            (0, Direction::North),
            (2, Direction::North),
        ] {
            maze.carve(i, d);
        }
        assert_eq!(
            path_cells(&maze, Cell::new(0, 0), Cell::new(2, 1))
                .unwrap()
                .len(),
            4
        );
    }
}
