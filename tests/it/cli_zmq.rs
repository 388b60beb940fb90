//! `serve --api zmq|both`, `apply --api zmq|auto --create-missing --save-scene` and `clear`
//! end to end through the binary.

use std::process::Command;

use predicates::prelude::*;

use crate::support::bin;
use crate::support::cli::{self, Serve};

fn serve(args: &[&str], lines: usize) -> Serve {
    Serve::start(args, lines)
}

fn generate(dir: &std::path::Path, seed: &str) -> String {
    cli::generate(dir, seed, "prim")
}

#[test]
fn zmq_cli_fresh_scene_create_missing_apply_save_clear() {
    let dir = tempfile::tempdir().unwrap();
    let s = serve(
        &[
            "--api",
            "zmq",
            "--listen",
            "127.0.0.1:0",
            "--scene",
            "empty",
        ],
        1,
    );
    let port = s.port();
    let m = generate(dir.path(), "42");
    bin()
        .args(["apply", &m, "--api", "zmq", "--port", &port])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "missing in the scene: Floor, Maze, Line, Start, End",
        ));
    let saved = dir.path().join("saved.json").display().to_string();
    bin()
        .args([
            "apply",
            &m,
            "--api",
            "zmq",
            "--port",
            &port,
            "--create-missing",
        ])
        .args(["--save-scene", &saved])
        .assert()
        .success()
        .stdout(
            predicate::str::contains("using the ZeroMQ remote API")
                .and(predicate::str::contains("protocol 2"))
                .and(predicate::str::contains(
                    "created Floor, Maze, Line, Start, End",
                ))
                .and(predicate::str::contains(
                    "drew 160 lines: 1 kept (the template: 0 already in place, 1 placed), 159 pasted",
                ))
                .and(predicate::str::contains("verified"))
                .and(predicate::str::contains("saved the scene")),
        );
    assert!(
        std::fs::read_to_string(&saved)
            .unwrap()
            .contains("vrep-maze scene")
    );
    bin()
        .args([
            "apply",
            &m,
            "--api",
            "zmq",
            "--port",
            &port,
            "--create-missing",
        ])
        .assert()
        .success()
        .stdout(
            predicate::str::contains("160 kept (the template and 159 earlier copies: 1 already in place, 0 placed, 159 set unread, as reading costs what setting does), 0 pasted; markers: 2 already in place, 0 placed; 0 earlier copies removed")
                .and(predicate::str::contains("created").not()),
        );
    bin()
        .args(["clear", "--api", "zmq", "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze copies"));
}

#[test]
fn zmq_cli_protocol_1_server() {
    let dir = tempfile::tempdir().unwrap();
    let s = serve(
        &[
            "--api",
            "zmq",
            "--listen",
            "127.0.0.1:0",
            "--protocol",
            "1",
            "--idle-fps",
            "0",
        ],
        1,
    );
    let m = generate(dir.path(), "5");
    bin()
        .args(["apply", &m, "--api", "zmq", "--port", &s.port()])
        .assert()
        .success()
        .stdout(
            predicate::str::contains("protocol 1, CoppeliaSim 4.5.1")
                .and(predicate::str::contains("verified")),
        );
}

#[test]
fn zmq_cli_both_apis_share_one_scene() {
    let dir = tempfile::tempdir().unwrap();
    let s = serve(
        &[
            "--api",
            "both",
            "--listen",
            "127.0.0.1:0",
            "--zmq-listen",
            "127.0.0.1:0",
            "--idle-fps",
            "0",
        ],
        2,
    );
    let (legacy, zmq) = (s.ports[0].to_string(), s.ports[1].to_string());
    let m = generate(dir.path(), "42");
    bin()
        .args(["apply", &m, "--port", &legacy])
        .assert()
        .success();
    bin()
        .args(["clear", "--api", "zmq", "--port", &zmq])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze copies"));
    bin()
        .args(["clear", "--port", &legacy])
        .assert()
        .success()
        .stdout(predicate::str::contains("nothing to remove"));
}

#[test]
fn zmq_cli_errors_are_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "3");
    bin()
        .args(["apply", &m, "--create-missing", "--api", "legacy"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "need the ZeroMQ remote API (--api zmq)",
        ));
    // a port where nothing listens, given by hand: one short line, and of the hints only
    // those that fit a typo (no minute of legacy refusal)
    bin()
        .args(["apply", &m, "--api", "auto", "--port", "1"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "error: no CoppeliaSim remote API answered: nothing accepts connections on 127.0.0.1:1 (tried for 1.5 s)\n  hint: check --port: CoppeliaSim serves the legacy remote API on 19997, the ZeroMQ one on 23000\n",
        ))
        .stderr(predicate::str::contains("about a minute").not());
    let free = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    bin()
        .args([
            "clear",
            "--api",
            "zmq",
            "--port",
            &free.to_string(),
            "--timeout",
            "1",
        ])
        .assert()
        .failure()
        .stderr(
            predicate::str::contains(format!("cannot connect to tcp://127.0.0.1:{free}"))
                .and(predicate::str::contains("ZeroMQ remote API add-on"))
                .and(predicate::function(|s: &str| {
                    // what is tried, then the error on one line
                    let mut lines = s.trim_end().lines();
                    lines
                        .next()
                        .is_some_and(|l| l.starts_with("connecting to "))
                        && lines.count() == 1
                })),
        );
    bin()
        .args(["serve", "--api", "zmq", "--zmq-listen", "127.0.0.1:0"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("--zmq-listen is for --api both"));
}

#[test]
fn zmq_cli_serve_dumps_the_scene_on_sigterm() {
    let dir = tempfile::tempdir().unwrap();
    let dump = dir.path().join("scene.json");
    let mut s = serve(
        &[
            "--api",
            "zmq",
            "--listen",
            "127.0.0.1:0",
            "--idle-fps",
            "0",
            "--dump",
            dump.to_str().unwrap(),
        ],
        1,
    );
    let m = generate(dir.path(), "11");
    bin()
        .args(["apply", &m, "--api", "zmq", "--port", &s.port()])
        .assert()
        .success();
    let pid = s.child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-TERM", &pid])
            .status()
            .unwrap()
            .success()
    );
    assert!(s.child.wait().unwrap().success());
    let text = std::fs::read_to_string(&dump).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let lines = v["scene"]["objects"]
        .as_object()
        .unwrap()
        .values()
        .filter(|o| o["alias"] == "Line")
        .count();
    assert_eq!(lines, 160);
}

/// `--api auto` on the default ports (moved to free ones, as a user's environment may):
/// nothing on the legacy one, `serve --api zmq` on the ZeroMQ one.
#[test]
fn zmq_cli_auto_falls_back_to_the_zeromq_port() {
    use crate::support::cli::{default_ports, free_port};
    let dir = tempfile::tempdir().unwrap();
    let s = serve(&["--api", "zmq", "--port", "0", "--idle-fps", "0"], 1);
    let zmq = s.ports[0];
    let m = generate(dir.path(), "8");
    bin()
        .envs(default_ports(free_port(), zmq))
        .args(["apply", &m, "--api", "auto", "--timeout", "3"])
        .assert()
        .success()
        .stdout(
            predicate::str::contains(format!(
                "using the ZeroMQ remote API at tcp://127.0.0.1:{zmq}"
            ))
            .and(predicate::str::contains("verified")),
        );
}
