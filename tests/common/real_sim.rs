//! A real, headless CoppeliaSim started by `../shared/coppeliasim/sim.sh` (folder named by
//! [`REAL_SIMS_VAR`]) on free loopback ports, in a folder of its own so that several run side
//! by side; stopped when dropped. Shared by the scenario tests and the benches
//! (`#[path]`-included: test infrastructure, not part of the library).

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable naming the folder of `sim.sh` and the simulator tarballs.
pub const REAL_SIMS_VAR: &str = "VREP_MAZE_REAL_SIMS";

/// The folder holding `sim.sh`, from [`REAL_SIMS_VAR`] (relative to the repository), if set.
pub fn real_sims_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(std::env::var_os(REAL_SIMS_VAR)?);
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
    Some(dir)
}

/// A free loopback port, and the one after it free too (4.5.1's ZeroMQ add-on also binds
/// its port + 1); never 19997 or 23000, where a user's CoppeliaSim lives.
pub fn free_port_pair() -> u16 {
    for _ in 0..200 {
        let a = TcpListener::bind("127.0.0.1:0").unwrap();
        let port = a.local_addr().unwrap().port();
        let usable = port < 65535 && ![19996, 19997, 22999, 23000].contains(&port);
        if usable && TcpListener::bind(("127.0.0.1", port + 1)).is_ok() {
            return port;
        }
    }
    panic!("no two consecutive free ports");
}

/// How many times [`RealSim::start_with`] tries `sim.sh start`.
const START_ATTEMPTS: usize = 3;

/// Held while `sim.sh start` runs: a first start installs libraries with apt-get, once.
static STARTING: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// A running real CoppeliaSim.
pub struct RealSim {
    script: PathBuf,
    /// `4.5.1` or `4.10.0`.
    pub version: &'static str,
    dir: tempfile::TempDir,
    /// Its legacy remote API port (4.5.1 only).
    pub legacy: Option<u16>,
    /// Its ZeroMQ remote API port.
    pub zmq: u16,
}

impl RealSim {
    /// Starts `version` with the course scene from the `sim.sh` in `sims`.
    pub fn start(sims: &Path, version: &'static str) -> RealSim {
        Self::start_with(sims, version, &[])
    }

    /// Starts `version` from the `sim.sh` in `sims` with more of its options: `--robot`
    /// (the course scene with the wheeled robot), `--display` (cameras render).
    ///
    /// A start that fails is tried again ([`START_ATTEMPTS`] in all), each time in a fresh
    /// folder on fresh ports: the private Xvfb of `--display` sometimes refuses the
    /// simulator's connection ("could not connect to display": CI, 2026-12-02), and a free
    /// port can be taken between choosing it and binding it. A retried start is reported on
    /// stderr; every attempt's output is in the failure.
    pub fn start_with(sims: &Path, version: &'static str, options: &[&str]) -> RealSim {
        let mut failures = Vec::new();
        for attempt in 1..=START_ATTEMPTS {
            match Self::try_start(sims, version, options) {
                Ok(real) => {
                    if let Some(first) = failures.first() {
                        eprintln!("sim.sh start {version} worked at attempt {attempt}: {first}");
                    }
                    return real;
                }
                Err(failure) => failures.push(failure),
            }
        }
        panic!(
            "sim.sh start {version} failed {START_ATTEMPTS} times:\n{}",
            failures.join("\n---\n")
        );
    }

    /// One `sim.sh start`: the simulator, or what its start printed and its logs.
    fn try_start(sims: &Path, version: &'static str, options: &[&str]) -> Result<RealSim, String> {
        let script = sims.join("sim.sh");
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
        cmd.args(options);
        let out = {
            let _one = STARTING.lock().unwrap_or_else(|e| e.into_inner());
            cmd.output().unwrap()
        };
        let real = RealSim {
            script,
            version,
            dir,
            legacy,
            zmq,
        };
        if out.status.success() {
            return Ok(real);
        }
        let xvfb = std::fs::read_to_string(real.dir.path().join(format!("{version}.xvfb.log")))
            .map(|log| format!("\nXvfb's log:\n{log}"))
            .unwrap_or_default();
        Err(format!(
            "{}{}\n{}{xvfb}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
            real.log_tail()
        ))
    }

    /// Its process id (`sim.sh` writes it beside the log), if readable.
    pub fn pid(&self) -> Option<u32> {
        let file = self.dir.path().join(format!("{}.pid", self.version));
        std::fs::read_to_string(file).ok()?.trim().parse().ok()
    }

    /// Whether its process still runs, and the last lines of its log, for a failure message.
    pub fn log_tail(&self) -> String {
        let process = match self.pid() {
            Some(pid) if Path::new(&format!("/proc/{pid}")).exists() => {
                format!("CoppeliaSim {} (pid {pid}) still runs", self.version)
            }
            Some(pid) => format!("CoppeliaSim {} (pid {pid}) has exited", self.version),
            None => format!("CoppeliaSim {} has no process id on record", self.version),
        };
        let log = std::fs::read_to_string(self.dir.path().join(format!("{}.log", self.version)))
            .unwrap_or_default();
        let lines: Vec<&str> = log.lines().collect();
        format!(
            "{process}; its log ends:\n{}",
            lines[lines.len().saturating_sub(30)..].join("\n")
        )
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
