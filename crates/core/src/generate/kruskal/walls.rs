//! The inner walls of a grid, named so that both the cells a wall separates and the two
//! corners it runs between are a few additions away.
//!
//! A wall is `2 * q` (the east side of a cell) or `2 * q + 1` (its north side), where
//! `q = y * stride + x` numbers the cells row by row with one spare column
//! (`stride = width + 1`). The spare column makes the corners just as easy: the corner
//! south-west of cell (x, y) is `y * stride + x`, on a grid of `stride` x `height + 1`
//! corners whose outer ring is the maze's border.

use fixedbitset::FixedBitSet;

use crate::maze::{Direction, Grid};

use super::union_find::UnionFind;

/// A grid's inner walls and the arithmetic on their names (see the module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct Walls {
    width: usize,
    height: usize,
    stride: usize,
}

impl Walls {
    /// The walls of `grid`.
    pub fn new(grid: Grid) -> Self {
        let width = grid.width() as usize;
        Self {
            width,
            height: grid.height() as usize,
            stride: width + 1,
        }
    }

    /// Every inner wall, cell by cell in row-major order, each cell's east before its
    /// north: the order the shuffle starts from (so it decides the maze).
    pub fn list(&self) -> Vec<u32> {
        let mut walls = Vec::with_capacity(2 * self.width * self.height);
        for y in 0..self.height {
            for x in 0..self.width {
                let q = (y * self.stride + x) as u32;
                if x + 1 < self.width {
                    walls.push(2 * q);
                }
                if y + 1 < self.height {
                    walls.push(2 * q + 1);
                }
            }
        }
        walls
    }

    /// How many names there are (a bitset over walls needs this many bits).
    pub fn name_count(&self) -> usize {
        2 * self.stride * self.height
    }

    /// Sets over the cells, each cell in its own.
    pub fn cell_sets(&self) -> UnionFind {
        UnionFind::new(self.stride * self.height)
    }

    /// The two cells `wall` separates.
    #[inline]
    pub fn cells(&self, wall: u32) -> (usize, usize) {
        let q = (wall / 2) as usize;
        if wall.is_multiple_of(2) {
            (q, q + 1)
        } else {
            (q, q + self.stride)
        }
    }

    /// Sets over the corners, the border's all in one set.
    pub fn corner_sets(&self) -> UnionFind {
        let (columns, rows) = (self.stride, self.height + 1);
        let sides = (1..rows - 1).flat_map(|y| [y * columns, y * columns + columns - 1]);
        let border = (0..columns)
            .chain(sides)
            .chain((rows - 1) * columns..rows * columns);
        UnionFind::with_joined(columns * rows, border)
    }

    /// The two corners `wall` runs between: for the east side of a cell its south-east and
    /// north-east corner, for the north side its north-west and north-east corner.
    #[inline]
    pub fn corners(&self, wall: u32) -> (usize, usize) {
        let q = (wall / 2) as usize;
        let north_east = q + self.stride + 1;
        if wall.is_multiple_of(2) {
            (q + 1, north_east)
        } else {
            (q + self.stride, north_east)
        }
    }

    /// Calls `open` with every wall in `opened`, as the row-major index of the cell west
    /// or south of it and the direction to cross it, in row-major order. The set walls are
    /// visited directly (no test per wall, whose outcome the CPU could not guess), and the
    /// row is followed along instead of divided out.
    pub fn for_each_opened(&self, opened: &FixedBitSet, mut open: impl FnMut(usize, Direction)) {
        let (mut row_start, mut row_index) = (0, 0);
        for wall in opened.ones() {
            let q = wall / 2;
            while q >= row_start + self.stride {
                row_start += self.stride;
                row_index += self.width;
            }
            let dir = match wall % 2 {
                0 => Direction::East,
                _ => Direction::North,
            };
            open(row_index + q - row_start, dir);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_name_their_cells_and_corners() {
        // 3 x 2 cells: q = y * 4 + x; corners on a 4 x 3 grid.
        let walls = Walls::new(Grid::new(3, 2).unwrap());
        assert_eq!(walls.list(), [0, 1, 2, 3, 5, 8, 10]);
        // East of cell (1, 0): cells 1 and 2, corners (2, 0) and (2, 1).
        assert_eq!(walls.cells(2), (1, 2));
        assert_eq!(walls.corners(2), (2, 6));
        // North of cell (1, 0): cells (1, 0) and (1, 1), corners (1, 1) and (2, 1).
        assert_eq!(walls.cells(3), (1, 5));
        assert_eq!(walls.corners(3), (5, 6));
        let mut opened = FixedBitSet::with_capacity(walls.name_count());
        opened.insert(3);
        opened.insert(10);
        let mut openings = Vec::new();
        walls.for_each_opened(&opened, |index, dir| openings.push((index, dir)));
        assert_eq!(openings, [(1, Direction::North), (4, Direction::East)]);
    }

    #[test]
    fn the_border_is_one_set_and_inner_corners_are_apart() {
        let walls = Walls::new(Grid::new(3, 2).unwrap());
        let mut corners = walls.corner_sets();
        // Corners 5 and 6 are the only inner ones; 0, 3, 8 and 11 are border corners.
        assert!(!corners.union(0, 11));
        assert!(!corners.union(3, 8));
        assert!(corners.union(5, 6));
        assert!(corners.union(6, 7));
        assert!(!corners.union(5, 0));
    }
}
