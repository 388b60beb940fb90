//! Ctrl-C during `apply`, against `vrep-maze serve` with its realistic model on (paced by
//! the idle rate, per-line server costs, and the one-minute TIME_WAIT after a session the
//! server closed first): wherever the signal lands, apply stops cleanly (exit 130, idle rate restored,
//! connection closed as the official client closes it), and the next apply connects at once
//! and repairs the scene.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStderr, Command, ExitStatus, Stdio};
use std::time::Duration;

use tempfile::TempDir;

use crate::support::backend::{Kind, TIMEOUT};
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::{Serve, interrupt};

/// A layout of `size` cells (`24x24`) from `seed`, written into `dir`.
fn layout(dir: &TempDir, seed: &str, size: &str) -> PathBuf {
    let layout = dir.path().join("m.json");
    bin()
        .args(["generate", "--seed", seed, "--size", size, "-o"])
        .arg(&layout)
        .assert()
        .success();
    layout
}

/// A spawned command whose standard error is read as it comes, so a test acts on what the
/// program has done (a line it printed), not on how long it has run.
struct Running {
    child: Child,
    stderr: BufReader<ChildStderr>,
    said: String,
}

impl Running {
    /// Spawns `command` (its standard error piped).
    fn spawn(mut command: Command) -> Running {
        let mut child = command.stderr(Stdio::piped()).spawn().unwrap();
        let stderr = BufReader::new(child.stderr.take().unwrap());
        Running {
            child,
            stderr,
            said: String::new(),
        }
    }

    /// Reads standard error until a line contains `text`; false if it ended first.
    fn wait_for(&mut self, text: &str) -> bool {
        loop {
            let mut line = String::new();
            if self.stderr.read_line(&mut line).unwrap() == 0 {
                return false;
            }
            self.said.push_str(&line);
            if line.contains(text) {
                return true;
            }
        }
    }

    /// Sends it Ctrl-C.
    fn interrupt(&self) {
        interrupt(self.child.id());
    }

    /// Waits for its end: how it ended and all it printed on standard error.
    fn finish(mut self) -> (ExitStatus, String) {
        self.stderr.read_to_string(&mut self.said).unwrap();
        (self.child.wait().unwrap(), self.said)
    }
}

/// What every connecting command says once its Ctrl-C handler is installed, before it
/// connects: the line to wait for before interrupting it.
const CONNECTING: &str = "connecting to CoppeliaSim's";

/// `vrep-maze apply layout --port port`, its standard error piped, ready to spawn.
fn apply_command(layout: &Path, port: &str) -> Command {
    let mut command = crate::support::cli::spawnable();
    command
        .args(["apply", layout.to_str().unwrap(), "--port", port])
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    command
}

#[test]
fn ctrl_c_at_any_point_leaves_a_scene_the_next_apply_repairs_at_once() {
    let dir = TempDir::new().unwrap();
    let layout = layout(&dir, "5", "24x24");
    // the realistic model is serve's default: idle fps 8 and the one-minute TIME_WAIT
    let scene = crate::support::layouts::big_course_file(dir.path());
    let serve = Serve::start(&["--listen", "127.0.0.1:0", "--scene", &scene], 1);
    let port = serve.port();
    let mut interrupted = 0;
    // the delays sample where the signal lands, counted from the line apply prints as it
    // starts to connect (its handler is installed by then)
    for delay_ms in [0u64, 150, 400, 700, 1000, 1400] {
        let mut apply = Running::spawn(apply_command(&layout, &port));
        assert!(apply.wait_for(CONNECTING), "{delay_ms} ms: {}", apply.said);
        std::thread::sleep(Duration::from_millis(delay_ms));
        apply.interrupt();
        let (status, stderr) = apply.finish();
        match status.code() {
            Some(130) => {
                interrupted += 1;
                assert!(stderr.contains("interrupted"), "{delay_ms} ms: {stderr}");
            }
            Some(0) => {}
            other => panic!("{delay_ms} ms: exit {other:?}: {stderr}"),
        }
        // no refusal to wait out (the wait that says "refuses"), and the repair verifies
        let again = bin()
            .args([
                "apply",
                layout.to_str().unwrap(),
                "--port",
                &port,
                "--timeout",
                "5",
            ])
            .output()
            .unwrap();
        assert!(
            again.status.success(),
            "{delay_ms} ms: the next apply failed: {}",
            String::from_utf8_lossy(&again.stderr)
        );
        assert!(
            String::from_utf8_lossy(&again.stdout).contains("verified"),
            "{delay_ms} ms"
        );
        let waited = String::from_utf8_lossy(&again.stderr);
        assert!(
            !waited.contains("refuses"),
            "{delay_ms} ms: the next apply was refused: {waited}"
        );
        // start over from an empty maze, so the next interrupt lands in a first draw
        bin()
            .args(["clear", "--port", &port, "--timeout", "5"])
            .assert()
            .success();
    }
    assert!(interrupted >= 2, "only {interrupted} runs were interrupted");
}

