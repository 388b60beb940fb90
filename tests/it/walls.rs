//! Wall mazes and micromouse: `generate --style walls` and `--preset micromouse` validate
//! and render; apply draws walls (and posts) into each emulated server and verifies; a line
//! maze applied over walls replaces them (and the reverse), a wall maze without posts
//! removes the posts; `clear` removes walls and posts.

use std::fs;

use vrep_maze::cli::remedies;
use vrep_maze::draw::{self, ApplyOptions, Backend, DrawError, Drawing, ObjectNames, Sizes};
use vrep_maze::layout::json::parse_layout;
use vrep_maze::layout::walls::{WallOptions, into_walls, length_between_posts};
use vrep_maze::layout::{Layout, Style, passages};
use vrep_maze::maze::Grid;
use vrep_maze::sim::Scene;
use vrep_maze::validate::validate;

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::Serve;
use crate::support::layouts::course_layout;
use predicates::prelude::*;

backend_tests!(
    walls_apply_verify_then_lines_replace_them,
    clear_removes_walls_and_leaves_the_templates,
    posts_apply_verify_then_plain_walls_and_lines_remove_them,
    clear_removes_walls_and_posts,
    parentless_post_copies_are_reused_or_removed,
);

fn no_progress(_: draw::Stage) {}

fn apply(b: &mut Box<dyn Backend>, d: &Drawing) -> Result<draw::ApplyReport, DrawError> {
    draw::apply(&mut **b, d, &ApplyOptions::default(), &mut no_progress)
}

/// The course layout of `seed` (Prim, `n` x `n`) drawn with walls.
fn wall_layout(n: u64, seed: u64) -> Layout {
    let mut layout = course_layout(vrep_maze::generate::Algorithm::Prim, n, n, seed);
    let grid = Grid::new(n, n).unwrap();
    let maze = passages::decode(grid, &layout.passages).unwrap();
    into_walls(&mut layout, &maze, &WallOptions::default(), true).unwrap();
    layout
}

/// [`wall_layout`] with posts of the default size (the wall thickness) at every corner.
fn post_layout(n: u64, seed: u64) -> Layout {
    let mut layout = course_layout(vrep_maze::generate::Algorithm::Prim, n, n, seed);
    let grid = Grid::new(n, n).unwrap();
    let maze = passages::decode(grid, &layout.passages).unwrap();
    let options = WallOptions {
        length: length_between_posts(1.0, 0.05),
        posts: Some(0.05),
        ..WallOptions::default()
    };
    into_walls(&mut layout, &maze, &options, true).unwrap();
    layout
}

/// Copies of `Wall` in the scene (the template not counted) and whether each is a child of
/// `Maze`.
fn wall_copies(s: &Server) -> (usize, bool) {
    copies_of(s, "Wall")
}

/// Copies of `Post` in the scene, as [`wall_copies`].
fn post_copies(s: &Server) -> (usize, bool) {
    copies_of(s, "Post")
}

/// Copies of the template `name` in the scene (the template not counted) and whether each
/// is a child of `Maze`.
fn copies_of(s: &Server, name: &str) -> (usize, bool) {
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        let copies: Vec<_> = sim
            .scene
            .objects()
            .filter(|o| o.alias == name && o.name != name)
            .map(|o| o.parent)
            .collect();
        let all_children = copies.iter().all(|&p| p == Some(maze));
        (copies.len(), all_children)
    })
}

fn walls_apply_verify_then_lines_replace_them(kind: Kind) {
    let s = kind.serve(Scene::course_walls(), 8);
    let walls = Drawing::try_from(&wall_layout(5, 3)).unwrap();
    assert_eq!(walls.style, Style::Walls);
    let mut b = s.connect();
    let r = apply(&mut b, &walls).unwrap_or_else(|e| panic!("{}: {e}", kind.name()));
    assert_eq!(
        r.pasted,
        walls.pieces.len(),
        "{}: every wall is a copy",
        kind.name()
    );
    assert_eq!(
        wall_copies(&s),
        (walls.pieces.len(), true),
        "{}",
        kind.name()
    );
    draw::verify(&mut *b, &walls, &ObjectNames::default()).unwrap();
    // the template stays where the scene has it, beside the floor
    let template_y = s.with_sim(|sim| {
        let h = sim.scene.resolve("Wall").unwrap();
        sim.scene.get(h).unwrap().position[1]
    });
    assert_eq!(template_y, -6.0);
    // again: nothing to paste, nothing to move
    let again = apply(&mut b, &walls).unwrap();
    assert_eq!(
        (again.pasted, again.removed, again.edits),
        (0, 0, 0),
        "{}",
        kind.name()
    );
    // a line maze over it: every wall copy goes, none is reused as a line
    let lines = Drawing::try_from(&course_layout(
        vrep_maze::generate::Algorithm::Prim,
        5,
        5,
        3,
    ))
    .unwrap();
    let r = apply(&mut b, &lines).unwrap_or_else(|e| panic!("{}: {e}", kind.name()));
    assert_eq!(r.reused, 0, "{}: no wall reused as a line", kind.name());
    assert_eq!(r.removed, walls.pieces.len(), "{}", kind.name());
    assert_eq!(wall_copies(&s).0, 0, "{}", kind.name());
    assert_eq!(s.line_count(), lines.pieces.len());
    draw::verify(&mut *b, &lines, &ObjectNames::default()).unwrap();
    // and walls over the lines again: every line copy goes
    let r = apply(&mut b, &walls).unwrap();
    assert_eq!(
        (r.reused, r.removed),
        (0, lines.pieces.len() - 1),
        "{}",
        kind.name()
    );
    assert_eq!(
        s.line_count(),
        1,
        "{}: only the line template is left",
        kind.name()
    );
    draw::verify(&mut *b, &walls, &ObjectNames::default()).unwrap();
}

