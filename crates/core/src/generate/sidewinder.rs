//! Sidewinder: runs of passages east, each closed by one passage north.

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Row by row from the south: extends the current run east on a coin flip; otherwise
/// (and always at the east edge) closes the run by opening north from a random cell of
/// the run. The north row, which cannot open north, is one straight corridor. About 28%
/// dead ends; solutions run up without ever needing to go south. Memory: nothing beyond
/// the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sidewinder;

impl Generator for Sidewinder {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let width = grid.width() as usize;
        let height = grid.height() as usize;
        for y in 0..height {
            let row_start = y * width;
            if y + 1 == height {
                for x in 0..width - 1 {
                    maze.carve(row_start + x, Direction::East);
                }
                break;
            }
            let mut run_start = 0;
            for x in 0..width {
                if x + 1 < width && rng.coin() {
                    maze.carve(row_start + x, Direction::East);
                } else {
                    let pick = run_start + rng.index(x - run_start + 1);
                    maze.carve(row_start + pick, Direction::North);
                    run_start = x + 1;
                }
            }
        }
    }
}
