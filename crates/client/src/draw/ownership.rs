//! Which objects of a scene are ours: the one test of a template's copy (the copy record
//! first, then name, type, size, colour and children), the survey sorted into what a drawing
//! may consider and what is the user's, and an earlier maze's lines or walls and another
//! style's copies.

use super::backend::ObjectInfo;
use super::names::Handles;
use super::survey::Traits;
use super::tolerance::{same_colour, same_extents};
use vrep_maze_core::coppelia::names;

/// The name a template's copies are named after, from the reference that names it: a
/// plain name as it is (`Line`, `Line5`, `Seg#0`), a path (`/Line[0]`, `/Maze/Line{2}`,
/// `./Line`) by its last alias without the index (`Line`): a copy keeps its original's
/// alias, wherever the path found it.
pub fn family(template: &str) -> &str {
    if !template.starts_with(['/', '.', ':']) {
        return template;
    }
    let last = template.rsplit('/').next().unwrap_or(template);
    let last = last.trim_start_matches(['.', ':']);
    last.split(['[', '{']).next().unwrap_or(last)
}

/// True if `name` is a pasted copy of the template named `template`: `Line0`, `Line17`
/// (plain naming) or `Line#0` (hash naming). A template named `Line5` has copies `Line6`...
/// A template named by a path (`/Line[0]`) has the copies of its alias ([`family`]).
pub fn is_copy_name(name: &str, template: &str) -> bool {
    if name == template {
        return false;
    }
    let template = family(template);
    // ZeroMQ backend: copies keep the template's alias, so a root copy's path is `/Line[n]`
    let alias = template.rsplit('/').next().unwrap_or(template);
    let path_copy = name
        .strip_prefix('/')
        .and_then(|r| r.strip_prefix(alias))
        .and_then(|r| r.strip_prefix('['))
        .and_then(|r| r.strip_suffix(']'))
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|c| c.is_ascii_digit()));
    path_copy || names::is_copy_of(name, template)
}

/// What differs between the copy `handle` and its `template` by what a backend read
/// (`traits`: sizes, colours, visibility layers), `None` when nothing read differs: "is 0.78 x 0.13 x 0 m, the
/// template 0.6 x 0.1 x 0 m", "is coloured ...". What a backend did not read is no evidence.
pub fn spoiled(traits: &Traits, handle: i32, template: i32) -> Option<String> {
    let size = |h: i32| traits.sizes.get(&h).copied();
    let colour = |h: i32| traits.colours.get(&h).copied();
    let metres = |s: [f64; 3]| s.map(|v| format!("{:.4}", v + 0.0)).join(" x ");
    let rgb = |c: [f64; 3]| c.map(|v| format!("{:.2}", v + 0.0)).join(", ");
    if let (Some(a), Some(b)) = (size(handle), size(template))
        && !same_extents(a, b)
    {
        return Some(format!("is {} m, the template {} m", metres(a), metres(b)));
    }
    if let (Some(a), Some(b)) = (colour(handle), colour(template))
        && !same_colour(a, b)
    {
        return Some(format!(
            "is coloured ({}), the template ({})",
            rgb(a),
            rgb(b)
        ));
    }
    let layer = |h: i32| traits.layers.get(&h).copied();
    if let (Some(a), Some(b)) = (layer(handle), layer(template))
        && a != b
    {
        let hidden = if a == 0 { " (hidden)" } else { "" };
        return Some(format!(
            "is on visibility layer {a}{hidden}, the template on {b}"
        ));
    }
    None
}

/// `true` if what a backend read of `handle` ([`Traits`]) says it is no copy of the
/// template `template`, though named and typed like one: it has children of its own, or
/// both sizes were read and differ ([`same_extents`]), or both colours were read and differ
/// (a user's red copy of `Line` is no line of the maze, nor a source to paste from). A
/// copy the record holds ([`Traits::recorded`]) is contradicted only by children of its
/// own (the user put something under it: never reused, moved or removed); a recorded copy
/// of another size or colour is still ours ([`Traits::spoiled`]).
pub fn contradicts_copy(traits: &Traits, handle: i32, template: Option<i32>) -> bool {
    if traits.recorded.contains(&handle) {
        return traits.with_children.contains(&handle);
    }
    let size = |h: i32| traits.sizes.get(&h).copied();
    let colour = |h: i32| traits.colours.get(&h).copied();
    traits.with_children.contains(&handle)
        || matches!(
            (size(handle), template.and_then(size)),
            (Some(a), Some(b)) if !same_extents(a, b)
        )
        || matches!(
            (colour(handle), template.and_then(colour)),
            (Some(a), Some(b)) if !same_colour(a, b)
        )
}

