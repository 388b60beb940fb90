//! One rule for what is ours (issue 30, items 1, 3-6 and 11), over each API: a user's
//! recoloured look-alike of `Line` under `Maze` never spreads (pasting copies only the
//! template and this run's copies); a name that finds one of our copies is refused as a
//! template or marker; a path with an index names the template's family; a user's dummy
//! named like our mesh holder is left alone; a copies apply over a mesh maze counts it
//! apart; a failed `--create-missing` leaves nothing.

use tempfile::TempDir;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::mesh::MeshMaze;
use vrep_maze::draw::{self, ApplyOptions, ClearOptions, DrawError, Drawing, ObjectNames};
use vrep_maze::layout::{Layout, read_layout};
use vrep_maze::sim::{NewObject, ObjectType, Scene};

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::bin;

backend_tests!(
    a_red_look_alike_under_the_maze_never_spreads,
    a_name_that_finds_our_copy_is_refused_before_any_edit,
    an_indexed_path_to_the_template_draws_and_clears_its_copies,
    a_users_dummy_named_like_the_mesh_holder_is_left_alone,
    a_copies_apply_counts_an_earlier_mesh_maze_apart,
);

/// The layout `generate --seed 1 ARGS` writes to `dir/name`.
fn layout(dir: &TempDir, args: &[&str]) -> Layout {
    let path = dir.path().join("maze.json");
    bin()
        .args(["generate", "--seed", "1", "-o"])
        .arg(&path)
        .args(args)
        .assert()
        .success();
    read_layout(&path).unwrap()
}

fn apply_with(
    b: &mut dyn draw::Backend,
    d: &Drawing,
    names: ObjectNames,
) -> Result<draw::ApplyReport, DrawError> {
    let opts = ApplyOptions {
        names,
        ..Default::default()
    };
    draw::apply(b, d, &opts, &mut |_| {})
}

/// Handles and colours of every shape under `Maze`, and the template's colour.
fn colours_under_the_maze(s: &Server) -> (Vec<(i32, [u8; 3])>, [u8; 3]) {
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        let kids = sim
            .scene
            .children(Some(maze))
            .map(|h| (h, sim.scene.get(h).unwrap().colour))
            .collect();
        (kids, sim.scene.get(line).unwrap().colour)
    })
}

/// Item 1: the user copies `Line`, puts the copy under `Maze` and colours it red. Drawing
/// pastes only from the template (and this run's copies), so one red object stays, the
/// user's; over ZeroMQ, which reads colours, it is named as left alone, not reused.
fn a_red_look_alike_under_the_maze_never_spreads(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let d = Drawing::try_from(&layout(&dir, &["--size", "5x5"])).unwrap();
    let s = kind.serve(Scene::course(), 0);
    let red = s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        let maze = sim.scene.resolve("Maze").unwrap();
        let red = sim.scene.copy_paste(&[line]).unwrap()[0];
        sim.scene.set_parent(red, Some(maze), true).unwrap();
        sim.scene.set_colour(red, [255, 0, 0]).unwrap();
        red
    });
    let mut b = s.connect();
    for run in 0..2 {
        let r = apply_with(&mut *b, &d, ObjectNames::default()).unwrap();
        let (kids, green) = colours_under_the_maze(&s);
        let reds: Vec<i32> = kids
            .iter()
            .filter(|(_, c)| *c != green)
            .map(|(h, _)| *h)
            .collect();
        assert_eq!(reds, vec![red], "{k} run {run}: only the user's is red");
        if kind != Kind::Legacy {
            assert_eq!(r.left_alone.len(), 1, "{k} run {run}: {:?}", r.left_alone);
            assert_eq!(
                kids.len(),
                d.pieces.len(),
                "{k} run {run}: 1 user's + copies"
            );
        }
    }
    drop(b);
    s.shutdown();
}

/// Item 4: after a draw, `--line /Maze/Line` and `--start '/Maze/Line[3]'` find copies we
/// pasted: refused before any edit, the scene as it was.
fn a_name_that_finds_our_copy_is_refused_before_any_edit(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let d = Drawing::try_from(&layout(&dir, &["--size", "4x4"])).unwrap();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    apply_with(&mut *b, &d, ObjectNames::default()).unwrap();
    let before = s.snapshot();
    let copy = |role: &str, name: &str| {
        let mut names = ObjectNames::default();
        match role {
            "line" => names.line = name.into(),
            _ => names.start = name.into(),
        }
        names
    };
    for (role, name) in [
        ("line", "/Maze/Line"),
        ("start", "/Maze/Line[3]"),
        ("line", "/Line[2]"),
    ] {
        let e = apply_with(&mut *b, &d, copy(role, name)).unwrap_err();
        assert!(
            matches!(e, DrawError::OurCopy { .. }) && e.to_string().contains(name),
            "{k} {role} {name}: {e}"
        );
        assert_eq!(s.snapshot(), before, "{k} {role} {name}: nothing moved");
        let opts = ClearOptions {
            names: copy(role, name),
            ..Default::default()
        };
        let e = draw::clear(&mut *b, &opts).unwrap_err();
        assert!(matches!(e, DrawError::OurCopy { .. }), "{k} clear: {e}");
        assert_eq!(s.snapshot(), before, "{k} clear {name}: nothing removed");
    }
    drop(b);
    s.shutdown();
}

