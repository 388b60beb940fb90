//! Whether the scene's templates, markers and floor have the sizes a drawing asks of them:
//! a template's full extents (a line lies flat on the floor, a wall and a post are boxes),
//! the markers flat and no wider than a cell, and the floor at least as large as the
//! layout's. Pure: a backend reads the sizes, [`check_sizes`] judges them.

use super::error::DrawError;
use super::extent::{FloorShort, Resize, extents, metres};
use super::names::ObjectNames;
use super::tolerance::{SIZE_TOLERANCE, same_size};
use vrep_maze_core::coppelia::OBJECT_SHAPE_TYPE;
use vrep_maze_core::layout::Geometry;
use vrep_maze_core::layout::Style;
use vrep_maze_core::layout::limits::{self, Naming};
use vrep_maze_core::layout::sizes::TemplateUse;
use vrep_maze_core::wording::{Message, Opt, Setting, Value};

/// The bounding-box extents (x, y, z, metres) a backend read of each object a drawing
/// checks; `None`: not read (the simulator gave none).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Measured {
    /// The style's template: `Line`, or `Wall` in a wall maze.
    pub template: Option<[f64; 3]>,
    /// The post template (a wall maze with posts).
    pub post: Option<[f64; 3]>,
    /// The start marker.
    pub start: Option<[f64; 3]>,
    /// The end marker.
    pub end: Option<[f64; 3]>,
    /// The floor.
    pub floor: Option<[f64; 3]>,
}

/// What [`check_sizes`] found: refusals (the drawing would not be the layout), warnings,
/// and a floor smaller than the layout's (refused unless `apply --resize-floor` grows it).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SizeCheck {
    /// One line per template or marker that contradicts the layout, with what to change.
    pub refusals: Vec<Message>,
    /// Markers larger than a cell, sizes that could not be read.
    pub warnings: Vec<String>,
    /// The scene's floor, if smaller than the layout's.
    pub floor: Option<FloorShort>,
}

impl SizeCheck {
    /// The refusal of a drawing or a comparison (`apply`, `verify`, `inspect`): every line
    /// of [`SizeCheck::refusals`], and the floor's when templates are refused too (alone,
    /// a short floor is [`DrawError::Floor`], which `apply --resize-floor` answers).
    pub fn refused(&self, names: &ObjectNames) -> Option<DrawError> {
        if self.refusals.is_empty() {
            return None;
        }
        self.differences(names, None, false)
    }

    /// What a comparison with the layout (`verify`, `inspect --layout`) reports: every
    /// refusal and a floor smaller than the layout's, `None` when there is neither. A short
    /// floor alone is [`DrawError::Floor`], whose remedy is the floor's, not the templates':
    /// the one [`resize_offer`] finds for a floor of `floor_kind` on this connection.
    pub fn differences(
        &self,
        names: &ObjectNames,
        floor_kind: Option<i32>,
        can_resize: bool,
    ) -> Option<DrawError> {
        if let (true, Some(short)) = (self.refusals.is_empty(), self.floor) {
            return Some(DrawError::Floor {
                floor: names.floor.clone(),
                short,
                resize: resize_offer(&short, floor_kind, can_resize),
            });
        }
        let mut lines = self.refusals.clone();
        lines.extend(self.floor.map(|f| f.describe(&names.floor).into()));
        (!lines.is_empty()).then_some(DrawError::Sizes(lines))
    }
}

/// What `apply --resize-floor` can do about a floor that is `short`: nothing for a floor
/// without extent along x or y, or for one of type `floor_kind` that is no shape (a dummy
/// scales along z too), nor on a connection that cannot resize (`can_resize`: the legacy
/// remote API); otherwise it is offered.
pub fn resize_offer(short: &FloorShort, floor_kind: Option<i32>, can_resize: bool) -> Resize {
    if short.factors().is_none() {
        Resize::NoExtent
    } else if let Some(kind) = floor_kind.filter(|k| *k != OBJECT_SHAPE_TYPE) {
        Resize::NotAShape { kind }
    } else if !can_resize {
        Resize::NoApi
    } else {
        Resize::Offered
    }
}

/// The most a flat object lying at height `z` (its centre) may measure along z: twice `z`,
/// so it does not reach below the floor, and never less than [`SIZE_TOLERANCE`].
fn flat_limit(z: f64) -> f64 {
    (2.0 * z).max(0.0) + SIZE_TOLERANCE
}