/// `serve` arguments and `apply` arguments for `kind`.
fn serve_and_apply_args(kind: Kind) -> (Vec<&'static str>, Vec<&'static str>) {
    match kind {
        Kind::Legacy => (vec!["--listen", "127.0.0.1:0"], vec![]),
        Kind::Zmq1 => (
            vec!["--api", "zmq", "--protocol", "1", "--listen", "127.0.0.1:0"],
            vec!["--api", "zmq"],
        ),
        Kind::Zmq2 => (
            vec!["--api", "zmq", "--protocol", "2", "--listen", "127.0.0.1:0"],
            vec!["--api", "zmq"],
        ),
    }
}

backend_tests!(
    ctrl_c_always_exits_130_with_the_idle_rate_restored,
    a_server_killed_mid_apply_is_named_as_gone,
);

/// Wherever Ctrl-C lands in an apply (paced by serve's realistic idle rate, 8 fps), the run
/// ends with exit 130 (or 0 if it had finished), never with an error: a signal that
/// interrupts a wait for a reply is not a failure. The user's idle rate is back after it.
fn ctrl_c_always_exits_130_with_the_idle_rate_restored(kind: Kind) {
    let dir = TempDir::new().unwrap();
    let layout = layout(&dir, "2", "30x30");
    let (serve_args, apply_args) = serve_and_apply_args(kind);
    let scene = crate::support::layouts::big_course_file(dir.path());
    let serve_args = [serve_args, vec!["--scene", &scene]].concat();
    let serve = Serve::start(&serve_args, 1);
    let port = serve.port();
    let mut interrupted = 0;
    // from the line apply prints as it starts to connect (its handler installed): the
    // first signals land in the connection (the ZeroMQ greeting, the first calls)
    for delay_ms in [0u64, 20, 100, 300, 600, 900, 1200, 1600] {
        let mut command = apply_command(&layout, &port);
        command.args(&apply_args).env("XDG_RUNTIME_DIR", dir.path());
        let mut apply = Running::spawn(command);
        assert!(
            apply.wait_for(CONNECTING),
            "{}, {delay_ms} ms: {}",
            kind.name(),
            apply.said
        );
        std::thread::sleep(Duration::from_millis(delay_ms));
        apply.interrupt();
        let (status, stderr) = apply.finish();
        match status.code() {
            Some(130) => {
                interrupted += 1;
                assert!(stderr.contains("interrupted"), "{delay_ms} ms: {stderr}");
            }
            Some(0) => {}
            other => panic!("{}, {delay_ms} ms: exit {other:?}: {stderr}", kind.name()),
        }
        let mut scene = kind.connect(serve.ports[0], TIMEOUT).unwrap();
        let rates = scene.idle_rates().unwrap();
        assert_eq!(
            (rates.current, rates.saved),
            (8, None),
            "{}, {delay_ms} ms: {stderr}",
            kind.name()
        );
        scene.close().unwrap();
        drop(scene);
        bin()
            .args(["clear", "--port", &port, "--timeout", "5"])
            .args(&apply_args)
            .env("XDG_RUNTIME_DIR", dir.path())
            .assert()
            .success();
    }
    assert!(
        interrupted >= 2,
        "{}: only {interrupted} runs were interrupted",
        kind.name()
    );
}