/// Item 3: `--line '/Line[0]'` is a path to the template: its copies are the maze's, so a
/// draw verifies, a second draw pastes nothing, and clear removes every copy.
fn an_indexed_path_to_the_template_draws_and_clears_its_copies(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let d = Drawing::try_from(&layout(&dir, &["--size", "4x4"])).unwrap();
    let s = kind.serve(Scene::course(), 0);
    let objects = s.with_sim(|sim| sim.scene.len());
    let mut b = s.connect();
    let names = ObjectNames {
        line: "/Line[0]".into(),
        ..Default::default()
    };
    apply_with(&mut *b, &d, names.clone()).unwrap();
    let again = apply_with(&mut *b, &d, names.clone()).unwrap();
    assert_eq!(
        (again.pasted, again.removed),
        (0, 0),
        "{k}: the copies are the maze's: {again:?}"
    );
    assert_eq!(
        s.with_sim(|sim| sim.scene.len()),
        objects + d.pieces.len() - 1
    );
    let r = draw::clear(
        &mut *b,
        &ClearOptions {
            names,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.removed.len(), d.pieces.len() - 1, "{k}");
    assert_eq!(s.with_sim(|sim| sim.scene.len()), objects, "{k}: all gone");
    drop(b);
    s.shutdown();
}

/// Item 5: the user's dummy `MazeMeshes` under `Maze`, holding their 0.3 m cuboid, is
/// neither removed by a copies apply or a clear nor taken for a mesh maze; a mesh apply
/// puts its meshes beside the cuboid and leaves it; both are named as left alone.
fn a_users_dummy_named_like_the_mesh_holder_is_left_alone(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let l = layout(&dir, &["--size", "4x4"]);
    let d = Drawing::try_from(&l).unwrap();
    let mut scene = Scene::course();
    let maze = scene.resolve("Maze").unwrap();
    let thing = |kind, parent, size| NewObject {
        kind,
        parent: Some(parent),
        position: [6.0, 6.0, 0.15],
        orientation: [0.0; 3],
        size,
        colour: [200, 200, 0],
    };
    let holder = scene.add(
        "MazeMeshes",
        thing(ObjectType::Dummy, maze, [0.01, 0.01, 0.01]),
    );
    let cuboid = scene.add("Cuboid", thing(ObjectType::Shape, holder, [0.3; 3]));
    let s = kind.serve(scene, 0);
    let exists = |h: i32| s.with_sim(|sim| sim.scene.get(h).is_ok());
    let at = |h: i32| s.with_sim(|sim| sim.scene.pose(h, HANDLE_WORLD).unwrap());
    let first = at(cuboid);
    let mut b = s.connect();
    let r = apply_with(&mut *b, &d, ObjectNames::default()).unwrap();
    assert_eq!((r.removed, r.removed_meshes), (0, 0), "{k}: {r:?}");
    assert!(
        r.left_alone.contains(&"MazeMeshes".to_string())
            && r.left_alone.contains(&"Cuboid".to_string()),
        "{k}: {:?}",
        r.left_alone
    );
    assert!(exists(holder) && exists(cuboid), "{k}: copies apply");
    draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap();
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(c.removed_meshes.is_empty(), "{k}: {:?}", c.removed_meshes);
    assert!(exists(holder) && exists(cuboid), "{k}: clear");
    let maze_meshes = MeshMaze::try_from(&l).unwrap();
    let opts = ApplyOptions::default();
    let r = draw::mesh::apply(&mut *b, &maze_meshes, &opts, &mut |_| {}).unwrap();
    assert!(r.left_alone.contains(&"Cuboid".to_string()), "{k}: {r:?}");
    draw::mesh::verify(&mut *b, &maze_meshes, &ObjectNames::default()).unwrap();
    assert!(exists(cuboid), "{k}: mesh apply");
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    let meshes: Vec<String> = maze_meshes.meshes.iter().map(|m| m.name()).collect();
    assert_eq!(c.removed_meshes, meshes, "{k}: ours, not the user's holder");
    assert!(
        exists(holder) && exists(cuboid),
        "{k}: clear of a mesh maze"
    );
    assert_eq!(at(cuboid), first, "{k}: never moved");
    drop(b);
    s.shutdown();
}

/// Item 11: a copies apply over a mesh maze says it removed a mesh maze, not copies.
fn a_copies_apply_counts_an_earlier_mesh_maze_apart(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let l = layout(&dir, &["--size", "4x4"]);
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let opts = ApplyOptions::default();
    let maze = MeshMaze::try_from(&l).unwrap();
    draw::mesh::apply(&mut *b, &maze, &opts, &mut |_| {}).unwrap();
    let d = Drawing::try_from(&l).unwrap();
    let r = apply_with(&mut *b, &d, ObjectNames::default()).unwrap();
    assert_eq!(
        (r.removed, r.removed_meshes),
        (0, maze.meshes.len() + 1),
        "{k}: {r:?}"
    );
    let text = vrep_maze::cli::summary::apply_line(&r);
    assert!(
        text.contains(&format!(
            "0 earlier copies removed; {} object(s) of an earlier mesh maze removed;",
            maze.meshes.len() + 1
        )),
        "{k}: {text}"
    );
    drop(b);
    s.shutdown();
}

/// Item 6: `--create-missing` with a start marker under an object that does not exist
/// fails before creating anything.
#[test]
fn a_failed_create_missing_leaves_nothing() {
    let dir = TempDir::new().unwrap();
    layout(&dir, &["--size", "3x3"]);
    let s = Kind::Zmq2.serve(Scene::course(), 0);
    let before = s.snapshot();
    bin()
        .args(["apply", "--api", "zmq", "--port"])
        .arg(s.addr().port().to_string())
        .args(["--start", "Go/Start", "--create-missing", "-q"])
        .arg(dir.path().join("maze.json"))
        .assert()
        .failure()
        .stderr(predicates::str::contains(
            "`Go` does not exist (nothing was created)",
        ));
    assert_eq!(s.snapshot(), before, "nothing was created");
    s.shutdown();
}