/// "the scene's `Line` is 0.3 m high but ...": a refusal for an object that must lie flat
/// at height `z` (a line, a marker) and measures `have`, or `None` if it is flat enough.
fn too_high(name: &str, what: &str, have: [f64; 3], z: f64) -> Option<Message> {
    // NaN is never flat
    (have[2].is_nan() || have[2] > flat_limit(z)).then(|| {
        Message::text(format!(
            "the scene's `{name}` is {} m high but {what} lies flat on the floor (at z = {} m it may be at most {} m thick): make it a plane, or resize `{name}` to {} x 0 m",
            metres(have[2]),
            metres(z),
            metres(2.0 * z.max(0.0)),
            extents(&have[..2])
        ))
    })
}

/// What `generate` says of a line template of `have` (length x width) on the drawing's
/// cells: `Ok` with the options if it would generate with them, else why not.
fn line_options(drawing: &TemplateUse<'_>, have: [f64; 3]) -> Result<Vec<Setting>, Message> {
    let sizes = drawing.sizes;
    let geometry = Geometry {
        cell_size: sizes.cell,
        origin: [0.0, 0.0],
        rotation: 0.0,
        line_length: have[0],
        line_width: have[1],
        line_z: sizes.line_z,
        marker_z: sizes.marker_z[0],
    };
    match limits::check_template(&geometry, Naming::Options).first() {
        None => Ok(vec![
            setting(Opt::LineLength, have[0]),
            setting(Opt::LineWidth, have[1]),
        ]),
        Some(v) => Err(v.line()),
    }
}

/// What `generate --style walls` says of a wall template of `wall` and, in a maze with
/// posts, a post template of side `post`, on the drawing's cells: `Ok` with the options if
/// it would generate with them, else why not.
fn wall_options(
    drawing: &TemplateUse<'_>,
    wall: [f64; 3],
    post: Option<f64>,
) -> Result<Vec<Setting>, Message> {
    let cell = drawing.sizes.cell;
    let found = vrep_maze_core::layout::walls::check_template(
        cell,
        wall[0],
        wall[1],
        wall[2],
        post,
        Naming::Options,
    );
    match found.first() {
        None => {
            let mut options = vec![
                setting(Opt::WallLength, wall[0]),
                setting(Opt::WallThickness, wall[1]),
                setting(Opt::WallHeight, wall[2]),
            ];
            if let Some(p) = post {
                options.extend(posts(p));
            }
            Ok(options)
        }
        Some(v) => Err(v.line()),
    }
}

/// What `generate --style walls --posts` says of a post template of `post` (x, y, z) with
/// the layout's walls, as high as the post, on the drawing's cells (`scene_wall`: the
/// scene's wall template, which must be as high): `Ok` with the options if it would
/// generate with them, else why not.
fn post_options(
    drawing: &TemplateUse<'_>,
    scene_wall: Option<[f64; 3]>,
    post: [f64; 3],
) -> Result<Vec<Setting>, Message> {
    let sizes = drawing.sizes;
    let Some(wall) = sizes.wall else {
        return Err(Message::text("the layout has no walls"));
    };
    let height = scene_wall.map_or(wall[2], |w| w[2]);
    if !same_size(height, post[2]) {
        return Err(Message::text(format!(
            "a post is as high as the walls, and the wall template is {} m high",
            metres(height)
        )));
    }
    let side = post[0].max(post[1]);
    let found = vrep_maze_core::layout::walls::check_template(
        sizes.cell,
        wall[0],
        wall[1],
        post[2],
        Some(side),
        Naming::Options,
    );
    match found.first() {
        None => {
            let mut options = posts(side).to_vec();
            options.push(setting(Opt::WallHeight, post[2]));
            Ok(options)
        }
        Some(v) => Err(v.line()),
    }
}

/// `opt` given a length in metres, as messages show it ([`metres`]).
fn setting(opt: Opt, value: f64) -> Setting {
    Setting {
        opt,
        value: Value::Number(metres(value)),
    }
}

/// Posts of side `side`: `--posts --post-size 0.012`.
fn posts(side: f64) -> [Setting; 2] {
    [
        Setting {
            opt: Opt::Posts,
            value: Value::On,
        },
        setting(Opt::PostSize, side),
    ]
}

/// "generate with OPTIONS, or resize ...", or where `generate` refuses those options
/// (`options` is the reason), only the resize, with the reason.
fn remedy(options: Result<Vec<Setting>, Message>, resize: String) -> Message {
    match options {
        Ok(options) => Message::text("generate with ")
            .and_settings(options)
            .and(format!(" (and the layout's other options), or {resize}")),
        Err(why) => Message::text(format!(
            "{resize} (no layout is generated for it as it is: "
        ))
        .and_message(why)
        .and(")"),
    }
}

