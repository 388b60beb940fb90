//! Benchmark: `apply` against the emulator's realistic model of CoppeliaSim 4.5.1
//! (`Timing::realistic()`: one ZeroMQ request per main-loop pass, pasting, re-parenting and
//! removing growing with the objects in the scene, meshes and XML models priced as measured;
//! every figure cites `../shared/spec/real-coppeliasim-4.5.1.md`), for every row of issue 18's
//! table in both draw modes ([`Mode`]), beside what a real CoppeliaSim 4.5.1 took for the same
//! step in copies mode (spec "Costs that grow with the scene"), then issue 18's targets for
//! `--draw mesh`. Each row's earlier mazes are drawn in the row's mode on an instant emulator
//! first (not timed); only its own step sleeps.
//!
//!     cargo bench --bench apply_realistic                   # every row (about 10 minutes)
//!     cargo bench --bench apply_realistic -- --mesh-only    # mesh mode only (about a minute)
//!     cargo bench --bench apply_realistic -- 9x9 300x300    # rows whose step contains a word
//!     cargo bench --bench apply_realistic -- --first-draws  # also the first draws of issue 11
//!     cargo bench --bench apply_realistic -- --charges      # also where each row's time goes
//!
//! "fps" is the user's idle rate (CoppeliaSim's default is 8); "emulated" the wall time of
//! `apply` against the realistic emulator (the connection is made before the clock starts);
//! "ledger" the same step with its connection, priced from the emulator's ledger of the
//! simulator's work (`vrep_maze::sim::cost::price_all`: every request that waited for an idle
//! main-loop pass a whole pass, what a command-line run waits at worst); "real"
//! the spec's figure (copies mode); "x real" emulated / real; "target" issue 18's target for
//! mesh mode.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use vrep_maze::coppelia::DEFAULT_IDLE_FPS;
use vrep_maze::draw::mesh::{self, MeshMaze};
use vrep_maze::draw::{self, ApplyOptions, Backend, Drawing};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, Layout, build_layout};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::maze::Grid;
use vrep_maze::sim::cost::{Charge, price_all};
use vrep_maze::sim::{Clock, CostModel, Scene, Simulator, Timing};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, ZmqBackend};

/// The `n` x `n` course maze of the spec's runs (Prim, seed 42: 160, 1,798, 7,198 and 19,998
/// lines for 9, 30, 60, 100); another seed gives another maze of the same size.
fn layout(n: u64, seed: u64) -> Layout {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, seed);
    build_layout(&spec).unwrap()
}

/// How a maze is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// One copy of the template per line (`--draw copies`, the default).
    Copies,
    /// A few mesh shapes (`--draw mesh`): `sim.createMeshShape` over ZeroMQ, an XML model
    /// loaded by `simxLoadModel` over the legacy API.
    Mesh,
}

impl Mode {
    /// Every mode, each a row of the table.
    const ALL: [Mode; 2] = [Mode::Copies, Mode::Mesh];

