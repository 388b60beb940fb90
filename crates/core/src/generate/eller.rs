//! Eller's algorithm: one row at a time, with set labels for what is already joined.

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::MazeRng;

/// Builds the maze row by row from the south. Each cell of the current row carries the
/// label of its set (cells already joined through earlier rows). In each row:
/// 1. neighbours in different sets are joined eastwards on a coin flip, merging their
///    whole sets (a small union-find over the row's labels; never two cells of one set,
///    so no loop);
/// 2. every set opens at least one passage north (a coin flip per cell, forced on the
///    set's last cell if none opened yet), so no set is cut off;
/// 3. the next row keeps the labels of cells reached from below and gives fresh labels
///    to the others, renumbered `0..width` in order of first appearance.
///
/// The last row joins every pair of neighbours in different sets, leaving one set: a
/// spanning tree. Deterministic: labels are plain arrays scanned west to east, no hash
/// map anywhere. Memory: a few `u32`s per column besides the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct Eller;

/// No label assigned yet (in the renumbering table).
const UNSET: u32 = u32::MAX;

impl Generator for Eller {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let width = grid.width() as usize;
        let height = grid.height() as usize;
        // Labels are always below `width`: there are never more sets than cells in a row.
        let mut label: Vec<u32> = (0..width as u32).collect();
        let mut parent: Vec<u32> = vec![0; width];
        let mut left_in_row: Vec<u32> = vec![0; width];
        let mut went_north: Vec<bool> = vec![false; width];
        let mut opened: Vec<bool> = vec![false; width];
        let mut renumber: Vec<u32> = vec![UNSET; width];
        for y in 0..height {
            let row_start = y * width;
            let last_row = y + 1 == height;
            for (l, p) in parent.iter_mut().enumerate() {
                *p = l as u32;
            }
            // 1. Join east across different sets, merging whole sets.
            for x in 0..width.saturating_sub(1) {
                let a = find(&mut parent, label[x]);
                let b = find(&mut parent, label[x + 1]);
                if a != b && (last_row || rng.coin()) {
                    maze.carve(row_start + x, Direction::East);
                    parent[b as usize] = a;
                }
            }
            if last_row {
                break;
            }
            for l in label.iter_mut() {
                *l = find(&mut parent, *l);
            }
            // 2. At least one passage north per set.
            left_in_row.fill(0);
            went_north.fill(false);
            for &l in &label {
                left_in_row[l as usize] += 1;
            }
            for x in 0..width {
                let set = label[x] as usize;
                left_in_row[set] -= 1;
                let up = rng.coin() || (left_in_row[set] == 0 && !went_north[set]);
                opened[x] = up;
                if up {
                    went_north[set] = true;
                    maze.carve(row_start + x, Direction::North);
                }
            }
            // 3. Labels for the next row: kept from below, or fresh; renumbered 0..width.
            renumber.fill(UNSET);
            let mut next_label = 0;
            for x in 0..width {
                if opened[x] {
                    let old = label[x] as usize;
                    if renumber[old] == UNSET {
                        renumber[old] = next_label;
                        next_label += 1;
                    }
                    label[x] = renumber[old];
                }
            }
            for x in 0..width {
                if !opened[x] {
                    label[x] = next_label;
                    next_label += 1;
                }
            }
        }
    }
}

/// The root of `label` in the row's union-find, halving the path on the way.
fn find(parent: &mut [u32], mut label: u32) -> u32 {
    while parent[label as usize] != label {
        let grandparent = parent[parent[label as usize] as usize];
        parent[label as usize] = grandparent;
        label = grandparent;
    }
    label
}
