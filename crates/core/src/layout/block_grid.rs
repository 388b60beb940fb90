//! A layout as a block grid: the `maze_map` of Gymnasium-Robotics' PointMaze and AntMaze
//! (and the grid MiniGrid builds). A W x H maze becomes 2H+1 rows of 2W+1 blocks: the cell
//! (x, y) is block (2(H-1-y)+1, 2x+1), the block between two cells is free where a passage
//! joins them, every other block is a wall. Row 0 is the north edge, as PointMaze draws its
//! map (row i at y = +(rows-1)/2 - i blocks). The outer border is always wall, so a wall
//! maze's openings are closed: PointMaze's arena has no outside. A line maze means the same
//! graph: a passage is a free block, everything the robot may not cross is a wall.

use serde::Serialize;

use crate::layout::Layout;
use crate::layout::passages;
use crate::maze::{Cell, Direction, Grid, GridError};

/// Why a layout has no block grid.
#[derive(Debug, thiserror::Error)]
pub enum BlockGridError {
    /// The layout's grid is no grid.
    #[error("grid: {0}")]
    Grid(#[from] GridError),
    /// Its passages do not decode.
    #[error("{0}")]
    Passages(String),
    /// An endpoint's cell lies off the grid.
    #[error("endpoint cell {cell} is outside the {grid} grid")]
    Outside {
        /// The endpoint's cell.
        cell: Cell,
        /// The layout's grid.
        grid: Grid,
    },
}

/// One block of the grid, serialized as PointMaze reads it: `1`, `0`, `"r"`, `"g"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// A wall (`1`).
    Wall,
    /// Free floor (`0`).
    Free,
    /// The start cell, where the agent is reset (`"r"`).
    Reset,
    /// The end cell, the goal (`"g"`).
    Goal,
}

impl Serialize for Block {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Block::Wall => serializer.serialize_u8(1),
            Block::Free => serializer.serialize_u8(0),
            Block::Reset => serializer.serialize_str("r"),
            Block::Goal => serializer.serialize_str("g"),
        }
    }
}

/// The block grid of a layout, with the block size that keeps the layout's cell size.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockGrid {
    /// Rows of blocks, row 0 the north edge, column 0 the west edge.
    pub maze_map: Vec<Vec<Block>>,
    /// A block's side in metres: half the layout's cell size, since a cell and the wall
    /// beside it are two blocks (PointMaze's `maze_size_scaling`).
    pub maze_size_scaling: f64,
}

impl BlockGrid {
    /// The block grid of `layout`, or why its passages do not decode.
    pub fn of(layout: &Layout) -> Result<BlockGrid, BlockGridError> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())?;
        let maze = passages::decode(grid, &layout.passages).map_err(BlockGridError::Passages)?;
        let (width, height) = (grid.width() as usize, grid.height() as usize);
        let mut maze_map = vec![vec![Block::Wall; 2 * width + 1]; 2 * height + 1];
        for index in 0..grid.cell_count() {
            let cell = grid.cell(index);
            let [row, column] = block_of(grid, cell);
            maze_map[row][column] = Block::Free;
            if maze.is_open(index, Direction::East) {
                maze_map[row][column + 1] = Block::Free;
            }
            if maze.is_open(index, Direction::North) {
                maze_map[row - 1][column] = Block::Free;
            }
        }
        for (endpoint, block) in [(&layout.start, Block::Reset), (&layout.end, Block::Goal)] {
            let cell = Cell::new(endpoint.cell[0], endpoint.cell[1]);
            if !grid.contains(cell) {
                return Err(BlockGridError::Outside { cell, grid });
            }
            let [row, column] = block_of(grid, cell);
            maze_map[row][column] = block;
        }
        Ok(BlockGrid {
            maze_map,
            maze_size_scaling: layout.grid.cell_size / 2.0,
        })
    }
}