fn clear_removes_walls_and_leaves_the_templates(kind: Kind) {
    let s = kind.serve(Scene::course_walls(), 8);
    let walls = Drawing::try_from(&wall_layout(3, 1)).unwrap();
    let mut b = s.connect();
    apply(&mut b, &walls).unwrap();
    let report = draw::clear(&mut *b, &draw::ClearOptions::default()).unwrap();
    assert_eq!(report.removed.len(), walls.pieces.len(), "{}", kind.name());
    assert_eq!(wall_copies(&s).0, 0);
    s.with_sim(|sim| {
        for name in ["Wall", "Line", "Start", "End", "Maze", "Floor"] {
            assert!(
                sim.scene.resolve(name).is_ok(),
                "{}: {name} kept",
                kind.name()
            );
        }
    });
}

fn posts_apply_verify_then_plain_walls_and_lines_remove_them(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course_walls(), 8);
    let posts = Drawing::try_from(&post_layout(5, 3)).unwrap();
    let (walls_n, posts_n) = (posts.pieces.len(), posts.posts.len());
    assert_eq!(posts_n, 36, "every corner of the 6 x 6 lattice");
    let mut b = s.connect();
    let r = apply(&mut b, &posts).unwrap_or_else(|e| panic!("{k}: {e}"));
    crate::support::layouts::assert_counts_add_up(&r, &posts);
    assert_eq!((r.pieces, r.posts), (walls_n, posts_n), "{k}");
    assert_eq!(
        r.pasted,
        walls_n + posts_n,
        "{k}: every wall and post is a copy"
    );
    assert!(
        vrep_maze::cli::summary::apply_line(&r).contains(&format!("walls and {posts_n} posts")),
        "{r:?}"
    );
    assert_eq!(wall_copies(&s), (walls_n, true), "{k}");
    assert_eq!(post_copies(&s), (posts_n, true), "{k}");
    draw::verify(&mut *b, &posts, &ObjectNames::default()).unwrap();
    // the post template stays where the scene has it
    let template = s.with_sim(|sim| {
        let h = sim.scene.resolve("Post").unwrap();
        sim.scene.get(h).unwrap().position
    });
    assert_eq!(template, [0.0, -6.3, 0.1]);
    // again: nothing to paste, nothing to move
    let again = apply(&mut b, &posts).unwrap();
    assert_eq!(
        (again.reused, again.pasted, again.removed, again.edits),
        (walls_n + posts_n, 0, 0, 0),
        "{k}"
    );
    crate::support::layouts::assert_counts_add_up(&again, &posts);
    // the same maze without posts: the walls stay (their centres are the same), the posts go
    let plain = Drawing::try_from(&wall_layout(5, 3)).unwrap();
    assert_eq!(plain.pieces.len(), walls_n);
    let r = apply(&mut b, &plain).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        (r.reused, r.removed, r.pasted),
        (walls_n, posts_n, 0),
        "{k}"
    );
    crate::support::layouts::assert_counts_add_up(&r, &plain);
    assert_eq!(post_copies(&s).0, 0, "{k}");
    draw::verify(&mut *b, &plain, &ObjectNames::default()).unwrap();
    // verify tells a maze with posts from one without
    let e = draw::verify(&mut *b, &posts, &ObjectNames::default()).unwrap_err();
    assert!(e.to_string().contains("no post at ("), "{k}: {e}");
    // posts again, then a line maze over it: every wall and post copy goes
    let r = apply(&mut b, &posts).unwrap();
    assert_eq!((r.reused, r.pasted), (walls_n, posts_n), "{k}");
    let e = draw::verify(&mut *b, &plain, &ObjectNames::default()).unwrap_err();
    assert!(
        e.to_string()
            .contains(&format!("{posts_n} stray maze object(s)")),
        "{k}: {e}"
    );
    let lines = Drawing::try_from(&course_layout(
        vrep_maze::generate::Algorithm::Prim,
        5,
        5,
        3,
    ))
    .unwrap();
    let r = apply(&mut b, &lines).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!((r.reused, r.removed), (0, walls_n + posts_n), "{k}");
    assert_eq!((wall_copies(&s).0, post_copies(&s).0), (0, 0), "{k}");
    draw::verify(&mut *b, &lines, &ObjectNames::default()).unwrap();
    // and posts over the lines: every line copy goes
    let r = apply(&mut b, &posts).unwrap();
    assert_eq!((r.reused, r.removed), (0, lines.pieces.len() - 1), "{k}");
    assert_eq!(s.line_count(), 1, "{k}: only the line template is left");
    draw::verify(&mut *b, &posts, &ObjectNames::default()).unwrap();
}

