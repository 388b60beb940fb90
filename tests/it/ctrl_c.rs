//! Ctrl-C during `apply`, against `vrep-maze serve` with its realistic model on (paced by
//! the idle rate, per-line server costs, and the one-minute TIME_WAIT after a session the
//! server closed first): wherever the signal lands, apply stops cleanly (exit 130, idle rate restored,
//! connection closed as the official client closes it), and the next apply connects at once
//! and repairs the scene.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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
    for delay_ms in [150u64, 400, 700, 1000, 1400] {
        let apply = apply_command(&layout, &port).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        interrupt(apply.id());
        let out = apply.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        match out.status.code() {
            Some(130) => {
                interrupted += 1;
                assert!(stderr.contains("interrupted"), "{delay_ms} ms: {stderr}");
            }
            Some(0) => {}
            other => panic!("{delay_ms} ms: exit {other:?}: {stderr}"),
        }
        // no refusal to wait out: a short wait is enough, and the repair verifies
        let started = Instant::now();
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
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "{delay_ms} ms: the next apply waited {:?}",
            started.elapsed()
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
    for delay_ms in [100u64, 300, 600, 900, 1200, 1600] {
        let apply = apply_command(&layout, &port)
            .args(&apply_args)
            .env("XDG_RUNTIME_DIR", dir.path())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        interrupt(apply.id());
        let out = apply.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        match out.status.code() {
            Some(130) => interrupted += 1,
            Some(0) => {}
            // on a loaded machine the signal can land before apply has read its layout and
            // installed its handler: the default action ends it, before anything changed
            None if std::os::unix::process::ExitStatusExt::signal(&out.status) == Some(2) => {}
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
    let apply = apply_command(&layout, &port)
        .args(["--timeout", "2"])
        .args(&apply_args)
        .env("XDG_RUNTIME_DIR", dir.path())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(800));
    serve.child.kill().unwrap();
    serve.child.wait().unwrap();
    let out = apply.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        return; // it finished before the kill: nothing to see on this machine
    }
    assert_eq!(out.status.code(), Some(1), "{}: {stderr}", kind.name());
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
