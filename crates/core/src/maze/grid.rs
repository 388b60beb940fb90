//! Rectangular grids: their size limits, cells, directions and index arithmetic.

use std::fmt;

/// The largest grid we build: 4096 x 4096 cells. Larger requests are refused before any
/// allocation, with an error that names this limit.
pub const MAX_CELLS: u64 = 4096 * 4096;

/// A cell's column (`x`, growing east) and row (`y`, growing north), both from 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Cell {
    /// Column, 0 at the west edge.
    pub x: u32,
    /// Row, 0 at the south edge.
    pub y: u32,
}

impl Cell {
    /// The cell at column `x`, row `y`.
    pub const fn new(x: u32, y: u32) -> Self {
        Self { x, y }
    }
}

impl fmt::Display for Cell {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({},{})", self.x, self.y)
    }
}

/// One of the four passage directions. The discriminant is the direction's bit in a
/// cell's open-passage mask (also the layout's hex digit encoding).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(u8)]
pub enum Direction {
    /// +x.
    East = 1,
    /// +y.
    North = 2,
    /// -x.
    West = 4,
    /// -y.
    South = 8,
}

impl Direction {
    /// All four, in bit order.
    pub const ALL: [Direction; 4] = [
        Direction::East,
        Direction::North,
        Direction::West,
        Direction::South,
    ];

    /// This direction's bit in an open-passage mask.
    pub const fn bit(self) -> u8 {
        self as u8
    }

    /// The direction back.
    pub const fn opposite(self) -> Direction {
        match self {
            Direction::East => Direction::West,
            Direction::North => Direction::South,
            Direction::West => Direction::East,
            Direction::South => Direction::North,
        }
    }

    /// `true` for east and west.
    pub const fn is_horizontal(self) -> bool {
        matches!(self, Direction::East | Direction::West)
    }
}

/// Why a grid size was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    /// A side of 0 cells.
    #[error("grid size {width}x{height}: both sides need at least 1 cell")]
    Empty {
        /// Requested columns.
        width: u64,
        /// Requested rows.
        height: u64,
    },
    /// More cells than [`MAX_CELLS`].
    #[error(
        "grid size {width}x{height} has {cells} cells; the limit is {MAX_CELLS} cells (4096x4096)"
    )]
    TooLarge {
        /// Requested columns.
        width: u64,
        /// Requested rows.
        height: u64,
        /// Their product.
        cells: u128,
    },
}

/// A `width` x `height` grid of cells, indexed row by row from the south-west corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Grid {
    width: u32,
    height: u32,
}

impl Grid {
    /// A grid of `width` columns and `height` rows, checked against the size limits.
    pub fn new(width: u64, height: u64) -> Result<Self, GridError> {
        if width == 0 || height == 0 {
            return Err(GridError::Empty { width, height });
        }
        let cells = u128::from(width) * u128::from(height);
        if cells > u128::from(MAX_CELLS) {
            return Err(GridError::TooLarge {
                width,
                height,
                cells,
            });
        }
        // Both fit in u32 because their product is at most 2^24.
        Ok(Self {
            width: width as u32,
            height: height as u32,
        })
    }

    /// Number of columns (cells along x).
    pub const fn width(&self) -> u32 {
        self.width
    }

    /// Number of rows (cells along y; row 0 is the south row).
    pub const fn height(&self) -> u32 {
        self.height
    }

    /// Number of cells.
    pub const fn cell_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// `true` if `cell` lies on this grid.
    pub const fn contains(&self, cell: Cell) -> bool {
        cell.x < self.width && cell.y < self.height
    }

    /// The row-major index of `cell` (which must be on the grid).
    pub const fn index(&self, cell: Cell) -> usize {
        cell.y as usize * self.width as usize + cell.x as usize
    }

    /// The cell with row-major index `index`.
    pub const fn cell(&self, index: usize) -> Cell {
        Cell::new(
            (index % self.width as usize) as u32,
            (index / self.width as usize) as u32,
        )
    }

    /// The neighbour of `cell` in direction `dir`, if it is on the grid.
    pub const fn step(&self, cell: Cell, dir: Direction) -> Option<Cell> {
        match dir {
            Direction::East if cell.x + 1 < self.width => Some(Cell::new(cell.x + 1, cell.y)),
            Direction::North if cell.y + 1 < self.height => Some(Cell::new(cell.x, cell.y + 1)),
            Direction::West if cell.x > 0 => Some(Cell::new(cell.x - 1, cell.y)),
            Direction::South if cell.y > 0 => Some(Cell::new(cell.x, cell.y - 1)),
            _ => None,
        }
    }

    /// The index of the neighbour of cell `index` in direction `dir`, if it is on the grid.
    /// The fast path for generators: no [`Cell`] round trip.
    #[inline]
    pub fn step_index(&self, index: usize, dir: Direction) -> Option<usize> {
        let w = self.width as usize;
        match dir {
            Direction::East if (index % w) + 1 < w => Some(index + 1),
            Direction::North if index + w < self.cell_count() => Some(index + w),
            Direction::West if !index.is_multiple_of(w) => Some(index - 1),
            Direction::South if index >= w => Some(index - w),
            _ => None,
        }
    }

    /// Number of passages a spanning tree of this grid has: cells - 1.
    pub const fn tree_edge_count(&self) -> usize {
        self.cell_count() - 1
    }
}

impl fmt::Display for Grid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_checked_before_allocation() {
        assert!(matches!(Grid::new(0, 5), Err(GridError::Empty { .. })));
        let err = Grid::new(100_000, 100_000).unwrap_err();
        assert!(err.to_string().contains("4096x4096"), "{err}");
        assert!(Grid::new(u64::MAX, u64::MAX).is_err());
        assert_eq!(Grid::new(4096, 4096).unwrap().cell_count(), 1 << 24);
        assert_eq!(Grid::new(1, 1 << 24).unwrap().height(), 1 << 24);
    }

    #[test]
    fn index_and_cell_round_trip() {
        let grid = Grid::new(5, 3).unwrap();
        for i in 0..grid.cell_count() {
            assert_eq!(grid.index(grid.cell(i)), i);
        }
        assert_eq!(grid.cell(7), Cell::new(2, 1));
    }

    #[test]
    fn steps_stop_at_the_edges() {
        let grid = Grid::new(3, 2).unwrap();
        let corner = Cell::new(0, 0);
        assert_eq!(grid.step(corner, Direction::West), None);
        assert_eq!(grid.step(corner, Direction::South), None);
        assert_eq!(grid.step(corner, Direction::East), Some(Cell::new(1, 0)));
        assert_eq!(grid.step(Cell::new(2, 1), Direction::North), None);
        for i in 0..grid.cell_count() {
            for dir in Direction::ALL {
                let by_cell = grid.step(grid.cell(i), dir).map(|c| grid.index(c));
                assert_eq!(grid.step_index(i, dir), by_cell);
            }
        }
    }
}
