//! The scene objects a drawing needs: their names ([`ObjectNames`], one per [`Role`]) and
//! their handles in one scene ([`Handles`], resolved by `session::resolve_handles`).

use vrep_maze_core::layout::Style;

use super::error::DrawError;
use super::role::Role;
use super::survey::{SurveyNames, SurveyRoles};

/// Names of the scene objects a drawing needs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjectNames {
    /// Reference frame of every coordinate (`Floor`).
    pub floor: String,
    /// Dummy every line is a child of (`Maze`).
    pub parent: String,
    /// Line template (`Line`).
    pub line: String,
    /// Start marker (`Start`).
    pub start: String,
    /// End marker (`End`).
    pub end: String,
    /// Wall template (`Wall`), the template of wall mazes.
    pub wall: String,
    /// Post template (`Post`), standing at the lattice corners of wall mazes with posts.
    pub post: String,
}

impl Default for ObjectNames {
    fn default() -> Self {
        ObjectNames {
            floor: "Floor".into(),
            parent: "Maze".into(),
            line: "Line".into(),
            start: "Start".into(),
            end: "End".into(),
            wall: "Wall".into(),
            post: "Post".into(),
        }
    }
}

impl ObjectNames {
    /// Every template: line, wall, post ([`ownership::sort_out`](super::ownership::sort_out) keeps their copies).
    pub fn templates(&self) -> [&str; 3] {
        [&self.line, &self.wall, &self.post]
    }

    /// The template `style` copies.
    pub fn template(&self, style: Style) -> &str {
        self.name(Role::template(style))
    }

    /// The name of `role`'s object.
    pub fn name(&self, role: Role) -> &str {
        match role {
            Role::Floor => &self.floor,
            Role::Parent => &self.parent,
            Role::Line => &self.line,
            Role::Wall => &self.wall,
            Role::Post => &self.post,
            Role::Start => &self.start,
            Role::End => &self.end,
        }
    }

    /// The templates other than `style`'s: the other style's, then the post template. Their
    /// copies in the maze are never reused as the style's (a wall is no line, a post no
    /// wall), and they themselves are never touched.
    pub fn others(&self, style: Style) -> Vec<&str> {
        match style {
            Style::Lines => vec![&self.wall, &self.post],
            Style::Walls => vec![&self.line, &self.post],
        }
    }

    /// The templates whose copies in the maze drawing `style` removes: [`ObjectNames::others`],
    /// less the post template when the drawing has `posts` (its copies are the drawing's).
    pub fn foreign(&self, style: Style, posts: bool) -> Vec<&str> {
        let mut others = self.others(style);
        if posts {
            others.truncate(1);
        }
        others
    }

    /// What [`Backend::survey`](super::backend::Backend::survey) is asked for when drawing `style`: the names of the floor,
    /// the parent, the style's template, start and end, then [`ObjectNames::others`] (the
    /// other style's template and the post template, optional).
    pub fn survey(&self, style: Style) -> SurveyNames<'_> {
        Self::survey_roles(style).map(|role| self.name(role))
    }

    /// Every role and the name of its object: floor, parent, line, wall, post, start, end.
    pub fn roles(&self) -> [(Role, &str); 7] {
        Role::ALL.map(|role| (role, self.name(role)))
    }

    /// The roles of [`ObjectNames::survey`]'s names.
    pub(crate) fn survey_roles(style: Style) -> SurveyRoles<Role> {
        let (template, other_template) = match style {
            Style::Lines => (Role::Line, Role::Wall),
            Style::Walls => (Role::Wall, Role::Line),
        };
        SurveyRoles {
            floor: Role::Floor,
            parent: Role::Parent,
            template,
            start: Role::Start,
            end: Role::End,
            other_template,
            post: Role::Post,
        }
    }

    /// Refuses two roles given one name (`Maze` and `/Maze` are one name: a ZeroMQ path
    /// of the scene root): one object cannot be the floor and the maze dummy, a template
    /// and a marker, ... Pure, so it is checked before anything is sent.
    pub fn check_roles(&self) -> Result<(), DrawError> {
        let roles = self.roles();
        let key = |n: &str| n.strip_prefix('/').unwrap_or(n).to_string();
        for (i, (first, a)) in roles.iter().enumerate() {
            if let Some((second, b)) = roles[i + 1..].iter().find(|(_, b)| key(a) == key(b)) {
                return Err(DrawError::SameObject {
                    names: if a == b {
                        format!("`{a}`")
                    } else {
                        format!("`{a}` and `{b}`")
                    },
                    first: *first,
                    second: *second,
                });
            }
        }
        Ok(())
    }
}

/// Handles of the objects [`ObjectNames`] names, resolved in one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Handles {
    /// The floor: every pose is relative to it.
    pub floor: i32,
    /// The dummy every maze line is a child of.
    pub parent: i32,
    /// The style's template, the one copied: `Line` (also the first line of the maze) or,
    /// for walls, `Wall`.
    pub template: i32,
    /// The start marker.
    pub start: i32,
    /// The end marker.
    pub end: i32,
    /// The post template, if the scene has one (a drawing with posts needs it).
    pub post: Option<i32>,
}

impl Handles {
    /// The objects a drawing moves but never removes: the style's template and the start
    /// and end markers.
    pub fn never_removed(&self) -> [i32; 3] {
        [self.template, self.start, self.end]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_name_in_two_roles_is_refused_naming_both() {
        assert!(ObjectNames::default().check_roles().is_ok());
        let names = ObjectNames {
            end: "/Floor".into(),
            ..Default::default()
        };
        let e = names.check_roles().unwrap_err();
        assert!(
            matches!(
                &e,
                DrawError::SameObject { names, first: Role::Floor, second: Role::End }
                    if names == "`Floor` and `/Floor`"
            ),
            "{e}"
        );
        let names = ObjectNames {
            post: "Line".into(),
            ..Default::default()
        };
        let e = names.check_roles().unwrap_err().to_string();
        assert!(
            e.starts_with("`Line` would be both the line template and the post template"),
            "{e}"
        );
    }
}