fn clear_removes_walls_and_posts(kind: Kind) {
    let s = kind.serve(Scene::course_walls(), 8);
    let posts = Drawing::try_from(&post_layout(3, 1)).unwrap();
    let mut b = s.connect();
    apply(&mut b, &posts).unwrap();
    let report = draw::clear(&mut *b, &draw::ClearOptions::default()).unwrap();
    assert_eq!(
        report.removed.len(),
        posts.pieces.len() + posts.posts.len(),
        "{}",
        kind.name()
    );
    assert_eq!((wall_copies(&s).0, post_copies(&s).0), (0, 0));
    s.with_sim(|sim| {
        for name in ["Post", "Wall", "Line", "Start", "End", "Maze", "Floor"] {
            assert!(
                sim.scene.resolve(name).is_ok(),
                "{}: {name} kept",
                kind.name()
            );
        }
    });
}

/// Copies of `Post` an interrupted run left at the scene root (pasted, never parented) are
/// the maze's: reused by a maze with posts, removed by one without.
fn parentless_post_copies_are_reused_or_removed(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course_walls(), 8);
    let template = s.with_sim(|sim| sim.scene.resolve("Post").unwrap());
    let mut b = s.connect();
    let left = b.copy_paste(&[vec![template], vec![template]]).unwrap();
    assert_eq!(left.len(), 2);
    let posts = Drawing::try_from(&post_layout(3, 1)).unwrap();
    let r = apply(&mut b, &posts).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        (r.reused, r.pasted),
        (2, posts.pieces.len() + posts.posts.len() - 2),
        "{k}"
    );
    assert_eq!(post_copies(&s), (posts.posts.len(), true), "{k}");
    b.copy_paste(&[vec![template]]).unwrap();
    let plain = Drawing::try_from(&wall_layout(3, 1)).unwrap();
    let r = apply(&mut b, &plain).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(r.removed, posts.posts.len() + 1, "{k}");
    assert_eq!(post_copies(&s).0, 0, "{k}");
}

#[test]
fn posts_need_a_post_template_and_say_how_to_make_one() {
    let mut scene = Scene::course_walls();
    let post = scene.resolve("Post").unwrap();
    scene.remove(post).unwrap();
    let s = Kind::Legacy.serve(scene, 8);
    let posts = Drawing::try_from(&post_layout(3, 1)).unwrap();
    let mut b = s.connect();
    let e = apply(&mut b, &posts).unwrap_err();
    assert_eq!(e.to_string(), "missing in the scene: Post");
    assert!(
        remedies::hints(&e)
            .iter()
            .any(|h| h.contains("`Post`: the post template")),
        "{:?}",
        remedies::hints(&e)
    );
    // a maze without posts needs none
    apply(&mut b, &Drawing::try_from(&wall_layout(3, 1)).unwrap()).unwrap();
}

#[test]
fn zmq_create_missing_makes_a_post_cuboid_too() {
    let s = Kind::Zmq2.serve(Scene::empty(), 8);
    let mut b = s.connect();
    let names = ObjectNames::default();
    let created = b
        .authoring()
        .unwrap()
        .create_missing(&names, &Sizes::of(&post_layout(3, 1)))
        .unwrap();
    assert_eq!(created, ["Floor", "Maze", "Wall", "Post", "Start", "End"]);
    let (size, position) = s.with_sim(|sim| {
        let h = sim.scene.resolve("Post").unwrap();
        let o = sim.scene.get(h).unwrap();
        (o.size, o.position)
    });
    assert_eq!(size, [0.05, 0.05, 0.2]);
    assert_eq!(position, [0.0, -6.3, 0.1], "0.25 m south of the wall");
    let posts = Drawing::try_from(&post_layout(3, 1)).unwrap();
    apply(&mut b, &posts).unwrap();
    assert_eq!(post_copies(&s), (posts.posts.len(), true));
}

