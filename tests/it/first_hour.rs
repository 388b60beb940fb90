//! The first hour of a new user (issues 21 and 41): what the command line says when
//! something is missing or wrong, and what it says it did.

use predicates::str::contains;

use crate::support::bin;
use crate::support::cli::{Serve, generate};

#[test]
fn a_missing_argument_is_named() {
    for (command, named) in [
        ("apply", "<LAYOUT>"),
        ("render", "<FILE>"),
        ("solve", "<FILE>"),
        ("batch", "--seeds <SEEDS>, --out-dir <OUT_DIR>"),
    ] {
        bin()
            .arg(command)
            .assert()
            .code(2)
            .stderr(contains(format!("not provided: {named}\n")));
    }
}

#[test]
fn a_file_that_is_not_a_layout_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let text = dir.path().join("prim.txt");
    std::fs::write(&text, "hello\n").unwrap();
    bin()
        .arg("validate")
        .arg(&text)
        .assert()
        .code(1)
        .stderr(contains("prim.txt:1:1: not a layout: expected JSON"));
    let layout = generate(dir.path(), "1", "dfs");
    bin()
        .args(["import", &layout])
        .assert()
        .code(1)
        .stderr(contains(
            "is a layout (JSON) already, not a maze drawn as text",
        ));
}

#[test]
fn auto_is_the_default_and_says_which_api_answered() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "5", "prim");
    let s = Serve::start(&["--listen", "127.0.0.1:0", "--idle-fps", "0"], 1);
    let port = s.port();
    bin()
        .args(["apply", &m, "--port", &port])
        .assert()
        .success()
        .stdout(contains(format!(
            "using the legacy remote API at 127.0.0.1:{port}"
        )));
}

#[test]
fn a_zeromq_scene_without_the_wall_template_points_to_create_missing() {
    let dir = tempfile::tempdir().unwrap();
    let walls = dir.path().join("w.json");
    bin()
        .args(["generate", "--style", "walls", "--seed", "1", "-o"])
        .arg(&walls)
        .assert()
        .success();
    let s = Serve::start(
        &["--api", "zmq", "--listen", "127.0.0.1:0", "--idle-fps", "0"],
        1,
    );
    bin()
        .arg("apply")
        .arg(&walls)
        .args(["--api", "zmq", "--port", &s.port()])
        .assert()
        .code(1)
        .stderr(contains("missing in the scene: Wall"))
        .stderr(contains("hint: or pass --create-missing"));
}

/// `generate` names a floor that is not the course's 10 m where it decides it, with the
/// hint that fits: `--resize-floor` always, a smaller `--cell-size` only where one makes
/// the maze fit the course's floor (checked by generating with it).
#[test]
fn generate_names_a_floor_other_than_the_courses() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.json");
    let run = |size: &str, extra: &[&str]| {
        let o = bin()
            .args(["generate", "--seed", "1", "--size", size, "-o"])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success());
        String::from_utf8(o.stderr).unwrap()
    };
    let course = run("9x9", &[]);
    assert!(!course.contains("floor"), "{course}");
    let large = run("30x30", &[]);
    assert!(
        large.contains(
            "solution 452 cells; floor 35 m x 35 m, larger than the course's 10 m x 10 m\n"
        ),
        "{large}"
    );
    assert!(large.contains("hint: the course scene's floor is 10 m x 10 m: draw it with `apply --resize-floor` (clear puts the floor back)\n"), "{large}");
    // no cell holds the course's 0.6 m line at 10/30 m
    assert!(!large.contains("--cell-size"), "{large}");
    let twelve = run("12x12", &[]);
    assert!(
        twelve.contains("or generate it with --cell-size 0.76 to fit that floor"),
        "{twelve}"
    );
    // the size said fits: generated with it, the floor is the course's
    let fitted = run("12x12", &["--cell-size", "0.76"]);
    assert!(!fitted.contains("floor"), "{fitted}");
    // written to standard output, the size is a note
    let o = bin()
        .args(["generate", "--seed", "1", "--size", "12x12"])
        .output()
        .unwrap();
    let stderr = String::from_utf8(o.stderr).unwrap();
    assert!(
        stderr.starts_with("note: floor 15 m x 15 m, larger than the course's"),
        "{stderr}"
    );
}

