//! Randomized Prim: grow one tree by attaching a random frontier cell.

use super::{Generator, Lattice, neighbours_where};
use crate::maze::Maze;
use crate::rng::MazeRng;

const OUTSIDE: u8 = 0;
const FRONTIER: u8 = 1;
const INSIDE: u8 = 2;

/// Keeps the frontier (cells next to the tree) in a vector; each step removes a random
/// entry in O(1) (swap-remove, never a linear scan) and joins it to a random neighbour
/// already in the tree. Many short dead ends. Memory: one byte of state per cell plus a
/// frontier of at most one `u32` per cell.
#[derive(Debug, Clone, Copy, Default)]
pub struct Prim;

impl Generator for Prim {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let lattice = Lattice::new(grid);
        let mut state = vec![OUTSIDE; grid.cell_count()];
        let mut frontier: Vec<u32> = Vec::new();
        let start = rng.index(grid.cell_count());
        add_to_tree(start, &mut state, &mut frontier, &lattice);
        while !frontier.is_empty() {
            let cell = frontier.swap_remove(rng.index(frontier.len())) as usize;
            let (inside, count) = neighbours_where(&lattice, cell, |n| state[n] == INSIDE);
            let (dir, _) = inside[rng.index(count)];
            maze.carve(cell, dir);
            add_to_tree(cell, &mut state, &mut frontier, &lattice);
        }
    }
}

/// Marks `cell` as part of the tree and puts its outside neighbours on the frontier.
fn add_to_tree(cell: usize, state: &mut [u8], frontier: &mut Vec<u32>, lattice: &Lattice) {
    state[cell] = INSIDE;
    let (outside, count) = neighbours_where(lattice, cell, |n| state[n] == OUTSIDE);
    for &(_, next) in &outside[..count] {
        state[next] = FRONTIER;
        frontier.push(next as u32);
    }
}
