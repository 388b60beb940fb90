//! "Verified" means what a person would see (issue 19, classes 1-4), over each API: the
//! user's objects under `Maze` are left alone and named; one object in two roles is refused
//! before any edit; templates and markers of the wrong size are refused (or warned about);
//! and no template is left lying on the floor, after `apply` or after `clear`.

use tempfile::TempDir;
use vrep_maze::cli::remedies;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::mesh::MeshMaze;
use vrep_maze::draw::signals::HOME;
use vrep_maze::draw::{self, ApplyOptions, Backend, ClearOptions, DrawError, Drawing, ObjectNames};
use vrep_maze::layout::{Layout, read_layout};
use vrep_maze::sim::{NewObject, ObjectType, Scene};

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::layouts::drawing;

backend_tests!(
    objects_that_are_not_ours_are_left_alone_and_named,
    one_object_in_two_roles_is_refused_before_any_edit,
    sizes_that_contradict_the_layout_are_refused,
    a_marker_larger_than_a_cell_is_a_warning,
    clear_puts_the_template_back_where_it_stood,
    a_one_cell_maze_puts_the_template_below_the_floor,
    a_maze_without_a_record_of_home_hides_the_template_on_clear,
    no_older_version_is_blamed_for_a_wall_maze_or_a_mesh_maze,
    a_wall_maze_sends_the_line_template_home,
    a_wall_template_standing_on_the_maze_is_a_warning,
    copy_named_objects_of_another_size_or_with_children_are_the_users,
    a_small_cuboid_named_like_a_wall_copy_is_the_users,
    mesh_mode_refuses_a_line_template_of_another_size,
);

/// Class 4 for wall mazes: the `Wall` and `Post` templates stay where the scene has them,
/// so one standing on the maze shows as an extra wall: a warning names it.
fn a_wall_template_standing_on_the_maze_is_a_warning(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course_walls(), 0);
    let mut b = s.connect();
    let walls = generated(&dir, "walls.json", &["--style", "walls", "--size", "3x3"]);
    let r = apply(&mut *b, &walls).unwrap();
    assert!(
        r.warnings.is_empty(),
        "{k}: the course Wall stands beside the floor: {:?}",
        r.warnings
    );
    s.with_sim(|sim| {
        let wall = sim.scene.resolve("Wall").unwrap();
        sim.scene
            .set_position(wall, HANDLE_WORLD, [0.5, 0.5, 0.1])
            .unwrap();
    });
    let r = apply(&mut *b, &walls).unwrap();
    assert!(
        r.warnings.len() == 1 && r.warnings[0].contains("`Wall` stands on the maze"),
        "{k}: {:?}",
        r.warnings
    );
    drop(b);
    s.shutdown();
}

/// An object of `kind` and `size` named `name`, under `parent` at (x, y, z).
fn object(kind: ObjectType, parent: Option<i32>, at: [f64; 3], size: [f64; 3]) -> NewObject {
    NewObject {
        kind,
        parent,
        position: at,
        orientation: [0.0; 3],
        size,
        colour: [200, 200, 0],
    }
}

/// The course scene with the user's objects: under `Maze` a dummy `MySensor`, a 0.2 m
/// cuboid `Box`, a 1 m plane `BigPlane`, a dummy `Line9` (a copy's name, not a plane) and a
/// 1 m plane `Line12` (a copy's name and type, not its size); at the root a dummy `Line5`. Returns the scene and the names under `Maze`.
pub fn scene_with_the_users_objects() -> (Scene, Vec<&'static str>) {
    let mut scene = Scene::course();
    let maze = scene.resolve("Maze").unwrap();
    let under = Some(maze);
    scene.add(
        "MySensor",
        object(ObjectType::Dummy, under, [1.0, 1.0, 0.3], [0.01; 3]),
    );
    scene.add(
        "Box",
        object(ObjectType::Shape, under, [-2.0, 3.0, 0.1], [0.2; 3]),
    );
    scene.add(
        "BigPlane",
        object(
            ObjectType::Shape,
            under,
            [4.0, -4.0, 0.001],
            [1.0, 1.0, 0.0],
        ),
    );
    scene.add(
        "Line9",
        object(ObjectType::Dummy, under, [0.5, 0.5, 0.5], [0.01; 3]),
    );
    scene.add(
        "Line12",
        object(
            ObjectType::Shape,
            under,
            [-4.0, -4.0, 0.001],
            [1.0, 1.0, 0.0],
        ),
    );
    scene.add(
        "Line5",
        object(ObjectType::Dummy, None, [3.0, 3.0, 0.5], [0.01; 3]),
    );
    (
        scene,
        vec!["MySensor", "Box", "BigPlane", "Line9", "Line12"],
    )
}

