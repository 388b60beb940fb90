//! What a survey asks for and finds, by role ([`SurveyRoles`]): the names
//! [`crate::draw::Backend::survey`] resolves and the handles it finds, so no caller counts
//! positions.

use std::collections::{HashMap, HashSet};

/// One value per object a survey of a scene looks for, by role. The style's template is the
/// one copied (`Line`, or `Wall` for walls); the other style's template and the post
/// template are optional (a scene may lack them).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SurveyRoles<T> {
    /// The floor: every pose is relative to it.
    pub floor: T,
    /// The dummy the maze's copies are children of.
    pub parent: T,
    /// The style's template (the one copied).
    pub template: T,
    /// The start marker.
    pub start: T,
    /// The end marker.
    pub end: T,
    /// The other style's template (its copies are never reused as the style's).
    pub other_template: T,
    /// The post template.
    pub post: T,
}

/// The names a survey resolves ([`crate::draw::ObjectNames::survey`]).
pub type SurveyNames<'a> = SurveyRoles<&'a str>;

/// The handles a survey found, `None` for a name the scene lacks.
pub type SurveyHandles = SurveyRoles<Option<i32>>;

impl<T> SurveyRoles<T> {
    /// Every value, in the order floor, parent, template, start, end, other template, post
    /// (the order [`SurveyRoles::from_array`] reads back).
    pub fn into_array(self) -> [T; 7] {
        [
            self.floor,
            self.parent,
            self.template,
            self.start,
            self.end,
            self.other_template,
            self.post,
        ]
    }

    /// The values of [`SurveyRoles::into_array`]'s order, back by role.
    pub fn from_array([floor, parent, template, start, end, other_template, post]: [T; 7]) -> Self {
        SurveyRoles {
            floor,
            parent,
            template,
            start,
            end,
            other_template,
            post,
        }
    }

    /// The same roles, each value mapped by `f`.
    pub fn map<U>(self, f: impl FnMut(T) -> U) -> SurveyRoles<U> {
        SurveyRoles::from_array(self.into_array().map(f))
    }

    /// The values a drawing needs (floor, parent, template, start, end), then the optional
    /// ones (other template, post).
    pub fn needed_and_optional(self) -> ([T; 5], [T; 2]) {
        let [floor, parent, template, start, end, other_template, post] = self.into_array();
        (
            [floor, parent, template, start, end],
            [other_template, post],
        )
    }

    /// The templates (the style's, the other style's, the post template): their copies are
    /// the maze's.
    pub fn templates(self) -> [T; 3] {
        [self.template, self.other_template, self.post]
    }
}

impl SurveyHandles {
    /// `true` when the objects a drawing needs (floor, parent, template, start, end) were
    /// all found: only then do backends list the scene's objects.
    pub fn needed_found(&self) -> bool {
        self.needed_and_optional().0.iter().all(Option::is_some)
    }
}

/// Object type codes by handle, as a survey read them ([`Traits::kinds`]).
pub type Kinds = HashMap<i32, i32>;

/// What a backend read of a survey's objects that tells a template's copy from the user's
/// object named like one (`Survey::traits`). A backend reads sizes and children
/// only where the name and type say "copy" and its record of the copies this tool pasted
/// ([`super::record`]) does not already say so (normally none), and the sizes of those
/// objects' templates: a fact not read is no evidence either way.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Traits {
    /// Object type codes (`sim_object_*_type`: 0 shape, 4 dummy, ...) by handle: at least
    /// the named objects and the objects that may be copies of a template.
    pub kinds: Kinds,
    /// Bounding-box extents (x, y, z, metres, `BoundingBox::size`) by handle: the
    /// copy candidates the backend sized, and their templates.
    pub sizes: HashMap<i32, [f64; 3]>,
    /// Copy candidates the backend found to have children of their own (a pasted copy has
    /// none: the copies are pasted without their trees).
    pub with_children: HashSet<i32>,
    /// Ambient-diffuse colours (RGB, 0..1) by handle: the copy candidates the backend read
    /// them of (an API that reads colours), and their templates.
    pub colours: HashMap<i32, [f64; 3]>,
    /// The surveyed objects (named ones included) that the scene's copy record
    /// ([`super::record`]) holds as this tool's copies, as the survey found it: ours, first
    /// of all, and never a template or a marker (`resolve_handles`).
    pub recorded: HashSet<i32>,
    /// Visibility layer bits by handle: the recorded copies the backend read them of (an
    /// API that reads them), and their templates.
    pub layers: HashMap<i32, i32>,
    /// Copies the record holds whose size, colour or visibility layer is no longer their
    /// template's (the user scaled, recoloured or hid them), with what differs: ours, but
    /// never reused as they are: a drawing removes and pastes them anew, a verification
    /// names them (`ownership::spoiled`).
    pub spoiled: HashMap<i32, String>,
}
