//! Growing tree: keep a list of active cells, grow from one of them, retire it when stuck.

use std::collections::VecDeque;

use fixedbitset::FixedBitSet;

use super::options::{GrowingMode, MixRatio};
use super::{Generator, Lattice, neighbours_where};
use crate::maze::Maze;
use crate::rng::MazeRng;

/// Starts with one random active cell. Each step selects an active cell by the
/// [`GrowingMode`]; if it has unvisited neighbours, one of them (at random) is carved to
/// and becomes the newest active cell, else the selected cell is retired. The mode sets
/// the texture: `newest` is DFS-like, `random` Prim-like, `oldest` and `middle` give long
/// straight corridors, `mix:P` blends newest and random.
///
/// Every selection and retirement is O(1) amortised (no `Vec::remove` shifting):
/// * newest, oldest, mix: the active list in insertion order, with retired entries left
///   as holes; holes at either end are trimmed at once, and the list is compacted (order
///   kept) when holes outnumber live cells. A random live cell is found by redrawing a
///   uniform position until it is not a hole (under two draws expected).
/// * random: order does not matter, so retired cells are swap-removed (no holes).
/// * middle: the list split into two deques around its middle, rebalanced on each change.
///
/// Memory: one bit per cell plus at most one `u32` per cell of active list.
#[derive(Debug, Clone, Copy, Default)]
pub struct GrowingTree {
    /// How the next active cell is selected.
    pub mode: GrowingMode,
}

impl Generator for GrowingTree {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        match self.mode {
            GrowingMode::Middle => grow(maze, rng, MiddleList::default()),
            mode => grow(maze, rng, HoleyList::new(mode)),
        }
    }
}

/// An active list: select a cell, retire the selected one, add a newest one.
trait ActiveList {
    /// Adds `cell` as the newest active cell.
    fn push(&mut self, cell: u32);
    /// Selects an active cell (remembered for [`retire_selected`](Self::retire_selected));
    /// `None` when the list is empty.
    fn select(&mut self, rng: &mut MazeRng) -> Option<u32>;
    /// Retires the cell of the last [`select`](Self::select) (no push in between).
    fn retire_selected(&mut self);
}

fn grow(maze: &mut Maze, rng: &mut MazeRng, mut active: impl ActiveList) {
    let grid = maze.grid();
    let lattice = Lattice::new(grid);
    let mut visited = FixedBitSet::with_capacity(grid.cell_count());
    let start = rng.index(grid.cell_count());
    visited.insert(start);
    active.push(start as u32);
    while let Some(cell) = active.select(rng) {
        let here = cell as usize;
        let (options, count) = neighbours_where(&lattice, here, |n| !visited.contains(n));
        if count == 0 {
            active.retire_selected();
            continue;
        }
        let (dir, next) = options[rng.index(count)];
        maze.carve(here, dir);
        visited.insert(next);
        active.push(next as u32);
    }
}

/// A retired entry.
const HOLE: u32 = u32::MAX;

/// The active cells in insertion order, retired ones as [`HOLE`]s. Invariants: the last
/// entry and the entry at `head` are live (or the list is empty); everything before
/// `head` is a hole.
struct HoleyList {
    entries: Vec<u32>,
    head: usize,
    live: usize,
    selected: usize,
    mode: GrowingMode,
}

impl HoleyList {
    fn new(mode: GrowingMode) -> Self {
        Self {
            entries: Vec::new(),
            head: 0,
            live: 0,
            selected: 0,
            mode,
        }
    }

    /// A uniformly random live position: uniform positions, holes redrawn.
    fn random_position(&self, rng: &mut MazeRng) -> usize {
        let span = self.entries.len() - self.head;
        loop {
            let position = self.head + rng.index(span);
            if self.entries[position] != HOLE {
                return position;
            }
        }
    }
}

impl ActiveList for HoleyList {
    fn push(&mut self, cell: u32) {
        self.entries.push(cell);
        self.live += 1;
    }

    fn select(&mut self, rng: &mut MazeRng) -> Option<u32> {
        if self.live == 0 {
            return None;
        }
        let newest = self.entries.len() - 1;
        self.selected = match self.mode {
            GrowingMode::Newest => newest,
            GrowingMode::Oldest => self.head,
            GrowingMode::Random => self.random_position(rng),
            GrowingMode::Mix(p) => {
                if rng.chance(p.millionths(), MixRatio::SCALE) {
                    newest
                } else {
                    self.random_position(rng)
                }
            }
            GrowingMode::Middle => unreachable!("middle uses MiddleList"),
        };
        Some(self.entries[self.selected])
    }

