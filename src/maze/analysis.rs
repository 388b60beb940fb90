//! What a maze is like: distances, the solution path, its structure and its metrics.
//! Traversals run on the compact [`Maze`] through petgraph's traits (see `graph.rs`);
//! the breadth-first distances, run several times per layout, are a plain queue.

use petgraph::algo::connected_components;
use petgraph::visit::IntoNeighbors;
use serde::{Deserialize, Serialize};

use super::grid::{Cell, Direction};
use super::model::Maze;

/// Marks a cell that the search did not reach.
pub const UNREACHED: u32 = u32::MAX;

/// Steps from `start` to every cell (breadth-first), [`UNREACHED`] where there is no path.
/// A plain queue over the distance array (which doubles as the visited set): the one
/// traversal every layout is measured with several times, so it is kept lean rather than
/// run through petgraph's `Bfs` and a second neighbour scan.
pub fn distances_from(maze: &Maze, start: usize) -> Vec<u32> {
    let mut dist = vec![UNREACHED; maze.grid().cell_count()];
    dist[start] = 0;
    let mut queue = Vec::with_capacity(maze.grid().cell_count());
    queue.push(start as u32);
    let mut next = 0;
    while let Some(&node) = queue.get(next) {
        next += 1;
        let step = dist[node as usize] + 1;
        for neighbour in maze.neighbors(node) {
            let d = &mut dist[neighbour as usize];
            if *d == UNREACHED {
                *d = step;
                queue.push(neighbour);
            }
        }
    }
    dist
}

/// The cell farthest from `start` along the maze (lowest index among equals) and its distance.
pub fn farthest_from(maze: &Maze, start: usize) -> (usize, u32) {
    farthest_in(&distances_from(maze, start))
}

fn farthest_in(dist: &[u32]) -> (usize, u32) {
    let mut best = (0, 0);
    for (index, &d) in dist.iter().enumerate() {
        if d != UNREACHED && d > best.1 {
            best = (index, d);
        }
    }
    best
}

/// Both ends of the maze's diameter by two breadth-first sweeps, and its length in steps.
/// Exact for a perfect maze (a tree); a lower bound when the maze has loops.
pub fn diameter_ends(maze: &Maze) -> (usize, usize, u32) {
    let (a, _) = farthest_from(maze, 0);
    let (b, length) = farthest_from(maze, a);
    (a, b, length)
}

/// The cells of a shortest path from `start` to `end`, both included; `None` if `end`
/// cannot be reached.
pub fn shortest_path(maze: &Maze, start: usize, end: usize) -> Option<Vec<usize>> {
    let dist = distances_from(maze, start);
    if dist[end] == UNREACHED {
        return None;
    }
    let mut path = vec![end];
    let mut here = end;
    while here != start {
        // Lowest-index predecessor, so the chosen path is deterministic.
        here = maze
            .neighbors(here as u32)
            .map(|n| n as usize)
            .filter(|&n| dist[n] + 1 == dist[here])
            .min()
            .expect("a reached cell has a predecessor");
        path.push(here);
    }
    path.reverse();
    Some(path)
}

/// Connected pieces of the maze (1 for a maze in which every cell can be reached).
pub fn component_count(maze: &Maze) -> usize {
    connected_components(maze)
}

/// Independent loops: passages beyond a spanning forest (`passages - cells + components`).
/// A perfect maze has 0.
pub fn loop_count(maze: &Maze) -> usize {
    maze.passage_count() + component_count(maze) - maze.grid().cell_count()
}

/// Numbers that say what a maze is like to solve; stored in the layout and printed by
/// `validate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Metrics {
    /// Cells in the grid.
    pub cells: u64,
    /// Open passages.
    pub passages: u64,
    /// Independent loops (0 for a perfect maze).
    pub loops: u64,
    /// Cells on the shortest path from start to end, both included.
    pub solution_cells: u64,
    /// Changes of direction along that path.
    pub solution_turns: u64,
    /// Cells on that path (end excluded) where more than one way leads on: the choices a
    /// line follower must get right.
    pub decision_points: u64,
    /// Cells with exactly one passage.
    pub dead_ends: u64,
    /// Cells with three or four passages.
    pub junctions: u64,
    /// Cells passed straight through (two opposite passages).
    pub straights: u64,
    /// Cells on the longest shortest path in the maze (exact for perfect mazes).
    pub diameter_cells: u64,
}

