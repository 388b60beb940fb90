//! What a wall maze's SVG and PNG pictures show besides the floor: its walls as dark bars,
//! merged into runs along the lattice lines, and its goal region.
//!
//! The walls are drawn from the passages and the wall template, never from the layout's
//! `walls`: a renderer is only given layouts that passed [`crate::validate::checked`],
//! which proves that the walls on every lattice line cover exactly its closed sides
//! ([`crate::layout::walls::is_closed`]), corner to corner, the template's thickness across.
//! So a run of closed sides is one bar from its first lattice corner to its last: where
//! two runs meet at a right angle, the picture (like the cuboids) leaves a notch
//! `thickness / 2` square at the outer corner. A maze with posts has one more square, the
//! post's, at every lattice corner (validation proves one stands at each), drawn with the
//! bars: walls and posts together cover each closed side corner to corner.

use super::{RenderError, Result};

use crate::layout::Layout;
use crate::layout::runs::OpenSides;
use crate::maze::{Cell, Maze};

/// What a wall maze draws besides the floor and the markers.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Walls {
    /// The wall template's thickness, metres.
    pub thickness: f64,
    /// The outer sides left open.
    pub open: OpenSides,
    /// The goal region's cells but the start and end (their markers cover them), tinted.
    pub goal: Vec<Cell>,
    /// The side of the post at every lattice corner, if the maze has posts.
    pub post: Option<f64>,
}

impl Walls {
    /// The walls of `layout`, whose passages are `maze`; `None` for a line maze.
    pub fn of(layout: &Layout, maze: &Maze, start: Cell, end: Cell) -> Result<Option<Self>> {
        if layout.style.is_lines() {
            return Ok(None);
        }
        let spec = layout.wall.as_ref().ok_or_else(|| {
            RenderError::Layout("a layout with style \"walls\" needs its wall template".into())
        })?;
        let goal = layout
            .end
            .region
            .iter()
            .map(|&[x, y]| Cell::new(x, y))
            .filter(|&c| c != start && c != end && maze.grid().contains(c))
            .collect();
        Ok(Some(Self {
            thickness: spec.thickness,
            open: OpenSides::of(maze, &spec.openings),
            goal,
            post: layout.post.as_ref().map(|post| post.size),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::passages;
    use crate::layout::runs::tests::wall_layout;
    use crate::maze::Grid;

    #[test]
    fn the_goal_tint_leaves_the_markers_cells_out() {
        let mut layout = wall_layout(3, 2, 1, 0.0, "none");
        layout.start.cell = [0, 0];
        layout.end.cell = [2, 1];
        layout.end.region = vec![[2, 1], [1, 1], [2, 0]];
        let maze = passages::decode(Grid::new(3, 2).unwrap(), &layout.passages).unwrap();
        let walls = Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1))
            .unwrap()
            .unwrap();
        assert_eq!(walls.goal, [Cell::new(1, 1), Cell::new(2, 0)]);
        assert_eq!(walls.thickness, 0.05);
        layout.wall = None;
        assert!(Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1)).is_err());
        layout.style = crate::layout::Style::Lines;
        assert_eq!(
            Walls::of(&layout, &maze, Cell::new(0, 0), Cell::new(2, 1)).unwrap(),
            None
        );
    }
}
