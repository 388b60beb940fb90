//! What a layout asks of the scene's templates and markers: the sizes it was generated
//! for ([`Sizes`]), and which of them a drawing copies ([`TemplateUse`]); the drawing checks
//! a scene against them, the mesh geometry draws with them.

use super::Style;

/// The sizes a layout was generated for (`fit::check_sizes` compares the scene's
/// templates and markers with them).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Sizes {
    /// Side of a cell, metres.
    pub cell: f64,
    /// Line template: length (x) and width (y), metres.
    pub line: [f64; 2],
    /// Wall template of a wall maze: length (x), thickness (y), height (z), metres.
    pub wall: Option<[f64; 3]>,
    /// Post template of a wall maze with posts: x, y, z, metres.
    pub post: Option<[f64; 3]>,
    /// Height of the lines above the floor, metres: a line template lies flat, at most
    /// twice as thick (`fit::check_sizes`).
    pub line_z: f64,
    /// Heights of the start and end markers above the floor, metres: flat as the lines.
    pub marker_z: [f64; 2],
    /// The floor the layout was made for (x, y), metres: the scene's must be as large.
    pub floor: [f64; 2],
}

impl Sizes {
    /// The sizes `layout` was generated for.
    pub fn of(layout: &super::Layout) -> Sizes {
        let wall = layout
            .wall
            .as_ref()
            .map(|w| [w.length, w.thickness, w.height]);
        Sizes {
            cell: layout.grid.cell_size,
            line: [layout.line.length, layout.line.width],
            wall,
            post: layout
                .post
                .as_ref()
                .zip(wall)
                .map(|(p, w)| [p.size, p.size, w[2]]),
            line_z: layout.line.z,
            marker_z: [layout.start.pose.z, layout.end.pose.z],
            floor: layout.floor.size,
        }
    }
}

/// What a drawing asks of the templates and markers (`fit::check_sizes`): its style, the
/// sizes it was generated for, whether the style's template lies on the maze (a line maze's
/// first line, or a wall maze's every wall) and whether posts are copies of the post
/// template.
#[derive(Debug, Clone, Copy)]
pub struct TemplateUse<'a> {
    /// Lines or walls.
    pub style: Style,
    /// The sizes the layout was generated for.
    pub sizes: &'a Sizes,
    /// The style's template is drawn on the maze, so it must have the layout's size.
    pub template: bool,
    /// The posts are copies of the post template.
    pub posts: bool,
}
