//! What a scenario runs against: `vrep-maze serve` (always) or a real, headless CoppeliaSim
//! started from `../shared/coppeliasim/` (only when asked: see [`real_sims_dir`]), each on free
//! ports of its own, never on 19997 or 23000.

use crate::support::real_sim::{self, REAL_SIMS_VAR, RealSim};

use crate::support::cli::Serve;

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
    /// Whether this is a real CoppeliaSim (not `serve`).
    pub fn real(self) -> bool {
        matches!(
            self,
            Target::Real451Legacy | Target::Real451Zmq | Target::Real410Zmq
        )
    }

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
            Target::Real451Legacy | Target::Real451Zmq => Sim::real(self, "4.5.1"),
            Target::Real410Zmq => Sim::real(self, "4.10.0"),
        }
    }
}

/// The folder holding `sim.sh`; a real-simulator test run without [`REAL_SIMS_VAR`] fails
/// with what to set (it is never skipped quietly).
fn real_sims_dir() -> std::path::PathBuf {
    real_sim::real_sims_dir().unwrap_or_else(|| {
        panic!(
            "the real-simulator scenarios need {REAL_SIMS_VAR}=<folder of sim.sh>, e.g. \
             {REAL_SIMS_VAR}=../shared/coppeliasim cargo test --test it on_real -- --ignored"
        )
    })
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
    fn real(target: Target, version: &'static str) -> Sim {
        let real = RealSim::start(&real_sims_dir(), version);
        Sim {
            target,
            legacy: real.legacy,
            zmq: real.zmq,
            running: Running::Real(real),
        }
    }

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
