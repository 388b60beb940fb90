//! Aldous-Broder: a random walk that opens the wall into every cell it enters first.

use super::Generator;
use super::padded::PaddedGrid;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Walks from a random cell to a uniformly random neighbour, step after step, and carves
/// the passage whenever the step enters a cell for the first time. The result is a
/// uniform spanning tree (every perfect maze of the grid equally likely): about 29% dead
/// ends, no directional bias.
///
/// Cost: the walk must visit every cell, so it runs for the grid's cover time, about
/// `(1/pi) n (ln n)^2` steps on an `n`-cell grid (the 2D torus asymptotics; n log^2 n,
/// not linear). Counted here (seeds 0-2): 0.34-0.41 n ln^2 n steps at 1000x1000 and
/// 2000x2000, i.e. 63-77 million and 310-370 million steps, against about 0.55 n ln n
/// (11-35 million) for Wilson. Each step is cheap (two pooled random bits, a table
/// offset, one byte test: 2-3 ns), so generation took 0.6 ms at 100x100, 0.1 s at
/// 1000x1000 and 0.5-0.8 s at 2000x2000 in release on the shared 2-core development
/// machine (`bench/run.sh`, table in `docs/history/algorithms.md`); 4096x4096 would take several
/// seconds. Use [`Wilson`](super::Wilson) for uniform mazes at scale: same
/// distribution, far fewer steps. The estimate is for roughly square grids: on a long
/// thin strip a random walk needs about length² steps to cover it (a 1 x 100,000 grid
/// would take about 10^10 steps), and so do Wilson's walks. Memory: one byte per cell (plus a one-cell frame)
/// besides the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct AldousBroder;

/// A cell the walk has not entered yet.
const FRESH: u8 = 0;
/// A cell the walk has entered.
const SEEN: u8 = 1;
/// The frame of cells around the grid that the walk may not enter.
const OFF_GRID: u8 = 2;

impl Generator for AldousBroder {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let width = grid.width() as usize;
        let mut walk = PaddedGrid::new(grid, FRESH, OFF_GRID);
        // One step in each of Direction::ALL in the maze (the padded steps are `offsets`).
        let cell_offsets = [1isize, width as isize, -1, -(width as isize)];
        let start = rng.index(grid.cell_count());
        let mut here = walk.position(start);
        let mut cell = start;
        walk.bytes[here] = SEEN;
        let mut remaining = grid.cell_count() - 1;
        while remaining > 0 {
            // A uniform direction; steps off the grid are redrawn, which leaves the
            // choice uniform among the neighbours that exist.
            let pick = rng.bits(2) as usize;
            let next = here.wrapping_add_signed(walk.offsets[pick]);
            let seen = walk.bytes[next];
            if seen == OFF_GRID {
                continue;
            }
            if seen == FRESH {
                walk.bytes[next] = SEEN;
                maze.carve(cell, Direction::ALL[pick]);
                remaining -= 1;
            }
            here = next;
            cell = cell.wrapping_add_signed(cell_offsets[pick]);
        }
    }
}