/// World pose and parent of each of `names`.
fn poses(s: &Server, names: &[&str]) -> Vec<([f64; 3], [f64; 3], Option<i32>)> {
    s.with_sim(|sim| {
        names
            .iter()
            .map(|n| {
                let h = sim
                    .scene
                    .resolve(n)
                    .unwrap_or_else(|_| panic!("{n} exists"));
                let (p, e) = sim.scene.pose(h, HANDLE_WORLD).unwrap();
                (p, e, sim.scene.get(h).unwrap().parent)
            })
            .collect()
    })
}

fn apply(b: &mut dyn draw::Backend, d: &Drawing) -> Result<draw::ApplyReport, DrawError> {
    draw::apply(b, d, &ApplyOptions::default(), &mut |_| {})
}

fn dry_run(b: &mut dyn draw::Backend, d: &Drawing) -> draw::ApplyReport {
    let opts = ApplyOptions {
        dry_run: true,
        ..Default::default()
    };
    draw::apply(b, d, &opts, &mut |_| {}).unwrap()
}

/// Class 1: apply (and dry runs), re-apply, verify and clear never move, reuse or remove the
/// user's objects, and name the ones under `Maze`.
fn objects_that_are_not_ours_are_left_alone_and_named(kind: Kind) {
    let k = kind.name();
    let (scene, under_maze) = scene_with_the_users_objects();
    let s = kind.serve(scene, 0);
    let mine = ["MySensor", "Box", "BigPlane", "Line9", "Line12", "Line5"];
    let before = poses(&s, &mine);
    let mut b = s.connect();
    let big = drawing(6, 3);
    let planned = dry_run(&mut *b, &big);
    for name in &under_maze {
        assert!(
            planned.left_alone.iter().any(|n| n == name),
            "{k}: dry run names {name}: {planned:?}"
        );
    }
    let r = apply(&mut *b, &big).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!((r.reused, r.removed), (0, 0), "{k}: {r:?}");
    for name in &under_maze {
        assert!(
            r.left_alone.iter().any(|n| n == name),
            "{k}: {name} named: {:?}",
            r.left_alone
        );
    }
    assert_eq!(
        s.line_count(),
        big.pieces.len(),
        "{k}: only copies of Line drawn"
    );
    draw::verify(&mut *b, &big, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    // a smaller maze over it removes copies only
    let small = drawing(3, 1);
    let r = apply(&mut *b, &small).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        r.removed,
        big.pieces.len() - small.pieces.len(),
        "{k}: {r:?}"
    );
    assert_eq!(
        poses(&s, &mine),
        before,
        "{k}: the user's objects untouched by apply"
    );
    let would = draw::clear(
        &mut *b,
        &ClearOptions {
            dry_run: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        would.removed.iter().all(|n| !mine.contains(&n.as_str())),
        "{k}: {would:?}"
    );
    let cleared = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        cleared.removed.len(),
        small.pieces.len() - 1,
        "{k}: {cleared:?}"
    );
    for name in &under_maze {
        assert!(
            cleared.left_alone.iter().any(|n| n == name),
            "{k}: clear names {name}"
        );
    }
    assert_eq!(
        poses(&s, &mine),
        before,
        "{k}: the user's objects untouched by clear"
    );
    drop(b);
    s.shutdown();
}

