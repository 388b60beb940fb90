//! `serve --api zmq|both`, `apply --api zmq|auto --create-missing --save-scene` and `clear`
//! end to end through the binary.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use assert_cmd::cargo::CommandCargoExt;
use predicates::prelude::*;

struct Serve(Child, Vec<u16>);

impl Drop for Serve {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `serve` with `args`; returns the ports it printed (one line per API).
fn serve(args: &[&str], lines: usize) -> Serve {
    let mut child = Command::cargo_bin("vrep-maze")
        .unwrap()
        .arg("serve")
        .args(args)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut ports = vec![];
    for _ in 0..lines {
        let mut line = String::new();
        out.read_line(&mut line).unwrap();
        let port = line
            .split("127.0.0.1:")
            .nth(1)
            .and_then(|r| r.split_whitespace().next())
            .unwrap_or_else(|| panic!("no address in {line:?}"))
            .parse()
            .unwrap();
        ports.push(port);
    }
    Serve(child, ports)
}

fn cmd() -> assert_cmd::Command {
    assert_cmd::Command::cargo_bin("vrep-maze").unwrap()
}

fn generate(dir: &std::path::Path, seed: &str) -> String {
    let path = dir.join(format!("m{seed}.json")).display().to_string();
    cmd()
        .args(["generate", "--seed", seed, "--algo", "prim", "-o", &path])
        .assert()
        .success();
    path
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
    let port = s.1[0].to_string();
    let m = generate(dir.path(), "42");
    cmd()
        .args(["apply", &m, "--api", "zmq", "--port", &port])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "missing in the scene: Floor, Maze, Line, Start, End",
        ));
    let saved = dir.path().join("saved.json").display().to_string();
    cmd()
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
                    "drew 160 lines: 0 reused, 159 pasted",
                ))
                .and(predicate::str::contains("verified"))
                .and(predicate::str::contains("saved the scene")),
        );
    assert!(
        std::fs::read_to_string(&saved)
            .unwrap()
            .contains("vrep-maze scene")
    );
    cmd()
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
            predicate::str::contains("159 reused, 0 pasted, 0 removed")
                .and(predicate::str::contains("created").not()),
        );
    cmd()
        .args(["clear", "--api", "zmq", "--port", &port])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze line(s)"));
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
    cmd()
        .args(["apply", &m, "--api", "zmq", "--port", &s.1[0].to_string()])
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
    let (legacy, zmq) = (s.1[0].to_string(), s.1[1].to_string());
    let m = generate(dir.path(), "42");
    cmd()
        .args(["apply", &m, "--port", &legacy])
        .assert()
        .success();
    cmd()
        .args(["clear", "--api", "zmq", "--port", &zmq])
        .assert()
        .success()
        .stdout(predicate::str::contains("removed 159 maze line(s)"));
    cmd()
        .args(["clear", "--port", &legacy])
        .assert()
        .success()
        .stdout(predicate::str::contains("nothing to remove"));
}

#[test]
fn zmq_cli_errors_are_one_clear_line() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "3");
    cmd()
        .args(["apply", &m, "--create-missing"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "need the ZeroMQ remote API (--api zmq)",
        ));
    cmd()
        .args(["apply", &m, "--api", "auto", "--port", "1"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "--port needs --api legacy or --api zmq",
        ));
    let free = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    cmd()
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
                    s.trim_end().lines().count() == 1
                })),
        );
    cmd()
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
    cmd()
        .args(["apply", &m, "--api", "zmq", "--port", &s.1[0].to_string()])
        .assert()
        .success();
    let pid = s.0.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-TERM", &pid])
            .status()
            .unwrap()
            .success()
    );
    assert!(s.0.wait().unwrap().success());
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

/// `--api auto` on the default ports: nothing on 19997, `serve --api zmq` on 23000. Skipped
/// when those ports are not in that state on this machine.
#[test]
fn zmq_cli_auto_falls_back_to_the_zeromq_port() {
    if std::net::TcpStream::connect("127.0.0.1:19997").is_ok() {
        eprintln!("something listens on 19997; skipped");
        return;
    }
    match std::net::TcpListener::bind("127.0.0.1:23000") {
        Ok(probe) => drop(probe),
        Err(_) => {
            eprintln!("port 23000 is busy; skipped");
            return;
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let _s = serve(&["--api", "zmq", "--idle-fps", "0"], 1);
    let m = generate(dir.path(), "8");
    cmd()
        .args(["apply", &m, "--api", "auto", "--timeout", "3"])
        .assert()
        .success()
        .stdout(
            predicate::str::contains("using the ZeroMQ remote API at tcp://127.0.0.1:23000")
                .and(predicate::str::contains("verified")),
        );
}
