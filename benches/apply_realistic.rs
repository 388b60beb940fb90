//! Benchmark: `apply` against the emulator's realistic model of CoppeliaSim 4.5.1
//! (`Timing::realistic()`: one ZeroMQ request per main-loop pass, per-call and per-object
//! server costs, legacy per-line costs growing with the scene; every figure cites
//! `../shared/spec/real-coppeliasim-4.5.1.md`), beside the targets of the "draw like the real
//! CoppeliaSim needs" issue and what the previous client measured on a real 4.5.1. The
//! user's idle rate is CoppeliaSim's default, 8 fps, in every case.
//!
//!     cargo bench --bench apply_realistic              # the cases
//!     cargo bench --bench apply_realistic -- --200     # also legacy 200x200 (many minutes)
//!
//! "x target" is target / time: above 1 the target is met.

use std::time::{Duration, Instant};

use vrep_maze::coppelia::DEFAULT_IDLE_FPS;
use vrep_maze::draw::{self, ApplyOptions, Backend, Drawing};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator, Timing};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, ZmqBackend};

fn drawing(n: u64, seed: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, seed);
    Drawing::try_from(&build_layout(&spec).unwrap()).unwrap()
}

/// What one apply cost.
struct Cost {
    wall: Duration,
    requests: usize,
    lines: usize,
}

/// The emulated server of one API, realistic, at the default idle rate.
enum Server {
    Legacy(legacy::ServerHandle),
    Zmq(zmq_api::ServerHandle),
}

impl Server {
    fn start(zmq: bool) -> Server {
        let sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        if zmq {
            let cfg = zmq_api::ServerConfig {
                listen: "127.0.0.1:0".parse().unwrap(),
                protocol: Protocol::V1,
                timing: Timing::realistic(),
                ..Default::default()
            };
            Server::Zmq(zmq_api::spawn(cfg, sim).unwrap())
        } else {
            let cfg = legacy::ServerConfig {
                listen: "127.0.0.1:0".parse().unwrap(),
                timing: Timing::realistic(),
                ..Default::default()
            };
            Server::Legacy(legacy::spawn(cfg, sim).unwrap())
        }
    }

    fn connect(&self) -> Box<dyn Backend> {
        let timeout = Duration::from_secs(60);
        match self {
            Server::Legacy(s) => Box::new(
                LegacyBackend::connect("127.0.0.1", s.local_addr().port(), timeout).unwrap(),
            ),
            Server::Zmq(s) => Box::new(
                ZmqBackend::connect(&ClientOptions {
                    port: s.local_addr().port(),
                    timeout,
                    ..Default::default()
                })
                .unwrap(),
            ),
        }
    }

    fn apply(&self, d: &Drawing) -> Cost {
        let mut b = self.connect();
        let t = Instant::now();
        let r = draw::apply(b.as_mut(), d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        let wall = t.elapsed();
        b.close().unwrap();
        Cost {
            wall,
            requests: r.round_trips,
            lines: d.lines.len(),
        }
    }

    fn shutdown(self) {
        match self {
            Server::Legacy(s) => drop(s.shutdown()),
            Server::Zmq(s) => s.shutdown(),
        }
    }
}

fn row(case: &str, cost: &Cost, target: Option<f64>, before: &str) {
    let secs = cost.wall.as_secs_f64();
    let (target, ratio) = match target {
        Some(t) => (format!("<= {t} s"), format!("{:.2}x", t / secs)),
        None => ("completes".into(), "-".into()),
    };
    println!(
        "{case:<34} {:>7} {:>9} {:>9.2} | {target:>10} {ratio:>8} | {before}",
        cost.lines, cost.requests, secs
    );
}

fn main() {
    let with_200 = std::env::args().any(|a| a == "--200");
    println!(
        "{:<34} {:>7} {:>9} {:>9} | {:>10} {:>8} | real 4.5.1, previous client",
        "case (user idle fps 8)", "lines", "requests", "time s", "target", "x target"
    );
    for (n, target, before) in [
        (9u64, None, "0.35 s, 7 round trips"),
        (30, None, "1.54 s, 6 round trips"),
        (60, None, "11.1 s, 6 round trips"),
        (100, Some(45.0), "fails: no reply within 60 s"),
    ] {
        let s = Server::start(false);
        row(
            &format!("legacy first draw {n}x{n}"),
            &s.apply(&drawing(n, 42)),
            target,
            before,
        );
        s.shutdown();
    }
    if with_200 {
        let s = Server::start(false);
        row(
            "legacy first draw 200x200",
            &s.apply(&drawing(200, 42)),
            None,
            "-",
        );
        s.shutdown();
    }
    let s = Server::start(true);
    row(
        "zmq first draw 30x30",
        &s.apply(&drawing(30, 42)),
        Some(2.5),
        "7.2 s, 5,468 calls",
    );
    row(
        "zmq replace 30x30 -> 9x9",
        &s.apply(&drawing(9, 42)),
        Some(1.5),
        "228 s, 2,155 calls",
    );
    s.shutdown();
    let s = Server::start(true);
    row(
        "zmq first draw 100x100",
        &s.apply(&drawing(100, 42)),
        Some(25.0),
        "-",
    );
    s.shutdown();
}
