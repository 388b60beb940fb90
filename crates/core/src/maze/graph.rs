//! petgraph's view of a [`Maze`]: cells are nodes (their row-major index as `u32`),
//! open passages are undirected edges. With these trait impls petgraph's algorithms
//! (`Bfs`, `depth_first_search`, `connected_components`, ...) run on the compact maze
//! directly, with no copy into a `petgraph::Graph`. The value traits are implemented
//! on `Maze` (petgraph lifts them to `&Maze`), the iterator traits on `&Maze`.

use fixedbitset::FixedBitSet;
use petgraph::Undirected;
use petgraph::visit::{
    Data, GraphBase, GraphProp, IntoEdgeReferences, IntoNeighbors, IntoNodeIdentifiers,
    NodeCompactIndexable, NodeCount, NodeIndexable, Visitable,
};

use super::grid::Direction;
use super::model::Maze;

impl GraphBase for Maze {
    type NodeId = u32;
    type EdgeId = (u32, u32);
}

impl GraphProp for Maze {
    type EdgeType = Undirected;
}

impl Data for Maze {
    type NodeWeight = ();
    type EdgeWeight = ();
}

impl NodeCount for Maze {
    fn node_count(&self) -> usize {
        self.grid().cell_count()
    }
}

impl NodeIndexable for Maze {
    fn node_bound(&self) -> usize {
        self.grid().cell_count()
    }

    fn to_index(&self, node: u32) -> usize {
        node as usize
    }

    fn from_index(&self, index: usize) -> u32 {
        index as u32
    }
}

impl NodeCompactIndexable for Maze {}

impl Visitable for Maze {
    type Map = FixedBitSet;

    fn visit_map(&self) -> FixedBitSet {
        FixedBitSet::with_capacity(self.grid().cell_count())
    }

    fn reset_map(&self, map: &mut FixedBitSet) {
        map.clear();
        map.grow(self.grid().cell_count());
    }
}

/// The cells joined to one cell by a passage.
///
/// A passage never leaves the grid (a [`Maze`] refuses one when it is carved or read), so
/// the neighbour across an open side is one step away with no edge test: this iterator is
/// in the inner loop of every breadth-first search.
#[derive(Debug, Clone)]
pub struct OpenNeighbours {
    cell: u32,
    width: u32,
    remaining: u8,
}

impl Iterator for OpenNeighbours {
    type Item = u32;

    #[inline]
    fn next(&mut self) -> Option<u32> {
        if self.remaining == 0 {
            return None;
        }
        let bit = self.remaining & self.remaining.wrapping_neg();
        self.remaining &= !bit;
        Some(match Direction::ALL[bit.trailing_zeros() as usize] {
            Direction::East => self.cell + 1,
            Direction::North => self.cell + self.width,
            Direction::West => self.cell - 1,
            Direction::South => self.cell - self.width,
        })
    }
}

impl IntoNeighbors for &Maze {
    type Neighbors = OpenNeighbours;

    fn neighbors(self, node: u32) -> OpenNeighbours {
        OpenNeighbours {
            cell: node,
            width: self.grid().width(),
            remaining: self.mask(node as usize),
        }
    }
}

/// Every cell of the maze, by index.
pub type CellIds = std::ops::Range<u32>;

impl IntoNodeIdentifiers for &Maze {
    type NodeIdentifiers = CellIds;

    fn node_identifiers(self) -> CellIds {
        0..self.grid().cell_count() as u32
    }
}

/// Every passage once, as (cell, east or north neighbour, no weight).
#[derive(Debug, Clone)]
pub struct PassageRefs<'a> {
    maze: &'a Maze,
    cell: usize,
    pending: u8,
}

impl<'a> Iterator for PassageRefs<'a> {
    type Item = (u32, u32, &'a ());

    fn next(&mut self) -> Option<Self::Item> {
        const FORWARD: u8 = Direction::East.bit() | Direction::North.bit();
        let grid = self.maze.grid();
        loop {
            if self.pending != 0 {
                let bit = self.pending & self.pending.wrapping_neg();
                self.pending &= !bit;
                let dir = Direction::ALL[bit.trailing_zeros() as usize];
                let next = grid.step_index(self.cell, dir)?;
                return Some((self.cell as u32, next as u32, &()));
            }
            self.cell = self.cell.wrapping_add(1);
            if self.cell >= grid.cell_count() {
                return None;
            }
            self.pending = self.maze.mask(self.cell) & FORWARD;
        }
    }
}

impl<'a> IntoEdgeReferences for &'a Maze {
    type EdgeRef = (u32, u32, &'a ());
    type EdgeReferences = PassageRefs<'a>;

    fn edge_references(self) -> PassageRefs<'a> {
        PassageRefs {
            maze: self,
            cell: usize::MAX,
            pending: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maze::grid::Grid;
    use petgraph::algo::connected_components;
    use petgraph::visit::Bfs;

    fn l_shape() -> Maze {
        let mut maze = Maze::closed(Grid::new(2, 2).unwrap());
        maze.carve(0, Direction::East);
        maze.carve(1, Direction::North);
        maze
    }

    #[test]
    fn petgraph_sees_the_passages() {
        let maze = l_shape();
        assert_eq!(connected_components(&maze), 2);
        let mut order = Vec::new();
        let mut bfs = Bfs::new(&maze, 0u32);
        while let Some(node) = bfs.next(&maze) {
            order.push(node);
        }
        assert_eq!(order, vec![0, 1, 3]);
        let edges: Vec<_> = (&maze).edge_references().map(|(a, b, _)| (a, b)).collect();
        assert_eq!(edges, vec![(0, 1), (1, 3)]);
        assert_eq!((&maze).neighbors(1).collect::<Vec<_>>(), vec![3, 0]);
    }
}
