//! Does a robot fit the maze? A warning, not a problem: the layout is sound either way, but
//! a robot wider than its passages cannot run it.
//!
//! A wall maze's passage is the clear width between two walls, the cell size less the wall
//! thickness (the walls stand centred on the cell sides), or less the post size where posts
//! stand (they are at least as thick as the walls). A line maze has nothing to bump into,
//! but it stands for corridors a cell wide, and its lines lie a cell apart: a robot wider
//! than the cell, centred on one line, covers the neighbouring parallel line wherever two
//! corridors run side by side, so what it sees under itself (a line sensor, a camera
//! looking down at its edge) is no longer one corridor's line. So its "passage" is the cell.

use crate::layout::{Layout, Style};

/// The narrowest passage of a layout and what bounds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Passage {
    /// Its width, metres.
    pub width: f64,
    /// What the width is measured between.
    pub between: Between,
}

/// What bounds a passage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Between {
    /// The walls of a wall maze without posts.
    Walls,
    /// The posts of a wall maze with posts.
    Posts,
    /// The lines of a line maze, a cell apart.
    Lines,
}

impl Between {
    /// The word for them: `walls`, `posts`, `lines`.
    pub fn word(self) -> &'static str {
        match self {
            Between::Walls => "walls",
            Between::Posts => "posts",
            Between::Lines => "lines",
        }
    }
}

/// The narrowest passage a robot of `layout` drives through ([`Passage`]).
pub fn narrowest_passage(layout: &Layout) -> Passage {
    let cell = layout.grid.cell_size;
    match (layout.style, &layout.wall, &layout.post) {
        (Style::Walls, Some(wall), post) => {
            let thickest = post
                .as_ref()
                .map_or(wall.thickness, |p| p.size.max(wall.thickness));
            Passage {
                width: cell - thickest,
                between: if post.is_some() {
                    Between::Posts
                } else {
                    Between::Walls
                },
            }
        }
        _ => Passage {
            width: cell,
            between: Between::Lines,
        },
    }
}

/// A warning when a robot `robot_width` metres wide does not fit the passages of `layout`
/// (as wide as the narrowest or wider); `None` when it fits.
pub fn robot_fit(layout: &Layout, robot_width: f64) -> Option<String> {
    let passage = narrowest_passage(layout);
    if robot_width < passage.width {
        return None;
    }
    let cell = layout.grid.cell_size;
    Some(match passage.between {
        Between::Lines => format!(
            "a robot {robot_width:.3} m wide does not fit between the lines, {:.3} m apart: centred on one, it covers the next where two corridors run side by side; a larger cell size would make room",
            passage.width
        ),
        between => format!(
            "a robot {robot_width:.3} m wide does not fit the passages: {:.3} m between the {} ({cell:.3} m cells); a larger cell size or thinner {} would make room",
            passage.width,
            between.word(),
            between.word()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::walls::{WallOptions, into_walls};
    use crate::layout::{GenerateSpec, PostSpec, build_layout, passages};
    use crate::maze::Grid;

    fn lines() -> Layout {
        let grid = Grid::new(3, 3).unwrap();
        build_layout(&GenerateSpec::course(grid, Algorithm::Dfs, 1)).unwrap()
    }

    fn walls(thickness: f64, post: Option<f64>) -> Layout {
        let mut layout = lines();
        let grid = Grid::new(3, 3).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        into_walls(&mut layout, &maze, &WallOptions::default(), true).unwrap();
        layout.wall.as_mut().unwrap().thickness = thickness;
        layout.post = post.map(|size| PostSpec { size });
        layout
    }

    #[test]
    fn a_wall_maze_s_passage_is_the_cell_less_the_wall_or_the_post() {
        let plain = narrowest_passage(&walls(0.05, None));
        assert_eq!(plain.between, Between::Walls);
        assert!((plain.width - 0.95).abs() < 1e-12, "{plain:?}");
        let posts = narrowest_passage(&walls(0.05, Some(0.1)));
        assert_eq!(posts.between, Between::Posts);
        assert!((posts.width - 0.9).abs() < 1e-12, "{posts:?}");
        assert_eq!(
            narrowest_passage(&lines()),
            Passage {
                width: 1.0,
                between: Between::Lines
            }
        );
    }

    #[test]
    fn a_robot_as_wide_as_the_passage_or_wider_is_warned_of_naming_both_widths() {
        let layout = walls(0.05, Some(0.1));
        assert_eq!(
            robot_fit(&layout, 0.2),
            None,
            "the course robot fits 1 m cells"
        );
        assert_eq!(robot_fit(&layout, 0.899), None);
        let warning = robot_fit(&layout, 0.9).unwrap();
        assert!(
            warning.contains("a robot 0.900 m wide does not fit the passages")
                && warning.contains("0.900 m between the posts (1.000 m cells)"),
            "{warning}"
        );
        assert_eq!(robot_fit(&lines(), 0.5), None);
        let wide = robot_fit(&lines(), 1.2).unwrap();
        assert!(
            wide.contains("a robot 1.200 m wide does not fit between the lines, 1.000 m apart"),
            "{wide}"
        );
    }
}
