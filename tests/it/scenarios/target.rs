//! What a scenario runs against: `vrep-maze serve` (always) or a real, headless CoppeliaSim
//! started from `../shared/coppeliasim/` (only when asked: see [`real_sims_dir`]), each on free
//! ports of its own, never on 19997 or 23000.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::support::cli::Serve;

/// The environment variable naming the folder of `sim.sh` and the simulator tarballs.
pub const REAL_SIMS_VAR: &str = "VREP_MAZE_REAL_SIMS";

/// A simulator and the API a scenario draws through.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// `serve --api both --protocol 1` (one scene, as 4.5.1 has), drawn over legacy.
    ServeLegacy,
    /// The same emulated 4.5.1, drawn over ZeroMQ protocol 1.
    ServeZmq1,
    /// `serve --api zmq --protocol 2` (as 4.10 has), drawn over ZeroMQ.
    ServeZmq2,
    /// Real CoppeliaSim 4.5.1, drawn over the legacy remote API.
    Real451Legacy,
    /// Real CoppeliaSim 4.5.1, drawn over ZeroMQ protocol 1.
    Real451Zmq,
    /// Real CoppeliaSim 4.10.0, drawn over ZeroMQ protocol 2.
    Real410Zmq,
}

impl Target {
    /// Whether the scenario draws over the legacy remote API.
    pub fn legacy(self) -> bool {
        matches!(self, Target::ServeLegacy | Target::Real451Legacy)
    }

    /// Starts the simulator with the course scene (`Floor`, `Maze`, `Line`, `Start`, `End`).
    pub fn start(self) -> Sim {
        match self {
            Target::ServeLegacy | Target::ServeZmq1 => {
                let serve = Serve::start(
                    &[
                        "--api",
                        "both",
                        "--protocol",
                        "1",
                        "--listen",
                        "127.0.0.1:0",
                        "--zmq-listen",
                        "127.0.0.1:0",
                    ],
                    2,
                );
                let (legacy, zmq) = (serve.ports[0], serve.ports[1]);
                Sim {
                    target: self,
                    legacy: Some(legacy),
                    zmq,
                    running: Running::Serve { _process: serve },
                }
            }
            Target::ServeZmq2 => {
                let serve = Serve::start(
                    &["--api", "zmq", "--protocol", "2", "--listen", "127.0.0.1:0"],
                    1,
                );
                let zmq = serve.ports[0];
                Sim {
                    target: self,
                    legacy: None,
                    zmq,
                    running: Running::Serve { _process: serve },
                }
            }
            Target::Real451Legacy | Target::Real451Zmq => RealSim::start(self, "4.5.1"),
            Target::Real410Zmq => RealSim::start(self, "4.10.0"),
        }
    }
}

/// The folder holding `sim.sh`, from [`REAL_SIMS_VAR`]; a real-simulator test run without it
/// fails with what to set (it is never skipped quietly).
pub fn real_sims_dir() -> PathBuf {
    let dir = std::env::var_os(REAL_SIMS_VAR).unwrap_or_else(|| {
        panic!(
            "the real-simulator scenarios need {REAL_SIMS_VAR}=<folder of sim.sh>, e.g. \
             {REAL_SIMS_VAR}=../shared/coppeliasim cargo test --test it on_real -- --ignored"
        )
    });
    let dir = PathBuf::from(dir);
    let dir = if dir.is_relative() {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(dir)
    } else {
        dir
    };
    assert!(
        dir.join("sim.sh").is_file(),
        "{REAL_SIMS_VAR}={} holds no sim.sh",
        dir.display()
    );
    dir
}

/// A free loopback port, and the one after it free too (4.5.1's ZeroMQ add-on also binds
/// its port + 1).
fn free_port_pair() -> u16 {
    for _ in 0..200 {
        let a = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = a.local_addr().unwrap().port();
        if port < 65535
            && port != 19997
            && port != 23000
            && TcpListener::bind(("127.0.0.1", port + 1)).is_ok()
        {
            return port;
        }
    }
    panic!("no two consecutive free ports");
}

/// What keeps the simulator running (each stops it when dropped).
enum Running {
    Serve { _process: Serve },
    Real(RealSim),
}

/// A running simulator: its ports and the API a scenario draws through.
pub struct Sim {
    /// What runs.
    pub target: Target,
    /// The legacy remote API's port, where there is one.
    pub legacy: Option<u16>,
    /// The ZeroMQ remote API's port (the observer reads the scene there, whatever API draws).
    pub zmq: u16,
    running: Running,
}

impl Sim {
    /// `--api ... --port ...` of the API the scenario draws through.
    pub fn api_args(&self) -> Vec<String> {
        if self.target.legacy() {
            let port = self.legacy.expect("a legacy target has a legacy port");
            vec![
                "--api".into(),
                "legacy".into(),
                "--port".into(),
                port.to_string(),
            ]
        } else {
            vec![
                "--api".into(),
                "zmq".into(),
                "--port".into(),
                self.zmq.to_string(),
            ]
        }
    }

    /// `--api zmq --port ...`: what a scenario uses to create objects legacy cannot.
    pub fn zmq_args(&self) -> Vec<String> {
        vec![
            "--api".into(),
            "zmq".into(),
            "--port".into(),
            self.zmq.to_string(),
        ]
    }

    /// The simulator's log so far (real ones), for a failure message.
    pub fn log_tail(&self) -> String {
        match &self.running {
            Running::Serve { .. } => String::new(),
            Running::Real(r) => r.log_tail(),
        }
    }
}

/// Held while `sim.sh start` runs.
static STARTING: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// A real CoppeliaSim started by `sim.sh` in a folder of its own (so tests run side by side
/// without sharing its process file), stopped when dropped.
struct RealSim {
    script: PathBuf,
    version: &'static str,
    dir: tempfile::TempDir,
}

impl RealSim {
    fn start(target: Target, version: &'static str) -> Sim {
        let script = real_sims_dir().join("sim.sh");
        let dir = tempfile::Builder::new()
            .prefix("vrep-maze-real-")
            .tempdir()
            .unwrap();
        let zmq = free_port_pair();
        let legacy = (version == "4.5.1").then(|| {
            let l = TcpListener::bind("127.0.0.1:0").unwrap();
            l.local_addr().unwrap().port()
        });
        let mut cmd = Command::new("bash");
        cmd.arg(&script)
            .args(["start", version, "--zmq-port", &zmq.to_string()])
            .env("COPPELIASIM_DIR", dir.path());
        if let Some(l) = legacy {
            cmd.args(["--legacy-port", &l.to_string()]);
        }
        // one start at a time: a first start installs libraries with apt-get, which runs once
        let out = {
            let _one = STARTING.lock().unwrap_or_else(|e| e.into_inner());
            cmd.output().unwrap()
        };
        let real = RealSim {
            script,
            version,
            dir,
        };
        assert!(
            out.status.success(),
            "sim.sh start {version}: {}{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
            real.log_tail()
        );
        Sim {
            target,
            legacy,
            zmq,
            running: Running::Real(real),
        }
    }

    fn log_tail(&self) -> String {
        let log = std::fs::read_to_string(self.dir.path().join(format!("{}.log", self.version)))
            .unwrap_or_default();
        let lines: Vec<&str> = log.lines().collect();
        lines[lines.len().saturating_sub(30)..].join("\n")
    }
}

impl Drop for RealSim {
    fn drop(&mut self) {
        let _ = Command::new("bash")
            .arg(&self.script)
            .args(["stop", self.version])
            .env("COPPELIASIM_DIR", self.dir.path())
            .output();
    }
}
