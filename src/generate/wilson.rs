//! Wilson's algorithm: loop-erased random walks grafted onto a growing tree.

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Marks a cell already in the tree in the per-cell walk byte.
const IN_TREE: u8 = 0xfe;
/// Marks the frame of cells around the grid that a walk may not enter.
const OFF_GRID: u8 = 0xff;

/// Starts the tree at a random cell, then, for every cell not yet in it (row-major
/// order), random-walks until the walk hits the tree and adds the walk's loop-erased
/// path. Loops are erased without any list: each cell's byte remembers the direction the
/// walk last left it by (overwritten when the walk comes back), so following those
/// bytes from the walk's start is exactly the loop-erased path. The result is a uniform
/// spanning tree, like [`AldousBroder`](super::AldousBroder), in far fewer steps
/// (expected walk length is the mean hitting time of the tree, about `n ln n` steps in
/// all on an `n`-cell grid, not the cover time). That is for roughly square grids: on a
/// long thin strip the walks need about length² steps in all (random walks diffuse),
/// so a 1 x 100,000 grid is slow with either uniform algorithm.
///
/// Speed: a walk step is the hot loop, so the walk bytes live in a grid padded with a
/// one-cell frame of off-grid markers: a step is two pooled random bits, a table offset
/// and one byte test, with no bounds arithmetic and no unpredictable branch. Memory: one byte per
/// cell (plus the frame) besides the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct Wilson;

impl Generator for Wilson {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let width = grid.width() as usize;
        let height = grid.height() as usize;
        let stride = width + 2;
        // Walk bytes for the padded grid: cell (x, y) is at (y + 1) * stride + x + 1.
        // Values: OFF_GRID, IN_TREE, or the index in Direction::ALL last left by.
        let mut walk = vec![OFF_GRID; stride * (height + 2)];
        for y in 0..height {
            let row = (y + 1) * stride + 1;
            walk[row..row + width].fill(0);
        }
        // Offsets of one step in each of Direction::ALL (east, north, west, south).
        let offsets = [1isize, stride as isize, -1, -(stride as isize)];
        let padded = |cell: usize| (cell / width + 1) * stride + cell % width + 1;
        walk[padded(rng.index(grid.cell_count()))] = IN_TREE;
        for y in 0..height {
            for x in 0..width {
                let start = (y + 1) * stride + x + 1;
                if walk[start] == IN_TREE {
                    continue;
                }
                // Walk until the tree is hit, recording each cell's last exit.
                let mut here = start;
                loop {
                    let pick = rng.bits(2) as u8;
                    let next = here.wrapping_add_signed(offsets[pick as usize]);
                    let seen = walk[next];
                    if seen == OFF_GRID {
                        continue;
                    }
                    walk[here] = pick;
                    here = next;
                    if seen == IN_TREE {
                        break;
                    }
                }
                // Add the loop-erased path: follow the last exits from the start.
                let mut here = start;
                let mut cell = y * width + x;
                while walk[here] != IN_TREE {
                    let pick = walk[here];
                    walk[here] = IN_TREE;
                    let dir = Direction::ALL[pick as usize];
                    maze.carve(cell, dir);
                    here = here.wrapping_add_signed(offsets[pick as usize]);
                    cell = match dir {
                        Direction::East => cell + 1,
                        Direction::West => cell - 1,
                        Direction::North => cell + width,
                        Direction::South => cell - width,
                    };
                }
            }
        }
    }
}
