//! What a survey asks for and finds, by role ([`SurveyRoles`]): the names
//! [`crate::draw::Backend::survey`] resolves and the handles it finds, so no caller counts
//! positions.

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
