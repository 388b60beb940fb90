//! Benchmark: `apply` against the emulator's realistic model of CoppeliaSim 4.5.1
//! (`Timing::realistic()`: one ZeroMQ request per main-loop pass, pasting, re-parenting and
//! removing growing with the objects in the scene; every figure cites
//! `../shared/spec/real-coppeliasim-4.5.1.md`), for every row of issue 18's table, beside
//! what a real CoppeliaSim 4.5.1 took for the same step (spec "Costs that grow with the
//! scene"). The user's idle rate is CoppeliaSim's default, 8 fps. Each row's earlier mazes
//! are drawn on an instant emulator first (not timed); only its own step sleeps.
//!
//!     cargo bench --bench apply_realistic                 # issue 18's rows (about 5 minutes)
//!     cargo bench --bench apply_realistic -- --first-draws  # also the first draws of issue 11
//!
//! "emulated" is the wall time against the realistic emulator; "ledger" the same step priced
//! from the emulator's ledger of the simulator's work (`vrep_maze::sim::cost::price_all`,
//! what the unit tests check); "x real" is emulated / real. Each row takes a draw mode
//! ([`Mode`]), so other modes are rows of the same table.

use std::time::{Duration, Instant};

use vrep_maze::coppelia::DEFAULT_IDLE_FPS;
use vrep_maze::draw::{self, ApplyOptions, Backend, Drawing};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::maze::Grid;
use vrep_maze::sim::cost::price_all;
use vrep_maze::sim::{Clock, CostModel, Scene, Simulator, Timing};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, ZmqBackend};

/// The `n` x `n` course maze of the spec's runs (Prim, seed 42: 160, 1,798, 7,198 and 19,998
/// lines for 9, 30, 60, 100).
fn drawing(n: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, 42);
    Drawing::try_from(&build_layout(&spec).unwrap()).unwrap()
}

/// How a maze is drawn.
#[derive(Debug, Clone, Copy)]
enum Mode {
    /// One copy of the template per line (`--draw copies`, the default).
    Copies,
}

impl Mode {
    /// Every mode, each a row of the table.
    const ALL: [Mode; 1] = [Mode::Copies];

    fn name(self) -> &'static str {
        match self {
            Mode::Copies => "copies",
        }
    }

    /// Draws `d` over `backend` in this mode.
    fn apply(self, backend: &mut dyn Backend, d: &Drawing) -> draw::ApplyReport {
        match self {
            Mode::Copies => draw::apply(backend, d, &ApplyOptions::default(), &mut |_| {}),
        }
        .unwrap()
    }
}

/// Which API a step uses.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Api {
    Legacy,
    Zmq,
}

const TIMEOUT: Duration = Duration::from_secs(120);

/// A running emulated server over a simulator.
enum Server {
    Legacy(legacy::ServerHandle),
    Zmq(zmq_api::ServerHandle),
}

impl Server {
    fn start(api: Api, sim: Simulator, timing: Timing) -> Server {
        match api {
            Api::Legacy => {
                let cfg = legacy::ServerConfig {
                    listen: "127.0.0.1:0".parse().unwrap(),
                    timing,
                    ..Default::default()
                };
                Server::Legacy(legacy::spawn(cfg, sim).unwrap())
            }
            Api::Zmq => {
                let cfg = zmq_api::ServerConfig {
                    listen: "127.0.0.1:0".parse().unwrap(),
                    protocol: Protocol::V1,
                    timing,
                    ..Default::default()
                };
                Server::Zmq(zmq_api::spawn(cfg, sim).unwrap())
            }
        }
    }

    fn connect(&self) -> Box<dyn Backend> {
        match self {
            Server::Legacy(s) => Box::new(
                LegacyBackend::connect("127.0.0.1", s.local_addr().port(), TIMEOUT).unwrap(),
            ),
            Server::Zmq(s) => Box::new(
                ZmqBackend::connect(&ClientOptions {
                    port: s.local_addr().port(),
                    timeout: TIMEOUT,
                    ..Default::default()
                })
                .unwrap(),
            ),
        }
    }

