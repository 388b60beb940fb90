//! Issue 38's smaller rows, each as a person meets it on `serve`: a raised floor (row 9),
//! a mesh apply's hints for a missing floor (row 10).

use tempfile::TempDir;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{self, ApplyOptions, ClearOptions};
use vrep_maze::sim::Scene;

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::{self, Serve};
use crate::support::layouts::drawing;

backend_tests!(a_raised_floor_puts_line_back_where_it_stood_and_says_so);

/// Row 9: `Floor` raised to z 0.5 leaves the course's `Line` below it. Applied and cleared,
/// `Line` goes back exactly where it stood, and `clear` says that, not that it put it "below
/// the floor" where an earlier maze had left it.
fn a_raised_floor_puts_line_back_where_it_stood_and_says_so(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let (line, before) = s.with_sim(|sim| {
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene
            .set_position(floor, HANDLE_WORLD, [0.0, 0.0, 0.5])
            .unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        (line, sim.scene.pose(line, HANDLE_WORLD).unwrap())
    });
    let mut b = s.connect();
    draw::apply(
        &mut *b,
        &drawing(4, 1),
        &ApplyOptions::default(),
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{k}: {e}"));
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        c.template.as_deref(),
        Some("put `Line` back where it stood before the first apply"),
        "{k}"
    );
    let after = s.with_sim(|sim| sim.scene.pose(line, HANDLE_WORLD).unwrap());
    for (a, b) in before
        .0
        .iter()
        .chain(&before.1)
        .zip(after.0.iter().chain(&after.1))
    {
        assert!((a - b).abs() < 1e-6, "{k}: {before:?} then {after:?}");
    }
    drop(b);
    s.shutdown();
}

/// Row 10: `apply --draw mesh` on a scene without `Floor` offers `--create-missing`, as a
/// copies apply does, and no `--resize-floor` for a floor that does not exist; the hint
/// followed, the maze is drawn.
#[test]
fn a_mesh_apply_without_a_floor_offers_create_missing_not_a_resize() {
    let dir = TempDir::new().unwrap();
    let mut scene = Scene::course();
    let floor = scene.resolve("Floor").unwrap();
    scene.remove(floor).unwrap();
    let file = dir.path().join("no-floor.json");
    std::fs::write(&file, scene.to_json().to_string()).unwrap();
    let file = file.display().to_string();
    let s = Serve::start(
        &["--api", "zmq", "--listen", "127.0.0.1:0", "--scene", &file],
        1,
    );
    let port = s.port();
    let layout = cli::generate(dir.path(), "3", "dfs");
    let apply = |draw: &str, more: &[&str]| {
        bin()
            .args([
                "apply", &layout, "--api", "zmq", "--port", &port, "--draw", draw,
            ])
            .args(more)
            .output()
            .unwrap()
    };
    for draw in ["copies", "mesh"] {
        let out = apply(draw, &[]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{draw}: {err}");
        assert!(err.contains("missing in the scene: Floor"), "{draw}: {err}");
        assert!(
            err.contains("hint: or pass --create-missing"),
            "{draw}: {err}"
        );
        assert!(!err.contains("resize-floor"), "{draw}: {err}");
    }
    let out = apply("mesh", &["--create-missing"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        said.contains("created Floor") && said.contains("verified"),
        "{said}"
    );
}