#[test]
fn walls_need_a_wall_template_and_say_how_to_make_one() {
    let s = Kind::Legacy.serve(Scene::course(), 8);
    let walls = Drawing::try_from(&wall_layout(3, 1)).unwrap();
    let mut b = s.connect();
    let e = apply(&mut b, &walls).unwrap_err();
    assert_eq!(e.to_string(), "missing in the scene: Wall");
    assert!(
        remedies::hints(&e)
            .iter()
            .any(|h| h.contains("a cuboid 1 x 0.05 x 0.2 m")
                && h.contains("Primitive shape > Cuboid")),
        "{:?}",
        remedies::hints(&e)
    );
}

/// The hint for a missing template or marker gives the layout's own sizes: a micromouse
/// layout's `Wall` is 0.18 x 0.012 x 0.05 m, never the course's 1 m wall, which the size
/// check would then refuse; its markers are a 0.18 m cell wide.
#[test]
fn a_missing_object_s_hint_gives_the_layout_s_sizes() {
    let micromouse = parse_layout(
        include_str!("../../mazes/dfs-micromouse-seed42.json"),
        "dfs-micromouse-seed42.json",
    )
    .unwrap();
    let s = Kind::Legacy.serve(Scene::empty(), 8);
    let mut b = s.connect();
    let e = apply(&mut b, &Drawing::try_from(&micromouse).unwrap()).unwrap_err();
    let hints = remedies::hints(&e).join("\n");
    for says in [
        "`Wall`: the wall template: a cuboid 0.18 x 0.012 x 0.05 m",
        "`Start`: the start marker: a plane 0.18 m x 0.18 m (a cell), pure blue, at z = 0.002",
        "`End`: the end marker: a plane 0.18 m x 0.18 m (a cell), pure red",
        "the maze needs at least 10 x 10 m",
    ] {
        assert!(hints.contains(says), "{says:?} not in {hints}");
    }
    assert!(!hints.contains("1 x 0.05"), "{hints}");
    let course = parse_layout(
        include_str!("../../mazes/dfs-9x9-seed42.json"),
        "dfs-9x9-seed42.json",
    )
    .unwrap();
    let e = apply(&mut b, &Drawing::try_from(&course).unwrap()).unwrap_err();
    let hints = remedies::hints(&e).join("\n");
    assert!(
        hints.contains("`Line`: the line template: a plane 0.6 x 0.1 m, pure green, at z = 0.001"),
        "{hints}"
    );
}

/// `--create-missing` over ZeroMQ makes what a micromouse layout is drawn with at its own
/// sizes, so the drawing that follows passes the size check.
#[test]
fn zmq_create_missing_makes_a_micromouse_layout_s_sizes() {
    let micromouse = parse_layout(
        include_str!("../../mazes/dfs-micromouse-seed42.json"),
        "dfs-micromouse-seed42.json",
    )
    .unwrap();
    let s = Kind::Zmq2.serve(Scene::empty(), 8);
    let mut b = s.connect();
    let created =
        draw::create_missing_for(b.authoring().unwrap(), &ObjectNames::default(), &micromouse)
            .unwrap();
    assert_eq!(created, ["Floor", "Maze", "Wall", "Start", "End"]);
    let sizes = s.with_sim(|sim| {
        ["Wall", "Start"].map(|n| sim.scene.get(sim.scene.resolve(n).unwrap()).unwrap().size)
    });
    assert_eq!(sizes[0], [0.18, 0.012, 0.05]);
    assert_eq!([sizes[1][0], sizes[1][1]], [0.18, 0.18]);
    apply(&mut b, &Drawing::try_from(&micromouse).unwrap()).unwrap();
}

#[test]
fn zmq_create_missing_makes_a_wall_cuboid() {
    let s = Kind::Zmq2.serve(Scene::empty(), 8);
    let mut b = s.connect();
    let names = ObjectNames::default();
    let created = b
        .authoring()
        .unwrap()
        .create_missing(&names, &Sizes::of(&wall_layout(3, 1)))
        .unwrap();
    assert_eq!(created, ["Floor", "Maze", "Wall", "Start", "End"]);
    let size = s.with_sim(|sim| {
        let h = sim.scene.resolve("Wall").unwrap();
        sim.scene.get(h).unwrap().size
    });
    assert_eq!(size, [1.0, 0.05, 0.2]);
    let walls = Drawing::try_from(&wall_layout(3, 1)).unwrap();
    apply(&mut b, &walls).unwrap();
}

