//! Hunt-and-kill: random walks into unvisited cells, restarted by a linear hunt.

use fixedbitset::FixedBitSet;

use super::{Generator, Lattice, neighbours_where};
use crate::maze::Maze;
use crate::rng::MazeRng;

/// Walks from the south-west corner into random unvisited neighbours ("kill") until stuck, then
/// hunts: the classic scan takes the first unvisited cell, row by row, that has a visited
/// neighbour, joins it to a random visited neighbour and walks on from there.
///
/// The hunt is not quadratic: every cell before the first unvisited cell (in row-major
/// order) is visited, so that first unvisited cell always has a visited neighbour (west,
/// or south at a row start) and is exactly the cell the classic scan finds. (That is why
/// the first walk starts at cell 0 rather than a random cell: an unvisited cell 0 would
/// have no visited neighbour to join.) A cursor that
/// only moves forward finds it, so all hunts together cost one pass over the grid.
/// Long winding corridors like DFS. Memory: one bit per cell.
#[derive(Debug, Clone, Copy, Default)]
pub struct HuntAndKill;

impl Generator for HuntAndKill {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let lattice = Lattice::new(grid);
        let cells = grid.cell_count();
        let mut visited = FixedBitSet::with_capacity(cells);
        let mut here = 0;
        visited.insert(here);
        // Every cell before `cursor` is visited.
        let mut cursor = 0;
        loop {
            // Kill: walk while an unvisited neighbour remains.
            loop {
                let (options, count) = neighbours_where(&lattice, here, |n| !visited.contains(n));
                if count == 0 {
                    break;
                }
                let (dir, next) = options[rng.index(count)];
                maze.carve(here, dir);
                visited.insert(next);
                here = next;
            }
            // Hunt: the first unvisited cell, joined to a random visited neighbour.
            while cursor < cells && visited.contains(cursor) {
                cursor += 1;
            }
            if cursor == cells {
                break;
            }
            here = cursor;
            let (options, count) = neighbours_where(&lattice, here, |n| visited.contains(n));
            let (dir, _) = options[rng.index(count)];
            maze.carve(here, dir);
            visited.insert(here);
        }
    }
}
