//! The first hour of a new user (issue 21): what the command line says when something is
//! missing or wrong, and what it says it did.

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