#[test]
fn walls_cli_generate_validate_render_and_apply() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walls.json");
    bin()
        .args(["generate", "--style", "walls", "--seed", "42", "-o"])
        .arg(&path)
        .assert()
        .success()
        .stderr(predicates::str::contains("walls, solution"));
    let layout = vrep_maze::layout::read_layout(&path).unwrap();
    assert_eq!(layout.style, Style::Walls);
    assert!(layout.segments.is_empty() && !layout.walls.is_empty());
    assert!(validate(&layout).is_ok());
    bin()
        .arg("validate")
        .arg(&path)
        .assert()
        .success()
        .stdout(predicates::str::contains(format!(
            "{} walls",
            layout.walls.len()
        )));
    let text = bin()
        .args(["render", "--solution"])
        .arg(&path)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(text).unwrap();
    assert!(text.starts_with("+---+"), "{text}");
    let svg = bin()
        .args(["render", "--format", "svg"])
        .arg(&path)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let svg = String::from_utf8(svg).unwrap();
    assert!(svg.contains(WALL_GROUP), "{svg}");
    assert!(!svg.contains("#00ff00"), "no green lines in a wall maze");
    for name in ["walls.svg", "walls.png"] {
        let out = dir.path().join(name);
        bin()
            .arg("render")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        assert!(fs::metadata(&out).unwrap().len() > 0, "{name}");
    }
    let png = png_pixels(&dir.path().join("walls.png"));
    assert_eq!((png.width, png.height), (800, 800));
    assert!(png.count(WALL) > 1000, "dark walls");
    // wall options without walls are refused
    bin()
        .args(["generate", "--wall-height", "0.3"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--wall-height shapes walls: add --style walls",
        ));
    // an opening beside an end inside the grid is refused
    bin()
        .args([
            "generate",
            "--style",
            "walls",
            "--openings",
            "start,end",
            "--seed",
            "42",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("is not on the edge"));
    bin()
        .args([
            "generate",
            "--style",
            "walls",
            "--openings",
            "start,end",
            "--end",
            "ne",
            "--seed",
            "42",
        ])
        .assert()
        .success();
}

#[test]
fn walls_cli_apply_into_serve_then_a_line_maze_replaces_them() {
    let dir = tempfile::tempdir().unwrap();
    let walls = dir.path().join("walls.json");
    bin()
        .args(["generate", "--style", "walls", "--seed", "42", "-o"])
        .arg(&walls)
        .assert()
        .success();
    let lines = crate::support::cli::generate(dir.path(), "42", "dfs");
    let s = Serve::start(
        &[
            "--listen",
            "127.0.0.1:0",
            "--scene",
            "course-walls",
            "--timing",
            "instant",
        ],
        1,
    );
    let port = s.port();
    bin()
        .arg("apply")
        .arg(&walls)
        .args(["--port", &port])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("walls: 0 kept, ").and(predicates::str::contains(
                "verified: every wall, start and end in place",
            )),
        );
    bin()
        .args(["apply", &lines, "--port", &port])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("drew 160 lines").and(predicates::str::contains(
                "verified: every line, start and end in place",
            )),
        );
    bin().args(["clear", "--port", &port]).assert().success();
}

