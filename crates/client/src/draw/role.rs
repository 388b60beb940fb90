//! The roles the scene's objects play in a drawing ([`Role`]), said plainly: each adapter
//! adds the option that names a role's object (the command line's `--floor`, Python's
//! `floor=`).

use std::fmt;

use super::Style;

/// What an object of the scene is to a drawing; [`super::ObjectNames`] names one object
/// per role.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The floor every coordinate is relative to.
    Floor,
    /// The dummy the maze's copies are children of.
    Parent,
    /// The line template.
    Line,
    /// The wall template.
    Wall,
    /// The post template.
    Post,
    /// The start marker.
    Start,
    /// The end marker.
    End,
}

impl Role {
    /// Every role, in the order floor, parent, line, wall, post, start, end.
    pub const ALL: [Role; 7] = [
        Role::Floor,
        Role::Parent,
        Role::Line,
        Role::Wall,
        Role::Post,
        Role::Start,
        Role::End,
    ];

    /// The template `style` copies: the line template, or the wall template.
    pub fn template(style: Style) -> Role {
        match style {
            Style::Lines => Role::Line,
            Style::Walls => Role::Wall,
        }
    }
}

impl fmt::Display for Role {
    /// What the object is: "the floor", "the maze dummy", "the line template", ...
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Role::Floor => "the floor",
            Role::Parent => "the maze dummy",
            Role::Line => "the line template",
            Role::Wall => "the wall template",
            Role::Post => "the post template",
            Role::Start => "the start marker",
            Role::End => "the end marker",
        })
    }
}
