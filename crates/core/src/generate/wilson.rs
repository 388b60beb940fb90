//! Wilson's algorithm: loop-erased random walks grafted onto a growing tree.

use super::Generator;
use super::padded::PaddedGrid;
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
        // Walk bytes: OFF_GRID, IN_TREE, or the index in Direction::ALL last left by.
        let mut padded = PaddedGrid::new(grid, 0, OFF_GRID);
        let offsets = padded.offsets;
        let root = padded.position(rng.index(grid.cell_count()));
        padded.bytes[root] = IN_TREE;
        for y in 0..height {
            for x in 0..width {
                let start = padded.position(y * width + x);
                if padded.bytes[start] == IN_TREE {
                    continue;
                }
                // Walk until the tree is hit, recording each cell's last exit.
                let mut here = start;
                loop {
                    let pick = rng.bits(2) as u8;
                    let next = here.wrapping_add_signed(offsets[pick as usize]);
                    let seen = padded.bytes[next];
                    if seen == OFF_GRID {
                        continue;
                    }
                    padded.bytes[here] = pick;
                    here = next;
                    if seen == IN_TREE {
                        break;
                    }
                }
                // Add the loop-erased path: follow the last exits from the start.
                let mut here = start;
                let mut cell = y * width + x;
                while padded.bytes[here] != IN_TREE {
                    let pick = padded.bytes[here];
                    padded.bytes[here] = IN_TREE;
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
