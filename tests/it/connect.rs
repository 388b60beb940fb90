//! Connecting `apply`, `clear` and `score`: what is tried is said at once, a port where nothing
//! listens is a clear error with hints within `--connect-timeout`, a port that speaks the
//! other remote API is named as such (quickly, and without disturbing that server), and a
//! refused legacy connection is retried silently when standard error is not a terminal.
//!
//! No assertion is on time: what a run printed proves how long it waited (the error names
//! its wait), so a loaded machine only makes the suite slower; every run has a generous
//! [`HANG`] guard.

use std::io::{BufRead, BufReader};
use std::net::TcpListener;
use std::process::{Command, Stdio};
use std::time::Duration;

use crate::support::bin;
use crate::support::cli::{Serve, generate, interrupt, spawnable};

/// A loopback port where nothing listens (bound, then released).
fn free_port() -> String {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
        .to_string()
}

/// How long a run may take before it counts as hung (killed, and the test fails): far
/// beyond any wait a test asks for.
const HANG: Duration = Duration::from_secs(180);

/// Runs `vrep-maze args`; returns the exit code and stderr.
fn run(args: &[&str]) -> (Option<i32>, String) {
    let out = bin().args(args).timeout(HANG).output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `command` (with its layout, if any) over `api` on `port`, then `extra`.
fn on<'a>(command: &[&'a str], api: &'a str, port: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    [command, &["--api", api, "--port", port], extra].concat()
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
    let mut child = spawnable()
        .args(on(
            &["apply", &m],
            "legacy",
            &port,
            &["--connect-timeout", "60"],
        ))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    // said while it still tries (for 60 s): before the wait, not after it
    let trying = child.try_wait().unwrap().is_none();
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(
        line.trim_end(),
        format!("connecting to CoppeliaSim's legacy remote API at 127.0.0.1:{port} ...")
    );
    assert!(trying, "the line came after the wait ended");
}

#[test]
fn nothing_listening_is_one_error_line_with_hints_within_the_connect_timeout() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    let port = free_port();
    let (code, stderr) = run(&on(
        &["apply", &m],
        "legacy",
        &port,
        &["--connect-timeout", "1"],
    ));
    assert_eq!(code, Some(1), "{stderr}");
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
    let (code, stderr) = run(&on(
        &["clear"],
        "legacy",
        &port,
        &["--connect-timeout", "0.5"],
    ));
    assert_eq!(code, Some(1), "{stderr}");
    assert_clear_error(&stderr);
    let (code, stderr) = run(&on(&["clear"], "zmq", &port, &[]));
    assert_eq!(code, Some(1), "{stderr}");
    assert_clear_error(&stderr);
    assert!(
        stderr.starts_with(&format!(
            "connecting to CoppeliaSim's ZeroMQ remote API at 127.0.0.1:{port} ...\n"
        )),
        "{stderr}"
    );
}

#[test]
fn score_connects_as_apply_does_with_the_same_hints() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    let port = free_port();
    let hints = |command: &str| {
        let args = ["--api", "legacy", "--port", &port, "--connect-timeout", "1"];
        let (code, stderr) = run(&[&[command, m.as_str()][..], &args].concat());
        assert_eq!(code, Some(1), "{stderr}");
        assert_clear_error(&stderr);
        stderr
            .lines()
            .filter(|line| line.starts_with("  hint: "))
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    let apply = hints("apply");
    assert!(
        apply
            .iter()
            .any(|h| h.contains("is CoppeliaSim running with the legacy remote API")),
        "{apply:?}"
    );
    assert_eq!(hints("score"), apply);
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
    let (code, stderr) = run(&on(&["apply", &m], "legacy", &port, &[]));
    assert_eq!(code, Some(1), "{stderr}");
    assert_clear_error(&stderr);
    assert!(
        stderr.contains(&format!(
            "error: port {port} speaks the ZeroMQ remote API, not the legacy one: use --api zmq"
        )),
        "{stderr}"
    );
    // the ZeroMQ server was not disturbed: it answers the next client at once
    bin()
        .args(on(
            &["apply", &m],
            "zmq",
            &port,
            &["--dry-run", "--timeout", "3"],
        ))
        .assert()
        .success();
}

