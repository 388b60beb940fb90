//! Compare a scene with a drawing: every line (or wall and post), `Start` and `End` in place
//! (1e-4 m, 1e-4 rad), copies parented to the maze dummy, and no other maze lines.

use std::collections::{HashMap, HashSet};

use super::backend::{Backend, ObjectInfo, Survey};
use super::drawing::Drawing;
use super::error::DrawError;
use super::names::{Handles, ObjectNames};
use super::ownership::{self, foreign_copies, maze_pieces};
use super::pose::{floor_frame, pose_differences, relative_pose};
use super::session::{raised, sizes_of, surveyed};
use super::survey::Traits;
use vrep_maze_core::coppelia::frame::Frame;
use vrep_maze_core::layout::sizes::TemplateUse;
use vrep_maze_core::layout::{Pose, Style};
use vrep_maze_core::wording::{Message, Opt};

/// Differences between `objects` and `drawing`, where `pieces[i]` is the object drawn for
/// `drawing.pieces[i]` (`pieces[0]` is the template in a line maze) and `posts[i]` the one
/// drawn for `drawing.posts[i]`. Empty when the scene matches.
pub fn check(
    objects: &[ObjectInfo],
    h: &Handles,
    names: &ObjectNames,
    pieces: &[i32],
    posts: &[i32],
    drawing: &Drawing,
) -> Vec<Message> {
    let mut problems: Vec<Message> = Vec::new();
    let Some(floor) = floor_frame(objects, h.floor) else {
        return vec!["the floor object disappeared".into()];
    };
    problems.extend(broken_frames(objects, h, names));
    let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
    let get = |handle: i32| by_handle.get(&handle).copied();
    let parts = [
        (
            noun(drawing.style),
            pieces,
            &drawing.pieces,
            usize::from(drawing.template_drawn()),
        ),
        ("post", posts, &drawing.posts, 0),
    ];
    for part in parts {
        part_problems(&floor, &by_handle, h.parent, part, &mut problems);
    }
    for (what, handle, want) in [
        ("start", h.start, &drawing.start),
        ("end", h.end, &drawing.end),
    ] {
        match get(handle) {
            None => problems.push(format!("the {what} marker is missing").into()),
            Some(o) => {
                if let Some(d) = pose_differences(&floor, o, want) {
                    problems.push(format!("{what} `{}` {d}", o.name).into());
                }
            }
        }
    }
    let first_copy = usize::from(drawing.template_drawn());
    let expected: HashSet<i32> = pieces
        .iter()
        .skip(first_copy)
        .chain(posts)
        .copied()
        .collect();
    let with_posts = !drawing.posts.is_empty();
    let stray: Vec<&str> = maze_pieces(
        objects,
        h,
        names.template(drawing.style),
        &names.others(drawing.style),
    )
    .into_iter()
    .chain(maze_posts(objects, h, names, with_posts))
    .chain(foreign_copies(
        objects,
        h,
        &names.foreign(drawing.style, with_posts),
    ))
    .filter(|x| !expected.contains(x))
    .filter_map(|x| get(x).map(|o| o.name.as_str()))
    .collect();
    if !stray.is_empty() {
        problems.push(stray_problem(&stray).into());
    }
    problems
}

/// Adds to `problems` how one part's `drawn` objects (a noun's: lines, walls or posts)
/// differ from the poses `wanted`: how many, which are missing, off their pose or, from
/// `first_copy` on, not under `parent`.
fn part_problems(
    floor: &Frame,
    by_handle: &HashMap<i32, &ObjectInfo>,
    parent: i32,
    (noun, drawn, wanted, first_copy): (&str, &[i32], &Vec<Pose>, usize),
    problems: &mut Vec<Message>,
) {
    if drawn.len() != wanted.len() {
        problems.push(
            format!(
                "{} {noun} objects for {} {noun}s",
                drawn.len(),
                wanted.len()
            )
            .into(),
        );
    }
    for (i, (&handle, want)) in drawn.iter().zip(wanted).enumerate() {
        match by_handle.get(&handle).copied() {
            None => problems.push(format!("{noun} {i} (handle {handle}) is missing").into()),
            Some(o) => {
                if let Some(d) = pose_differences(floor, o, want) {
                    problems.push(format!("{noun} {i} `{}` {d}", o.name).into());
                }
                if i >= first_copy && o.parent != Some(parent) {
                    problems.push(
                        format!(
                            "{noun} {i} `{}` has parent {:?}, expected {}",
                            o.name, o.parent, parent
                        )
                        .into(),
                    );
                }
            }
        }
    }
}

/// What a problem of [`broken_frames`] says, which [`DrawError::remedies`] recognises.
pub(crate) const BROKEN_POSE: &str = "is at a pose that is not a number (NaN)";

