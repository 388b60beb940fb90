//! The union-find both halves of Kruskal use, and the prefetching loop that feeds it.

use crate::rng::prefetch;

/// Disjoint sets in one array: an entry is its parent's index, or, for the root of a set,
/// [`ROOT`] plus the rank (an upper bound of the tree's height, at most log2 n). Keeping
/// the rank in the root's own entry saves a cache miss per union. Union by rank, path
/// halving.
pub(super) struct UnionFind {
    entry: Vec<u32>,
}

/// Marks a root's entry (indices stay below 2^26).
const ROOT: u32 = 1 << 31;

impl UnionFind {
    /// `n` elements, each in a set of its own.
    pub fn new(n: usize) -> Self {
        Self {
            entry: vec![ROOT; n],
        }
    }

    /// `n` elements, those in `joined` already in one set (rooted at the first of them).
    pub fn with_joined(n: usize, joined: impl IntoIterator<Item = usize>) -> Self {
        let mut sets = Self::new(n);
        let mut joined = joined.into_iter();
        if let Some(root) = joined.next() {
            // A star: every member one step from the root, so its height (rank) is 1.
            sets.entry[root] = ROOT + 1;
            for member in joined {
                sets.entry[member] = root as u32;
            }
        }
        sets
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
    #[inline]
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

    /// Joins the sets of `a` and `b`; `false` if they were already one.
    #[inline]
    pub fn union(&mut self, a: usize, b: usize) -> bool {
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

    /// Calls [`union`](Self::union) on the two `ends` of every wall of `walls`, in order,
    /// and hands each wall and its result to `decided`.
    ///
    /// The sets are far larger than the caches on big grids, so the cells of the wall
    /// [`LOOKAHEAD`] steps ahead are prefetched, their parents half as far ahead and their
    /// grandparents a quarter, each once the level below has had time to arrive.
    pub fn union_each(
        &mut self,
        walls: &[u32],
        ends: impl Fn(u32) -> (usize, usize),
        mut decided: impl FnMut(u32, bool),
    ) {
        for (i, &wall) in walls.iter().enumerate() {
            if let Some(&ahead) = walls.get(i + LOOKAHEAD) {
                let (a, b) = ends(ahead);
                self.prefetch(a);
                self.prefetch(b);
            }
            if let Some(&ahead) = walls.get(i + LOOKAHEAD / 2) {
                let (a, b) = ends(ahead);
                self.prefetch_parent(a);
                self.prefetch_parent(b);
            }
            if let Some(&ahead) = walls.get(i + LOOKAHEAD / 4) {
                let (a, b) = ends(ahead);
                self.prefetch_grandparent(a);
                self.prefetch_grandparent(b);
            }
            let (a, b) = ends(wall);
            decided(wall, self.union(a, b));
        }
    }
}

/// How many walls ahead [`UnionFind::union_each`] prefetches a wall's cells.
const LOOKAHEAD: usize = 32;

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

    #[test]
    fn joined_members_start_in_one_set() {
        let mut sets = UnionFind::with_joined(6, [4, 1, 5]);
        assert!(!sets.union(1, 5));
        assert!(!sets.union(4, 1));
        assert!(sets.union(0, 5));
        assert!(sets.union(2, 3));
        assert!(!sets.union(0, 4));
        assert_ne!(sets.find(2), sets.find(0));
    }

    #[test]
    fn walls_are_decided_in_order() {
        let walls = [1, 2, 3, 4];
        let ends = |wall: u32| (0, wall as usize % 2 + 1);
        let mut decided = Vec::new();
        UnionFind::new(3).union_each(&walls, ends, |w, joined| decided.push((w, joined)));
        assert_eq!(decided, [(1, true), (2, true), (3, false), (4, false)]);
    }
}
