//! Randomized Kruskal: knock down walls in random order unless that would make a loop.

use fixedbitset::FixedBitSet;

use super::Generator;
use crate::maze::{Direction, Maze};
use crate::rng::{MazeRng, prefetch};

/// Shuffles every inner wall, then opens each wall whose two cells are not yet joined,
/// tracked with a union-find (union by rank, path halving). Memory: one `u32` per wall
/// (about two per cell), the union-find's four bytes per cell and a bit per wall: about
/// 13.25 bytes per cell with the maze.
///
/// Speed: at 2000 x 2000 the walls and the union-find are far larger than the caches,
/// so the shuffle (in [`MazeRng::shuffle`]) and the wall loop prefetch the cells they
/// will touch a few steps ahead. Which walls open depends only on which cells are
/// already joined, never on how the union-find stores it, so the maze is the one the
/// plain algorithm makes (the golden files pin it).
#[derive(Debug, Clone, Copy, Default)]
pub struct Kruskal;

/// How many walls ahead a wall's cells are prefetched; their parents are prefetched
/// half as far ahead and their grandparents a quarter, each once the level below has
/// had time to arrive.
const LOOKAHEAD: usize = 32;

impl Generator for Kruskal {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let grid = maze.grid();
        let cells = grid.cell_count();
        let width = grid.width() as usize;
        let height = grid.height() as usize;
        // A wall is `cell * 2` (its east side) or `cell * 2 + 1` (its north side).
        let mut walls: Vec<u32> = Vec::with_capacity(2 * cells);
        for y in 0..height {
            for x in 0..width {
                let index = (y * width + x) as u32;
                if x + 1 < width {
                    walls.push(2 * index);
                }
                if y + 1 < height {
                    walls.push(2 * index + 1);
                }
            }
        }
        rng.shuffle(&mut walls);
        let ends = |wall: u32| {
            let index = (wall / 2) as usize;
            if wall.is_multiple_of(2) {
                (index, index + 1, Direction::East)
            } else {
                (index, index + width, Direction::North)
            }
        };
        let mut sets = UnionFind::new(cells);
        // Opened walls are marked in a bitset (a quarter of the maze's size, so it stays
        // in cache) and carved afterwards in one row-major pass: sequential writes
        // instead of two random ones per opened wall.
        let mut opened = FixedBitSet::with_capacity(2 * cells);
        let mut remaining = cells - 1;
        for (i, &wall) in walls.iter().enumerate() {
            if remaining == 0 {
                break;
            }
            if let Some(&ahead) = walls.get(i + LOOKAHEAD) {
                let (a, b, _) = ends(ahead);
                sets.prefetch(a);
                sets.prefetch(b);
            }
            if let Some(&ahead) = walls.get(i + LOOKAHEAD / 2) {
                let (a, b, _) = ends(ahead);
                sets.prefetch_parent(a);
                sets.prefetch_parent(b);
            }
            if let Some(&ahead) = walls.get(i + LOOKAHEAD / 4) {
                let (a, b, _) = ends(ahead);
                sets.prefetch_grandparent(a);
                sets.prefetch_grandparent(b);
            }
            let (a, b, _) = ends(wall);
            if sets.union(a, b) {
                opened.insert(wall as usize);
                remaining -= 1;
            }
        }
        for wall in opened.ones() {
            let (a, _, dir) = ends(wall as u32);
            maze.carve(a, dir);
        }
    }
}

/// Disjoint sets of cells in one array: a cell's entry is its parent's index, or, for
/// the root of a set, [`ROOT`] plus the rank (an upper bound of the tree's height, at
/// most log2 n). Keeping the rank in the root's own entry saves a cache miss per union.
struct UnionFind {
    entry: Vec<u32>,
}

/// Marks a root's entry (cell indices stay below 2^24).
const ROOT: u32 = 1 << 31;

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            entry: vec![ROOT; n],
        }
    }

    fn prefetch(&self, x: usize) {
        prefetch(&self.entry[x]);
    }

    fn prefetch_parent(&self, x: usize) {
        let parent = self.entry[x];
        if parent & ROOT == 0 {
            prefetch(&self.entry[parent as usize]);
        }
    }

    fn prefetch_grandparent(&self, x: usize) {
        let parent = self.entry[x];
        if parent & ROOT == 0 {
            self.prefetch_parent(parent as usize);
        }
    }

    /// The root of `x`'s set, halving the path on the way.
    fn find(&mut self, mut x: u32) -> u32 {
        loop {
            let parent = self.entry[x as usize];
            if parent & ROOT != 0 {
                return x;
            }
            let grandparent = self.entry[parent as usize];
            if grandparent & ROOT != 0 {
                return parent;
            }
            self.entry[x as usize] = grandparent;
            x = grandparent;
        }
    }

    /// Joins the sets of `a` and `b` (union by rank); `false` if they were already one.
    fn union(&mut self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.find(a as u32), self.find(b as u32));
        if ra == rb {
            return false;
        }
        let (rank_a, rank_b) = (self.entry[ra as usize], self.entry[rb as usize]);
        if rank_a < rank_b {
            self.entry[ra as usize] = rb;
        } else {
            self.entry[rb as usize] = ra;
            if rank_a == rank_b {
                self.entry[ra as usize] += 1;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_find_joins_sets_once() {
        let mut sets = UnionFind::new(6);
        assert!(sets.union(0, 1));
        assert!(sets.union(2, 3));
        assert!(!sets.union(1, 0));
        assert!(sets.union(1, 3));
        assert!(!sets.union(0, 2));
        assert_eq!(sets.find(3), sets.find(0));
        assert_ne!(sets.find(4), sets.find(0));
    }
}