/// `true` if `o` is a copy of the template named `template` (handle `template_handle`, if
/// in the scene, whose type code is `template_kind`): named in its family (`Line0`,
/// `Line#0`, `/Line[1]`, [`is_copy_name`]), of the template's type where both types are
/// known (a dummy or a cuboid named `Line3` is no copy of the `Line` plane), and not
/// contradicted by its size or children ([`contradicts_copy`]: a 1 m plane named `Line9` is
/// no copy of the 0.6 m `Line`). The one test of what a drawing may reuse, move or remove:
/// anything else is the user's.
pub fn is_copy_of(
    o: &ObjectInfo,
    template: &str,
    template_handle: Option<i32>,
    traits: &Traits,
) -> bool {
    let template_kind = template_handle.and_then(|t| traits.kinds.get(&t));
    (is_copy_name(&o.name, template) || traits.recorded.contains(&o.handle))
        && match (traits.kinds.get(&o.handle), template_kind) {
            (Some(kind), Some(template_kind)) => kind == template_kind,
            _ => true,
        }
        && !contradicts_copy(traits, o.handle, template_handle)
}

/// The objects of a survey sorted into those a drawing may consider and those it must
/// leave alone ([`sort_out`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Sorted {
    /// Every object but the user's under the maze dummy or at the scene root: the named
    /// objects, the templates' copies, and objects elsewhere in the scene.
    pub objects: Vec<ObjectInfo>,
    /// Names of the user's objects that a drawing could have mistaken for its own: the maze
    /// dummy's children that are no copy of a template, and root objects named like a copy
    /// but of another type or size, or with children. Left alone, and named in reports.
    pub strangers: Vec<String>,
}

/// Sorts `objects` ([`Sorted`]): an object that is a child of the maze dummy or has no
/// parent, is not one of the handles of `h`, not named as one of `templates` (line, wall,
/// post) and no copy of any of them ([`is_copy_of`], judged by what the backend read:
/// `traits`) is the user's.
pub fn sort_out(
    objects: &[ObjectInfo],
    h: &Handles,
    templates: &[&str],
    traits: &Traits,
) -> Sorted {
    let named = [h.floor, h.parent, h.template, h.start, h.end];
    let handle_of = |name: &str| objects.iter().find(|o| o.name == name).map(|o| o.handle);
    let families: Vec<(&str, Option<i32>)> = templates.iter().map(|t| (*t, handle_of(t))).collect();
    let mut sorted = Sorted {
        objects: Vec::with_capacity(objects.len()),
        strangers: Vec::new(),
    };
    for o in objects {
        let under_maze = o.parent == Some(h.parent);
        let ours = !(under_maze || o.parent.is_none())
            || named.contains(&o.handle)
            || Some(o.handle) == h.post
            || (under_maze && o.name.rsplit('/').next() == Some(super::mesh::HOLDER))
            || families
                .iter()
                .any(|(t, handle)| o.name == *t || is_copy_of(o, t, *handle, traits));
        if ours {
            sorted.objects.push(o.clone());
        } else if under_maze || families.iter().any(|(t, _)| is_copy_name(&o.name, t)) {
            sorted.strangers.push(o.name.clone());
        }
    }
    sorted
}

/// `true` if `o` is one of the `foreign` templates or named like a copy of one.
fn is_foreign(o: &ObjectInfo, foreign: &[&str]) -> bool {
    foreign
        .iter()
        .any(|f| o.name == *f || is_copy_name(&o.name, f))
}

/// The lines of an earlier maze: every child of the maze parent except the templates and
/// the `foreign` templates' objects ([`foreign_copies`]), then every parentless object named
/// like a copy of the line template (left by an interrupted run between pasting and
/// re-parenting). Children first, each group in handle order.
pub fn maze_pieces(
    objects: &[ObjectInfo],
    h: &Handles,
    template_name: &str,
    foreign: &[&str],
) -> Vec<i32> {
    let never_removed = h.never_removed();
    let eligible = |o: &&ObjectInfo| {
        !never_removed.contains(&o.handle)
            && o.handle != h.parent
            && o.handle != h.floor
            && !is_foreign(o, foreign)
    };
    let mut children: Vec<i32> = objects
        .iter()
        .filter(eligible)
        .filter(|o| o.parent == Some(h.parent))
        .map(|o| o.handle)
        .collect();
    let mut strays: Vec<i32> = objects
        .iter()
        .filter(eligible)
        .filter(|o| o.parent.is_none() && is_copy_name(&o.name, template_name))
        .map(|o| o.handle)
        .collect();
    children.sort_unstable();
    strays.sort_unstable();
    children.extend(strays);
    children
}

