//! The `vrep-maze` binary: commands under test and a `serve` child process.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};

use assert_cmd::cargo::CommandCargoExt;

/// A loopback port where nothing listens (bound, then released).
pub fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// The environment that moves the binary's default ports (19997, 23000) to `legacy` and
/// `zmq`.
pub fn default_ports(legacy: u16, zmq: u16) -> [(&'static str, String); 2] {
    [
        ("VREP_MAZE_LEGACY_PORT", legacy.to_string()),
        ("VREP_MAZE_ZMQ_PORT", zmq.to_string()),
    ]
}

/// The environment that moves the default ports where nothing listens: a command without
/// `--port` never reaches a CoppeliaSim the suite did not start.
pub fn away_from_defaults() -> [(&'static str, String); 2] {
    default_ports(free_port(), free_port())
}

/// The `vrep-maze` binary under test, away from the default ports.
pub fn bin() -> assert_cmd::Command {
    let mut command = assert_cmd::Command::cargo_bin("vrep-maze").expect("binary built");
    command.envs(away_from_defaults());
    command
}

/// The `vrep-maze` binary as a [`Command`] to spawn, away from the default ports.
pub fn spawnable() -> Command {
    let mut command = Command::cargo_bin("vrep-maze").expect("binary built");
    command.envs(away_from_defaults());
    command
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
        let mut child = spawnable()
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