/// A simulator killed while apply waits for a reply: apply fails with one line that says
/// the simulator is gone (after one `--timeout`, not one per call still to make).
fn a_server_killed_mid_apply_is_named_as_gone(kind: Kind) {
    let dir = TempDir::new().unwrap();
    let layout = layout(&dir, "3", "40x40");
    let (serve_args, apply_args) = serve_and_apply_args(kind);
    let scene = crate::support::layouts::big_course_file(dir.path());
    let serve_args = [serve_args, vec!["--scene", &scene]].concat();
    let mut serve = Serve::start(&serve_args, 1);
    let port = serve.port();
    let mut command = apply_command(&layout, &port);
    command
        .args(["--timeout", "2"])
        .args(&apply_args)
        .env("XDG_RUNTIME_DIR", dir.path())
        .env("VREP_MAZE_TRACE", "1");
    let mut apply = Running::spawn(command);
    // the kill lands once apply is connected and drawing: after its first answered call
    assert!(
        apply.wait_for("answered"),
        "{}: {}",
        kind.name(),
        apply.said
    );
    serve.child.kill().unwrap();
    serve.child.wait().unwrap();
    let (status, stderr) = apply.finish();
    if status.success() {
        return; // it finished before the kill: nothing to see on this machine
    }
    assert_eq!(status.code(), Some(1), "{}: {stderr}", kind.name());
    let errors: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("error: "))
        .collect();
    assert_eq!(errors.len(), 1, "{}: {stderr}", kind.name());
    let gone = match kind {
        Kind::Legacy => "closed the connection",
        Kind::Zmq1 | Kind::Zmq2 => "nothing listens there any more",
    };
    assert!(errors[0].contains(gone), "{}: {stderr}", kind.name());
}

/// Ctrl-C while apply waits for a ZeroMQ server's first reply (a peer that greets as
/// ZeroMQ, takes the request and never answers): the wait ends at once as an interruption
/// (exit 130), not as a timeout or a verdict on the port. The signal is sent once the peer
/// holds the request, so the test waits on what apply has done, not on a delay; the long
/// `--timeout` is only there so that a regression shows as exit 1 rather than a pass.
#[test]
fn ctrl_c_while_connecting_over_zmq_ends_as_an_interruption() {
    let dir = TempDir::new().unwrap();
    let layout = layout(&dir, "1", "5x5");
    let context = zmq::Context::new();
    let peer = context.socket(zmq::ROUTER).unwrap();
    peer.set_rcvtimeo(120_000).unwrap();
    peer.bind("tcp://127.0.0.1:0").unwrap();
    let endpoint = peer.get_last_endpoint().unwrap().unwrap();
    let port = endpoint.rsplit(':').next().unwrap().to_string();
    let mut command = apply_command(&layout, &port);
    command.args(["--api", "zmq", "--timeout", "120"]);
    let apply = Running::spawn(command);
    // apply's first request (`zmqRemoteApi.require`): it has greeted and waits
    let request = peer.recv_multipart(0).unwrap();
    assert!(!request.is_empty());
    apply.interrupt();
    let (status, stderr) = apply.finish();
    assert_eq!(status.code(), Some(130), "{stderr}");
    assert!(
        stderr.contains(&format!(
            "interrupted while connecting to 127.0.0.1:{port}: nothing was changed"
        )),
        "{stderr}"
    );
    assert!(!stderr.contains("error:"), "{stderr}");
}