/// One problem for each of the floor and the maze dummy whose world pose in `objects` is not
/// finite: every pose relative to the floor, and every copy under the dummy, reads back
/// so, whatever a drawing sets, and vrep-maze never moves either object.
fn broken_frames(objects: &[ObjectInfo], h: &Handles, names: &ObjectNames) -> Vec<Message> {
    [
        (
            h.floor,
            &names.floor,
            Message::text("the floor, ").and_opt(Opt::Floor),
            "every pose relative to it",
        ),
        (
            h.parent,
            &names.parent,
            Message::text("the maze dummy, ").and_opt(Opt::Parent),
            "every copy under it",
        ),
    ]
    .into_iter()
    .filter(|(handle, ..)| {
        objects.iter().any(|o| {
            o.handle == *handle
                && !o
                    .position
                    .iter()
                    .chain(&o.orientation)
                    .all(|x| x.is_finite())
        })
    })
    .map(|(_, name, role, what)| {
        Message::text(format!("`{name}` ("))
            .and_message(role)
            .and(format!(") {BROKEN_POSE}: so is {what}"))
    })
    .collect()
}

/// The maze's copies of the post template when the drawing has posts (else they are
/// foreign, [`ObjectNames::foreign`]).
fn maze_posts(objects: &[ObjectInfo], h: &Handles, names: &ObjectNames, posts: bool) -> Vec<i32> {
    if posts {
        foreign_copies(objects, h, &[&names.post])
    } else {
        Vec::new()
    }
}

/// What the copies of a style's template are called in messages: `line` or `wall`.
fn noun(style: Style) -> &'static str {
    match style {
        Style::Lines => "line",
        Style::Walls => "wall",
    }
}

/// Side of the squares [`verify`] sorts objects into: far above the position tolerance, so
/// a line in place is always in its segment's square or a neighbour.
const BUCKET: f64 = 0.01;

/// The square of the floor a position lies in (`None` for a non-finite one, never in place).
fn bucket(position: [f64; 3]) -> Option<(i64, i64)> {
    let (x, y) = (position[0] / BUCKET, position[1] / BUCKET);
    (x.is_finite() && y.is_finite() && x.abs() < 1e15 && y.abs() < 1e15)
        .then(|| (x.floor() as i64, y.floor() as i64))
}

/// "N stray maze object(s): a, b, c, ..." naming at most the first few.
fn stray_problem(stray: &[&str]) -> String {
    const NAMED: usize = 5;
    let more = if stray.len() > NAMED {
        format!(", ... ({} more)", stray.len() - NAMED)
    } else {
        String::new()
    };
    format!(
        "{} stray maze object(s): {}{more}",
        stray.len(),
        stray[..stray.len().min(NAMED)].join(", ")
    )
}

/// Verifies a scene against a drawing without knowing which copy is which line: every
/// segment (wall, post) must be covered by a distinct maze copy of its template in place (a
/// line maze's template may cover any segment), copies must be children of the maze dummy,
/// no other maze copy may exist, and `Start`/`End` must be in place. Every pose is read
/// from the scene, with the idle rate raised while reading (and restored).
pub fn verify(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    names.check_roles()?;
    raised(scene, false, |scene| verify_raised(scene, drawing, names)).map(|(ok, _)| ok)
}

/// [`verify`] without touching the idle rate: only reads, for a caller that raised the rate
/// itself (`vrep-maze inspect`, [`super::session::raised_to_read`]).
pub fn verify_read_only(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    verify_raised(scene, drawing, names)
}

/// [`verify`] with the idle rate raised.
fn verify_raised(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    let style = drawing.style;
    let with_posts = !drawing.posts.is_empty();
    let asks = drawing.template_use();
    let (survey, h) = surveyed(scene, names, &asks, with_posts)?;
    refuse_size_differences(scene, &asks, names, &survey, &h)?;
    // every pose as the scene holds it now, not as a backend remembers setting it; the
    // user's objects are no maze lines
    let objects = &ownership::sort_out(
        &scene.objects_from_scene()?,
        &h,
        &names.templates(),
        &survey.traits,
    )
    .objects;
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
    let mut pool: Vec<i32> = if drawing.template_drawn() {
        vec![h.template]
    } else {
        vec![]
    };
    // an earlier mesh maze is stray; the holder is no line, and the user's holder stays
    let meshes = super::mesh::leftovers(scene, names, &h, &survey.objects)?;
    pool.extend(
        maze_pieces(objects, &h, names.template(style), &names.others(style))
            .into_iter()
            .filter(|x| Some(*x) != meshes.holder),
    );
    let mut problems = Vec::new();
    problems.extend(broken_frames(objects, &h, names));
    spoiled_problems(&survey.traits, &by_handle, style, &mut problems);
    let mut stray = Vec::new();
    let parts = [
        (noun(style), pool, &drawing.pieces),
        (
            "post",
            maze_posts(objects, &h, names, with_posts),
            &drawing.posts,
        ),
    ];
    for (noun, pool, wanted) in parts {
        let matched = Matching {
            floor: &floor,
            by_handle: &by_handle,
            h: &h,
            parent: &names.parent,
            noun,
        };
        stray.extend(matched.run(&pool, wanted, &mut problems));
    }
    stray.extend(foreign_copies(
        objects,
        &h,
        &names.foreign(style, with_posts),
    ));
    stray.retain(|x| Some(*x) != meshes.holder);
    let stray: Vec<&str> = stray
        .into_iter()
        .filter_map(|c| by_handle.get(&c).map(|o| o.name.as_str()))
        .chain(meshes.ours.iter().map(|(_, name)| name.as_str()))
        .collect();
    if !stray.is_empty() {
        problems.push(stray_problem(&stray).into());
    }
    marker_problems(&floor, &by_handle, &h, drawing, &mut problems);
    if problems.is_empty() {
        Ok(())
    } else {
        Err(DrawError::Verify(problems))
    }
}