#[test]
fn posts_cli_generate_validate_and_refuse_posts_without_walls() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("posts.json");
    bin()
        .args([
            "generate", "--style", "walls", "--posts", "--seed", "42", "-o",
        ])
        .arg(&path)
        .assert()
        .success()
        .stderr(predicates::str::contains("100 walls and 100 posts"));
    let layout = vrep_maze::layout::read_layout(&path).unwrap();
    assert_eq!(layout.post.as_ref().map(|p| p.size), Some(0.05));
    assert_eq!(layout.wall.as_ref().map(|w| w.length), Some(0.95));
    assert_eq!(
        layout.posts.len(),
        10 * 10,
        "every corner of the 9x9 lattice"
    );
    bin()
        .arg("validate")
        .arg(&path)
        .assert()
        .success()
        .stdout(predicates::str::contains("100 walls and 100 posts"));
    // the same maze without posts: the same sides closed, one wall each
    let plain = dir.path().join("plain.json");
    bin()
        .args(["generate", "--style", "walls", "--seed", "42", "-o"])
        .arg(&plain)
        .assert()
        .success();
    let plain = vrep_maze::layout::read_layout(&plain).unwrap();
    assert_eq!(plain.walls.len(), layout.walls.len());
    assert!(plain.post.is_none() && plain.posts.is_empty());
    bin()
        .args(["generate", "--posts"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--posts shapes walls: add --style walls",
        ));
    bin()
        .args(["generate", "--style", "walls", "--post-size", "0.1"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--post-size shapes posts: add --posts",
        ));
    bin()
        .args([
            "generate",
            "--style",
            "walls",
            "--posts",
            "--wall-length",
            "1",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--wall-length 1 m is longer than the 0.95 m between two posts",
        ));
    // a competition micromouse maze: 289 posts, walls of 0.168 m between them
    let out = bin()
        .args([
            "generate",
            "--preset",
            "micromouse",
            "--posts",
            "--seed",
            "42",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let mouse = parse_layout(&String::from_utf8(out).unwrap(), "stdout").unwrap();
    assert_eq!(mouse.posts.len(), 289);
    assert_eq!(mouse.post.as_ref().map(|p| p.size), Some(0.012));
    assert_eq!(mouse.wall.as_ref().map(|w| w.length), Some(0.168));
    assert!(validate(&mouse).is_ok());
}

#[test]
fn posts_cli_apply_into_serve_over_both_apis_then_a_line_maze_replaces_them() {
    let dir = tempfile::tempdir().unwrap();
    let posts = dir.path().join("posts.json");
    bin()
        .args([
            "generate", "--style", "walls", "--posts", "--seed", "42", "-o",
        ])
        .arg(&posts)
        .assert()
        .success();
    let lines = crate::support::cli::generate(dir.path(), "42", "dfs");
    let s = Serve::start(
        &[
            "--api",
            "both",
            "--listen",
            "127.0.0.1:0",
            "--zmq-listen",
            "127.0.0.1:0",
            "--scene",
            "course-walls",
            "--timing",
            "instant",
        ],
        2,
    );
    let (legacy, zmq) = (s.ports[0].to_string(), s.ports[1].to_string());
    bin()
        .arg("apply")
        .arg(&posts)
        .args(["--port", &legacy])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("drew 100 walls and 100 posts: 0 kept, 200 pasted").and(
                predicates::str::contains("verified: every wall, post, start and end in place"),
            ),
        );
    bin()
        .arg("apply")
        .arg(&posts)
        .args(["--api", "zmq", "--port", &zmq])
        .assert()
        .success()
        .stdout(predicates::str::contains(
            "drew 100 walls and 100 posts: 200 kept (200 earlier copies: 0 already in place, 0 placed, 200 set unread, as reading costs what setting does), 0 pasted",
        ));
    bin()
        .args(["apply", &lines, "--api", "zmq", "--port", &zmq])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("drew 160 lines: 1 kept (the template: ").and(
                predicates::str::contains(
                    "159 pasted; markers: 2 already in place, 0 placed; 200 earlier copies removed",
                ),
            ),
        );
    // posts again, then clear over the legacy API removes walls and posts
    bin()
        .arg("apply")
        .arg(&posts)
        .args(["--port", &legacy])
        .assert()
        .success();
    bin()
        .args(["clear", "--port", &legacy])
        .assert()
        .success()
        .stdout(predicates::str::contains("removed 200 maze"));
}

#[test]
fn posts_cli_zmq_create_missing_makes_wall_and_post() {
    let dir = tempfile::tempdir().unwrap();
    let posts = dir.path().join("posts.json");
    bin()
        .args([
            "generate", "--style", "walls", "--posts", "--size", "3x3", "--seed", "1", "-o",
        ])
        .arg(&posts)
        .assert()
        .success();
    let s = Serve::start(
        &[
            "--api",
            "zmq",
            "--listen",
            "127.0.0.1:0",
            "--scene",
            "empty",
            "--timing",
            "instant",
        ],
        1,
    );
    bin()
        .arg("apply")
        .arg(&posts)
        .args(["--api", "zmq", "--port", &s.port(), "--create-missing"])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("created Floor, Maze, Wall, Post, Start, End")
                .and(predicates::str::contains("and 16 posts"))
                .and(predicates::str::contains("verified: every wall, post")),
        );
}