    /// Draws `d` in `mode`; returns the wall time and the round trips.
    fn apply(&self, mode: Mode, d: &Drawing) -> (Duration, usize) {
        let mut b = self.connect();
        let t = Instant::now();
        let report = mode.apply(b.as_mut(), d);
        let wall = t.elapsed();
        b.close().unwrap();
        (wall, report.round_trips)
    }

    /// Stops the server and gives its simulator back.
    fn stop(self) -> Simulator {
        match self {
            Server::Legacy(s) => s.shutdown(),
            Server::Zmq(s) => {
                let sim = s.with_sim(|sim| sim.clone());
                s.shutdown();
                sim
            }
        }
    }
}

/// One row of the table: mazes drawn first (API, size), then the timed step.
struct Row {
    step: &'static str,
    before: &'static [(Api, u64)],
    api: Api,
    n: u64,
    /// Seconds a real CoppeliaSim 4.5.1 took (copies mode), from the spec.
    real: Option<f64>,
}

/// Issue 18's table (spec "Costs that grow with the scene", through vrep-maze).
const ISSUE_18: &[Row] = &[
    Row {
        step: "legacy: replace 60x60 by 100x100",
        before: &[(Api::Legacy, 60)],
        api: Api::Legacy,
        n: 100,
        real: Some(62.1),
    },
    Row {
        step: "ZeroMQ: replace 9x9 by 100x100",
        before: &[(Api::Legacy, 9)],
        api: Api::Zmq,
        n: 100,
        real: Some(139.8),
    },
    Row {
        step: "ZeroMQ: replace 100x100 by 9x9",
        before: &[(Api::Legacy, 100)],
        api: Api::Zmq,
        n: 9,
        real: Some(29.5),
    },
    Row {
        step: "ZeroMQ: replace 100x100 by 30x30",
        before: &[(Api::Legacy, 100)],
        api: Api::Zmq,
        n: 30,
        real: Some(32.4),
    },
];

/// Issue 11's first draws into the course scene.
const FIRST_DRAWS: &[Row] = &[
    Row {
        step: "legacy: first draw 9x9",
        before: &[],
        api: Api::Legacy,
        n: 9,
        real: Some(0.92),
    },
    Row {
        step: "legacy: first draw 60x60",
        before: &[],
        api: Api::Legacy,
        n: 60,
        real: None,
    },
    Row {
        step: "ZeroMQ: first draw 30x30",
        before: &[],
        api: Api::Zmq,
        n: 30,
        real: Some(7.2),
    },
];

/// Sets the row's scene up on an instant emulator, then times its step on a realistic one.
fn run(row: &Row, mode: Mode) {
    let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
    for &(api, n) in row.before {
        let s = Server::start(api, sim, Timing::instant());
        s.apply(Mode::Copies, &drawing(n));
        sim = s.stop();
    }
    sim.idle_fps = DEFAULT_IDLE_FPS;
    sim.ledger = Some(vec![]);
    let s = Server::start(row.api, sim, Timing::realistic());
    let (wall, requests) = s.apply(mode, &drawing(row.n));
    let ledger = s.stop().ledger.unwrap_or_default();
    let priced = price_all(&Clock::default(), &CostModel::measured(), &ledger);
    let secs = wall.as_secs_f64();
    let (real, ratio) = match row.real {
        Some(r) => (format!("{r:.2}"), format!("{:.2}", secs / r)),
        None => ("-".into(), "-".into()),
    };
    println!(
        "{:<34} {:<7} {:>9} {:>10.2} {:>8.2} {:>8} {:>7}",
        row.step,
        mode.name(),
        requests,
        secs,
        priced.as_secs_f64(),
        real,
        ratio
    );
}

fn main() {
    let first_draws = std::env::args().any(|a| a == "--first-draws");
    println!(
        "{:<34} {:<7} {:>9} {:>10} {:>8} {:>8} {:>7}",
        "step (user idle fps 8)", "mode", "requests", "emulated", "ledger", "real", "x real"
    );
    let mut rows: Vec<&Row> = ISSUE_18.iter().collect();
    if first_draws {
        rows.extend(FIRST_DRAWS);
    }
    for row in rows {
        for mode in Mode::ALL {
            run(row, mode);
        }
    }
}
