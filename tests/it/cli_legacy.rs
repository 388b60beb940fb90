//! The `serve`, `apply` and `clear` commands end to end (the binary, a real socket).

use predicates::prelude::*;

use crate::support::bin;
use crate::support::cli::{Serve, generate};

/// `serve --listen 127.0.0.1:0` plus `extra` (the legacy API only).
fn serve(extra: &[&str]) -> Serve {
    let mut args = vec!["--listen", "127.0.0.1:0"];
    args.extend(extra);
    Serve::start(&args, 1)
}

#[test]
fn legacy_cli_apply_replace_clear() {
    let dir = tempfile::tempdir().unwrap();
    let s = serve(&["--idle-fps", "8"]);
    let port = s.port();
    let m1 = generate(dir.path(), "42", "prim");
    let m2 = generate(dir.path(), "7", "dfs");
    bin()
        .args(["apply", &m1, "--port", &port])
        .assert()
        .success()
        .stdout(
            predicate::str::contains("drew 160 lines: 1 kept (the template: 0 already in place, 1 placed), 159 pasted; markers: 1 already in place, 1 placed; 0 earlier copies removed")
                .and(predicate::str::contains("verified")),
        );
    bin()
        .args(["apply", &m2, "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "160 kept (the template and 159 earlier copies: ",
        ));
    bin()
        .args(["apply", &m2, "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "drew 160 lines: 160 kept (the template and 159 earlier copies: 160 already in place, 0 placed), 0 pasted; markers: 2 already in place, 0 placed; 0 earlier copies removed",
        ));
    bin()
        .args(["clear", "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze copies: Line0"));
    bin()
        .args(["clear", "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains("nothing to remove"));
}

#[test]
fn legacy_cli_errors_are_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "1", "kruskal");
    let s = serve(&["--scene", "empty", "--idle-fps", "0"]);
    let port = s.port();
    bin()
        .args(["apply", &m, "--port", &port])
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("missing in the scene: Floor, Maze, Line, Start, End")
                .and(predicate::str::contains("panicked").not()),
        );
    // nothing listens on the port any more: --api auto says so in one line, with the hint
    // that fits a port given by hand
    drop(s);
    let nothing_accepts = predicate::str::contains(format!(
        "error: no CoppeliaSim remote API answered: nothing accepts connections on 127.0.0.1:{port} (tried for 0.3 s)\n  hint: check --port"
    ));
    bin()
        .args([
            "apply",
            &m,
            "--port",
            &port,
            "--timeout",
            "0.3",
            "--connect-timeout",
            "0.3",
        ])
        .assert()
        .failure()
        .stderr(nothing_accepts.clone());
    bin()
        .args([
            "clear",
            "--port",
            &port,
            "--timeout",
            "0.3",
            "--connect-timeout",
            "0.3",
        ])
        .assert()
        .failure()
        .stderr(nothing_accepts);
}

#[test]
fn legacy_cli_refuses_running_simulation_then_stops_it_and_dumps_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let dump = dir.path().join("scene.json");
    let m = generate(dir.path(), "3", "prim");
    let s = serve(&["--idle-fps", "0", "--dump", dump.to_str().unwrap()]);
    let port = s.port();
    // start the simulation with our client
    let mut c = vrep_maze::legacy::Client::connect(format!("127.0.0.1:{port}"), Default::default())
        .unwrap();
    c.call1(vrep_maze::legacy::command::Command::Simulation(
        vrep_maze::legacy::command::SimControl::Start,
    ))
    .unwrap();
    c.close().unwrap();
    bin()
        .args(["apply", &m, "--port", &port])
        .assert()
        .failure()
        .stderr(predicate::str::contains("simulation is running"));
    bin()
        .args(["apply", &m, "--port", &port, "--stop-simulation"])
        .assert()
        .success()
        .stdout(predicate::str::contains("stopped the simulation first"));
    // the dump is on disk before apply's last reply: no waiting, `apply && render` works
    let text = std::fs::read_to_string(&dump).unwrap();
    assert!(text.contains("\"Line158\""), "the dump has the drawn maze");
    let scene = vrep_maze::sim::Scene::from_json(&text).unwrap();
    assert_eq!(scene.len(), 5 + 159);
    // `render` draws a scene dump as SVG: Floor, Start, End and 160 lines (the dummy has no footprint)
    let svg = dir.path().join("scene.svg");
    bin()
        .args([
            "render",
            dump.to_str().unwrap(),
            "-o",
            svg.to_str().unwrap(),
        ])
        .assert()
        .success();
    let svg = std::fs::read_to_string(svg).unwrap();
    assert_eq!(svg.matches("<polygon").count(), 3 + 160);
    assert_eq!(svg.matches("rgb(0,255,0)").count(), 160);
    // a dump is a scene file for the next `serve`
    let s2 = serve(&["--scene", dump.to_str().unwrap(), "--idle-fps", "0"]);
    bin()
        .args(["clear", "--port", &s2.port()])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze copies"));
    bin()
        .args(["serve", "--scene", "/nonexistent/scene.json"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("cannot read scene file"));
    // on a terminal (standard output, no -o) a dump draws as text, as a layout does
    let out = bin()
        .args(["render", dump.to_str().unwrap()])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    assert!(text.lines().all(|l| l.chars().count() <= 80), "{text}");
    assert!(
        ["S", "E", "##", "..."].iter().all(|s| text.contains(s)),
        "{text}"
    );
    // and as PNG: the lines' green, Start's blue and End's red are all there
    let png = dir.path().join("scene.png");
    bin()
        .args([
            "render",
            dump.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
        ])
        .assert()
        .success()
        .stderr(
            predicate::str::contains("wrote ")
                .and(predicate::str::contains("png of the scene dump")),
        );
    let mut reader = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.width, 800);
    let pixels: Vec<&[u8]> = buf[..info.buffer_size()].chunks(3).collect();
    for colour in [[0, 255, 0], [0, 0, 255], [255, 0, 0], [128, 128, 128]] {
        assert!(pixels.iter().any(|p| *p == colour), "no {colour:?} pixel");
    }
    bin()
        .args(["render", dump.to_str().unwrap(), "--solution"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("a scene dump is drawn as it is"));
}

/// `drive --wheels` over the legacy API looks for the robot by name (serve's course scene
/// has none: it says so in one line) and leaves the session cleanly: the next client is
/// served.
#[test]
fn legacy_cli_drive_wheels_names_a_missing_robot_and_frees_the_port() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "3", "dfs");
    let s = serve(&["--idle-fps", "0"]);
    let port = s.port();
    bin()
        .args(["drive", &m, "--wheels", "--api", "legacy", "--port", &port])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "the scene has no object named `Robot` (the robot)",
        ));
    bin()
        .args(["apply", &m, "--api", "legacy", "--port", &port])
        .assert()
        .success();
}