    fn name(self) -> &'static str {
        match self {
            Mode::Copies => "copies",
            Mode::Mesh => "mesh",
        }
    }

    /// Draws `layout` over `backend` in this mode.
    fn apply(self, backend: &mut dyn Backend, layout: &Layout) -> draw::ApplyReport {
        let opts = ApplyOptions::default();
        match self {
            Mode::Copies => {
                let d = Drawing::try_from(layout).unwrap();
                draw::apply(backend, &d, &opts, &mut |_| {})
            }
            Mode::Mesh => {
                let m = MeshMaze::try_from(layout).unwrap();
                mesh::apply(backend, &m, &opts, &mut |_| {})
            }
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

const TIMEOUT: Duration = Duration::from_secs(600);

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

    /// Draws `layout` in `mode`; returns the wall time and the round trips.
    fn apply(&self, mode: Mode, layout: &Layout) -> (Duration, usize) {
        let mut b = self.connect();
        let t = Instant::now();
        let report = mode.apply(b.as_mut(), layout);
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

/// A maze of a row: the API that draws it, its size and seed.
#[derive(Debug, Clone, Copy)]
struct Maze {
    api: Api,
    n: u64,
    seed: u64,
}

/// The course maze of size `n` (seed 42) drawn over `api`.
const fn maze(api: Api, n: u64) -> Maze {
    Maze { api, n, seed: 42 }
}

/// One row of the table: mazes drawn first (in the row's mode), then the timed step.
struct Row {
    step: &'static str,
    before: &'static [Maze],
    then: Maze,
    /// The user's idle rate (CoppeliaSim's default is 8).
    idle_fps: i32,
    /// The modes the row is run in.
    modes: &'static [Mode],
    /// Seconds a real CoppeliaSim 4.5.1 took in copies mode, from the spec.
    real: Option<f64>,
    /// Issue 18's target for mesh mode, in seconds.
    target: Option<f64>,
}

/// Issue 18's table (spec "Costs that grow with the scene", through vrep-maze).
const ISSUE_18: &[Row] = &[
    Row {
        step: "legacy: replace 60x60 by 100x100",
        before: &[maze(Api::Legacy, 60)],
        then: maze(Api::Legacy, 100),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &Mode::ALL,
        real: Some(62.1),
        target: None,
    },
    Row {
        step: "ZeroMQ: replace 9x9 by 100x100",
        before: &[maze(Api::Legacy, 9)],
        then: maze(Api::Zmq, 100),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &Mode::ALL,
        real: Some(139.8),
        target: None,
    },
    Row {
        step: "ZeroMQ: replace 100x100 by 9x9",
        before: &[maze(Api::Legacy, 100)],
        then: maze(Api::Zmq, 9),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &Mode::ALL,
        real: Some(29.5),
        target: Some(0.5),
    },
    Row {
        step: "ZeroMQ: replace 100x100 by 30x30",
        before: &[maze(Api::Legacy, 100)],
        then: maze(Api::Zmq, 30),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &Mode::ALL,
        real: Some(32.4),
        target: None,
    },
];

/// Issue 18's targets for `--draw mesh` that are not rows of its table above (the replace
/// target over the legacy API too).
const MESH_TARGETS: &[Row] = &[
    Row {
        step: "legacy: replace 100x100 by 9x9",
        before: &[maze(Api::Legacy, 100)],
        then: maze(Api::Legacy, 9),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Mesh],
        real: None,
        target: Some(0.5),
    },
    Row {
        step: "ZeroMQ: first draw 100x100",
        before: &[],
        then: maze(Api::Zmq, 100),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Mesh],
        real: None,
        target: Some(3.0),
    },
    Row {
        step: "legacy: first draw 100x100",
        before: &[],
        then: maze(Api::Legacy, 100),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Mesh],
        real: None,
        target: Some(3.0),
    },
    Row {
        step: "ZeroMQ: replace 9x9 by 9x9, fps 0",
        before: &[maze(Api::Zmq, 9)],
        then: Maze {
            api: Api::Zmq,
            n: 9,
            seed: 43,
        },
        idle_fps: 0,
        modes: &[Mode::Mesh],
        real: None,
        target: Some(0.05),
    },
    Row {
        step: "ZeroMQ: first draw 300x300",
        before: &[],
        then: maze(Api::Zmq, 300),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Mesh],
        real: None,
        target: Some(30.0),
    },
];

/// Issue 11's first draws into the course scene.
const FIRST_DRAWS: &[Row] = &[
    Row {
        step: "legacy: first draw 9x9",
        before: &[],
        then: maze(Api::Legacy, 9),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Copies],
        real: Some(0.92),
        target: None,
    },
    Row {
        step: "legacy: first draw 60x60",
        before: &[],
        then: maze(Api::Legacy, 60),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Copies],
        real: None,
        target: None,
    },
    Row {
        step: "ZeroMQ: first draw 30x30",
        before: &[],
        then: maze(Api::Zmq, 30),
        idle_fps: DEFAULT_IDLE_FPS,
        modes: &[Mode::Copies],
        real: Some(7.2),
        target: None,
    },
];

/// `value` with two decimals, or "-".
fn or_dash(value: Option<f64>) -> String {
    value.map_or_else(|| "-".into(), |v| format!("{v:.2}"))
}

