//! apply / clear / verify over the legacy backend against the in-process server.

use std::time::Duration;

use vrep_maze::draw::{self, ApplyOptions, Backend, DrawError, Drawing, ObjectNames};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::{LegacyBackend, ServerConfig, ServerHandle, spawn};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{NamingMode, Scene, Simulator};

fn drawing(n: u64, seed: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, seed);
    Drawing::from(&build_layout(&spec).unwrap())
}

fn server_with(scene: Scene, fps: i32) -> ServerHandle {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        ..Default::default()
    };
    spawn(cfg, Simulator::new(scene, fps)).unwrap()
}

fn connect(s: &ServerHandle) -> LegacyBackend {
    LegacyBackend::connect("127.0.0.1", s.local_addr().port(), Duration::from_secs(3)).unwrap()
}

fn no_progress(_: draw::Stage) {}

fn line_count(s: &ServerHandle) -> usize {
    s.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count())
}

#[test]
fn legacy_apply_draws_verifies_and_reapplies_without_changes() {
    let s = server_with(Scene::course(), 0);
    let d = drawing(9, 42);
    assert_eq!(d.lines.len(), 160);
    let mut sc = connect(&s);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.lines, r.pasted, r.reused, r.removed), (160, 159, 0, 0));
    assert!(
        r.round_trips <= 15,
        "9x9 took {} round trips",
        r.round_trips
    );
    assert_eq!(line_count(&s), 160);
    draw::verify(&mut sc, &d, &ObjectNames::default()).unwrap();
    let again = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(
        (again.pasted, again.removed, again.edits, again.reused),
        (0, 0, 0, 159),
        "{again}"
    );
    // idle rate restored
    assert_eq!(s.with_sim(|sim| sim.idle_fps), 0);
    sc.close().unwrap();
    s.shutdown();
}

#[test]
fn legacy_apply_replaces_a_bigger_maze_and_clear_removes_it() {
    let s = server_with(Scene::course(), 8);
    let mut sc = connect(&s);
    let big = drawing(5, 1);
    let small = drawing(3, 2);
    draw::apply(&mut sc, &big, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(
        s.with_sim(|sim| sim.idle_fps),
        8,
        "user's idle rate restored"
    );
    let r = draw::apply(&mut sc, &small, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(
        (r.pasted, r.removed),
        (0, big.lines.len() - small.lines.len())
    );
    assert_eq!(line_count(&s), small.lines.len());
    draw::verify(&mut sc, &small, &ObjectNames::default()).unwrap();
    assert!(matches!(
        draw::verify(&mut sc, &big, &ObjectNames::default()),
        Err(DrawError::Verify(_))
    ));
    let c = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
    assert_eq!(c.removed.len(), small.lines.len() - 1);
    assert_eq!(line_count(&s), 1, "only the template is left");
    assert!(
        draw::clear(&mut sc, &ObjectNames::default(), false)
            .unwrap()
            .removed
            .is_empty(),
        "idempotent"
    );
    s.shutdown();
}

#[test]
fn legacy_apply_round_trips_30x30() {
    let s = server_with(Scene::course(), 0);
    let mut sc = connect(&s);
    let d = drawing(30, 7);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(r.lines, 1798);
    assert!(
        r.round_trips <= 20,
        "30x30 took {} round trips",
        r.round_trips
    );
    s.shutdown();
}

#[test]
fn legacy_apply_refuses_a_running_simulation_and_missing_objects() {
    let s = server_with(Scene::course(), 0);
    s.with_sim(|sim| sim.start());
    let mut sc = connect(&s);
    let d = drawing(3, 3);
    assert!(matches!(
        draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress),
        Err(DrawError::SimulationRunning)
    ));
    let opts = ApplyOptions {
        stop_simulation: true,
        ..Default::default()
    };
    let r = draw::apply(&mut sc, &d, &opts, &mut no_progress).unwrap();
    assert!(r.stopped_simulation);
    s.shutdown();

    let mut scene = Scene::course();
    for n in ["Maze", "End"] {
        let h = scene.resolve(n).unwrap();
        scene.remove(h).unwrap();
    }
    let s = server_with(scene, 0);
    let mut sc = connect(&s);
    let e = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, DrawError::Missing { .. })
            && msg.contains("Maze, End")
            && msg.contains("dummy"),
        "{msg}"
    );
    s.shutdown();
}

#[test]
fn legacy_apply_works_with_hash_names_and_repairs_parentless_copies() {
    let mut scene = Scene::course();
    scene.naming = NamingMode::Hash;
    let line = scene.resolve("Line").unwrap();
    // an interrupted run: copies pasted but never re-parented
    for _ in 0..3 {
        scene.copy_paste(&[line]).unwrap();
    }
    let s = server_with(scene, 0);
    let mut sc = connect(&s);
    let d = drawing(2, 5);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.reused, r.pasted, r.removed), (3, d.lines.len() - 4, 0));
    let names: Vec<String> =
        s.with_sim(|sim| sim.scene.objects().map(|o| o.name.clone()).collect());
    assert!(names.iter().any(|n| n == "Line#3"), "{names:?}");
    draw::verify(&mut sc, &d, &ObjectNames::default()).unwrap();
    s.shutdown();
}

