//! Depth-first search ("recursive backtracker") with an explicit stack.

use super::{Generator, Lattice, neighbours_where};
use crate::maze::Maze;
use crate::rng::MazeRng;
use fixedbitset::FixedBitSet;

/// Walks to a random unvisited neighbour until stuck, then backtracks: long corridors,
/// few dead ends. Memory: one bit per cell plus a stack of at most one `u32` per cell.
#[derive(Debug, Clone, Copy, Default)]
pub struct Dfs;

impl Generator for Dfs {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let lattice = Lattice::new(grid);
        let mut visited = FixedBitSet::with_capacity(grid.cell_count());
        let start = rng.index(grid.cell_count());
        visited.insert(start);
        let mut stack = vec![start as u32];
        while let Some(&top) = stack.last() {
            let here = top as usize;
            let (options, count) = neighbours_where(&lattice, here, |n| !visited.contains(n));
            if count == 0 {
                stack.pop();
                continue;
            }
            let (dir, next) = options[rng.index(count)];
            maze.carve(here, dir);
            visited.insert(next);
            stack.push(next as u32);
        }
    }
}
