//! The `vrep-maze` binary: commands under test and a `serve` child process.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};

use assert_cmd::cargo::CommandCargoExt;

/// Held by a test that uses the default ports (19997, 23000), so no two of them meet there.
pub static DEFAULT_PORTS: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The `vrep-maze` binary under test.
pub fn bin() -> assert_cmd::Command {
    assert_cmd::Command::cargo_bin("vrep-maze").expect("binary built")
}

/// Writes `generate --seed seed --algo algo` into `dir`; returns the file's path.
pub fn generate(dir: &Path, seed: &str, algo: &str) -> String {
    let path = dir
        .join(format!("{algo}-{seed}.json"))
        .display()
        .to_string();
    bin()
        .args(["generate", "--seed", seed, "--algo", algo, "-o", &path])
        .assert()
        .success();
    path
}

/// Sends SIGINT (Ctrl-C) to the process `pid`.
pub fn interrupt(pid: u32) {
    let status = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(status.success());
}

/// A `vrep-maze serve` child process, killed when dropped.
pub struct Serve {
    /// The process.
    pub child: Child,
    /// The ports it printed, one line per API (legacy first with `--api both`).
    pub ports: Vec<u16>,
}

impl Serve {
    /// Starts `vrep-maze serve args` and reads the `lines` lines that name its addresses.
    pub fn start(args: &[&str], lines: usize) -> Serve {
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
        Serve { child, ports }
    }

    /// The first port, as an argument.
    pub fn port(&self) -> String {
        self.ports[0].to_string()
    }
}

impl Drop for Serve {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
