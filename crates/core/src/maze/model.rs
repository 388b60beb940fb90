//! The maze itself: a grid plus, for every cell, the set of open passages (one byte).

use super::grid::{Cell, Direction, Grid};

/// A maze on a [`Grid`]: which neighbouring cells are joined by a passage.
///
/// Each cell stores a mask of [`Direction`] bits; a passage is always recorded on both
/// of its cells. One byte per cell, so a 4096 x 4096 maze takes 16 MiB.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Maze {
    grid: Grid,
    open: Vec<u8>,
}

impl Maze {
    /// A maze with every wall standing (no passages).
    pub fn closed(grid: Grid) -> Self {
        Self {
            grid,
            open: vec![0; grid.cell_count()],
        }
    }

    /// A maze from per-cell masks (row-major). `None` if the count is wrong, a mask has
    /// bits beyond the four directions, a passage leaves the grid, or a passage is open on
    /// one side only. [`Maze::check_masks`] says which.
    pub fn from_masks(grid: Grid, open: Vec<u8>) -> Result<Self, String> {
        Self::check_masks(grid, &open)?;
        Ok(Self { grid, open })
    }

    /// Explains the first inconsistency in a set of per-cell masks, if any.
    pub fn check_masks(grid: Grid, open: &[u8]) -> Result<(), String> {
        if open.len() != grid.cell_count() {
            return Err(format!(
                "{} cell masks for a {grid} grid of {} cells",
                open.len(),
                grid.cell_count()
            ));
        }
        for (index, &mask) in open.iter().enumerate() {
            let cell = grid.cell(index);
            if mask & !0x0f != 0 {
                return Err(format!("cell {cell} has mask {mask:#x} beyond 0xf"));
            }
            for dir in Direction::ALL {
                if mask & dir.bit() == 0 {
                    continue;
                }
                match grid.step_index(index, dir) {
                    None => {
                        return Err(format!(
                            "cell {cell} opens {dir:?} off the edge of the grid"
                        ));
                    }
                    Some(next) if open[next] & dir.opposite().bit() == 0 => {
                        return Err(format!(
                            "cell {cell} opens {dir:?} but cell {} does not open {:?}",
                            grid.cell(next),
                            dir.opposite()
                        ));
                    }
                    Some(_) => {}
                }
            }
        }
        Ok(())
    }

    /// The grid this maze lies on.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// The open-passage mask of every cell, row-major.
    pub fn masks(&self) -> &[u8] {
        &self.open
    }

    /// The open-passage mask of cell `index`.
    #[inline]
    pub fn mask(&self, index: usize) -> u8 {
        self.open[index]
    }

    /// Opens the passage from cell `index` in direction `dir` (on both cells).
    ///
    /// # Panics
    /// If that passage would leave the grid: generators only carve inside it.
    #[inline]
    pub fn carve(&mut self, index: usize, dir: Direction) {
        let next = self
            .grid
            .step_index(index, dir)
            .expect("carve leaves the grid");
        self.open[index] |= dir.bit();
        self.open[next] |= dir.opposite().bit();
    }

    /// [`carve`](Self::carve) for a caller that knows the passage stays on the grid
    /// (checked in debug builds only): the neighbour is found without the division that
    /// finds a cell's column, which shows when a generator carves millions of passages.
    #[inline]
    pub(crate) fn carve_inside(&mut self, index: usize, dir: Direction) {
        debug_assert!(
            self.grid.step_index(index, dir).is_some(),
            "carve leaves the grid"
        );
        let width = self.grid.width() as usize;
        let next = match dir {
            Direction::East => index + 1,
            Direction::North => index + width,
            Direction::West => index - 1,
            Direction::South => index - width,
        };
        self.open[index] |= dir.bit();
        self.open[next] |= dir.opposite().bit();
    }

    /// Opens the passage between two neighbouring cells, given by index.
    ///
    /// # Panics
    /// If the cells are not neighbours.
    pub fn carve_between(&mut self, a: usize, b: usize) {
        let dir = self
            .direction_between(a, b)
            .expect("cells are not neighbours");
        self.carve(a, dir);
    }

    /// The direction from cell `a` to its neighbour `b`, if they are neighbours.
    pub fn direction_between(&self, a: usize, b: usize) -> Option<Direction> {
        Direction::ALL
            .into_iter()
            .find(|&dir| self.grid.step_index(a, dir) == Some(b))
    }

    /// `true` if cell `index` has a passage in direction `dir`.
    #[inline]
    pub fn is_open(&self, index: usize, dir: Direction) -> bool {
        self.open[index] & dir.bit() != 0
    }

    /// Number of passages leaving cell `index`.
    #[inline]
    pub fn degree(&self, index: usize) -> u32 {
        self.open[index].count_ones()
    }

    /// The cells joined to cell `index` by a passage.
    pub fn open_neighbours(&self, index: usize) -> impl Iterator<Item = usize> + '_ {
        Direction::ALL
            .into_iter()
            .filter(move |&dir| self.is_open(index, dir))
            .filter_map(move |dir| self.grid.step_index(index, dir))
    }

    /// Number of passages (each counted once).
    pub fn passage_count(&self) -> usize {
        self.open
            .iter()
            .map(|&m| (m & (Direction::East.bit() | Direction::North.bit())).count_ones() as usize)
            .sum()
    }

    /// Every passage once, as (cell, East or North), row-major: the order the layout's
    /// segments follow.
    pub fn passages(&self) -> impl Iterator<Item = (Cell, Direction)> + '_ {
        self.open
            .iter()
            .enumerate()
            .flat_map(move |(index, &mask)| {
                let cell = self.grid.cell(index);
                [Direction::East, Direction::North]
                    .into_iter()
                    .filter(move |dir| mask & dir.bit() != 0)
                    .map(move |dir| (cell, dir))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn carving_opens_both_sides() {
        let grid = Grid::new(3, 3).unwrap();
        let mut maze = Maze::closed(grid);
        maze.carve(4, Direction::North);
        assert!(maze.is_open(4, Direction::North));
        assert!(maze.is_open(7, Direction::South));
        assert_eq!(maze.passage_count(), 1);
        assert_eq!(maze.open_neighbours(4).collect::<Vec<_>>(), vec![7]);
        maze.carve_between(4, 3);
        assert_eq!(maze.degree(4), 2);
        let passages: Vec<_> = maze.passages().collect();
        assert_eq!(
            passages,
            vec![
                (Cell::new(0, 1), Direction::East),
                (Cell::new(1, 1), Direction::North)
            ]
        );
    }

    #[test]
    fn masks_are_checked_for_consistency() {
        let grid = Grid::new(2, 1).unwrap();
        assert!(Maze::from_masks(grid, vec![1, 4]).is_ok());
        let one_sided = Maze::from_masks(grid, vec![1, 0]).unwrap_err();
        assert!(one_sided.contains("does not open West"), "{one_sided}");
        let off_edge = Maze::from_masks(grid, vec![4, 0]).unwrap_err();
        assert!(off_edge.contains("off the edge"), "{off_edge}");
        assert!(Maze::from_masks(grid, vec![0x10, 0]).is_err());
        assert!(Maze::from_masks(grid, vec![0]).is_err());
    }
}