/// Compares the bounding boxes the scene gave (`m`) with the sizes `drawing` was
/// generated for. A template drawn from ([`TemplateUse::template`] or
/// [`TemplateUse::posts`]) must have the layout's extents within [`SIZE_TOLERANCE`]: a line
/// template its length along x and width along y and lying flat (at most twice its height
/// above the floor thick); a wall and a post template all three, except that a wall
/// between posts may be as long as a cell side, its ends hidden in the posts. The markers
/// lie flat as well. A refusal says what to change: the options to generate with (only
/// those `generate` accepts) or the size to give the object. A marker wider than a cell is
/// a warning (it hides the neighbouring cells), as is a size the simulator did not give. A
/// floor smaller than the layout's along x or y is [`SizeCheck::floor`].
pub fn check_sizes(drawing: &TemplateUse<'_>, names: &ObjectNames, m: &Measured) -> SizeCheck {
    let mut check = SizeCheck::default();
    // a line maze's template is its first line, a wall maze's is copied for every wall
    if drawing.template {
        check_template(drawing, names, m.template, &mut check);
    }
    if let (Some(want), true) = (drawing.sizes.post, drawing.posts) {
        check_post(drawing, names, m, want, &mut check);
    }
    check_markers(drawing, names, m, &mut check);
    match m.floor {
        None => unread(&names.floor, &mut check),
        Some(have) => {
            let have = [have[0], have[1]];
            // NaN is never large enough
            let short = (0..2)
                .any(|k| have[k].is_nan() || have[k] < drawing.sizes.floor[k] - SIZE_TOLERANCE);
            if short {
                check.floor = Some(FloorShort {
                    have,
                    need: drawing.sizes.floor,
                });
            }
        }
    }
    check
}

/// Whether the sizes the scene gave differ from the layout's (NaN is never the same size).
fn differs(scene: &[f64], layout: &[f64]) -> bool {
    scene.iter().zip(layout).any(|(s, l)| !same_size(*s, *l))
}

/// Warns in `check` that the simulator did not give the size of `name`.
fn unread(name: &str, check: &mut SizeCheck) {
    check.warnings.push(format!(
        "the simulator did not give the size of `{name}`: not compared with the layout"
    ));
}

/// Compares the template drawn from (its size `template`, if given) with the layout's
/// lines or walls, refusing in `check` one that differs or (a line) does not lie flat.
fn check_template(
    drawing: &TemplateUse<'_>,
    names: &ObjectNames,
    template: Option<[f64; 3]>,
    check: &mut SizeCheck,
) {
    let sizes = drawing.sizes;
    let template_name = names.template(drawing.style);
    match (template, drawing.style, sizes.wall) {
        (None, ..) => unread(template_name, check),
        (Some(have), Style::Lines, _) => {
            if differs(&have[..2], &sizes.line) {
                check.refusals.push(
                    Message::text(format!(
                        "the scene's `{template_name}` is {} m but the layout was generated with ",
                        extents(&have[..2]),
                    ))
                    .and_settings(vec![
                        setting(Opt::LineLength, sizes.line[0]),
                        setting(Opt::LineWidth, sizes.line[1]),
                    ])
                    .and(": ")
                    .and_message(remedy(
                        line_options(drawing, have),
                        format!("resize `{template_name}` to {} m", extents(&sizes.line)),
                    )),
                );
            }
            check
                .refusals
                .extend(too_high(template_name, "a line", have, sizes.line_z));
        }
        (Some(have), Style::Walls, Some(wall)) => {
            // between posts a wall may reach into them, up to their centres (a whole
            // cell side): its ends are hidden inside the posts
            let longest = if !drawing.posts {
                wall[0]
            } else {
                sizes.cell.max(wall[0])
            };
            let length_ok =
                have[0] >= wall[0] - SIZE_TOLERANCE && have[0] <= longest + SIZE_TOLERANCE;
            if !length_ok || differs(&have[1..], &wall[1..]) {
                let post = sizes.post.filter(|_| drawing.posts).map(|p| p[0]);
                check.refusals.push(
                    Message::text(format!(
                        "the scene's `{template_name}` is {} m but the layout's walls are {} m (length x thickness x height): ",
                        extents(&have),
                        extents(&wall),
                    ))
                    .and_message(remedy(
                        wall_options(drawing, have, post),
                        format!("resize `{template_name}` to {} m", extents(&wall)),
                    )),
                );
            }
        }
        (Some(_), Style::Walls, None) => {}
    }
}