impl Metrics {
    /// Measures `maze` for the route `start` to `end`; `None` if `end` is unreachable.
    pub fn measure(maze: &Maze, start: usize, end: usize) -> Option<Self> {
        // Three breadth-first sweeps, the diameter's two beside the solution's.
        let (path, (_, _, diameter)) =
            rayon::join(|| shortest_path(maze, start, end), || diameter_ends(maze));
        let path = path?;
        let grid = maze.grid();
        let mut dead_ends = 0;
        let mut junctions = 0;
        let mut straights = 0;
        for index in 0..grid.cell_count() {
            let mask = maze.mask(index);
            match mask.count_ones() {
                1 => dead_ends += 1,
                3 | 4 => junctions += 1,
                2 if is_straight(mask) => straights += 1,
                _ => {}
            }
        }
        let mut turns = 0;
        for window in path.windows(3) {
            let first = maze.direction_between(window[0], window[1]);
            let second = maze.direction_between(window[1], window[2]);
            if first != second {
                turns += 1;
            }
        }
        let decision_points = path
            .iter()
            .take(path.len().saturating_sub(1))
            .enumerate()
            .filter(|&(step, &cell)| {
                let ways_on = maze.degree(cell) - u32::from(step > 0);
                ways_on >= 2
            })
            .count();
        Some(Self {
            cells: grid.cell_count() as u64,
            passages: maze.passage_count() as u64,
            loops: loop_count(maze) as u64,
            solution_cells: path.len() as u64,
            solution_turns: turns,
            decision_points: decision_points as u64,
            dead_ends,
            junctions,
            straights,
            diameter_cells: u64::from(diameter) + 1,
        })
    }

    /// Dead ends as a percentage of all cells.
    pub fn dead_end_percent(&self) -> f64 {
        100.0 * self.dead_ends as f64 / self.cells as f64
    }
}

fn is_straight(mask: u8) -> bool {
    let east_west = Direction::East.bit() | Direction::West.bit();
    let north_south = Direction::North.bit() | Direction::South.bit();
    mask == east_west || mask == north_south
}

/// The turns a robot makes along `path` (cells), as the cell where each turn happens.
pub fn turn_cells(maze: &Maze, path: &[usize]) -> Vec<Cell> {
    path.windows(3)
        .filter(|w| maze.direction_between(w[0], w[1]) != maze.direction_between(w[1], w[2]))
        .map(|w| maze.grid().cell(w[1]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maze::grid::Grid;

    /// A 3x2 maze shaped like an S:
    /// row 1:  3 - 4 - 5
    ///         |
    /// row 0:  0 - 1 - 2
    fn s_shape() -> Maze {
        let mut maze = Maze::closed(Grid::new(3, 2).unwrap());
        maze.carve(0, Direction::East);
        maze.carve(1, Direction::East);
        maze.carve(0, Direction::North);
        maze.carve(3, Direction::East);
        maze.carve(4, Direction::East);
        maze
    }

    #[test]
    fn distances_follow_passages() {
        let maze = s_shape();
        assert_eq!(distances_from(&maze, 2), vec![2, 1, 0, 3, 4, 5]);
        assert_eq!(farthest_from(&maze, 2), (5, 5));
        let (a, b, len) = diameter_ends(&maze);
        assert_eq!((a.min(b), a.max(b), len), (2, 5, 5));
    }

    #[test]
    fn shortest_path_and_metrics() {
        let maze = s_shape();
        assert_eq!(shortest_path(&maze, 2, 5), Some(vec![2, 1, 0, 3, 4, 5]));
        let m = Metrics::measure(&maze, 2, 5).unwrap();
        assert_eq!(m.cells, 6);
        assert_eq!(m.passages, 5);
        assert_eq!(m.loops, 0);
        assert_eq!(m.solution_cells, 6);
        assert_eq!(m.solution_turns, 2);
        assert_eq!(m.decision_points, 0);
        assert_eq!(m.dead_ends, 2);
        assert_eq!(m.junctions, 0);
        assert_eq!(m.straights, 2);
        assert_eq!(m.diameter_cells, 6);
        assert_eq!(
            turn_cells(&maze, &[2, 1, 0, 3, 4, 5]),
            vec![Cell::new(0, 0), Cell::new(0, 1)]
        );
    }

    #[test]
    fn unreachable_and_loops_are_seen() {
        let mut maze = Maze::closed(Grid::new(2, 2).unwrap());
        maze.carve(0, Direction::East);
        assert_eq!(shortest_path(&maze, 0, 3), None);
        assert_eq!(Metrics::measure(&maze, 0, 3), None);
        assert_eq!(component_count(&maze), 3);
        maze.carve(1, Direction::North);
        maze.carve(0, Direction::North);
        maze.carve(2, Direction::East);
        assert_eq!(loop_count(&maze), 1);
        let m = Metrics::measure(&maze, 0, 3).unwrap();
        assert_eq!(
            (m.solution_cells, m.decision_points, m.junctions),
            (3, 1, 0)
        );
    }
}
