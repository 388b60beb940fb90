//! Randomized Kruskal: knock down walls in random order unless that would make a loop.

use petgraph::unionfind::UnionFind;

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Shuffles every inner wall, then opens each wall whose two cells are not yet joined,
/// tracked with petgraph's union-find (union by rank, path halving). Memory: one `u32`
/// per wall (about two per cell) plus the union-find's five bytes per cell.
#[derive(Debug, Clone, Copy, Default)]
pub struct Kruskal;

impl Generator for Kruskal {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let cells = grid.cell_count();
        // A wall is `cell * 2` (its east side) or `cell * 2 + 1` (its north side).
        let mut walls: Vec<u32> = Vec::with_capacity(2 * cells);
        for index in 0..cells {
            let cell = grid.cell(index);
            if cell.x + 1 < grid.width() {
                walls.push(2 * index as u32);
            }
            if cell.y + 1 < grid.height() {
                walls.push(2 * index as u32 + 1);
            }
        }
        rng.shuffle(&mut walls);
        let mut sets = UnionFind::<u32>::new(cells);
        let mut remaining = cells - 1;
        for wall in walls {
            if remaining == 0 {
                break;
            }
            let index = (wall / 2) as usize;
            let dir = if wall % 2 == 0 {
                Direction::East
            } else {
                Direction::North
            };
            let next = grid.step_index(index, dir).expect("walls are inner walls");
            if sets.union(index as u32, next as u32) {
                maze.carve(index, dir);
                remaining -= 1;
            }
        }
    }
}