/// The course scene with the user's objects named and typed like copies of `Line` but no
/// copies: under `Maze` a 1 m plane `Line9`, a 0.3 m plane with `Line`'s own alias (as a
/// user renaming a new plane gets), a 0.6 x 0.1 x 0.05 cuboid `Line4` (another primitive
/// of the line's length and width), a plane of `Line`'s size `Line6` with a dummy of its
/// own under it, and a plane 0.7 mm longer than `Line`, `Line8`; at the root a 1 m plane
/// `Line7`. Returns the scene and their handles.
fn scene_with_copy_named_objects() -> (Scene, Vec<i32>) {
    let mut scene = Scene::course();
    let maze = Some(scene.resolve("Maze").unwrap());
    let plane = |size: [f64; 2], parent| {
        object(
            ObjectType::Shape,
            parent,
            [4.0, -4.0, 0.001],
            [size[0], size[1], 0.0],
        )
    };
    let mut mine = vec![
        scene.add("Line9", plane([1.0, 1.0], maze)),
        scene.create("Line", plane([0.3, 0.1], maze)),
        scene.add(
            "Line4",
            object(
                ObjectType::Shape,
                maze,
                [-4.0, 4.0, 0.025],
                [0.6, 0.1, 0.05],
            ),
        ),
        scene.add("Line6", plane([0.6, 0.1], maze)),
        scene.add("Line8", plane([0.6007, 0.1], maze)),
        scene.add("Line7", plane([1.0, 1.0], None)),
    ];
    let parent = Some(mine[3]);
    mine.push(scene.add(
        "Sensor6",
        object(ObjectType::Dummy, parent, [4.0, -4.0, 0.1], [0.01; 3]),
    ));
    (scene, mine)
}

/// World pose and parent of each of `handles`.
fn poses_of(s: &Server, handles: &[i32]) -> Vec<([f64; 3], [f64; 3], Option<i32>)> {
    s.with_sim(|sim| {
        handles
            .iter()
            .map(|&h| {
                let (p, e) = sim.scene.pose(h, HANDLE_WORLD).expect("still there");
                (p, e, sim.scene.get(h).unwrap().parent)
            })
            .collect()
    })
}

/// Class 1, by size and tree: an object under `Maze` named and typed like a copy of `Line`
/// but of another size (0.5 mm tolerance), another primitive of its length and width, or
/// with children of its own, is the user's: a dry run, apply, a smaller re-apply, verify
/// and clear leave it where it is and name the five under `Maze`.
fn copy_named_objects_of_another_size_or_with_children_are_the_users(kind: Kind) {
    let k = kind.name();
    let (scene, mine) = scene_with_copy_named_objects();
    let s = kind.serve(scene, 0);
    let before = poses_of(&s, &mine);
    let mut b = s.connect();
    let big = drawing(6, 3);
    let named = |left_alone: &[String]| {
        // the one with Line's alias is `Line0` over legacy, `/Line[k]` over ZeroMQ; the
        // legacy API lists the root `Line7` too (ZeroMQ reads no root object without a
        // template's alias)
        ["Line9", "Line4", "Line6", "Line8"]
            .iter()
            .all(|n| left_alone.iter().any(|l| l == n))
            && left_alone.iter().filter(|l| *l != "Line7").count() == 5
    };
    let planned = dry_run(&mut *b, &big);
    assert!(named(&planned.left_alone), "{k}: {planned:?}");
    assert_eq!(
        (planned.reused, planned.removed),
        (0, 0),
        "{k}: {planned:?}"
    );
    let r = apply(&mut *b, &big).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!((r.reused, r.removed), (0, 0), "{k}: {r:?}");
    assert!(named(&r.left_alone), "{k}: {:?}", r.left_alone);
    draw::verify(&mut *b, &big, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    let small = drawing(3, 1);
    let r = apply(&mut *b, &small).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        r.removed,
        big.pieces.len() - small.pieces.len(),
        "{k}: {r:?}"
    );
    // a new connection knows them from the scene alone
    drop(b);
    let mut b = s.connect();
    draw::verify(&mut *b, &small, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    let cleared = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        cleared.removed.len(),
        small.pieces.len() - 1,
        "{k}: {cleared:?}"
    );
    assert!(named(&cleared.left_alone), "{k}: {:?}", cleared.left_alone);
    assert_eq!(
        poses_of(&s, &mine),
        before,
        "{k}: the user's objects untouched"
    );
    drop(b);
    s.shutdown();
}

