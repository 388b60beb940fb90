//! The roles the scene's objects play in a drawing ([`Role`]), said plainly: each adapter
//! adds the option that names a role's object (the command line's `--floor`, Python's
//! `floor=`).

use std::fmt;

use super::extent;
use vrep_maze_core::layout::Style;
use vrep_maze_core::layout::sizes::Sizes;

/// What an object of the scene is to a drawing; `ObjectNames` names one object
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

    /// How to make the object `name` that plays this role in CoppeliaSim (one line), at the
    /// layout's `sizes` when a layout is drawn (`None`, as for `clear`: the sizes are the
    /// layout's, named by its fields). The floor's line offers no resize: there is nothing
    /// to scale until the floor exists.
    pub fn how_to_create(self, name: &str, sizes: Option<&Sizes>) -> String {
        let m = extent::metres;
        let recipe = match self {
            Role::Floor => {
                let needs = match sizes {
                    Some(s) => format!("at least {} m", extent::extents(&s.floor)),
                    None => "at least the layout's `floor.size`".into(),
                };
                format!(
                    "the floor every coordinate is relative to: a plane (Add > Primitive shape > Plane; CoppeliaSim's default scene has `Floor`, 10 m x 10 m); the maze needs {needs}"
                )
            }
            Role::Parent => {
                "a dummy that holds the maze lines (Add > Dummy, then rename it)".into()
            }
            Role::Line => {
                let plane = match sizes {
                    Some(s) => format!(
                        "{} m, pure green, at z = {}",
                        extent::extents(&s.line),
                        m(s.line_z)
                    ),
                    None => {
                        "the layout's `line.length` x `line.width`, pure green, at z = `line.z`"
                            .into()
                    }
                };
                format!("the line template: a plane {plane} (Add > Primitive shape > Plane)")
            }
            Role::Wall | Role::Post => {
                let (what, size, fields) = if self == Role::Wall {
                    let fields = "`wall.length` x `wall.thickness` x `wall.height`";
                    ("wall", sizes.and_then(|s| s.wall), fields)
                } else {
                    let fields = "`post.size` x `post.size` x `wall.height`";
                    ("post", sizes.and_then(|s| s.post), fields)
                };
                let cuboid = match size {
                    Some(size) => format!("{} m", extent::extents(&size)),
                    None => format!("the layout's {fields}"),
                };
                format!(
                    "the {what} template: a cuboid {cuboid}, dark grey, respondable and detectable (Add > Primitive shape > Cuboid); it stays where you put it, off the maze"
                )
            }
            Role::Start | Role::End => {
                let (what, colour, i) = if self == Role::Start {
                    ("start", "blue", 0)
                } else {
                    ("end", "red", 1)
                };
                let plane = match sizes {
                    Some(s) => format!(
                        "{} m x {} m (a cell), pure {colour}, at z = {}",
                        m(s.cell),
                        m(s.cell),
                        m(s.marker_z[i])
                    ),
                    None => format!(
                        "a cell wide (`grid.cell_size`), pure {colour}, at z = `{what}.pose.z`"
                    ),
                };
                format!("the {what} marker: a plane {plane}")
            }
        };
        format!("`{name}`: {recipe}")
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
