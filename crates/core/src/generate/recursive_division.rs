//! Recursive division, with an explicit stack of chambers instead of recursion.

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// A rectangle of cells still to be divided.
#[derive(Debug, Clone, Copy)]
struct Chamber {
    x: u32,
    y: u32,
    width: u32,
    height: u32,
}

/// The classic wall-adder, written as carving: the grid starts as one open chamber; a
/// chamber is split by a wall across its shorter side (a coin flip for squares) at a
/// random position, with one random gap, and both halves are divided in turn until they
/// are one cell wide or tall, which stay fully open. Here the maze starts closed, so the
/// generator carves what the classic version leaves open: each wall's gap, and the inside
/// of every one-cell-wide chamber. Long straight walls and a boxy, room-like texture.
/// Chambers wait on an explicit stack (no recursion). Memory: the stack, at most one
/// chamber per division level.
#[derive(Debug, Clone, Copy, Default)]
pub struct RecursiveDivision;

impl Generator for RecursiveDivision {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let row = grid.width() as usize;
        let index = |x: u32, y: u32| y as usize * row + x as usize;
        let mut stack = vec![Chamber {
            x: 0,
            y: 0,
            width: grid.width(),
            height: grid.height(),
        }];
        while let Some(c) = stack.pop() {
            if c.width == 1 {
                for y in c.y..c.y + c.height - 1 {
                    maze.carve(index(c.x, y), Direction::North);
                }
                continue;
            }
            if c.height == 1 {
                for x in c.x..c.x + c.width - 1 {
                    maze.carve(index(x, c.y), Direction::East);
                }
                continue;
            }
            let split_rows = match c.width.cmp(&c.height) {
                std::cmp::Ordering::Less => true,
                std::cmp::Ordering::Greater => false,
                std::cmp::Ordering::Equal => rng.coin(),
            };
            if split_rows {
                // A wall between rows c.y + south - 1 and c.y + south, gap in one column.
                let south = 1 + rng.below(c.height - 1);
                let gap = c.x + rng.below(c.width);
                maze.carve(index(gap, c.y + south - 1), Direction::North);
                stack.push(Chamber {
                    height: c.height - south,
                    y: c.y + south,
                    ..c
                });
                stack.push(Chamber { height: south, ..c });
            } else {
                let west = 1 + rng.below(c.width - 1);
                let gap = c.y + rng.below(c.height);
                maze.carve(index(c.x + west - 1, gap), Direction::East);
                stack.push(Chamber {
                    width: c.width - west,
                    x: c.x + west,
                    ..c
                });
                stack.push(Chamber { width: west, ..c });
            }
        }
    }
}
