//! Terminal pictures: walls as `+---+`, north at the top, `S` start, `E` end, `G` the rest
//! of a goal region, `.` the solution. A wall maze's openings are gaps in the outer wall.

use std::io::{BufWriter, Write};

use super::Result;
use crate::progress::Progress;

use super::{MazeView, RenderOptions, Renderer};
use crate::layout::Layout;
use crate::maze::{Cell, Direction};

/// The ASCII renderer.
#[derive(Debug, Clone, Copy, Default)]
pub struct Ascii;

impl Renderer for Ascii {
    /// Sets `progress` to the maze's rows and advances it a row at a time.
    fn render(
        &self,
        layout: &Layout,
        options: &RenderOptions,
        out: &mut dyn Write,
        progress: &dyn Progress,
    ) -> Result<()> {
        let view = MazeView::of(layout, options)?;
        let grid = view.maze.grid();
        progress.set_length(u64::from(grid.height()));
        let mut on_path = vec![false; grid.cell_count()];
        for cell in &view.solution {
            on_path[grid.index(*cell)] = true;
        }
        // the outer sides a wall maze leaves open
        let openings: Vec<(Cell, Direction)> = layout
            .wall
            .iter()
            .flat_map(|w| &w.openings)
            .map(|o| (Cell::new(o.cell[0], o.cell[1]), o.side.direction()))
            .collect();
        let open = |cell: Cell, dir: Direction| {
            view.maze.is_open(grid.index(cell), dir) || openings.contains(&(cell, dir))
        };
        let goal: Vec<Cell> = layout
            .end
            .region
            .iter()
            .map(|c| Cell::new(c[0], c[1]))
            .collect();
        let mut out = BufWriter::new(out);
        let mut line = String::new();
        let wall_row = |line: &mut String, y: u32, dir: Direction| {
            line.clear();
            line.push('+');
            for x in 0..grid.width() {
                let open = open(Cell::new(x, y), dir);
                line.push_str(if open { "   +" } else { "---+" });
            }
            line.push('\n');
        };
        for y in (0..grid.height()).rev() {
            wall_row(&mut line, y, Direction::North);
            out.write_all(line.as_bytes())?;
            line.clear();
            line.push(if open(Cell::new(0, y), Direction::West) {
                ' '
            } else {
                '|'
            });
            for x in 0..grid.width() {
                let cell = Cell::new(x, y);
                line.push(' ');
                line.push(mark(&view, &goal, on_path[grid.index(cell)], cell));
                line.push(' ');
                line.push(if open(cell, Direction::East) {
                    ' '
                } else {
                    '|'
                });
            }
            line.push('\n');
            out.write_all(line.as_bytes())?;
            progress.advance(1);
        }
        wall_row(&mut line, 0, Direction::South);
        out.write_all(line.as_bytes())?;
        out.flush()?;
        Ok(())
    }
}

/// What `cell` shows: `S` start, `E` end, `G` the rest of a goal region, `.` the solution
/// (`on_path`), else a space.
fn mark(view: &MazeView, goal: &[Cell], on_path: bool, cell: Cell) -> char {
    if cell == view.start {
        'S'
    } else if cell == view.end {
        'E'
    } else if goal.contains(&cell) {
        'G'
    } else if on_path {
        '.'
    } else {
        ' '
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
        let mut bytes = Vec::new();
        Ascii
            .render(
                &layout,
                &RenderOptions {
                    solution: true,
                    ..Default::default()
                },
                &mut bytes,
                &crate::progress::Silent,
            )
            .unwrap();
        let text = String::from_utf8(bytes).unwrap();
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

    #[test]
    fn wall_openings_are_gaps_in_the_outer_wall() {
        let grid = Grid::new(3, 2).unwrap();
        let mut layout = build_layout(&GenerateSpec::course(grid, Algorithm::Dfs, 1)).unwrap();
        let maze = crate::layout::passages::decode(grid, &layout.passages).unwrap();
        let options = crate::layout::walls::WallOptions {
            openings: "start".parse().unwrap(),
            ..Default::default()
        };
        crate::layout::walls::into_walls(&mut layout, &maze, &options, true).unwrap();
        let picture = crate::render::Format::Ascii
            .render_to_vec(
                &layout,
                &RenderOptions {
                    solution: false,
                    ..Default::default()
                },
            )
            .unwrap();
        let text = String::from_utf8(picture).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        // the start (0,0) opens south: a gap at the west end of the bottom wall
        assert_eq!(lines[4], "+   +---+---+", "{text}");
    }
}
