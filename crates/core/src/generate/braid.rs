//! Braiding: open walls at dead ends so the maze gets loops (where wall-following fails).

use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Removes `share` (0..=1) of the maze's dead ends by opening one wall of each, preferring
/// a wall to a neighbour that is a dead end too (which removes two at once). Dead ends are
/// visited in a random order drawn from `rng`; a dead end with no wall left to open (the
/// ends of a one-cell-wide maze) is kept. Returns the number of passages opened, which is
/// the number of loops added.
pub fn braid(maze: &mut Maze, rng: &mut MazeRng, share: f64) -> usize {
    let grid = maze.grid();
    let mut dead_ends: Vec<u32> = (0..grid.cell_count())
        .filter(|&i| maze.degree(i) == 1)
        .map(|i| i as u32)
        .collect();
    let target = (share.clamp(0.0, 1.0) * dead_ends.len() as f64).round() as usize;
    rng.shuffle(&mut dead_ends);
    let mut removed = 0;
    let mut opened = 0;
    for cell in dead_ends {
        if removed >= target {
            break;
        }
        let cell = cell as usize;
        if maze.degree(cell) != 1 {
            continue; // an earlier opening already joined it
        }
        let mut walls = [(Direction::East, false); 4];
        let mut count = 0;
        let mut dead_neighbours = 0;
        for dir in Direction::ALL {
            if maze.is_open(cell, dir) {
                continue;
            }
            if let Some(next) = grid.step_index(cell, dir) {
                let dead = maze.degree(next) == 1;
                walls[count] = (dir, dead);
                dead_neighbours += usize::from(dead);
                count += 1;
            }
        }
        if count == 0 {
            continue;
        }
        let preferred: Vec<Direction> = walls[..count]
            .iter()
            .filter(|&&(_, dead)| dead || dead_neighbours == 0)
            .map(|&(dir, _)| dir)
            .collect();
        let dir = preferred[rng.index(preferred.len())];
        let next = grid.step_index(cell, dir).expect("wall to a neighbour");
        removed += 1 + usize::from(maze.degree(next) == 1);
        maze.carve(cell, dir);
        opened += 1;
    }
    opened
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{Algorithm, generate};
    use crate::maze::Grid;
    use crate::maze::analysis::{component_count, loop_count};

    fn dead_ends(maze: &Maze) -> usize {
        (0..maze.grid().cell_count())
            .filter(|&i| maze.degree(i) == 1)
            .count()
    }

    #[test]
    fn braiding_removes_the_asked_share_and_adds_loops() {
        for share in [0.0, 0.25, 0.5, 1.0] {
            let mut maze = generate(Grid::new(30, 30).unwrap(), Algorithm::Prim, 9);
            let before = dead_ends(&maze);
            let opened = braid(&mut maze, &mut MazeRng::from_seed(1), share);
            let after = dead_ends(&maze);
            assert_eq!(component_count(&maze), 1);
            assert_eq!(loop_count(&maze), opened);
            let target = (share * before as f64).round() as usize;
            assert!(before - after >= target, "{share}: {before} -> {after}");
            assert!(
                before - after <= target + 1,
                "{share}: overshoot {before} -> {after}"
            );
            if share == 1.0 {
                assert_eq!(after, 0);
            }
        }
    }

    #[test]
    fn braiding_is_deterministic_and_keeps_corridor_ends() {
        let grid = Grid::new(12, 12).unwrap();
        let run = || {
            let mut maze = generate(grid, Algorithm::Dfs, 4);
            braid(&mut maze, &mut MazeRng::from_seed(4), 0.5);
            maze
        };
        assert_eq!(run(), run());
        let mut corridor = generate(Grid::new(1, 9).unwrap(), Algorithm::Dfs, 1);
        assert_eq!(braid(&mut corridor, &mut MazeRng::from_seed(1), 1.0), 0);
    }
}