/// A ZeroMQ port where something answers but not as the remote API (CoppeliaSim 4.3 to
/// 4.5 publish the simulation step on a PUB socket one port above it) fails at the
/// handshake, naming the socket and the port below, where the remote API answers. The long
/// `--timeout` only makes a regression (a wait for a reply that never comes) fail by its
/// message, not by time.
#[test]
fn a_zeromq_port_that_only_publishes_names_the_remote_apis_port() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "1", "dfs");
    let context = zmq::Context::new();
    let publisher = context.socket(zmq::PUB).unwrap();
    // a free port with a free one below it: the remote API below, the publisher above
    let (serve, pub_port) = (0..50)
        .find_map(|_| {
            let rpc = crate::support::cli::free_port();
            let above = rpc.checked_add(1)?;
            publisher.bind(&format!("tcp://127.0.0.1:{above}")).ok()?;
            let serve = Serve::start(
                &[
                    "--api",
                    "zmq",
                    "--port",
                    &rpc.to_string(),
                    "--idle-fps",
                    "0",
                ],
                1,
            );
            Some((serve, above))
        })
        .expect("two free ports side by side");
    let rpc = serve.ports[0];
    let out = bin()
        .args(["apply", &m, "--api", "zmq", "--port", &pub_port.to_string()])
        .args(["--timeout", "60"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "error: tcp://127.0.0.1:{pub_port} is a ZeroMQ PUB socket, which answers no request: not the remote API (a REP socket)\n  hint: the ZeroMQ remote API answers on 127.0.0.1:{rpc}: use --port {rpc}"
        )),
        "{stderr}"
    );
}

/// A layout edited by hand whose metrics no longer fit its maze is refused with the
/// fields, and a hint that says how to mend it, by `validate` and by every command that
/// reads it.
#[test]
fn metrics_that_disagree_with_the_maze_say_how_to_mend_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = generate(dir.path(), "1", "dfs");
    let mut layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let cells = layout["metrics"]["solution_cells"].as_u64().unwrap();
    layout["metrics"]["solution_cells"] = (cells + 17).into();
    std::fs::write(&path, layout.to_string()).unwrap();
    let hint = "hint: the layout's metrics describe another maze (an edit of its passages, start or end?): write the maze's values the lines above give into those `metrics` fields, or make the layout anew with `vrep-maze generate`";
    for args in [
        vec!["validate", path.as_str()],
        vec!["render", path.as_str()],
    ] {
        bin()
            .args(&args)
            .assert()
            .code(1)
            .stderr(contains(format!(
                "metrics.solution_cells: says {} but the maze has {cells}",
                cells + 17
            )))
            .stderr(contains(hint));
    }
}

/// `serve --api both --port P` moves the legacy port and never leaves the ZeroMQ one on
/// 23000, where a CoppeliaSim may be: `--zmq-port` names it, and without it a free one is
/// taken and printed.
#[test]
fn serve_both_with_a_port_keeps_zeromq_off_its_default() {
    let legacy = crate::support::cli::free_port();
    let zmq = crate::support::cli::free_port();
    let serve = Serve::start(
        &[
            "--api",
            "both",
            "--port",
            &legacy.to_string(),
            "--zmq-port",
            &zmq.to_string(),
        ],
        2,
    );
    assert_eq!(serve.ports, [legacy, zmq]);
    drop(serve);
    let legacy = crate::support::cli::free_port();
    let serve = Serve::start(&["--api", "both", "--port", &legacy.to_string()], 2);
    assert_eq!(serve.ports[0], legacy);
    assert_ne!(serve.ports[1], 23000);
    assert_ne!(serve.ports[1], legacy);
    drop(serve);
    bin()
        .args(["serve", "--api", "zmq", "--zmq-port", "0"])
        .assert()
        .code(2)
        .stderr(contains(
            "--zmq-port is for --api both; use --port with --api zmq",
        ));
}