/// Compares the post template (`want` the layout's posts) with the layout's posts,
/// refusing in `check` one that differs.
fn check_post(
    drawing: &TemplateUse<'_>,
    names: &ObjectNames,
    m: &Measured,
    want: [f64; 3],
    check: &mut SizeCheck,
) {
    match m.post {
        None => unread(&names.post, check),
        Some(have) => {
            if differs(&have, &want) {
                let options = post_options(drawing, m.template, have);
                check.refusals.push(
                    Message::text(format!(
                        "the scene's `{}` is {} m but the layout's posts are {} m: ",
                        names.post,
                        extents(&have),
                        extents(&want),
                    ))
                    .and_message(remedy(
                        options,
                        format!("resize `{}` to {} m", names.post, extents(&want)),
                    )),
                );
            }
        }
    }
}

/// Checks that Start and End lie flat (refused in `check`) and are no wider than a cell
/// (a warning).
fn check_markers(
    drawing: &TemplateUse<'_>,
    names: &ObjectNames,
    m: &Measured,
    check: &mut SizeCheck,
) {
    let sizes = drawing.sizes;
    for ((name, b), z) in [(&names.start, m.start), (&names.end, m.end)]
        .into_iter()
        .zip(sizes.marker_z)
    {
        match b {
            None => unread(name, check),
            Some(have) => {
                check.refusals.extend(too_high(name, "a marker", have, z));
                if have[0].max(have[1]) > sizes.cell + SIZE_TOLERANCE {
                    check.warnings.push(format!(
                        "the scene's `{name}` is {} m but the cells are {} m: it covers the neighbouring cells; resize `{name}` to at most {} x {} m",
                        extents(&have[..2]),
                        metres(sizes.cell),
                        metres(sizes.cell),
                        metres(sizes.cell)
                    ));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::Drawing;
    use vrep_maze_core::wording::Wording;

    /// Options as `--name value`, as the command line words them.
    struct Dashes;

    impl Wording for Dashes {
        fn option(&self, opt: Opt) -> String {
            format!("--{}", Message::opt(opt))
        }

        fn setting(&self, opt: Opt, value: &Value) -> String {
            match value {
                Value::Number(v) | Value::Word(v) => format!("{} {v}", self.option(opt)),
                Value::Placeholder(v) => format!("{} {v}", self.option(opt)),
                Value::On => self.option(opt),
            }
        }

        fn separator(&self) -> &str {
            " "
        }

        fn generate(&self, settings: &str) -> String {
            format!("vrep-maze generate {settings}")
        }
    }

    /// `refusals` worded by [`Dashes`], joined.
    fn dashed(refusals: &[Message]) -> String {
        refusals.iter().map(|r| r.worded(&Dashes)).collect()
    }

    /// A size the simulator gave.
    fn bbox(size: [f64; 3]) -> Option<[f64; 3]> {
        Some(size)
    }

    fn course_drawing() -> Drawing {
        let layout =
            vrep_maze_core::layout::build_layout(&vrep_maze_core::layout::GenerateSpec::course(
                vrep_maze_core::maze::Grid::new(3, 3).unwrap(),
                vrep_maze_core::generate::Algorithm::Prim,
                1,
            ))
            .unwrap();
        Drawing::try_from(&layout).unwrap()
    }

    /// The course's markers and floor, and `template` as the template.
    fn course(template: [f64; 3]) -> Measured {
        Measured {
            template: bbox(template),
            post: None,
            start: bbox([1.0, 1.0, 0.0]),
            end: bbox([1.0, 1.0, 0.0]),
            floor: bbox([10.0, 10.0, 0.0]),
        }
    }

    #[test]
    fn sizes_within_half_a_millimetre_fit_and_others_are_refused_with_the_fix() {
        let d = course_drawing();
        let names = ObjectNames::default();
        let check = |line: [f64; 3]| check_sizes(&d.template_use(), &names, &course(line));
        assert_eq!(check([0.6, 0.1, 0.0]), SizeCheck::default());
        // single precision and millimetre dialogs: within 0.5 mm is the same size
        assert_eq!(
            check([0.6 + 4.9e-4, 0.1 - 4.9e-4, 0.0]),
            SizeCheck::default()
        );
        let refused = check([0.6 + 6e-4, 0.1, 0.0]);
        assert_eq!(refused.refusals.len(), 1, "{refused:?}");
        let refused = dashed(&check([0.3, 0.05, 0.0]).refusals);
        assert!(
            refused.contains("`Line` is 0.3 x 0.05 m")
                && refused.contains("generate with --line-length 0.3 --line-width 0.05")
                && refused.contains("resize `Line` to 0.6 x 0.1 m"),
            "{refused}"
        );
        assert_eq!(
            check([f64::NAN, 0.1, 0.0]).refusals.len(),
            1,
            "NaN never fits"
        );
        // a marker wider than a cell is a warning; a size not read is said
        let wide = check_sizes(
            &d.template_use(),
            &names,
            &Measured {
                start: bbox([1.2, 1.0, 0.0]),
                end: None,
                ..course([0.6, 0.1, 0.0])
            },
        );
        assert!(wide.refusals.is_empty());
        assert_eq!(wide.warnings.len(), 2, "{wide:?}");
        assert!(wide.warnings[0].contains("`Start` is 1.2 x 1 m but the cells are 1 m"));
        assert!(wide.warnings[1].contains("did not give the size of `End`"));
    }

    #[test]
    fn a_tall_line_or_marker_is_refused_and_a_flat_one_fits() {
        let d = course_drawing();
        let names = ObjectNames::default();
        // lines at z = 0.001 may be 2 mm thick (within half a millimetre)
        let thin = check_sizes(&d.template_use(), &names, &course([0.6, 0.1, 0.0024]));
        assert_eq!(thin, SizeCheck::default());
        let tall = check_sizes(&d.template_use(), &names, &course([0.6, 0.1, 0.3]));
        assert_eq!(tall.refusals.len(), 1, "{tall:?}");
        assert!(
            tall.refusals[0]
                .to_string()
                .starts_with("the scene's `Line` is 0.3 m high but a line lies flat")
                && tall.refusals[0]
                    .to_string()
                    .contains("resize `Line` to 0.6 x 0.1 x 0 m"),
            "{tall:?}"
        );
        let start = check_sizes(
            &d.template_use(),
            &names,
            &Measured {
                start: bbox([1.0, 1.0, 0.5]),
                ..course([0.6, 0.1, 0.0])
            },
        );
        assert_eq!(start.refusals.len(), 1, "{start:?}");
        assert!(
            start.refusals[0]
                .to_string()
                .contains("`Start` is 0.5 m high but a marker lies flat"),
            "{start:?}"
        );
    }

    #[test]
    fn a_floor_smaller_than_the_layouts_is_found_and_a_larger_one_fits() {
        let d = course_drawing();
        let names = ObjectNames::default();
        let on = |floor: [f64; 3]| {
            check_sizes(
                &d.template_use(),
                &names,
                &Measured {
                    floor: bbox(floor),
                    ..course([0.6, 0.1, 0.0])
                },
            )
        };
        assert_eq!(on([10.0, 10.0, 0.0]), SizeCheck::default());
        assert_eq!(on([50.0, 12.0, 0.0]), SizeCheck::default());
        let short = on([4.0, 12.0, 0.0]).floor.unwrap();
        assert_eq!(short.resized(), [10.0, 12.0]);
        assert_eq!(short.factors(), Some([2.5, 1.0, 1.0]));
        assert_eq!(
            short.describe("Floor"),
            "the scene's `Floor` is 4 x 12 m but the layout's floor is 10 x 10 m"
        );
        assert!(on([f64::NAN, 10.0, 0.0]).floor.is_some(), "NaN never fits");
        assert_eq!(on([0.0, 10.0, 0.0]).floor.unwrap().factors(), None);
    }

    #[test]
    fn generate_options_are_offered_only_where_generate_takes_them() {
        let d = course_drawing();
        let names = ObjectNames::default();
        // a template turned a quarter: 0.1 along x, 0.6 along y
        let turned = check_sizes(&d.template_use(), &names, &course([0.1, 0.6, 0.0]));
        let refusal = dashed(&turned.refusals);
        assert!(
            !refusal.contains("generate with")
                && refusal.contains("resize `Line` to 0.6 x 0.1 m (no layout is generated for it as it is: --line-width 0.6 m is not narrower")
                    | refusal.contains("resize `Line` to 0.6 x 0.1 m (no layout is generated for it as it is: --line-length 0.1 m is not longer"),
            "{refusal}"
        );
    }
}
