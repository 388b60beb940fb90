//! The README's front door: its two set-up commands, and its "In 30 seconds" section
//! followed word for word against `vrep-maze serve`.

use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use assert_cmd::cargo::CommandCargoExt;

use crate::support::cli::{default_ports, free_port};

/// The command lines of the first `sh` block of the README's section `heading`, comments
/// dropped.
fn commands(heading: &str) -> Vec<String> {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md")).unwrap();
    let section = readme
        .split(&format!("## {heading}\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("the README has a '{heading}' section"));
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a sh block");
    block
        .lines()
        .map(|l| l.split(" #").next().unwrap().trim().to_string())
        .filter(|l| !l.is_empty())
        .collect()
}

/// The 30-second path's command lines.
fn thirty_seconds() -> Vec<String> {
    commands("In 30 seconds")
}

/// The set-up is two commands: the main job on its embedded default (`demo`, run by
/// `cli::demo_runs_the_whole_job`) built in release, whose binary the 30-second path then
/// uses, and the test suite as CI runs it (`.ci/run` calls `cargo test`).
#[test]
fn the_set_up_is_two_commands_ci_runs_the_second() {
    assert_eq!(
        commands("Set-up: two commands"),
        ["cargo run --release -- demo", "cargo test"]
    );
    let ci =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(".ci/run")).unwrap();
    assert!(
        ci.lines().any(|l| l.trim() == "cargo test"),
        ".ci/run runs `cargo test`"
    );
}

/// A background process, killed at the end.
struct Background(Child);

impl Drop for Background {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The path runs on default ports moved to free ones: whatever listens on 19997 or 23000
/// (the user's CoppeliaSim) is neither needed nor touched.
#[test]
fn the_thirty_second_path_works_word_for_word() {
    let (legacy, zmq) = (free_port(), free_port());
    let lines = thirty_seconds();
    // the binary `cargo run --release` built, not a second build (this test runs the one
    // cargo built for it)
    assert_eq!(
        lines.first().map(String::as_str),
        Some(r#"export PATH="$PWD/target/release:$PATH""#),
        "the path starts with the set-up's binary"
    );
    let dir = tempfile::tempdir().unwrap();
    let mut background = Vec::new();
    let mut outputs = Vec::new();
    let mut stopped = false;
    for line in &lines[1..] {
        if line == "kill %1" {
            // the shell's job 1 is the first command started with `&`: `serve` stops on
            // SIGTERM, saying so, and exits 0
            let Background(serve) = background.first_mut().expect("a job to stop");
            let killed = Command::new("kill")
                .arg(serve.id().to_string())
                .status()
                .unwrap();
            assert!(killed.success());
            let status = serve.wait().unwrap();
            assert!(status.success(), "serve stopped by kill exits {status}");
            stopped = true;
            continue;
        }
        let (line, in_background) = match line.strip_suffix('&') {
            Some(l) => (l.trim(), true),
            None => (line.as_str(), false),
        };
        let words: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(words[0], "vrep-maze", "{line}");
        let mut command = Command::cargo_bin("vrep-maze").unwrap();
        command
            .args(&words[1..])
            .envs(default_ports(legacy, zmq))
            .current_dir(dir.path());
        if in_background {
            let child = command.stdout(Stdio::null()).spawn().unwrap();
            background.push(Background(child));
            // bounded: until the emulator listens, at most 10 s
            let listening = (0..100).any(|_| {
                std::thread::sleep(Duration::from_millis(100));
                TcpStream::connect(("127.0.0.1", legacy)).is_ok()
            });
            assert!(listening, "`{line}` does not listen on its default port");
            continue;
        }
        let out = command.output().unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "`{line}` failed: {}\n{stdout}",
            String::from_utf8_lossy(&out.stderr)
        );
        outputs.push((line.to_string(), stdout));
    }
    let said = |command: &str| {
        outputs
            .iter()
            .find(|(l, _)| l.starts_with(command))
            .map(|(_, out)| out.as_str())
            .unwrap_or_else(|| panic!("the path has no `{command}`"))
    };
    assert!(said("vrep-maze apply").contains("verified"));
    let picture = said("vrep-maze render");
    assert!(picture.contains('S') && picture.contains('E') && picture.contains('.'));
    assert!(dir.path().join("maze.json").exists());
    assert!(stopped, "the path says how to stop serve (`kill %1`)");
}

/// `serve` on a taken port, started in the background as the path does: it exits at once
/// (non-zero) with one error line naming the address and a hint naming `--port`, instead
/// of a server that never listens.
#[test]
fn serve_on_a_taken_port_fails_at_once_with_a_hint() {
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    for (api, env) in [
        ("legacy", "VREP_MAZE_LEGACY_PORT"),
        ("zmq", "VREP_MAZE_ZMQ_PORT"),
    ] {
        let child = Command::cargo_bin("vrep-maze")
            .unwrap()
            .args(["serve", "--api", api])
            .env(env, port.to_string())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{api}: {stderr}");
        assert!(out.stdout.is_empty(), "{api}: announced no server");
        let lines: Vec<&str> = stderr.lines().collect();
        assert!(
            lines[0].starts_with(&format!(
                "error: cannot listen on 127.0.0.1:{port}: something already listens there"
            )),
            "{api}: {stderr}"
        );
        assert!(
            lines.len() == 2 && lines[1].contains("hint:") && lines[1].contains("--port 0"),
            "{api}: {stderr}"
        );
    }
}