/// Class 1 in a wall maze: a 0.2 m cuboid `Wall3` under `Maze` is no copy of the 1 x 0.05 x
/// 0.2 m `Wall`: apply, verify and clear leave it alone and name it.
fn a_small_cuboid_named_like_a_wall_copy_is_the_users(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let mut scene = Scene::course_walls();
    let maze = scene.resolve("Maze").unwrap();
    let cuboid = scene.add(
        "Wall3",
        object(ObjectType::Shape, Some(maze), [-2.0, 3.0, 0.1], [0.2; 3]),
    );
    let s = kind.serve(scene, 0);
    let before = poses_of(&s, &[cuboid]);
    let mut b = s.connect();
    let walls = generated(&dir, "walls.json", &["--style", "walls", "--size", "4x4"]);
    let r = apply(&mut *b, &walls).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!((r.reused, r.removed), (0, 0), "{k}: {r:?}");
    assert_eq!(r.left_alone, vec!["Wall3"], "{k}");
    draw::verify(&mut *b, &walls, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    let cleared = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        cleared.removed.len(),
        walls.pieces.len(),
        "{k}: {cleared:?}"
    );
    assert_eq!(cleared.left_alone, vec!["Wall3"], "{k}");
    assert_eq!(poses_of(&s, &[cuboid]), before, "{k}: untouched");
    drop(b);
    s.shutdown();
}

/// Class 1: a copy-named object of the template's type and size that the drawing did not
/// place is a stray line: verify fails, and apply removes it.
#[test]
fn a_stray_copy_of_the_template_never_verifies() {
    for kind in Kind::ALL {
        let s = kind.serve(Scene::course(), 0);
        let d = drawing(3, 3);
        let mut b = s.connect();
        apply(&mut *b, &d).unwrap();
        s.with_sim(|sim| {
            let maze = sim.scene.resolve("Maze").unwrap();
            // the template's colour too: a copy in every way the APIs read
            let green = sim
                .scene
                .get(sim.scene.resolve("Line").unwrap())
                .unwrap()
                .colour;
            sim.scene.add(
                "Line77",
                NewObject {
                    colour: green,
                    ..object(
                        ObjectType::Shape,
                        Some(maze),
                        [9.0, 9.0, 0.001],
                        [0.6, 0.1, 0.0],
                    )
                },
            );
        });
        let e = draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap_err();
        assert!(
            vrep_maze::cli::remedies::message(&e).contains("1 stray maze object"),
            "{}: {e}",
            kind.name()
        );
        let r = apply(&mut *b, &d).unwrap();
        assert_eq!(r.removed, 1, "{}: {r:?}", kind.name());
        drop(b);
        s.shutdown();
    }
}

/// Class 2: any two roles on one object (one name, or two names of one object) are refused
/// before anything changes, naming both roles; apply, clear and verify alike.
fn one_object_in_two_roles_is_refused_before_any_edit(kind: Kind) {
    let k = kind.name();
    let mut scene = Scene::course_walls();
    let maze = scene.resolve("Maze").unwrap();
    let line = scene.resolve("Line").unwrap();
    scene.set_parent(line, Some(maze), true).unwrap();
    let s = kind.serve(scene, 8);
    let before = s.snapshot();
    let mut b = s.connect();
    let d = drawing(3, 1);
    let base = ObjectNames::default();
    let cases: Vec<(ObjectNames, &str, &str)> = vec![
        (
            ObjectNames {
                line: "Maze".into(),
                ..base.clone()
            },
            "--parent",
            "--line",
        ),
        (
            ObjectNames {
                line: "Floor".into(),
                ..base.clone()
            },
            "--floor",
            "--line",
        ),
        (
            ObjectNames {
                parent: "Floor".into(),
                ..base.clone()
            },
            "--floor",
            "--parent",
        ),
        (
            ObjectNames {
                line: "Start".into(),
                ..base.clone()
            },
            "--line",
            "--start",
        ),
        (
            ObjectNames {
                wall: "Line".into(),
                ..base.clone()
            },
            "--line",
            "--wall",
        ),
        (
            ObjectNames {
                end: "/Start".into(),
                ..base.clone()
            },
            "--start",
            "--end",
        ),
        (
            ObjectNames {
                post: "Wall".into(),
                ..base.clone()
            },
            "--wall",
            "--post",
        ),
        // two names, one object: resolved by the simulator
        (
            ObjectNames {
                line: "/Maze/Line".into(),
                start: "Line".into(),
                ..base.clone()
            },
            "--line",
            "--start",
        ),
    ];
    for (names, first, second) in cases {
        let opts = ApplyOptions {
            names: names.clone(),
            ..Default::default()
        };
        let e = draw::apply(&mut *b, &d, &opts, &mut |_| {}).unwrap_err();
        let text = remedies::message(&e);
        assert!(
            matches!(e, DrawError::SameObject { .. })
                && text.contains(first)
                && text.contains(second),
            "{k}: {names:?}: {text}"
        );
        let clear = ClearOptions {
            names: names.clone(),
            ..Default::default()
        };
        assert!(
            matches!(
                draw::clear(&mut *b, &clear),
                Err(DrawError::SameObject { .. })
            ),
            "{k}"
        );
        assert!(
            matches!(
                draw::verify(&mut *b, &d, &names),
                Err(DrawError::SameObject { .. })
            ),
            "{k}"
        );
    }
    assert_eq!(s.snapshot(), before, "{k}: nothing moved");
    assert_eq!(s.idle_fps(), 8, "{k}");
    drop(b);
    s.shutdown();
}