/// Copies of the `foreign` templates (another style's: walls when drawing lines, lines when
/// drawing walls) among the children of the maze parent and the parentless objects, in
/// handle order: an earlier maze of the other style, removed and never reused. The
/// templates themselves (named exactly so) are not among them.
pub fn foreign_copies(objects: &[ObjectInfo], h: &Handles, foreign: &[&str]) -> Vec<i32> {
    let mut copies: Vec<i32> = objects
        .iter()
        .filter(|o| o.parent == Some(h.parent) || o.parent.is_none())
        .filter(|o| foreign.iter().any(|f| is_copy_name(&o.name, f)))
        .map(|o| o.handle)
        .collect();
    copies.sort_unstable();
    copies
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::backend::object_at_origin as obj;

    /// The handles of the tests' scenes: Floor 1, Maze 2, Line 3, Start 4, End 5, no post
    /// template.
    fn handles() -> Handles {
        Handles {
            floor: 1,
            parent: 2,
            template: 3,
            start: 4,
            end: 5,
            post: None,
        }
    }

    /// The named objects of [`handles`], all at the scene root, then `more`.
    fn course(more: impl IntoIterator<Item = ObjectInfo>) -> Vec<ObjectInfo> {
        let named = ["Floor", "Maze", "Line", "Start", "End"];
        (1..)
            .zip(named)
            .map(|(h, name)| obj(h, name, None))
            .chain(more)
            .collect()
    }

    #[test]
    fn copy_names() {
        for yes in ["Line0", "Line12", "Line#0", "Line#33"] {
            assert!(is_copy_name(yes, "Line"), "{yes}");
        }
        for no in [
            "Line", "Lines0", "Line#", "Line#x", "Start0", "MyLine0", "Line0a",
        ] {
            assert!(!is_copy_name(no, "Line"), "{no}");
        }
        assert!(is_copy_name("Line6", "Line5"));
        assert!(is_copy_name("/Line[1]", "Line") && is_copy_name("/Line[12]", "/Line"));
        assert!(!is_copy_name("/Line", "Line") && !is_copy_name("/Line[x]", "Line"));
        assert!(is_copy_name("Seg#1", "Seg#0"));
        // a path to the template names its alias's family, index or not
        for template in ["/Line[0]", "/Line", "/Line{0}", "./Line", "/Course/Line[2]"] {
            assert_eq!(family(template), "Line", "{template}");
            for copy in ["/Line[1]", "Line#4", "Line7"] {
                assert!(is_copy_name(copy, template), "{copy} of {template}");
            }
            assert!(!is_copy_name("Line", template) && !is_copy_name("/Line", template));
        }
        assert_eq!(family("Line[0]"), "Line[0]", "a plain name is a name");
    }

    #[test]
    fn the_record_decides_first_then_colour_and_size() {
        let h = handles();
        let objects = course([
            obj(6, "Line0", Some(2)),
            obj(7, "Line1", Some(2)),
            obj(8, "Line2", Some(2)),
            obj(9, "Renamed", Some(2)),
        ]);
        let (green, red) = ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        let traits = Traits {
            kinds: (3..=9).map(|h| (h, 0)).collect(),
            // 7 is a red look-alike; 8 is within the dialogs' step of green
            colours: [
                (3, green),
                (6, green),
                (7, red),
                (8, [0.0, 0.995, 0.0]),
                (9, red),
            ]
            .into_iter()
            .collect(),
            // 9 was pasted by us and renamed; a recorded copy is never doubted
            recorded: [9].into_iter().collect(),
            ..Default::default()
        };
        let sorted = sort_out(&objects, &h, &["Line"], &traits);
        assert_eq!(sorted.strangers, vec!["Line1"]);
        assert!(sorted.objects.iter().any(|o| o.handle == 9));
        // a recorded copy is spoiled by its colour, not the user's; with a child it is
        assert_eq!(
            spoiled(&traits, 9, 3).as_deref(),
            Some("is coloured (1.00, 0.00, 0.00), the template (0.00, 1.00, 0.00)")
        );
        assert_eq!(spoiled(&traits, 6, 3), None);
        let mut parent = traits.clone();
        parent.with_children.insert(9);
        let sorted = sort_out(&objects, &h, &["Line"], &parent);
        assert_eq!(sorted.strangers, vec!["Line1", "Renamed"]);
    }

    #[test]
    fn maze_pieces_are_children_and_parentless_copies() {
        let h = handles();
        let mut objects = course([
            obj(9, "Line7", Some(2)),
            obj(8, "Renamed", Some(2)),
            obj(12, "Line#3", None),
            obj(11, "Line2", None),
            obj(13, "Line4", Some(1)),
            obj(14, "Cuboid0", None),
        ]);
        // the template and a marker under the maze dummy are none of its lines
        objects[2].parent = Some(2);
        objects[4].parent = Some(2);
        assert_eq!(maze_pieces(&objects, &h, "Line", &[]), vec![8, 9, 11, 12]);
    }

    #[test]
    fn another_styles_copies_are_foreign_and_its_template_untouched() {
        let h = handles();
        let mut objects = course([
            obj(6, "Wall", Some(2)),
            obj(7, "Wall0", Some(2)),
            obj(8, "Line0", Some(2)),
            obj(9, "/Wall[3]", None),
            obj(10, "Wall1", Some(1)),
        ]);
        assert_eq!(maze_pieces(&objects, &h, "Line", &["Wall"]), vec![8]);
        assert_eq!(foreign_copies(&objects, &h, &["Wall"]), vec![7, 9]);
        assert_eq!(maze_pieces(&objects, &h, "Line", &[]), vec![6, 7, 8]);
        // a wall maze with posts: the posts are neither walls nor lines
        objects.extend([
            obj(11, "Post", None),
            obj(12, "Post0", Some(2)),
            obj(13, "/Post[2]", None),
            obj(14, "Wall2", Some(2)),
        ]);
        let walls = Handles { template: 6, ..h };
        assert_eq!(
            maze_pieces(&objects, &walls, "Wall", &["Line", "Post"]),
            vec![7, 14, 9]
        );
        assert_eq!(foreign_copies(&objects, &h, &["Post"]), vec![12, 13]);
        assert_eq!(foreign_copies(&objects, &h, &["Line"]), vec![8]);
    }

    #[test]
    fn only_copies_of_a_template_by_name_and_type_are_the_mazes() {
        let h = handles();
        let objects = course([
            obj(6, "Line0", Some(2)),
            obj(7, "MySensor", Some(2)),
            obj(8, "Line1", Some(2)),
            obj(9, "/Line[2]", None),
            obj(10, "Line3", None),
            obj(11, "Camera", None),
            obj(12, "Wall0", Some(2)),
            obj(13, "Other", Some(1)),
        ]);
        // 0 shape, 4 dummy: Line1 and the root Line3 are dummies
        let traits = Traits {
            kinds: [(3, 0), (6, 0), (7, 4), (8, 4), (9, 0), (10, 4), (12, 0)]
                .into_iter()
                .collect(),
            ..Default::default()
        };
        let sorted = sort_out(&objects, &h, &["Line", "Wall", "Post"], &traits);
        let kept: Vec<i32> = sorted.objects.iter().map(|o| o.handle).collect();
        assert_eq!(kept, vec![1, 2, 3, 4, 5, 6, 9, 12, 13]);
        assert_eq!(sorted.strangers, vec!["MySensor", "Line1", "Line3"]);
        // a type nobody read: the name decides
        let sorted = sort_out(&objects, &h, &["Line"], &Traits::default());
        assert_eq!(sorted.strangers, vec!["MySensor", "Wall0"]);
    }

    #[test]
    fn a_copy_named_shape_of_another_size_or_with_children_is_the_users() {
        let h = handles();
        let objects = course([
            obj(6, "Line0", Some(2)),
            obj(7, "Line9", Some(2)),
            obj(8, "/Line[3]", Some(2)),
            obj(9, "Line4", Some(2)),
            obj(10, "Line5", None),
            obj(11, "Line6", Some(2)),
        ]);
        let line = [0.6, 0.1, 0.0];
        let traits = Traits {
            kinds: (3..=11).map(|h| (h, 0)).collect(),
            sizes: [
                (3, line),
                // single precision: within half a millimetre is the template's size
                (6, [0.6 + 4e-4, 0.1 - 4e-4, 0.0]),
                (7, [1.0, 1.0, 0.0]),
                (8, [0.6, 0.1, 0.05]),
                (9, line),
                (10, [0.6 + 7e-4, 0.1, 0.0]),
                (11, [f64::NAN, 0.1, 0.0]),
            ]
            .into_iter()
            .collect(),
            with_children: [9].into_iter().collect(),
            ..Default::default()
        };
        let sorted = sort_out(&objects, &h, &["Line", "Wall", "Post"], &traits);
        let kept: Vec<i32> = sorted.objects.iter().map(|o| o.handle).collect();
        assert_eq!(kept, vec![1, 2, 3, 4, 5, 6]);
        assert_eq!(
            sorted.strangers,
            vec!["Line9", "/Line[3]", "Line4", "Line5", "Line6"]
        );
        // a size read without its template's (or the other way round) is no evidence
        let mut unread = traits.clone();
        unread.sizes.remove(&3);
        unread.with_children.clear();
        assert_eq!(
            sort_out(&objects, &h, &["Line"], &unread).objects.len(),
            objects.len()
        );
    }
}
