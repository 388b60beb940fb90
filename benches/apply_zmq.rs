//! Benchmark: `apply` over the ZeroMQ remote API (against `serve --api zmq`, protocols 2 and 1)
//! side by side with the legacy backend, on the same 9x9 and 30x30 layouts, in the same run,
//! at idle fps 8 (CoppeliaSim's default) and 0.
//!
//!     cargo bench --bench apply_zmq
//!
//! Calls = remote function calls; round trips = request/reply exchanges (calls plus
//! `_*wait*_` turns) for ZeroMQ, blocking messages for legacy. Each run starts from the course
//! scene; "re-apply" draws the same layout again (nothing to paste, poses read and compared).

use std::time::{Duration, Instant};

use vrep_maze::draw::{self, ApplyOptions, Backend, Drawing};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator, Timing};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, ZmqBackend};

struct Run {
    calls: u64,
    round_trips: usize,
    wall: Duration,
    again_round_trips: usize,
    again_wall: Duration,
}

fn legacy_run(d: &Drawing, fps: i32) -> Run {
    let cfg = legacy::ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        timing: Timing::realistic(),
        ..Default::default()
    };
    let s = legacy::spawn(
        cfg,
        Simulator::new(Scene::course().with_floor([500.0, 500.0]), fps),
    )
    .unwrap();
    let t = Instant::now();
    let mut sc =
        LegacyBackend::connect("127.0.0.1", s.local_addr().port(), Duration::from_secs(60))
            .unwrap();
    let r = draw::apply(&mut sc, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    let wall = t.elapsed();
    let t = Instant::now();
    let again = draw::apply(&mut sc, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    let again_wall = t.elapsed();
    sc.close().unwrap();
    s.shutdown();
    Run {
        calls: r.round_trips as u64,
        round_trips: r.round_trips,
        wall,
        again_round_trips: again.round_trips,
        again_wall,
    }
}

fn zmq_run(d: &Drawing, fps: i32, protocol: Protocol) -> Run {
    let cfg = zmq_api::ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol,
        timing: Timing::realistic(),
        ..Default::default()
    };
    let s = zmq_api::spawn(
        cfg,
        Simulator::new(Scene::course().with_floor([500.0, 500.0]), fps),
    )
    .unwrap();
    let t = Instant::now();
    let opts = ClientOptions {
        port: s.local_addr().port(),
        timeout: Duration::from_secs(60),
        ..Default::default()
    };
    let mut sc = ZmqBackend::connect(&opts).unwrap();
    let c0 = sc.client().stats().calls;
    let r = draw::apply(&mut sc, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    let calls = sc.client().stats().calls - c0;
    let wall = t.elapsed();
    let t = Instant::now();
    let again = draw::apply(&mut sc, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    let again_wall = t.elapsed();
    drop(sc);
    s.shutdown();
    Run {
        calls,
        round_trips: r.round_trips,
        wall,
        again_round_trips: again.round_trips,
        again_wall,
    }
}

fn main() {
    println!("apply benchmark, ZeroMQ vs legacy (emulated CoppeliaSim in-process, loopback)");
    println!(
        "{:<6} {:>4} {:>6} {:<12} | {:>7} {:>11} {:>8} | {:>15} {:>10}",
        "maze",
        "fps",
        "lines",
        "api",
        "calls",
        "round trips",
        "wall s",
        "re-apply rt",
        "re-apply s"
    );
    for n in [9u64, 30] {
        let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, 42);
        let d = Drawing::try_from(&build_layout(&spec).unwrap()).unwrap();
        for fps in [8, 0] {
            let runs = [
                ("legacy", legacy_run(&d, fps)),
                ("zmq proto 2", zmq_run(&d, fps, Protocol::V2)),
                ("zmq proto 1", zmq_run(&d, fps, Protocol::V1)),
            ];
            for (api, r) in runs {
                println!(
                    "{:<6} {:>4} {:>6} {:<12} | {:>7} {:>11} {:>8.3} | {:>15} {:>10.3}",
                    format!("{n}x{n}"),
                    fps,
                    d.pieces.len(),
                    api,
                    r.calls,
                    r.round_trips,
                    r.wall.as_secs_f64(),
                    r.again_round_trips,
                    r.again_wall.as_secs_f64()
                );
            }
        }
    }
}