/// A layout generated by the binary with `args` (and `--seed 1`).
fn generated(dir: &TempDir, name: &str, args: &[&str]) -> Drawing {
    Drawing::try_from(&generated_layout(dir, name, args)).unwrap()
}

/// The layout `generate --seed 1 ARGS` writes to `dir/name`.
fn generated_layout(dir: &TempDir, name: &str, args: &[&str]) -> Layout {
    let path = dir.path().join(name);
    bin()
        .args(["generate", "--seed", "1", "-o"])
        .arg(&path)
        .args(args)
        .assert()
        .success();
    read_layout(&path).unwrap()
}

/// Class 3: the help's own example on the course scene (0.6 x 0.1 Line), a micromouse
/// layout over a 1 m Wall, and walls of the wrong height are refused with what to change,
/// before any edit (also by verify, and in a dry run).
fn sizes_that_contradict_the_layout_are_refused(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course_walls(), 0);
    let before = s.snapshot();
    let mut b = s.connect();
    let short = generated(
        &dir,
        "short.json",
        &[
            "--size",
            "4x4",
            "--cell-size",
            "0.5",
            "--line-length",
            "0.3",
            "--line-width",
            "0.05",
        ],
    );
    let e = apply(&mut *b, &short).unwrap_err();
    let text = vrep_maze::cli::remedies::message(&e);
    assert!(
        matches!(e, DrawError::Sizes(_))
            && text.contains("`Line` is 0.6 x 0.1 m")
            && text.contains("generate with --line-length 0.6 --line-width 0.1")
            && text.contains("resize `Line` to 0.3 x 0.05 m"),
        "{k}: {text}"
    );
    let dry = ApplyOptions {
        dry_run: true,
        ..Default::default()
    };
    assert!(
        matches!(
            draw::apply(&mut *b, &short, &dry, &mut |_| {}),
            Err(DrawError::Sizes(_))
        ),
        "{k}"
    );
    assert!(
        matches!(
            draw::verify(&mut *b, &short, &ObjectNames::default()),
            Err(DrawError::Sizes(_))
        ),
        "{k}"
    );
    let mouse = generated(&dir, "mouse.json", &["--preset", "micromouse-half"]);
    let e = apply(&mut *b, &mouse).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    assert!(
        e.contains("`Wall` is 1 x 0.05 x 0.2 m") && e.contains("--wall-length 1 "),
        "{k}: {e}"
    );
    let thick = generated(
        &dir,
        "posts.json",
        &[
            "--style",
            "walls",
            "--posts",
            "--post-size",
            "0.1",
            "--size",
            "3x3",
        ],
    );
    let e = apply(&mut *b, &thick).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    assert!(
        e.contains("`Post` is 0.05 x 0.05 x 0.2 m")
            && e.contains("--post-size 0.05")
            && !e.contains("`Wall`"),
        "{k}: a 1 m wall between posts hides its ends in them; the post is refused: {e}"
    );
    let low = generated(
        &dir,
        "low.json",
        &["--style", "walls", "--wall-height", "0.1", "--size", "3x3"],
    );
    let e = apply(&mut *b, &low).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    assert!(e.contains("--wall-height 0.2"), "{k}: {e}");
    assert_eq!(s.snapshot(), before, "{k}: nothing drawn");
    // the same layout fits once the template is resized
    s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_size(line, [0.3, 0.05, 0.0]).unwrap();
    });
    apply(&mut *b, &short).unwrap_or_else(|e| panic!("{k}: {e}"));
    // within half a millimetre is the same size (single precision, millimetre dialogs)
    s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_size(line, [0.3004, 0.0496, 0.0]).unwrap();
    });
    draw::verify(&mut *b, &short, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_size(line, [0.3007, 0.05, 0.0]).unwrap();
    });
    assert!(
        matches!(apply(&mut *b, &short), Err(DrawError::Sizes(_))),
        "{k}"
    );
    drop(b);
    s.shutdown();
}

