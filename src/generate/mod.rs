//! Maze generators: one file per algorithm, all behind the [`Generator`] trait, all
//! driven only by a [`MazeRng`] so the same seed always gives the same maze.

mod braid;
mod dfs;
mod kruskal;
mod prim;

use std::fmt;
use std::str::FromStr;

use crate::maze::{Grid, Maze};
use crate::rng::MazeRng;

pub use braid::braid;
pub use dfs::Dfs;
pub use kruskal::Kruskal;
pub use prim::Prim;

/// Something that carves a perfect maze (a spanning tree of the grid).
pub trait Generator {
    /// Opens passages in `maze`, which starts with every wall standing, until every cell
    /// is reachable from every other by exactly one path. Every random choice comes from
    /// `rng`; no recursion (4096 x 4096 must fit a default stack).
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng);
}

/// The algorithms `--algo` accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Algorithm {
    /// Depth-first search (recursive backtracker, run with an explicit stack): long,
    /// winding corridors, few dead ends (about 10%).
    Dfs,
    /// Randomized Prim (random frontier cell): many short dead ends (about 36%).
    Prim,
    /// Randomized Kruskal (shuffled walls, union-find): an even texture (about 30% dead ends).
    Kruskal,
}

impl Algorithm {
    /// Every algorithm, in the order help texts list them.
    pub const ALL: [Algorithm; 3] = [Algorithm::Dfs, Algorithm::Prim, Algorithm::Kruskal];

    /// The name used on the command line and in layouts.
    pub const fn name(self) -> &'static str {
        match self {
            Algorithm::Dfs => "dfs",
            Algorithm::Prim => "prim",
            Algorithm::Kruskal => "kruskal",
        }
    }

    /// The generator that implements this algorithm.
    pub fn generator(self) -> Box<dyn Generator> {
        match self {
            Algorithm::Dfs => Box::new(Dfs),
            Algorithm::Prim => Box::new(Prim),
            Algorithm::Kruskal => Box::new(Kruskal),
        }
    }

    /// All names, comma-separated, for error messages.
    pub fn names() -> String {
        Self::ALL.map(Algorithm::name).join(", ")
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Algorithm {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown algorithm '{s}' (known: {})", Self::names()))
    }
}

/// A perfect maze on `grid`, carved by `algorithm` from the stream of `seed`.
pub fn generate(grid: Grid, algorithm: Algorithm, seed: u64) -> Maze {
    generate_braided(grid, algorithm, seed, 0.0)
}

/// A maze carved by `algorithm` from the stream of `seed`, then braided: `braid_share`
/// of its dead ends opened (0 keeps it perfect) with the same stream, so seed and share
/// decide the result.
pub fn generate_braided(grid: Grid, algorithm: Algorithm, seed: u64, braid_share: f64) -> Maze {
    let mut maze = Maze::closed(grid);
    let mut rng = MazeRng::from_seed(seed);
    algorithm.generator().carve(&mut maze, &mut rng);
    if braid_share > 0.0 {
        braid::braid(&mut maze, &mut rng, braid_share);
    }
    maze
}

/// The unvisited neighbours of cell `index` (up to four), in [`Direction::ALL`] order.
/// Shared by the walkers (DFS, Prim).
///
/// [`Direction::ALL`]: crate::maze::Direction::ALL
fn neighbours_where(
    grid: Grid,
    index: usize,
    mut wanted: impl FnMut(usize) -> bool,
) -> ([(crate::maze::Direction, usize); 4], usize) {
    let mut found = [(crate::maze::Direction::East, 0); 4];
    let mut count = 0;
    for dir in crate::maze::Direction::ALL {
        if let Some(next) = grid.step_index(index, dir) {
            if wanted(next) {
                found[count] = (dir, next);
                count += 1;
            }
        }
    }
    (found, count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maze::analysis::component_count;

    #[test]
    fn every_algorithm_carves_a_spanning_tree() {
        for algorithm in Algorithm::ALL {
            for (w, h) in [(1, 1), (1, 7), (7, 1), (2, 2), (9, 9), (31, 17)] {
                let maze = generate(Grid::new(w, h).unwrap(), algorithm, 42);
                assert_eq!(component_count(&maze), 1, "{algorithm} {w}x{h}");
                assert_eq!(
                    maze.passage_count(),
                    maze.grid().tree_edge_count(),
                    "{algorithm} {w}x{h}"
                );
            }
        }
    }

    #[test]
    fn seeds_decide_the_maze() {
        let grid = Grid::new(12, 12).unwrap();
        for algorithm in Algorithm::ALL {
            assert_eq!(
                generate(grid, algorithm, 5),
                generate(grid, algorithm, 5),
                "{algorithm}"
            );
            assert_ne!(
                generate(grid, algorithm, 5),
                generate(grid, algorithm, 6),
                "{algorithm}"
            );
        }
    }

    #[test]
    fn names_parse_back() {
        for algorithm in Algorithm::ALL {
            assert_eq!(algorithm.name().parse::<Algorithm>(), Ok(algorithm));
        }
        let err = "wilsonx".parse::<Algorithm>().unwrap_err();
        assert!(err.contains("dfs, prim, kruskal"), "{err}");
    }
}
