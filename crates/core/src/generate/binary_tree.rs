//! Binary tree: every cell opens towards one of two fixed directions.

use super::Generator;
use super::options::Bias;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Each cell opens towards the bias's vertical or horizontal direction on a coin flip,
/// or towards the one that stays on the grid; the corner the bias points at opens
/// nothing. Every cell but that corner has exactly one parent, so the result is a tree
/// rooted in the corner. The two sides the bias faces (north row and east column for
/// `ne`) are single straight corridors; dead ends are 25% of the cells on large grids.
/// Memory: nothing beyond the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct BinaryTree {
    /// The two directions carved towards.
    pub bias: Bias,
}

impl Generator for BinaryTree {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let (width, height) = (grid.width(), grid.height());
        let (vertical, horizontal) = self.bias.directions();
        let mut index = 0;
        for y in 0..height {
            let can_vertical = match vertical {
                Direction::North => y + 1 < height,
                _ => y > 0,
            };
            for x in 0..width {
                let can_horizontal = match horizontal {
                    Direction::East => x + 1 < width,
                    _ => x > 0,
                };
                let dir = match (can_vertical, can_horizontal) {
                    (true, true) => Some(if rng.coin() { vertical } else { horizontal }),
                    (true, false) => Some(vertical),
                    (false, true) => Some(horizontal),
                    (false, false) => None,
                };
                if let Some(dir) = dir {
                    maze.carve(index, dir);
                }
                index += 1;
            }
        }
    }
}
