//! Ctrl-C during `apply`, against `vrep-maze serve` with its realistic model on (paced by
//! the idle rate, per-line server costs, and the one-minute refusal after a client leaves
//! abruptly): wherever the signal lands, apply stops cleanly (exit 130, idle rate restored,
//! connection closed as the official client closes it), and the next apply connects at once
//! and repairs the scene.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use assert_cmd::cargo::CommandCargoExt;
use tempfile::TempDir;

use crate::support::bin;
use crate::support::cli::Serve;

fn interrupt(pid: u32) {
    let status = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

#[test]
fn ctrl_c_at_any_point_leaves_a_scene_the_next_apply_repairs_at_once() {
    let dir = TempDir::new().unwrap();
    let layout = dir.path().join("m.json");
    bin()
        .args(["generate", "--seed", "5", "--size", "24x24", "-o"])
        .arg(&layout)
        .assert()
        .success();
    // the realistic model is serve's default: idle fps 8 and the one-minute refusal
    let serve = Serve::start(&["--listen", "127.0.0.1:0"], 1);
    let port = serve.port();
    let mut interrupted = 0;
    for delay_ms in [150u64, 400, 700, 1000, 1400] {
        let apply = Command::cargo_bin("vrep-maze")
            .unwrap()
            .args(["apply", layout.to_str().unwrap(), "--port", &port])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
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
