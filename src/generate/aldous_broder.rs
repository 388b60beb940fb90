//! Aldous-Broder: a random walk that opens the wall into every cell it enters first.

use fixedbitset::FixedBitSet;

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Walks from a random cell to a uniformly random neighbour, step after step, and carves
/// the passage whenever the step enters a cell for the first time. The result is a
/// uniform spanning tree (every perfect maze of the grid equally likely): about 29% dead
/// ends, no directional bias.
///
/// Cost: the walk must visit every cell, so it runs for the grid's cover time, about
/// `(4/pi) n (ln n)^2` steps on an `n`-cell grid (n log^2 n, not linear). Measured in
/// release on the 2-core development machine (`cargo bench --bench generate`, see
/// `NOTES-algos.md`): 0.2 ms at 100x100, 0.4 s at 1000x1000, 2.0 s at 2000x2000. Each
/// step is cheap (two pooled random bits, a bounds check, a bit test), but use
/// [`Wilson`](super::Wilson) for uniform mazes at scale: same distribution, far fewer
/// steps. Memory: one bit per cell.
#[derive(Debug, Clone, Copy, Default)]
pub struct AldousBroder;

impl Generator for AldousBroder {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let cells = grid.cell_count();
        let (width, height) = (grid.width(), grid.height());
        let mut visited = FixedBitSet::with_capacity(cells);
        let start = rng.index(cells);
        visited.insert(start);
        let mut remaining = cells - 1;
        let (mut x, mut y) = (grid.cell(start).x, grid.cell(start).y);
        let mut here = start;
        while remaining > 0 {
            // A uniform direction; steps off the grid are redrawn, which leaves the
            // choice uniform among the neighbours that exist.
            let dir = Direction::ALL[rng.bits(2) as usize];
            let next = match dir {
                Direction::East if x + 1 < width => {
                    x += 1;
                    here + 1
                }
                Direction::West if x > 0 => {
                    x -= 1;
                    here - 1
                }
                Direction::North if y + 1 < height => {
                    y += 1;
                    here + width as usize
                }
                Direction::South if y > 0 => {
                    y -= 1;
                    here - width as usize
                }
                _ => continue,
            };
            if !visited.put(next) {
                maze.carve(here, dir);
                remaining -= 1;
            }
            here = next;
        }
    }
}
