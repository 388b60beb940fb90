//! Connecting `apply` and `clear`: what is tried is said at once, a port where nothing
//! listens is a clear error with hints within `--connect-timeout`, a port that speaks the
//! other remote API is named as such (quickly, and without disturbing that server), and a
//! refused legacy connection is retried silently when standard error is not a terminal.
//!
//! Times are only generous upper bounds that prove "did not hang".

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use assert_cmd::cargo::CommandCargoExt;

use crate::support::bin;
use crate::support::cli::{Serve, generate};

/// A loopback port where nothing listens (bound, then released).
fn free_port() -> String {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
        .to_string()
}

/// Runs `vrep-maze args`; returns the exit code, stderr and how long it took.
fn run(args: &[&str]) -> (Option<i32>, String, Duration) {
    let started = Instant::now();
    let out = bin().args(args).output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        started.elapsed(),
    )
}

/// Every stderr line is the `connecting to` line, the one `error:` line, or a hint.
fn assert_clear_error(stderr: &str) {
    let errors = stderr.lines().filter(|l| l.starts_with("error: ")).count();
    assert_eq!(errors, 1, "{stderr}");
    for line in stderr.lines() {
        assert!(
            line.starts_with("connecting to ")
                || line.starts_with("error: ")
                || line.starts_with("  hint: "),
            "unexpected line {line:?} in\n{stderr}"
        );
    }
}

#[test]
fn the_first_line_says_what_is_tried_before_any_wait() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "1", "kruskal");
    let port = free_port();
    let started = Instant::now();
    let mut child = Command::cargo_bin("vrep-maze")
        .unwrap()
        .args(["apply", &m, "--port", &port, "--connect-timeout", "60"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let waited = started.elapsed();
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(
        line.trim_end(),
        format!("connecting to CoppeliaSim's legacy remote API at 127.0.0.1:{port} ...")
    );
    // well before the 60 s it would keep trying
    assert!(waited < Duration::from_secs(20), "{waited:?}");
}

#[test]
fn nothing_listening_is_one_error_line_with_hints_within_the_connect_timeout() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    let port = free_port();
    let (code, stderr, took) = run(&[
        "apply",
        &m,
        "--api",
        "legacy",
        "--port",
        &port,
        "--connect-timeout",
        "1",
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(took < Duration::from_secs(15), "{took:?}");
    assert_clear_error(&stderr);
    assert!(
        stderr.contains(&format!(
            "error: cannot connect to 127.0.0.1:{port}: nothing accepted a connection within 1 s"
        )),
        "{stderr}"
    );
    assert!(
        stderr.contains("hint: is CoppeliaSim running with the legacy remote API"),
        "{stderr}"
    );
    assert!(stderr.contains("for about a minute"), "{stderr}");
    assert!(stderr.contains("--connect-timeout 75"), "{stderr}");
    // `clear` connects the same way; over ZeroMQ a refused port fails at once
    let (code, stderr, took) = run(&[
        "clear",
        "--api",
        "legacy",
        "--port",
        &port,
        "--connect-timeout",
        "0.5",
    ]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(took < Duration::from_secs(15), "{took:?}");
    assert_clear_error(&stderr);
    let (code, stderr, took) = run(&["clear", "--api", "zmq", "--port", &port]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(took < Duration::from_secs(8), "{took:?}");
    assert_clear_error(&stderr);
    assert!(
        stderr.starts_with(&format!(
            "connecting to CoppeliaSim's ZeroMQ remote API at 127.0.0.1:{port} ...\n"
        )),
        "{stderr}"
    );
}

#[test]
fn a_legacy_client_on_a_zeromq_port_is_told_to_use_api_zmq_quickly() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "3", "dfs");
    let s = Serve::start(
        &["--api", "zmq", "--listen", "127.0.0.1:0", "--idle-fps", "0"],
        1,
    );
    let port = s.port();
    let (code, stderr, took) = run(&["apply", &m, "--api", "legacy", "--port", &port]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(took < Duration::from_secs(5), "{took:?}: {stderr}");
    assert_clear_error(&stderr);
    assert!(
        stderr.contains(&format!(
            "error: port {port} speaks the ZeroMQ remote API, not the legacy one: use --api zmq"
        )),
        "{stderr}"
    );
    // the ZeroMQ server was not disturbed: it answers the next client at once
    bin()
        .args([
            "apply",
            &m,
            "--api",
            "zmq",
            "--port",
            &port,
            "--dry-run",
            "--timeout",
            "3",
        ])
        .assert()
        .success();
}

#[test]
fn a_zeromq_client_on_a_legacy_port_is_told_to_use_api_legacy() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "4", "kruskal");
    let s = Serve::start(&["--listen", "127.0.0.1:0", "--idle-fps", "0"], 1);
    let port = s.port();
    let (code, stderr, took) = run(&["apply", &m, "--api", "zmq", "--port", &port]);
    assert_eq!(code, Some(1), "{stderr}");
    // no reply timeout (10 s) was waited for
    assert!(took < Duration::from_secs(8), "{took:?}: {stderr}");
    assert_clear_error(&stderr);
    assert!(
        stderr.contains(&format!(
            "error: port {port} speaks the legacy remote API, not the ZeroMQ one: use --api legacy"
        )),
        "{stderr}"
    );
    // the probe left the legacy server politely: the next client is served
    bin()
        .args(["apply", &m, "--port", &port, "--dry-run"])
        .assert()
        .success();
}

#[test]
fn a_refused_legacy_connection_is_retried_without_a_countdown_off_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "5", "prim");
    // after each client the server refuses connections for 2 s
    let s = Serve::start(
        &[
            "--listen",
            "127.0.0.1:0",
            "--idle-fps",
            "0",
            "--rebind-delay-ms",
            "2000",
        ],
        1,
    );
    let port = s.port();
    let client =
        vrep_maze::legacy::Client::connect(format!("127.0.0.1:{port}"), Default::default())
            .unwrap();
    client.close().unwrap();
    let (code, stderr, took) = run(&[
        "apply",
        &m,
        "--api",
        "legacy",
        "--port",
        &port,
        "--dry-run",
        "--connect-timeout",
        "30",
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(took < Duration::from_secs(25), "{took:?}");
    assert_eq!(
        stderr.trim_end(),
        format!("connecting to CoppeliaSim's legacy remote API at 127.0.0.1:{port} ..."),
        "only the first line when stderr is not a terminal"
    );
}
