//! What a copies draw places ([`Drawing`]): one pose per copy of a template, made only from
//! a valid layout.

use vrep_maze_core::layout::sizes::{Sizes, TemplateUse};
use vrep_maze_core::layout::{Pose, Style};

/// What to draw: one pose per copy of the style's template (`Line`: the template itself is
/// the first; `Wall`: copies only, the template stays where the scene has it), one per copy
/// of `Post` in a wall maze with posts (copies only, as walls), plus where `Start` and `End`
/// go. All in the Floor frame. Made only from a valid layout
/// (`Drawing::try_from(&layout)`), so its fields can be read but not assembled by hand.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Drawing {
    /// Lines or walls: which template is copied.
    pub style: Style,
    /// Poses of the pieces of the maze drawn as the style's template: the line segments
    /// (`segments`, the first one the template itself) or the walls (`walls`, every one a
    /// copy), in the layout's order. The posts are apart ([`Drawing::posts`]).
    pub pieces: Vec<Pose>,
    /// Poses of the `Post` copies (`posts`): empty unless the maze has posts.
    pub posts: Vec<Pose>,
    /// Pose of the start marker.
    pub start: Pose,
    /// Pose of the end marker.
    pub end: Pose,
    /// The sizes the layout was generated for, which the templates and markers must have.
    pub sizes: Sizes,
}

impl Drawing {
    /// What this drawing asks of the templates: the style's template is the first line (or
    /// copied for every wall) when there is any, the post template for every post.
    pub fn template_use(&self) -> TemplateUse<'_> {
        TemplateUse {
            style: self.style,
            sizes: &self.sizes,
            template: !self.pieces.is_empty(),
            posts: !self.posts.is_empty(),
        }
    }

    /// `true` when the template itself is the first copy drawn (lines); a wall template
    /// stays where the scene has it and every wall is a copy.
    pub fn template_drawn(&self) -> bool {
        self.style == Style::Lines
    }

    /// Lines, or walls and posts: the objects placed, as progress counts them.
    pub fn copies(&self) -> usize {
        self.pieces.len() + self.posts.len()
    }
}

impl TryFrom<&vrep_maze_core::layout::Layout> for Drawing {
    type Error = vrep_maze_core::validate::Invalid;

    /// The layout's segments (template first) or walls, posts, start and end poses, once
    /// the layout has passed [`vrep_maze_core::validate::checked`]: the only way to make a drawing,
    /// so nothing invalid is ever drawn.
    fn try_from(layout: &vrep_maze_core::layout::Layout) -> Result<Drawing, Self::Error> {
        vrep_maze_core::validate::checked(layout)?;
        let pieces = match layout.style {
            Style::Lines => layout.segments.clone(),
            Style::Walls => layout.walls.clone(),
        };
        Ok(Drawing {
            style: layout.style,
            pieces,
            posts: layout.posts.clone(),
            start: layout.start.pose,
            end: layout.end.pose,
            sizes: Sizes::of(layout),
        })
    }
}
