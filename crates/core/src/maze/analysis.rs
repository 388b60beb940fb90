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
pub fn distances_from(maze: &Maze, start: usize) -> Vec<u32> {
    Distances::from(maze, start).steps
}

/// Steps from one cell to every cell, kept so that the next question about the same
/// start (the farthest cell, a path, the diameter) does not search the maze again: on a
/// big maze each search is most of a second.
#[derive(Debug, Clone, PartialEq)]
pub struct Distances {
    source: usize,
    steps: Vec<u32>,
}

impl Distances {
    /// Breadth-first from `source`: a plain queue over the distance array (which doubles
    /// as the visited set), the one traversal every layout is measured with, so kept lean
    /// rather than run through petgraph's `Bfs` and a second neighbour scan.
    pub fn from(maze: &Maze, source: usize) -> Self {
        let mut steps = vec![UNREACHED; maze.grid().cell_count()];
        steps[source] = 0;
        let mut queue = Vec::with_capacity(maze.grid().cell_count());
        queue.push(source as u32);
        let mut next = 0;
        while let Some(&node) = queue.get(next) {
            next += 1;
            let step = steps[node as usize] + 1;
            for neighbour in maze.neighbors(node) {
                let d = &mut steps[neighbour as usize];
                if *d == UNREACHED {
                    *d = step;
                    queue.push(neighbour);
                }
            }
        }
        Self { source, steps }
    }

    /// The farthest cell (lowest index among equals) and its distance.
    pub fn farthest(&self) -> (usize, u32) {
        let mut best = (0, 0);
        for (index, &d) in self.steps.iter().enumerate() {
            if d != UNREACHED && d > best.1 {
                best = (index, d);
            }
        }
        best
    }

    /// Steps from the source to `cell`, [`UNREACHED`] if there is no path.
    pub fn steps_to(&self, cell: usize) -> u32 {
        self.steps[cell]
    }

    /// `true` if every cell can be reached.
    pub fn reach_all(&self) -> bool {
        !self.steps.contains(&UNREACHED)
    }

    /// The cells of a shortest path from the source to `end`, both included; `None` if
    /// `end` cannot be reached.
    pub fn path_to(&self, maze: &Maze, end: usize) -> Option<Vec<usize>> {
        let dist = &self.steps;
        if dist[end] == UNREACHED {
            return None;
        }
        let mut path = vec![end];
        let mut here = end;
        while here != self.source {
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
}

/// The cell farthest from `start` along the maze (lowest index among equals) and its distance.
pub fn farthest_from(maze: &Maze, start: usize) -> (usize, u32) {
    Distances::from(maze, start).farthest()
}

/// Both ends of the maze's diameter by two breadth-first sweeps, and its length in steps.
/// Exact for a perfect maze (a tree); a lower bound when the maze has loops.
pub fn diameter_ends(maze: &Maze) -> (usize, usize, u32) {
    diameter_ends_from(maze, &Distances::from(maze, 0))
}

/// [`diameter_ends`] with the first sweep (from cell 0) already done.
fn diameter_ends_from(maze: &Maze, from_zero: &Distances) -> (usize, usize, u32) {
    debug_assert_eq!(
        from_zero.source, 0,
        "the diameter's first sweep starts at cell 0"
    );
    let (a, _) = from_zero.farthest();
    let (b, length) = farthest_from(maze, a);
    (a, b, length)
}

/// The cells of a shortest path from `start` to `end`, both included; `None` if `end`
/// cannot be reached.
pub fn shortest_path(maze: &Maze, start: usize, end: usize) -> Option<Vec<usize>> {
    Distances::from(maze, start).path_to(maze, end)
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
        Self::measure_from(maze, &Distances::from(maze, start), end)
    }

    /// [`measure`](Self::measure) from the start's distances, already searched (to find
    /// the end, say): the solution needs no further search, and the diameter one more
    /// when the start is cell 0, where the diameter's first sweep begins.
    pub fn measure_from(maze: &Maze, from_start: &Distances, end: usize) -> Option<Self> {
        let (path, (_, _, diameter)) = rayon::join(
            || from_start.path_to(maze, end),
            || match from_start.source {
                0 => diameter_ends_from(maze, from_start),
                _ => diameter_ends(maze),
            },
        );
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
            // Reaching every cell from the start means one piece: no component search.
            loops: match from_start.reach_all() {
                true => maze.passage_count() + 1 - grid.cell_count(),
                false => loop_count(maze),
            } as u64,
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