/// Prints where a step's priced time goes, the connection included: the requests that waited
/// for an idle main-loop pass (spec "Pacing"; not those served by the pass of the request
/// before them) and the work of every kind of operation.
fn print_charges(ledger: &[Charge]) {
    let clock = Clock::default();
    let model = CostModel::measured();
    let paced: Vec<&Charge> = ledger
        .iter()
        .filter(|c| !c.queued && clock.period(c.state, c.idle_fps).is_some())
        .collect();
    let waited: f64 = paced
        .iter()
        .filter_map(|c| clock.period(c.state, c.idle_fps))
        .map(|p| p.as_secs_f64())
        .sum();
    println!(
        "    paced: {} request(s) waited {waited:.3} s for a main-loop pass",
        paced.len()
    );
    let mut work: BTreeMap<String, (usize, f64)> = BTreeMap::new();
    for charge in ledger {
        for op in &charge.ops {
            let kind = format!("{op:?}");
            let kind = kind
                .split([' ', '{'])
                .next()
                .unwrap_or_default()
                .to_string();
            let entry = work.entry(kind).or_default();
            entry.0 += 1;
            entry.1 += model.ops(std::slice::from_ref(op)).as_secs_f64();
        }
    }
    let ops: f64 = work.values().map(|(_, secs)| secs).sum();
    for (kind, (count, secs)) in work {
        println!("    {kind:<14} x{count:<6} {secs:.3} s");
    }
    // a legacy pass at idle fps 0 takes at least `legacy_pass_floor`, whatever its commands
    let priced = price_all(&clock, &model, ledger).as_secs_f64();
    println!("    pass floors           {:.3} s", priced - waited - ops);
}

/// Sets the row's scene up on an instant emulator, then times its step on a realistic one.
fn run(row: &Row, mode: Mode, charges: bool) {
    let mut sim = Simulator::new(Scene::course().with_floor([500.0, 500.0]), DEFAULT_IDLE_FPS);
    for m in row.before {
        let s = Server::start(m.api, sim, Timing::instant());
        s.apply(mode, &layout(m.n, m.seed));
        sim = s.stop();
    }
    sim.idle_fps = row.idle_fps;
    sim.ledger = Some(vec![]);
    let s = Server::start(row.then.api, sim, Timing::realistic());
    let (wall, requests) = s.apply(mode, &layout(row.then.n, row.then.seed));
    let ledger = s.stop().ledger.unwrap_or_default();
    let priced = price_all(&Clock::default(), &CostModel::measured(), &ledger);
    let secs = wall.as_secs_f64();
    let real = row.real.filter(|_| mode == Mode::Copies);
    let target = row.target.filter(|_| mode == Mode::Mesh);
    println!(
        "{:<34} {:>3} {:<6} {:>8} {:>9.2} {:>8.2} {:>7} {:>6} {:>6}",
        row.step,
        row.idle_fps,
        mode.name(),
        requests,
        secs,
        priced.as_secs_f64(),
        or_dash(real),
        or_dash(real.map(|r| secs / r)),
        target.map_or_else(|| "-".into(), |t| format!("<={t}")),
    );
    if charges {
        print_charges(&ledger);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let first_draws = args.iter().any(|a| a == "--first-draws");
    let only_mesh = args.iter().any(|a| a == "--mesh-only");
    let charges = args.iter().any(|a| a == "--charges");
    let filters: Vec<&String> = args.iter().filter(|a| !a.starts_with("--")).collect();
    println!(
        "{:<34} {:>3} {:<6} {:>8} {:>9} {:>8} {:>7} {:>6} {:>6}",
        "step", "fps", "mode", "requests", "emulated", "ledger", "real", "x real", "target"
    );
    let mut rows: Vec<&Row> = ISSUE_18.iter().chain(MESH_TARGETS).collect();
    if first_draws {
        rows.extend(FIRST_DRAWS);
    }
    let chosen =
        |row: &&Row| filters.is_empty() || filters.iter().any(|f| row.step.contains(f.as_str()));
    for row in rows.into_iter().filter(chosen) {
        for &mode in row.modes {
            if !only_mesh || mode == Mode::Mesh {
                run(row, mode, charges);
            }
        }
    }
}