/// The block (row, column) of `cell`.
pub fn block_of(grid: Grid, cell: Cell) -> [usize; 2] {
    [
        2 * (grid.height() - 1 - cell.y) as usize + 1,
        2 * cell.x as usize + 1,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maze::analysis::shortest_path;
    use std::path::Path;

    fn golden(name: &str) -> Layout {
        crate::layout::read_layout(
            &Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../mazes")
                .join(name),
        )
        .unwrap()
    }

    /// Every free block reached from the reset block by steps between free blocks.
    fn reachable(map: &[Vec<Block>], from: [usize; 2]) -> Vec<[usize; 2]> {
        let mut seen = vec![from];
        let mut next = 0;
        while next < seen.len() {
            let [r, c] = seen[next];
            next += 1;
            for [dr, dc] in [[0, 1], [2, 1], [1, 0], [1, 2]] {
                let (r2, c2) = (r + dr - 1, c + dc - 1);
                if map[r2][c2] != Block::Wall && !seen.contains(&[r2, c2]) {
                    seen.push([r2, c2]);
                }
            }
        }
        seen
    }

    #[test]
    fn a_nine_by_nine_maze_is_nineteen_rows_of_nineteen_walled_in() {
        let layout = golden("dfs-9x9-seed42.json");
        let blocks = BlockGrid::of(&layout).unwrap();
        assert_eq!(blocks.maze_map.len(), 19);
        assert!(blocks.maze_map.iter().all(|row| row.len() == 19));
        assert!(blocks.maze_map[0].iter().all(|b| *b == Block::Wall));
        assert!(blocks.maze_map[18].iter().all(|b| *b == Block::Wall));
        assert!(blocks.maze_map.iter().all(|row| row[0] == Block::Wall));
        assert_eq!(blocks.maze_size_scaling, layout.grid.cell_size / 2.0);
    }

    #[test]
    fn free_blocks_are_the_cells_and_passages_of_a_perfect_maze() {
        let layout = golden("prim-20x15-seed7.json");
        let blocks = BlockGrid::of(&layout).unwrap();
        let open = blocks
            .maze_map
            .iter()
            .flatten()
            .filter(|b| **b != Block::Wall)
            .count();
        // a perfect maze: cells plus cells - 1 passages
        assert_eq!(open, 2 * 20 * 15 - 1);
        let grid = Grid::new(20, 15).unwrap();
        let start = block_of(grid, Cell::new(layout.start.cell[0], layout.start.cell[1]));
        assert_eq!(blocks.maze_map[start[0]][start[1]], Block::Reset);
        assert_eq!(reachable(&blocks.maze_map, start).len(), open);
    }

    #[test]
    fn the_solution_walks_free_blocks_from_reset_to_goal() {
        for name in ["dfs-9x9-seed42-walls.json", "dfs-micromouse-seed42.json"] {
            let layout = golden(name);
            let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into()).unwrap();
            let maze = passages::decode(grid, &layout.passages).unwrap();
            let [start, end] =
                [&layout.start, &layout.end].map(|e| grid.index(Cell::new(e.cell[0], e.cell[1])));
            let path = shortest_path(&maze, start, end).unwrap();
            let map = BlockGrid::of(&layout).unwrap().maze_map;
            for pair in path.windows(2) {
                let [a, b] = [pair[0], pair[1]].map(|i| block_of(grid, grid.cell(i)));
                let between = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
                assert_eq!(map[between[0]][between[1]], Block::Free, "{name}");
            }
            let goal = block_of(grid, grid.cell(end));
            assert_eq!(map[goal[0]][goal[1]], Block::Goal, "{name}");
        }
    }

    #[test]
    fn serializes_as_pointmaze_reads_it() {
        let text =
            serde_json::to_string(&[Block::Wall, Block::Free, Block::Reset, Block::Goal]).unwrap();
        assert_eq!(text, r#"[1,0,"r","g"]"#);
    }
}