    fn retire_selected(&mut self) {
        if self.mode == GrowingMode::Random {
            // Order is irrelevant when every pick is uniform: keep the list dense.
            self.entries.swap_remove(self.selected);
            self.live -= 1;
            return;
        }
        self.entries[self.selected] = HOLE;
        self.live -= 1;
        while self.entries.last() == Some(&HOLE) {
            self.entries.pop();
        }
        while self.head < self.entries.len() && self.entries[self.head] == HOLE {
            self.head += 1;
        }
        if self.live == 0 {
            self.entries.clear();
            self.head = 0;
        } else if self.entries.len() - self.head >= self.live + self.live / 4 + 64 {
            // Holes are a fifth of the span: squeeze them out, keeping the order. Each
            // compaction removes at least a quarter as many holes as it moves live
            // cells, so it is O(1) amortised per retirement, and a random pick needs at
            // most 1.25 probes on average.
            let head = self.head;
            self.entries.drain(..head);
            self.entries.retain(|&c| c != HOLE);
            self.head = 0;
        }
    }
}

/// The active cells in insertion order, split so that the middle one (index `len / 2`)
/// is the front of `upper`: `lower` holds the first `len / 2` cells.
#[derive(Default)]
struct MiddleList {
    lower: VecDeque<u32>,
    upper: VecDeque<u32>,
}

impl ActiveList for MiddleList {
    fn push(&mut self, cell: u32) {
        self.upper.push_back(cell);
        if self.upper.len() > self.lower.len() + 1 {
            let moved = self.upper.pop_front().expect("upper is not empty");
            self.lower.push_back(moved);
        }
    }

    fn select(&mut self, _rng: &mut MazeRng) -> Option<u32> {
        self.upper.front().copied()
    }

    fn retire_selected(&mut self) {
        self.upper.pop_front();
        if self.upper.len() < self.lower.len() {
            let moved = self.lower.pop_back().expect("lower is longer than upper");
            self.upper.push_front(moved);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The active lists against a plain `Vec` with `remove`, the obvious reference.
    #[test]
    fn active_lists_select_like_a_plain_list() {
        let mut rng = MazeRng::from_seed(11);
        for mode in [
            GrowingMode::Newest,
            GrowingMode::Oldest,
            GrowingMode::Middle,
        ] {
            let mut list: Box<dyn ActiveList> = match mode {
                GrowingMode::Middle => Box::new(MiddleList::default()),
                mode => Box::new(HoleyList::new(mode)),
            };
            let mut reference: Vec<u32> = Vec::new();
            let mut next = 0;
            for step in 0..5000 {
                if rng.chance(3, 5) || reference.is_empty() {
                    list.push(next);
                    reference.push(next);
                    next += 1;
                    continue;
                }
                let position = match mode {
                    GrowingMode::Newest => reference.len() - 1,
                    GrowingMode::Oldest => 0,
                    _ => reference.len() / 2,
                };
                assert_eq!(
                    list.select(&mut rng),
                    Some(reference[position]),
                    "{mode} step {step}"
                );
                list.retire_selected();
                reference.remove(position);
            }
        }
    }

    #[test]
    fn random_selection_only_finds_live_cells_in_order() {
        let mut rng = MazeRng::from_seed(12);
        let mut list = HoleyList::new(GrowingMode::Mix(MixRatio::from_millionths(0).unwrap()));
        let mut reference: Vec<u32> = Vec::new();
        for cell in 0..3000 {
            list.push(cell);
            reference.push(cell);
            if cell % 3 == 0 {
                let picked = list.select(&mut rng).unwrap();
                list.retire_selected();
                let at = reference.iter().position(|&c| c == picked).expect("live");
                reference.remove(at);
            }
        }
        while let Some(picked) = list.select(&mut rng) {
            list.retire_selected();
            let at = reference.iter().position(|&c| c == picked).expect("live");
            reference.remove(at);
            let live: Vec<u32> = list.entries[list.head..]
                .iter()
                .copied()
                .filter(|&c| c != HOLE)
                .collect();
            assert_eq!(live, reference);
        }
        assert!(reference.is_empty());
    }
}
