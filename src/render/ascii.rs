//! Terminal pictures: walls as `+---+`, north at the top, `S` start, `E` end, `.` the
//! solution.

use anyhow::Result;

use super::{MazeView, RenderOptions, Renderer};
use crate::layout::Layout;
use crate::maze::{Cell, Direction};

/// The ASCII renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Ascii;

impl Renderer for Ascii {
    fn render(&self, layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>> {
        let view = MazeView::of(layout, options)?;
        let grid = view.maze.grid();
        let mut on_path = vec![false; grid.cell_count()];
        for cell in &view.solution {
            on_path[grid.index(*cell)] = true;
        }
        let mut out = String::new();
        let wall_row = |out: &mut String, y: u32, dir: Direction| {
            out.push('+');
            for x in 0..grid.width() {
                let open = view.maze.is_open(grid.index(Cell::new(x, y)), dir);
                out.push_str(if open { "   +" } else { "---+" });
            }
            out.push('\n');
        };
        for y in (0..grid.height()).rev() {
            wall_row(&mut out, y, Direction::North);
            out.push('|');
            for x in 0..grid.width() {
                let cell = Cell::new(x, y);
                let index = grid.index(cell);
                let mark = if cell == view.start {
                    'S'
                } else if cell == view.end {
                    'E'
                } else if on_path[index] {
                    '.'
                } else {
                    ' '
                };
                out.push(' ');
                out.push(mark);
                out.push(' ');
                out.push(if view.maze.is_open(index, Direction::East) {
                    ' '
                } else {
                    '|'
                });
            }
            out.push('\n');
        }
        wall_row(&mut out, 0, Direction::South);
        Ok(out.into_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    #[test]
    fn draws_walls_and_markers() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(3, 2).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let text = String::from_utf8(
            Ascii
                .render(&layout, &RenderOptions { solution: true })
                .unwrap(),
        )
        .unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 5);
        assert!(lines.iter().all(|l| l.len() == 13));
        assert_eq!(lines[0], "+---+---+---+");
        assert_eq!(lines[4], "+---+---+---+");
        assert!(lines[3].starts_with("| S"), "{text}");
        assert_eq!(text.matches('E').count(), 1);
        // A perfect 3x2 maze has 5 passages: 7 inner walls minus 5 open ones.
        let open_gaps = text.matches("   +").count() + lines[1].matches("   ").count();
        assert!(open_gaps > 0);
    }
}