#[test]
fn micromouse_preset_has_the_right_size_and_a_goal_with_one_entrance() {
    for (preset, side, cell) in [("micromouse", 16u32, 0.18), ("micromouse-half", 32, 0.09)] {
        let out = bin()
            .args(["generate", "--preset", preset, "--seed", "5"])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let layout = parse_layout(&String::from_utf8(out).unwrap(), "stdout").unwrap();
        assert_eq!((layout.grid.columns, layout.grid.rows), (side, side));
        assert_eq!(layout.grid.cell_size, cell);
        let wall = layout.wall.as_ref().unwrap();
        assert_eq!(wall.length, cell);
        assert!(wall.openings.is_empty());
        assert_eq!(layout.start.cell, [0, 0]);
        assert_eq!(layout.end.region.len(), 4);
        assert_eq!(layout.metrics.loops, 1, "the goal's inside is one loop");
        let report = validate(&layout);
        assert!(report.is_ok(), "{preset}: {:?}", report.problems);
        let grid = Grid::new(side.into(), side.into()).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let goal: Vec<usize> = layout
            .end
            .region
            .iter()
            .map(|c| grid.index(vrep_maze::maze::Cell::new(c[0], c[1])))
            .collect();
        let entrances: usize = goal
            .iter()
            .map(|&g| {
                maze.open_neighbours(g)
                    .filter(|n| !goal.contains(n))
                    .count()
            })
            .sum();
        assert_eq!(entrances, 1, "{preset}");
        assert_eq!(maze.degree(0), 1, "{preset}: the start opens one way");
    }
    bin()
        .args(["generate", "--preset", "micromouse", "--size", "5x5"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("cannot be used with"));
}

/// The group of a wall maze's walls in its SVG.
const WALL_GROUP: &str = r##"<g fill="#202020">"##;
/// The colours of the walls and of the goal region in a picture.
const WALL: [u8; 3] = [0x20, 0x20, 0x20];
const GOAL: [u8; 3] = [0xe6, 0xa0, 0xa0];

/// A decoded RGB PNG.
struct Pixels {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Pixels {
    /// Pixels of exactly `colour`.
    fn count(&self, colour: [u8; 3]) -> usize {
        self.rgb.chunks_exact(3).filter(|p| *p == colour).count()
    }
}

fn png_pixels(path: &std::path::Path) -> Pixels {
    let file = std::io::BufReader::new(fs::File::open(path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut rgb).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    Pixels {
        width: info.width,
        height: info.height,
        rgb,
    }
}

#[test]
fn micromouse_and_imported_mazes_render_as_svg_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    bin()
        .args(["generate", "--preset", "micromouse", "--seed", "5", "-o"])
        .arg(p("m.json"))
        .assert()
        .success();
    // a gap in the north wall, the goal the two G cells (the end the one nearer S)
    let drawing = "o---o---o   o\n| S     |   |\no---o   o   o\n|     G   G |\no---o---o---o\n";
    fs::write(p("i.txt"), drawing).unwrap();
    bin()
        .arg("import")
        .arg(p("i.txt"))
        .arg("-o")
        .arg(p("i.json"))
        .assert()
        .success();
    let imported = vrep_maze::layout::read_layout(&p("i.json")).unwrap();
    assert_eq!(imported.wall.as_ref().unwrap().openings.len(), 1);
    for (name, goal_cells, walls) in [("m", 3, 1000), ("i", 1, 100)] {
        for ext in ["svg", "png"] {
            bin()
                .args(["render", "--solution"])
                .arg(p(&format!("{name}.json")))
                .arg("-o")
                .arg(p(&format!("{name}.{ext}")))
                .assert()
                .success();
        }
        let svg = fs::read_to_string(p(&format!("{name}.svg"))).unwrap();
        assert!(svg.contains(WALL_GROUP), "{name}");
        assert!(svg.contains("<polyline"), "{name}: the solution");
        let tinted = svg.split(r##"<g fill="#e6a0a0">"##).nth(1).map_or(0, |g| {
            g.split("</g>").next().unwrap().matches("<rect").count()
        });
        assert_eq!(tinted, goal_cells, "{name}: the goal region but the end");
        let png = png_pixels(&p(&format!("{name}.png")));
        assert!(png.count(WALL) > walls, "{name}: dark walls");
        assert!(
            png.count([0, 0, 255]) > 0 && png.count([255, 0, 0]) > 0,
            "{name}"
        );
        assert_eq!(png.count(GOAL) > 0, goal_cells > 0, "{name}");
    }
}

#[test]
fn walls_validation_names_a_missing_wall_a_wall_over_a_passage_and_a_duplicate() {
    let layout = wall_layout(4, 2);
    assert!(validate(&layout).is_ok());
    let dir = tempfile::tempdir().unwrap();
    let mut broken = layout.clone();
    broken.walls.remove(0);
    let first = layout.walls[1];
    broken.walls.push(first);
    // a wall across the first open passage east of a cell in row 0
    let grid = Grid::new(4, 4).unwrap();
    let maze = passages::decode(grid, &layout.passages).unwrap();
    let x = (0..3)
        .find(|&x| maze.is_open(x, vrep_maze::maze::Direction::East))
        .expect("row 0 has an open passage east");
    let mut across = layout.walls[0];
    across.x = layout.grid.origin[0] + x as f64 + 0.5;
    across.y = layout.grid.origin[1];
    across.yaw = vrep_maze::layout::geometry::round_um(std::f64::consts::FRAC_PI_2);
    broken.walls.push(across);
    let path = dir.path().join("broken.json");
    fs::write(&path, vrep_maze::layout::json::to_string(&broken)).unwrap();
    let out = bin()
        .arg("validate")
        .arg(&path)
        .assert()
        .code(1)
        .get_output()
        .clone();
    let text = String::from_utf8(out.stdout).unwrap() + &String::from_utf8(out.stderr).unwrap();
    assert!(
        text.contains("is closed but not covered gap-free by walls"),
        "{text}"
    );
    assert!(text.contains("duplicates walls[0]"), "{text}");
    assert!(
        text.contains("stands in the open passage between cells"),
        "{text}"
    );
}

#[test]
fn import_round_trips_through_the_ascii_render() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    bin()
        .args(["generate", "--preset", "micromouse", "--seed", "11", "-o"])
        .arg(p("m.json"))
        .assert()
        .success();
    bin()
        .arg("render")
        .arg(p("m.json"))
        .arg("-o")
        .arg(p("m.txt"))
        .assert()
        .success();
    bin()
        .arg("import")
        .arg(p("m.txt"))
        .arg("-o")
        .arg(p("i.json"))
        .assert()
        .success();
    bin()
        .arg("render")
        .arg(p("i.json"))
        .arg("-o")
        .arg(p("i.txt"))
        .assert()
        .success();
    bin()
        .arg("import")
        .arg(p("i.txt"))
        .arg("-o")
        .arg(p("j.json"))
        .assert()
        .success();
    let read = |name: &str| vrep_maze::layout::read_layout(&p(name)).unwrap();
    let (m, i, j) = (read("m.json"), read("i.json"), read("j.json"));
    assert_eq!(m.passages, i.passages);
    assert_eq!(i.passages, j.passages);
    assert_eq!((m.start.cell, m.end.cell), (i.start.cell, i.end.cell));
    let sorted = |mut r: Vec<[u32; 2]>| {
        r.sort();
        r
    };
    assert_eq!(sorted(m.end.region.clone()), sorted(i.end.region.clone()));
    assert_eq!(i.generator.algorithm, "import");
    assert_eq!(
        i.walls.len(),
        m.walls.len(),
        "the same walls at the same cell size"
    );
    assert!(validate(&i).is_ok());
    // a line maze in our own render round-trips too
    bin()
        .args(["generate", "--seed", "4", "-o"])
        .arg(p("l.json"))
        .assert()
        .success();
    bin()
        .arg("render")
        .arg(p("l.json"))
        .arg("-o")
        .arg(p("l.txt"))
        .assert()
        .success();
    bin()
        .args(["import", "--lines", "--cell-size", "1"])
        .arg(p("l.txt"))
        .arg("-o")
        .arg(p("k.json"))
        .assert()
        .success();
    let (l, k) = (read("l.json"), read("k.json"));
    assert_eq!(l.passages, k.passages);
    assert_eq!(
        l.segments, k.segments,
        "the same lines at the course geometry"
    );
}