#[test]
fn a_zeromq_client_on_a_legacy_port_is_told_to_use_api_legacy() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "4", "kruskal");
    let s = Serve::start(&["--listen", "127.0.0.1:0", "--idle-fps", "0"], 1);
    let port = s.port();
    let (code, stderr) = run(&on(&["apply", &m], "zmq", &port, &[]));
    assert_eq!(code, Some(1), "{stderr}");
    // no reply timeout (10 s) was waited for
    assert_clear_error(&stderr);
    assert!(
        stderr.contains(&format!(
            "error: port {port} speaks the legacy remote API, not the ZeroMQ one: use --api legacy"
        )),
        "{stderr}"
    );
    // the probe left the legacy server politely: the next client is served
    bin()
        .args(on(&["apply", &m], "legacy", &port, &["--dry-run"]))
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
    let (code, stderr) = run(&on(
        &["apply", &m],
        "legacy",
        &port,
        &["--dry-run", "--connect-timeout", "30"],
    ));
    assert_eq!(code, Some(0), "{stderr}");
    let mut lines = stderr.lines();
    assert_eq!(
        lines.next(),
        Some(
            format!("connecting to CoppeliaSim's legacy remote API at 127.0.0.1:{port} ...")
                .as_str()
        ),
    );
    // no countdown when stderr is not a terminal: at most the one notice of a refusal
    // that goes on (the server's 2 s may outlast the notice's)
    for line in lines {
        assert!(line.starts_with("nothing listens on "), "{stderr}");
    }
}

/// `vrep-maze args` with its session markers in `markers` (a directory of its own).
fn command_with_markers(markers: &std::path::Path, args: &[&str]) -> Command {
    let mut command = spawnable();
    command.env("XDG_RUNTIME_DIR", markers).args(args);
    command
}

/// The session marker of the legacy API at `127.0.0.1:port` in `markers`.
fn marker(markers: &std::path::Path, port: &str) -> std::path::PathBuf {
    markers.join(format!("vrep-maze-legacy-127.0.0.1-{port}.open"))
}

#[test]
fn with_no_simulator_the_wait_says_nothing_listens_and_ends_at_the_default() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    let port = free_port();
    let out = command_with_markers(dir.path(), &on(&["apply", &m], "legacy", &port, &[]))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "nothing listens on 127.0.0.1:{port} (Connection refused"
        )),
        "{stderr}"
    );
    assert!(stderr.contains("trying until 10 s"), "{stderr}");
    assert!(stderr.contains("within 10 s"), "{stderr}");
    assert!(!stderr.contains("earlier vrep-maze run"), "{stderr}");
    assert!(stderr.contains("--connect-timeout 75"), "{stderr}");
}

#[test]
fn an_abruptly_left_session_is_waited_out_and_ctrl_c_ends_the_wait_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    let port = free_port();
    // an earlier run (a process id no system runs) left its session open
    std::fs::write(marker(dir.path(), &port), "4194305\n").unwrap();
    let mut child = command_with_markers(dir.path(), &on(&["apply", &m], "legacy", &port, &[]))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut said = String::new();
    for _ in 0..2 {
        stderr.read_line(&mut said).unwrap();
    }
    assert!(
        said.contains(
            "an earlier vrep-maze run (process 4194305) ended with its session there open"
        ) && said.contains("waiting up to 75 s"),
        "{said}"
    );
    interrupt(child.id());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130), "{said}{rest}");
    assert!(
        rest.contains(&format!("interrupted while connecting to 127.0.0.1:{port}")),
        "{rest}"
    );
}

#[test]
fn a_clean_session_leaves_no_marker_and_a_killed_one_is_named_by_the_next_run() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "4", "prim");
    // serve's realistic model: paced by the idle rate, the one-minute refusal after a
    // client left abruptly
    let s = Serve::start(&["--listen", "127.0.0.1:0"], 1);
    let port = s.port();
    let out = command_with_markers(dir.path(), &on(&["apply", &m], "legacy", &port, &[]))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(!marker(dir.path(), &port).exists(), "closed cleanly");
    // a run killed while connected leaves its marker
    let big = dir.path().join("big.json");
    bin()
        .args(["generate", "--seed", "1", "--size", "40x40", "-o"])
        .arg(&big)
        .assert()
        .success();
    let mut child = command_with_markers(
        dir.path(),
        &on(&["apply", big.to_str().unwrap()], "legacy", &port, &[]),
    )
    .stdout(Stdio::null())
    .stderr(Stdio::null())
    .spawn()
    .unwrap();
    // looked at until it appears (the apply of a 40 x 40 takes far longer than connecting)
    let marked = (0..4000).any(|_| {
        std::thread::sleep(Duration::from_millis(25));
        marker(dir.path(), &port).exists()
    });
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(marked, "no marker while connected");
    let pid = std::fs::read_to_string(marker(dir.path(), &port)).unwrap();
    assert_eq!(pid.trim(), child.id().to_string());
    let out = command_with_markers(
        dir.path(),
        &on(
            &["clear"],
            "legacy",
            &port,
            &["--dry-run", "--connect-timeout", "1"],
        ),
    )
    .output()
    .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!(
            "127.0.0.1:{port} refuses (Connection refused (os error 111)); an earlier vrep-maze run (process {}) ended with its session there open",
            child.id()
        )),
        "{stderr}"
    );
}