/// Class 3: `Start` and `End` wider than a cell cover the neighbouring cells: drawn, with a
/// warning naming each and the size to give it.
fn a_marker_larger_than_a_cell_is_a_warning(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let mut scene = Scene::course();
    let line = scene.resolve("Line").unwrap();
    scene.set_size(line, [0.3, 0.05, 0.0]).unwrap();
    let s = kind.serve(scene, 0);
    let mut b = s.connect();
    let small = generated(
        &dir,
        "small.json",
        &[
            "--size",
            "4x4",
            "--cell-size",
            "0.5",
            "--line-length",
            "0.3",
            "--line-width",
            "0.05",
        ],
    );
    let r = apply(&mut *b, &small).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(r.warnings.len(), 2, "{k}: {:?}", r.warnings);
    assert!(
        r.warnings[0].contains("`Start` is 1 x 1 m but the cells are 0.5 m")
            && r.warnings[1].contains("`End`")
            && r.warnings[0].contains("at most 0.5 x 0.5 m"),
        "{k}: {:?}",
        r.warnings
    );
    let course = drawing(3, 1);
    s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_size(line, [0.6, 0.1, 0.0]).unwrap();
    });
    // the copies of the smaller template are replaced (named in a warning of their own):
    // no warning about the markers
    let r = apply(&mut *b, &course).unwrap();
    assert!(
        r.warnings.iter().all(|w| w.starts_with("replaced ")),
        "{k}: 1 m markers on 1 m cells: {:?}",
        r.warnings
    );
    drop(b);
    s.shutdown();
}

/// The floor-frame position of `name`.
fn position(s: &Server, name: &str) -> [f64; 3] {
    s.with_sim(|sim| {
        let h = sim.scene.resolve(name).unwrap();
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene.pose(h, floor).unwrap().0
    })
}

fn near(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-4)
}

/// Class 4: after apply and clear (twice, with a re-apply between) the template stands
/// where it stood before the first apply, and the record is gone.
fn clear_puts_the_template_back_where_it_stood(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let home = position(&s, "Line");
    let mut b = s.connect();
    let d = drawing(4, 2);
    apply(&mut *b, &d).unwrap();
    assert!(
        !near(position(&s, "Line"), home),
        "{k}: the template is the first line"
    );
    apply(&mut *b, &drawing(5, 7)).unwrap();
    let r = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(
        r.template
            .as_deref()
            .is_some_and(|t| t.contains("back where it stood")),
        "{k}: {r:?}"
    );
    assert!(
        near(position(&s, "Line"), home),
        "{k}: {:?} != {home:?}",
        position(&s, "Line")
    );
    let left = s.with_sim(|sim| {
        HOME.iter()
            .filter(|n| sim.int_signals.contains_key(n.name))
            .count()
    });
    assert_eq!(left, 0, "{k}: the record is deleted");
    let again = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(again.template, None, "{k}");
    assert!(near(position(&s, "Line"), home), "{k}");
    drop(b);
    s.shutdown();
}

/// Class 4: a 1 x 1 layout has no line: the template goes below the floor, and clear
/// brings it back.
fn a_one_cell_maze_puts_the_template_below_the_floor(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let home = position(&s, "Line");
    let mut b = s.connect();
    apply(&mut *b, &drawing(3, 1)).unwrap();
    let one = drawing(1, 1);
    apply(&mut *b, &one).unwrap();
    let at = position(&s, "Line");
    assert!(at[2] < -0.05, "{k}: below the floor: {at:?}");
    draw::verify(&mut *b, &one, &ObjectNames::default()).unwrap();
    draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(near(position(&s, "Line"), home), "{k}");
    drop(b);
    s.shutdown();
}

