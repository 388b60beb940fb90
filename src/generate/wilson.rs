//! Wilson's algorithm: loop-erased random walks grafted onto a growing tree.

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Marks a cell already in the tree in the per-cell walk byte.
const IN_TREE: u8 = 0xff;

/// Starts the tree at a random cell, then, for every cell not yet in it (row-major
/// order), random-walks until the walk hits the tree and adds the walk's loop-erased
/// path. Loops are erased without any list: each cell's byte remembers the direction the
/// walk last left it by (overwritten when the walk comes back), so following those
/// bytes from the walk's start is exactly the loop-erased path. The result is a uniform
/// spanning tree, like [`AldousBroder`](super::AldousBroder), in far fewer steps
/// (expected walk length is the mean hitting time of the tree, not the cover time).
/// Memory: one byte per cell besides the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct Wilson;

impl Generator for Wilson {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let cells = grid.cell_count();
        let (width, height) = (grid.width(), grid.height());
        let row = width as usize;
        // Per cell: IN_TREE, or the index in Direction::ALL the current walk last left by.
        let mut exit = vec![0u8; cells];
        exit[rng.index(cells)] = IN_TREE;
        let (mut start_x, mut start_y) = (0u32, 0u32);
        for start in 0..cells {
            if start > 0 {
                start_x += 1;
                if start_x == width {
                    start_x = 0;
                    start_y += 1;
                }
            }
            if exit[start] == IN_TREE {
                continue;
            }
            // Walk until the tree is hit, recording each cell's last exit.
            let (mut x, mut y, mut here) = (start_x, start_y, start);
            while exit[here] != IN_TREE {
                let pick = rng.bits(2) as u8;
                let next = match Direction::ALL[pick as usize] {
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
                        here + row
                    }
                    Direction::South if y > 0 => {
                        y -= 1;
                        here - row
                    }
                    _ => continue,
                };
                exit[here] = pick;
                here = next;
            }
            // Add the loop-erased path: follow the last exits from the start.
            let mut here = start;
            while exit[here] != IN_TREE {
                let dir = Direction::ALL[exit[here] as usize];
                exit[here] = IN_TREE;
                maze.carve(here, dir);
                here = match dir {
                    Direction::East => here + 1,
                    Direction::West => here - 1,
                    Direction::North => here + row,
                    Direction::South => here - row,
                };
            }
        }
    }
}