/// A web server on a loopback port: it answers each connection with an HTTP 400, at once
/// when `eager`, else only once a request's header has ended (as most do).
fn web_server(eager: bool) -> String {
    use std::io::{Read, Write};
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port().to_string();
    std::thread::spawn(move || {
        for stream in listener.incoming().take(20) {
            let Ok(mut stream) = stream else { return };
            std::thread::spawn(move || {
                let mut got = Vec::new();
                let mut buf = [0u8; 512];
                while !eager && !got.windows(4).any(|w| w == b"\r\n\r\n") {
                    match stream.read(&mut buf) {
                        Ok(0) | Err(_) => return,
                        Ok(n) => got.extend_from_slice(&buf[..n]),
                    }
                }
                if eager {
                    let _ = stream.read(&mut buf);
                }
                let _ = stream.write_all(b"HTTP/1.1 400 Bad Request\r\n\r\n");
            });
        }
    });
    port
}

#[test]
fn a_web_server_on_the_legacy_port_is_named_as_not_coppeliasim() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "prim");
    for eager in [true, false] {
        let port = web_server(eager);
        let (code, stderr) = run(&on(
            &["apply", &m],
            "legacy",
            &port,
            &["--timeout", "1", "--connect-timeout", "3"],
        ));
        assert_eq!(code, Some(1), "{stderr}");
        assert_clear_error(&stderr);
        assert!(
            stderr.contains(&format!(
                "127.0.0.1:{port} is not a CoppeliaSim legacy remote API server: it answers in HTTP"
            )),
            "eager {eager}: {stderr}"
        );
        assert!(!stderr.contains("another client"), "{stderr}");
    }
}

#[test]
fn a_legacy_failure_hints_the_zeromq_port_it_found_with_its_port() {
    use crate::support::cli::default_ports;
    let s = Serve::start(&["--api", "zmq", "--port", "0", "--idle-fps", "0"], 1);
    let zmq = s.ports[0];
    let port = free_port();
    let out = bin()
        .envs(default_ports(crate::support::cli::free_port(), zmq))
        .args(["inspect", "--api", "legacy", "--port", &port])
        .args(["--connect-timeout", "1"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "hint: the ZeroMQ remote API answers on 127.0.0.1:{zmq}: try --api zmq --port {zmq}"
        )),
        "{stderr}"
    );
}

#[test]
fn auto_on_a_web_server_says_it_is_not_coppeliasim_without_the_refusal_hints() {
    let port = web_server(true);
    let (code, stderr) = run(&["inspect", "--port", &port, "--connect-timeout", "2"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("hint: something other than CoppeliaSim listens there: check --port"),
        "{stderr}"
    );
    assert!(!stderr.contains("refuses"), "{stderr}");
    assert!(!stderr.contains("is CoppeliaSim running"), "{stderr}");
}

#[test]
fn a_default_port_from_the_environment_that_is_not_a_port_is_a_usage_error() {
    let out = bin()
        .env("VREP_MAZE_LEGACY_PORT", "19997x")
        .args(["inspect", "--api", "legacy"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("VREP_MAZE_LEGACY_PORT=\"19997x\" is not a port"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn two_roles_on_one_name_are_conflicting_options_in_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "6", "prim");
    let port = free_port();
    for args in [
        vec!["clear", "--line", "Maze"],
        vec!["apply", m.as_str(), "--line", "Maze"],
        vec!["inspect", "--start", "Floor"],
        vec!["score", m.as_str(), "--end", "Start"],
    ] {
        let (code, stderr) = run(&[&args[..], &["--port", &port]].concat());
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains("one object cannot play two roles"),
            "{stderr}"
        );
        // refused before connecting
        assert!(!stderr.contains("connecting to"), "{stderr}");
    }
}