#[test]
fn legacy_dry_run_changes_nothing() {
    let s = server_with(Scene::course(), 0);
    let mut sc = connect(&s);
    let opts = ApplyOptions {
        dry_run: true,
        ..Default::default()
    };
    let r = draw::apply(&mut sc, &drawing(4, 4), &opts, &mut no_progress).unwrap();
    assert!(r.dry_run && r.pasted > 0);
    assert_eq!(line_count(&s), 1);
    s.shutdown();
}

#[test]
fn legacy_one_cell_maze_hides_the_template_under_start() {
    let s = server_with(Scene::course(), 0);
    let mut sc = connect(&s);
    draw::apply(
        &mut sc,
        &drawing(3, 1),
        &ApplyOptions::default(),
        &mut no_progress,
    )
    .unwrap();
    let one = drawing(1, 1);
    assert!(one.lines.is_empty());
    let r = draw::apply(&mut sc, &one, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(r.removed, 15);
    assert_eq!(line_count(&s), 1);
    let (line, start) = s.with_sim(|sim| {
        let l = sim.scene.resolve("Line").unwrap();
        let st = sim.scene.resolve("Start").unwrap();
        (
            sim.scene.pose(l, -1).unwrap().0,
            sim.scene.pose(st, -1).unwrap().0,
        )
    });
    assert!(
        (line[0] - start[0]).abs() < 1e-6
            && (line[1] - start[1]).abs() < 1e-6
            && line[2] < start[2]
    );
    s.shutdown();
}

#[test]
fn legacy_idle_rate_is_restored_after_an_error() {
    // Maze hangs under a parentless Line copy: re-parenting that copy to Maze is a cycle
    let mut scene = Scene::course();
    let (line, maze) = (
        scene.resolve("Line").unwrap(),
        scene.resolve("Maze").unwrap(),
    );
    let copy = scene.copy_paste(&[line]).unwrap()[0];
    scene.set_parent(maze, Some(copy), true).unwrap();
    let s = server_with(scene, 8);
    let mut sc = connect(&s);
    let e = draw::apply(
        &mut sc,
        &drawing(3, 1),
        &ApplyOptions::default(),
        &mut no_progress,
    )
    .unwrap_err();
    assert!(e.to_string().contains("set the parent of object"), "{e}");
    assert_eq!(s.with_sim(|sim| sim.idle_fps), 8);
    s.shutdown();
}

#[test]
fn legacy_apply_in_a_moved_floor_with_templates_under_maze() {
    let mut scene = Scene::course();
    let h = |s: &Scene, n: &str| s.resolve(n).unwrap();
    let (floor, maze) = (h(&scene, "Floor"), h(&scene, "Maze"));
    scene.set_position(floor, -1, [1.0, 2.0, 0.05]).unwrap();
    scene.set_orientation(floor, -1, [0.0, 0.0, 0.3]).unwrap();
    scene.set_position(maze, -1, [-3.0, 0.5, 0.0]).unwrap();
    scene.set_orientation(maze, -1, [0.0, 0.0, -1.0]).unwrap();
    for t in ["Line", "Start", "End"] {
        let th = h(&scene, t);
        scene.set_parent(th, Some(maze), true).unwrap();
    }
    let s = server_with(scene, 0);
    let mut sc = connect(&s);
    let d = drawing(4, 9);
    draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    draw::verify(&mut sc, &d, &ObjectNames::default()).unwrap();
    // every line sits where the layout says, in the Floor frame
    let ok = s.with_sim(|sim| {
        let floor = sim.scene.resolve("Floor").unwrap();
        let lines: Vec<i32> = sim
            .scene
            .objects()
            .filter(|o| o.alias == "Line")
            .map(|o| o.handle)
            .collect();
        d.lines.iter().all(|p| {
            lines.iter().any(|&l| {
                let (q, e) = sim.scene.pose(l, floor).unwrap();
                (q[0] - p.x).abs() < 1e-5
                    && (q[1] - p.y).abs() < 1e-5
                    && (q[2] - p.z).abs() < 1e-5
                    && (e[2] - p.yaw).abs() < 1e-5
            })
        })
    });
    assert!(ok);
    let c = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
    assert_eq!(c.removed.len(), d.lines.len() - 1);
    for t in ["Line", "Start", "End"] {
        assert!(
            s.with_sim(|sim| sim.scene.resolve(t).is_ok()),
            "template {t} kept"
        );
    }
    s.shutdown();
}
