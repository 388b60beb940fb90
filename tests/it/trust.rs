//! Trust at the edges: nothing invalid is drawn or rendered, "verified" cannot describe a
//! wrong scene, clear refuses a running simulation, and the command line never panics,
//! floods or writes where it should not.

use std::io::Read;
use std::process::Stdio;

use tempfile::TempDir;
use vrep_maze::cli::remedies;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{self, ApplyOptions, ClearOptions, DrawError, ObjectNames};
use vrep_maze::sim::{NewObject, ObjectType, Scene, SimState};

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::Serve;
use crate::support::layouts::drawing;

backend_tests!(
    clear_refuses_a_running_simulation_or_stops_it_first,
    a_non_finite_pose_never_verifies_and_apply_repairs_it,
    an_extra_object_under_the_maze_never_verifies,
    a_maze_dummy_moved_between_two_applies_is_repaired_by_the_second,
);

/// The copies move with the maze dummy: moved (by the user) between two applies over one
/// connection, the second apply finds every line out of place and puts it back, though a
/// ZeroMQ connection remembers where it set them rather than read them back.
fn a_maze_dummy_moved_between_two_applies_is_repaired_by_the_second(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let d = drawing(3, 2);
    let mut b = s.connect();
    draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        sim.scene
            .set_position(maze, HANDLE_WORLD, [0.5, 0.0, 0.0])
            .unwrap();
    });
    let r = draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {})
        .unwrap_or_else(|e| panic!("{k}: {e}"));
    // the template is no child of the dummy: it stays in place
    assert_eq!(r.placed, d.pieces.len() - 1, "{k}: {r:?}");
    draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    drop(b);
    s.shutdown();
}

/// `clear` while the simulation runs would be undone at stop: refused, or with
/// `stop_simulation` the simulation is stopped first and the removal stays.
fn clear_refuses_a_running_simulation_or_stops_it_first(kind: Kind) {
    let s = kind.serve(Scene::course(), 0);
    let d = drawing(4, 1);
    let mut b = s.connect();
    draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    s.with_sim(|sim| sim.start());
    let refused = draw::clear(&mut *b, &ClearOptions::default()).unwrap_err();
    assert!(matches!(refused, DrawError::SimulationRunning), "{refused}");
    assert_eq!(s.line_count(), d.pieces.len(), "nothing removed");
    let opts = ClearOptions {
        stop_simulation: true,
        ..Default::default()
    };
    let r = draw::clear(&mut *b, &opts).unwrap();
    assert!(r.stopped_simulation);
    assert_eq!(r.removed.len(), d.pieces.len() - 1);
    drop(b);
    let state = s.with_sim(|sim| sim.state);
    assert_eq!(state, SimState::Stopped);
    assert_eq!(s.line_count(), 1, "only the template is left, and stays");
    s.shutdown();
}

/// A line or marker at NaN is never "in place": verify fails, and apply moves it back.
fn a_non_finite_pose_never_verifies_and_apply_repairs_it(kind: Kind) {
    let s = kind.serve(Scene::course(), 0);
    let d = drawing(3, 2);
    let mut b = s.connect();
    draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    for name in ["Start", "Line"] {
        s.with_sim(|sim| {
            let h = sim.scene.resolve(name).unwrap();
            sim.scene
                .set_position(h, HANDLE_WORLD, [f64::NAN, 0.0, 0.001])
                .unwrap();
        });
        let e = draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap_err();
        assert!(
            matches!(e, DrawError::Verify(_)),
            "{}: {name}: {e}",
            kind.name()
        );
        // its own pose, not the floor's or the maze dummy's: a re-run repairs it
        assert!(
            remedies::hints(&e)
                .iter()
                .any(|h| h.contains("it repairs what differs")),
            "{}: {name}: {:?}",
            kind.name(),
            remedies::hints(&e)
        );
        let r = draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        assert!(r.edits > 0, "{}: {name} was re-placed", kind.name());
        draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap();
    }
    drop(b);
    s.shutdown();
}

/// A copy of the template under `Maze` that the drawing does not account for fails
/// verification, with a count (an object of another name is the user's and left alone:
/// `trust_draw`).
fn an_extra_object_under_the_maze_never_verifies(kind: Kind) {
    let s = kind.serve(Scene::course(), 0);
    let d = drawing(3, 3);
    let mut b = s.connect();
    draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        sim.scene.add(
            "Line77",
            NewObject {
                kind: ObjectType::Shape,
                parent: Some(maze),
                position: [9.0, 9.0, 0.001],
                orientation: [0.0; 3],
                size: [0.6, 0.1, 0.0],
                colour: [0, 255, 0],
            },
        );
    });
    let e = draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap_err();
    assert!(
        e.to_string().contains("1 stray maze object"),
        "{}: {e}",
        kind.name()
    );
    drop(b);
    s.shutdown();
}

/// Writes a copy of a golden layout with `edit` applied; returns its path.
fn broken_layout(dir: &TempDir, name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/dfs-9x9-seed42.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(golden).unwrap()).unwrap();
    edit(&mut v);
    let path = dir.path().join(name);
    std::fs::write(&path, v.to_string()).unwrap();
    path.display().to_string()
}