/// Refuses templates or markers whose sizes differ from what `asks` wants of them, and a
/// floor smaller than the layout's (with what would fit it on this connection).
pub(crate) fn refuse_size_differences(
    scene: &mut dyn Backend,
    asks: &TemplateUse<'_>,
    names: &ObjectNames,
    survey: &Survey,
    h: &Handles,
) -> Result<(), DrawError> {
    let sizes = sizes_of(scene, asks, names, h)?;
    let floor_kind = survey.traits.kinds.get(&h.floor).copied();
    let can_resize = scene.authoring().is_some();
    match sizes.differences(names, floor_kind, can_resize) {
        Some(differences) => Err(differences),
        None => Ok(()),
    }
}

/// Adds to `problems` each copy of ours the user scaled or recoloured (`traits.spoiled`),
/// in handle order: it is no line of the layout's.
fn spoiled_problems(
    traits: &Traits,
    by_handle: &HashMap<i32, &ObjectInfo>,
    style: Style,
    problems: &mut Vec<Message>,
) {
    let mut spoiled: Vec<(i32, &String)> = traits.spoiled.iter().map(|(h, w)| (*h, w)).collect();
    spoiled.sort_unstable();
    for (handle, why) in spoiled {
        if let Some(o) = by_handle.get(&handle) {
            problems.push(format!("{} copy `{}` {why}", noun(style), o.name).into());
        }
    }
}

/// Adds to `problems` how Start and End stand apart from where `drawing` wants them
/// (relative to `floor`).
fn marker_problems(
    floor: &Frame,
    by_handle: &HashMap<i32, &ObjectInfo>,
    h: &Handles,
    drawing: &Drawing,
    problems: &mut Vec<Message>,
) {
    for (what, handle, want) in [
        ("start", h.start, &drawing.start),
        ("end", h.end, &drawing.end),
    ] {
        if let Some(d) = by_handle
            .get(&handle)
            .and_then(|o| pose_differences(floor, o, want))
        {
            problems.push(format!("{what} {d}").into());
        }
    }
}

/// What [`verify`] matches one template's copies with.
struct Matching<'a> {
    floor: &'a Frame,
    by_handle: &'a HashMap<i32, &'a ObjectInfo>,
    h: &'a Handles,
    /// The maze dummy's name, for messages.
    parent: &'a str,
    /// What a copy is called in messages.
    noun: &'static str,
}

impl Matching<'_> {
    /// Finds a distinct object of `pool` in place for each of `wanted`, adding what is
    /// missing or wrongly parented to `problems`; returns the copies of `pool` left over
    /// (the line template, if in the pool, is never left over).
    fn run(&self, pool: &[i32], wanted: &[Pose], problems: &mut Vec<Message>) -> Vec<i32> {
        let get = |handle: i32| self.by_handle.get(&handle).copied();
        // the pool by where each object lies on the floor, so each segment finds its copy
        // among a few neighbours instead of all of them
        let mut near: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (k, &c) in pool.iter().enumerate() {
            if let Some(key) = get(c).and_then(|o| bucket(relative_pose(self.floor, o).0)) {
                near.entry(key).or_default().push(k);
            }
        }
        let mut used = vec![false; pool.len()];
        for (i, want) in wanted.iter().enumerate() {
            // the lowest pool index among the copies in place: the template first, as before
            let hit = bucket(crate::draw::pose::position(want)).and_then(|(bx, by)| {
                (-1..=1)
                    .flat_map(|dx| (-1..=1).map(move |dy| (bx + dx, by + dy)))
                    .filter_map(|key| near.get(&key))
                    .flatten()
                    .copied()
                    .filter(|&k| {
                        !used[k]
                            && get(pool[k])
                                .is_some_and(|o| pose_differences(self.floor, o, want).is_none())
                    })
                    .min()
            });
            match hit {
                Some(k) => {
                    used[k] = true;
                    let c = pool[k];
                    if c != self.h.template && get(c).and_then(|o| o.parent) != Some(self.h.parent)
                    {
                        problems.push(
                            format!(
                                "{} {i} `{}` is not a child of `{}`",
                                self.noun,
                                get(c).map(|o| o.name.as_str()).unwrap_or("?"),
                                self.parent
                            )
                            .into(),
                        );
                    }
                }
                None => problems.push(
                    format!(
                        "no {} at ({:.3}, {:.3}, {:.3}) yaw {:.4}",
                        self.noun, want.x, want.y, want.z, want.yaw
                    )
                    .into(),
                ),
            }
        }
        pool.iter()
            .zip(&used)
            .filter(|&(&c, &u)| !u && c != self.h.template)
            .map(|(&c, _)| c)
            .collect()
    }
}
