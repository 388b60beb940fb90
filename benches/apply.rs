//! Benchmark: `apply` against the emulated legacy server versus a baseline client that draws
//! the way the course script does (one blocking call per copy-paste, set-parent, set-position
//! and set-orientation of every line), on 9x9 and 30x30 layouts at idle fps 8 and 0.
//!
//!     cargo bench --bench apply                   # baseline sampled, per-line cost extrapolated
//!     cargo bench --bench apply -- --full-baseline  # baseline draws every line (minutes at 8 fps)
//!
//! Round trips = blocking requests (one main-loop pass each on the server).

use std::time::{Duration, Instant};

use vrep_maze::draw::{self, ApplyOptions, Backend, Drawing};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::command::{Command, decode_handle_list, read_i32};
use vrep_maze::legacy::{Client, ClientOptions, LegacyBackend, ServerConfig, ServerHandle, spawn};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator, Timing};

fn server(fps: i32) -> ServerHandle {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        timing: Timing::realistic(),
        ..Default::default()
    };
    spawn(
        cfg,
        Simulator::new(Scene::course().with_floor([500.0, 500.0]), fps),
    )
    .unwrap()
}

fn opts() -> ClientOptions {
    ClientOptions {
        reply_timeout: Duration::from_secs(30),
        ..Default::default()
    }
}

/// Our `apply`: (round trips, wall time).
fn ours(d: &Drawing, fps: i32) -> (usize, Duration) {
    let s = server(fps);
    let t = Instant::now();
    let mut sc =
        LegacyBackend::connect("127.0.0.1", s.local_addr().port(), Duration::from_secs(30))
            .unwrap();
    let r = draw::apply(&mut sc, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    sc.close().unwrap();
    let wall = t.elapsed();
    s.shutdown();
    (r.round_trips, wall)
}

/// The course script's way, for the first `sample` lines: (round trips, time of the set-up
/// (connect + 5 look-ups), time of the lines).
fn baseline(d: &Drawing, fps: i32, sample: usize) -> (usize, Duration, Duration) {
    let s = server(fps);
    let t = Instant::now();
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    let mut h = Vec::new();
    for n in ["Floor", "Maze", "Line", "Start", "End"] {
        h.push(
            read_i32(
                &c.call1(Command::GetObjectHandle(n.into())).unwrap().data,
                0,
            )
            .unwrap(),
        );
    }
    let (floor, maze, line) = (h[0], h[1], h[2]);
    let setup = t.elapsed();
    let t = Instant::now();
    for p in d.pieces.iter().take(sample) {
        let r = c.call1(Command::CopyPaste(vec![line])).unwrap();
        let copy = decode_handle_list(&r.data).unwrap()[0];
        c.call1(Command::SetObjectParent {
            handle: copy,
            parent: maze,
            keep_in_place: false,
        })
        .unwrap();
        c.call1(Command::SetPosition {
            handle: copy,
            relative_to: floor,
            xyz: [p.x as f32, p.y as f32, p.z as f32],
        })
        .unwrap();
        c.call1(Command::SetOrientation {
            handle: copy,
            relative_to: floor,
            euler: [0.0, 0.0, p.yaw as f32],
        })
        .unwrap();
    }
    let rt = c.round_trips();
    let lines = t.elapsed();
    c.close().unwrap();
    s.shutdown();
    (rt, setup, lines)
}

fn main() {
    let full = std::env::args().any(|a| a == "--full-baseline");
    println!("legacy apply benchmark (emulated CoppeliaSim, `vrep-maze serve` server, loopback)");
    println!(
        "{:<6} {:>4} {:>6} | {:>9} {:>9} | {:>9} {:>10} {:>8} | {:>8} {:>8}",
        "maze",
        "fps",
        "lines",
        "ours rt",
        "ours s",
        "base rt",
        "base s",
        "sampled",
        "rt ratio",
        "speedup"
    );
    for n in [9u64, 30] {
        let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, 42);
        let d = Drawing::try_from(&build_layout(&spec).unwrap()).unwrap();
        for fps in [8, 0] {
            let (rt, wall) = ours(&d, fps);
            let sample = if full {
                d.pieces.len()
            } else if fps == 0 {
                100.min(d.pieces.len())
            } else {
                10
            };
            let (brt, setup, lines) = baseline(&d, fps, sample);
            // extrapolate the baseline linearly in lines (5 look-ups, then 4 calls per line)
            let base_s =
                setup.as_secs_f64() + lines.as_secs_f64() / sample as f64 * d.pieces.len() as f64;
            let base_rt = 5 + 4 * d.pieces.len();
            assert_eq!(brt, 5 + 4 * sample);
            println!(
                "{:<6} {:>4} {:>6} | {:>9} {:>9.3} | {:>9} {:>10.2} {:>8} | {:>7.0}x {:>7.0}x",
                format!("{n}x{n}"),
                fps,
                d.pieces.len(),
                rt,
                wall.as_secs_f64(),
                base_rt,
                base_s,
                if sample == d.pieces.len() {
                    "all".to_string()
                } else {
                    sample.to_string()
                },
                base_rt as f64 / rt as f64,
                base_s / wall.as_secs_f64()
            );
        }
    }
}