/// One representative per class of broken layout the trust issue found drawn and
/// "verified": each is refused before anything is drawn, and the scene is untouched.
#[test]
fn apply_draws_nothing_from_a_layout_validate_rejects() {
    let dir = TempDir::new().unwrap();
    let serve = Serve::start(&["--listen", "127.0.0.1:0", "--idle-fps", "0"], 1);
    let port = serve.port();
    let good = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/prim-9x9-seed42.json");
    bin()
        .args(["apply", good, "--port", &port])
        .assert()
        .success();
    type Break = Box<dyn Fn(&mut serde_json::Value)>;
    let cases: Vec<(&str, Break)> = vec![
        (
            "no-segments",
            Box::new(|v| v["segments"] = serde_json::json!([])),
        ),
        (
            "start-off-grid",
            Box::new(|v| v["start"]["cell"] = serde_json::json!([100, 100])),
        ),
        (
            "bad-passages",
            Box::new(|v| v["passages"][0] = serde_json::json!("zzz")),
        ),
        (
            "moved-segment",
            Box::new(|v| v["segments"][5]["x"] = serde_json::json!(0.37)),
        ),
        (
            "negative-cell",
            Box::new(|v| v["grid"]["cell_size"] = serde_json::json!(-1)),
        ),
        (
            "far-segment",
            Box::new(|v| v["segments"][3]["x"] = serde_json::json!(1e308)),
        ),
        (
            "deleted-passage",
            Box::new(|v| v["passages"][0] = serde_json::json!("000000000")),
        ),
    ];
    for (name, edit) in cases {
        let path = broken_layout(&dir, &format!("{name}.json"), edit);
        let out = bin()
            .args(["apply", &path, "--port", &port])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
        assert!(stderr.contains("nothing was drawn"), "{name}: {stderr}");
        assert!(
            !String::from_utf8_lossy(&out.stdout).contains("verified"),
            "{name}"
        );
        assert!(
            stderr.len() < 4096,
            "{name}: {} bytes of errors",
            stderr.len()
        );
    }
    // the scene still holds the good maze, untouched
    bin()
        .args(["apply", good, "--port", &port, "--dry-run"])
        .assert()
        .success()
        .stdout(predicates::str::contains(
            "nothing to do: the scene already shows this layout",
        ));
}

/// A failing OS call is named once: no "No such file or directory (os error 2): No such
/// file or directory (os error 2)".
#[test]
fn each_cause_is_printed_once() {
    for args in [
        &["validate", "/nonexistent/m.json"][..],
        &["render", "/nonexistent/m.json"],
        &["apply", "/nonexistent/m.json"],
        &["generate", "-o", "/nonexistent/dir/m.json"],
    ] {
        let out = bin().args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert_eq!(
            stderr.matches("os error 2").count(),
            1,
            "{args:?}: {stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    }
}

/// Output closed early (`| head -1`) ends the run quietly with success.
#[test]
fn a_closed_output_pipe_ends_quietly_with_success() {
    for args in [
        &["completions", "bash"][..],
        &["generate", "--size", "200x200", "--seed", "1"],
        &[
            "render",
            concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/prim-20x15-seed7.json"),
        ],
    ] {
        let mut child = crate::support::cli::spawnable()
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut first = [0u8; 16];
        child
            .stdout
            .as_mut()
            .unwrap()
            .read_exact(&mut first)
            .unwrap();
        drop(child.stdout.take());
        let status = child.wait().unwrap();
        let mut stderr = String::new();
        child
            .stderr
            .take()
            .unwrap()
            .read_to_string(&mut stderr)
            .unwrap();
        assert_eq!(status.code(), Some(0), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

/// Special files are written through, never replaced; render refuses extensions it does
/// not write and never puts PNG bytes into a .svg or ASCII into a .jpg.
#[test]
fn outputs_go_where_asked_in_the_format_asked() {
    let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/dfs-9x9-seed42.json");
    bin()
        .args(["generate", "--seed", "1", "-o", "/dev/null"])
        .assert()
        .success();
    assert!(!std::fs::metadata("/dev/null").unwrap().is_file());
    let out = bin()
        .args(["generate", "--seed", "1", "-o", "/dev/stdout"])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("\"vrep-maze/layout\""));
    let dir = TempDir::new().unwrap();
    for (file, code) in [("m.jpg", 2), ("m.png", 0), ("m.svg", 0), ("m.txt", 0)] {
        let path = dir.path().join(file);
        let out = bin()
            .args(["render", golden, "-o", path.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(code), "{file}");
    }
    let png = std::fs::read(dir.path().join("m.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG"), "a .png holds PNG");
    let svg = std::fs::read_to_string(dir.path().join("m.svg")).unwrap();
    assert!(svg.contains("<svg"), "a .svg holds SVG");
    assert!(
        !dir.path().join("m.jpg").exists(),
        "nothing written for a refused extension"
    );
    let clash = dir.path().join("x.png");
    bin()
        .args([
            "render",
            golden,
            "--format",
            "svg",
            "-o",
            clash.to_str().unwrap(),
        ])
        .assert()
        .code(2);
}