/// Class 4: a maze drawn by an older version has no record of the template's home: clear
/// says so and puts the template below the floor, not on the maze's first line.
fn a_maze_without_a_record_of_home_hides_the_template_on_clear(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    apply(&mut *b, &drawing(4, 2)).unwrap();
    s.with_sim(|sim| {
        HOME.iter().for_each(|n| {
            sim.int_signals.remove(n.name);
        })
    });
    let r = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    let said = r.template.unwrap_or_default();
    assert!(
        said.contains("no record") && said.contains("below the floor"),
        "{k}: {said}"
    );
    assert!(position(&s, "Line")[2] < -0.05, "{k}");
    // and an apply over such a maze warns that clear will do so
    apply(&mut *b, &drawing(4, 2)).unwrap();
    s.with_sim(|sim| {
        HOME.iter().for_each(|n| {
            sim.int_signals.remove(n.name);
        })
    });
    let r = apply(&mut *b, &drawing(3, 2)).unwrap();
    assert!(
        r.warnings.iter().any(|w| w.contains("no record")),
        "{k}: {:?}",
        r.warnings
    );
    drop(b);
    s.shutdown();
}

/// Class 4: a wall maze replacing a line maze does not leave the line template lying where
/// the first line was, nor anywhere on the floor: it goes below the floor under where it
/// stood before the first apply, and `clear` puts it back there.
fn a_wall_maze_sends_the_line_template_home(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course_walls(), 0);
    let home = position(&s, "Line");
    let mut b = s.connect();
    apply(&mut *b, &drawing(3, 2)).unwrap();
    let walls = generated(&dir, "walls.json", &["--style", "walls", "--size", "3x3"]);
    apply(&mut *b, &walls).unwrap_or_else(|e| panic!("{k}: {e}"));
    let below = [home[0], home[1], -vrep_maze::draw::home::HIDDEN_DEPTH];
    assert!(
        near(position(&s, "Line"), below),
        "{k}: {:?}",
        position(&s, "Line")
    );
    draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(
        near(position(&s, "Line"), home),
        "{k}: {:?}",
        position(&s, "Line")
    );
    drop(b);
    s.shutdown();
}

/// Class 2 on the command line: refused at once, before connecting (no simulator needed).
#[test]
fn cli_refuses_two_roles_before_connecting() {
    let dir = TempDir::new().unwrap();
    let layout = crate::support::cli::generate(dir.path(), "1", "dfs");
    for (args, roles) in [
        (vec!["--line", "Maze"], ["--parent", "--line"]),
        (vec!["--parent", "Floor"], ["--floor", "--parent"]),
        (vec!["--wall", "Line"], ["--line", "--wall"]),
    ] {
        let out = bin()
            .args(["apply", &layout, "--port", "9", "--connect-timeout", "30"])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(
            err.contains("two roles")
                && roles.iter().all(|r| err.contains(r))
                && !err.contains("connect"),
            "{args:?}: {err}"
        );
        let out = bin()
            .args(["clear", "--port", "9", "--connect-timeout", "30"])
            .args(&args)
            .output()
            .unwrap();
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("two roles"),
            "clear {args:?}"
        );
    }
}