#[test]
fn import_refuses_malformed_drawings_with_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.txt");
    fs::write(&path, "o---o---o\n|   |   |\no---o-x-o\n").unwrap();
    let shown = path.display().to_string();
    bin()
        .arg("import")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(predicates::str::contains(format!(
            "{shown}:3:7: expected a wall '---' or a gap '   ' between posts, found '-x-'"
        )));
    fs::write(&path, "o---o---o\n| S | S |\no---o---o\n").unwrap();
    bin()
        .arg("import")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(predicates::str::contains(format!(
            "{shown}:2:7: a second 'S': the first is at line 2, column 3"
        )));
    // two cells walled apart: refused as a whole
    fs::write(&path, "o---o---o\n|   |   |\no---o---o\n").unwrap();
    bin()
        .arg("import")
        .arg(&path)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("1 of 2 cells cannot be reached"));
}

/// Over the legacy API a mesh's bounding box is its size about its centre (spec "Meshes on
/// the real 4.5.1"), whichever API drew it: meshes drawn over ZeroMQ verify over the legacy
/// API, and those loaded from a legacy XML model verify over ZeroMQ, with no false
/// difference.
#[test]
fn meshes_drawn_over_one_api_verify_over_the_other() {
    let dir = tempfile::tempdir().unwrap();
    let posts = dir.path().join("posts.json");
    bin()
        .args([
            "generate", "--style", "walls", "--posts", "--seed", "7", "--size", "9x9", "-o",
        ])
        .arg(&posts)
        .assert()
        .success();
    let s = Serve::start(
        &[
            "--api",
            "both",
            "--listen",
            "127.0.0.1:0",
            "--zmq-listen",
            "127.0.0.1:0",
            "--scene",
            "course-walls",
            "--timing",
            "instant",
        ],
        2,
    );
    let (legacy, zmq) = (s.ports[0].to_string(), s.ports[1].to_string());
    let posts = posts.to_str().unwrap();
    let matches = |api: &str, port: &str| {
        bin()
            .args(["inspect", "--api", api, "--port", port, "--layout", posts])
            .assert()
            .success()
            .stdout(predicates::str::contains("the scene matches it"));
    };
    for (draw_api, draw_port, other_api, other_port) in [
        ("zmq", &zmq, "legacy", &legacy),
        ("legacy", &legacy, "zmq", &zmq),
    ] {
        bin()
            .args(["apply", posts, "--draw", "mesh", "--api", draw_api])
            .args(["--port", draw_port])
            .assert()
            .success();
        matches(other_api, other_port);
        // drawn again over the other API: the meshes are kept and verify
        bin()
            .args(["apply", posts, "--draw", "mesh", "--api", other_api])
            .args(["--port", other_port])
            .assert()
            .success()
            .stdout(predicates::str::contains("0 created"));
        bin()
            .args(["clear", "--api", draw_api, "--port", draw_port])
            .assert()
            .success();
    }
}