/// Class 3 in mesh mode (`apply --draw mesh`): `Line` lies on the first line, so a template
/// of another size than the layout's lines is refused before any edit, by apply and verify;
/// a wall maze's boxes take the layout's sizes whatever `Wall` and `Post` measure (only
/// their looks are read), so those are not compared; a marker wider than a cell is a warning.
fn mesh_mode_refuses_a_line_template_of_another_size(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course_walls(), 0);
    let before = s.snapshot();
    let mut b = s.connect();
    let mesh = |name: &str, args: &[&str]| {
        MeshMaze::try_from(&generated_layout(&dir, name, args)).unwrap()
    };
    let short = mesh(
        "short.json",
        &[
            "--size",
            "4x4",
            "--line-length",
            "0.3",
            "--line-width",
            "0.05",
            "--cell-size",
            "0.5",
        ],
    );
    let draw_mesh = |b: &mut dyn Backend, m: &MeshMaze| {
        draw::mesh::apply(b, m, &ApplyOptions::default(), &mut |_| {})
    };
    let e = draw_mesh(&mut *b, &short).unwrap_err();
    let text = vrep_maze::cli::remedies::message(&e);
    assert!(
        matches!(e, DrawError::Sizes(_)) && text.contains("resize `Line` to 0.3 x 0.05 m"),
        "{k}: {text}"
    );
    assert!(
        matches!(
            draw::mesh::verify(&mut *b, &short, &ObjectNames::default()),
            Err(DrawError::Sizes(_))
        ),
        "{k}"
    );
    assert_eq!(s.snapshot(), before, "{k}: nothing drawn");
    // micromouse walls (0.168 m cells) over the course's 1 m Wall: boxes of the layout's size
    let mouse = mesh("mouse.json", &["--preset", "micromouse-half"]);
    let r = draw_mesh(&mut *b, &mouse).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert!(
        r.warnings.iter().any(|w| w.contains("`Start`")),
        "{k}: the 1 m Start covers the neighbouring cells: {:?}",
        r.warnings
    );
    drop(b);
    s.shutdown();
}

/// A way of drawing a layout (as copies or as meshes).
type DrawWith<'a> = dyn Fn(&mut dyn Backend, &Layout) -> draw::ApplyReport + 'a;

/// Class 4: the "older vrep-maze" warning is for line copies without a record only. A wall
/// maze never moves the line template, so a line maze drawn after one (copies or meshes, over
/// copies or meshes) records the template where it stands, without a warning; a line mesh
/// maze without a record (a scene loaded from `export -o x.simscene.xml`, which puts the
/// template on the first line under a mesh) hides it below the floor, silently.
fn no_older_version_is_blamed_for_a_wall_maze_or_a_mesh_maze(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let walls = generated_layout(&dir, "walls.json", &["--style", "walls", "--size", "3x3"]);
    let lines = generated_layout(&dir, "lines.json", &["--size", "3x3"]);
    let forget = |s: &Server| {
        s.with_sim(|sim| {
            HOME.iter().for_each(|n| {
                sim.int_signals.remove(n.name);
                sim.int_signals.remove(n.old);
            })
        })
    };
    let opts = ApplyOptions::default();
    let copies = |b: &mut dyn Backend, l: &Layout| {
        draw::apply(b, &Drawing::try_from(l).unwrap(), &opts, &mut |_| {}).unwrap()
    };
    let meshes = |b: &mut dyn Backend, l: &Layout| {
        draw::mesh::apply(b, &MeshMaze::try_from(l).unwrap(), &opts, &mut |_| {}).unwrap()
    };
    let modes: [(&str, &DrawWith<'_>); 2] = [("copies", &copies), ("meshes", &meshes)];
    for (first, draw_walls) in modes {
        for (then, draw_lines) in modes {
            let s = kind.serve(Scene::course_walls(), 0);
            let home = position(&s, "Line");
            let mut b = s.connect();
            draw_walls(&mut *b, &walls);
            let r = draw_lines(&mut *b, &lines);
            assert_eq!(
                r.warnings,
                Vec::<String>::new(),
                "{k}: walls {first}, lines {then}"
            );
            draw::clear(&mut *b, &ClearOptions::default()).unwrap();
            assert!(
                near(position(&s, "Line"), home),
                "{k}: walls {first}, lines {then}"
            );
            drop(b);
            s.shutdown();
        }
    }
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let r = meshes(&mut *b, &lines);
    // three poses counted: the template on the first line is named with the markers
    assert!(
        vrep_maze::cli::summary::apply_line(&r)
            .contains("; Start, End and the line template: 0 already in place, 3 placed; "),
        "{k}: {r:?}"
    );
    forget(&s);
    let r = copies(&mut *b, &lines);
    assert_eq!(
        r.warnings,
        Vec::<String>::new(),
        "{k}: a mesh maze without a record"
    );
    draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(
        position(&s, "Line")[2] < -0.05,
        "{k}: hidden below the floor"
    );
    drop(b);
    s.shutdown();
}
