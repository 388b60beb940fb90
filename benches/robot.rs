//! Benchmark: the course robot runs the maze on the real CoppeliaSim builds (issue 37), each
//! row `--runs N` times (default 3), median printed beside the target and their
//! ratio: `drive --wheels` by camera on a 5x5 line maze (4.10 ZeroMQ, 4.5.1 ZeroMQ and legacy), on the
//! 9x9 course maze (4.10), by pose on the 9x9 (4.10) and a 6x6 wall maze of 1 m cells (4.10),
//! and the README's kinematic pair (`drive --api zmq &`, `score --start-simulation`) on the
//! plain course scene, which must never be graded complete with SPL 1 from samples that
//! jump across the maze. Needs `VREP_MAZE_REAL_SIMS` (the folder of `sim.sh`); the
//! simulators run with `--robot --display` (cameras render).
//!
//!     VREP_MAZE_REAL_SIMS=/abs/path/shared/coppeliasim cargo bench --bench robot
//!     VREP_MAZE_REAL_SIMS=... cargo bench --bench robot -- --runs 1 camera

#[path = "../tests/common/real_sim.rs"]
mod real_sim;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use real_sim::{RealSim, real_sims_dir};
use serde_json::Value;

/// The `vrep-maze` binary cargo built.
const BIN: &str = env!("CARGO_BIN_EXE_vrep-maze");

/// One row: what is driven, how, and the target.
struct Row {
    name: &'static str,
    version: &'static str,
    /// `zmq` or `legacy`.
    api: &'static str,
    layout: &'static [&'static str],
    apply: &'static [&'static str],
    steer: &'static str,
    /// Target wall seconds at most, and SPL at least.
    target: (f64, f64),
}

const ROWS: &[Row] = &[
    Row {
        name: "camera 5x5 lines, 4.10 ZeroMQ",
        version: "4.10.0",
        api: "zmq",
        layout: &["--size", "5x5", "--seed", "7"],
        apply: &[],
        steer: "camera",
        target: (300.0, 0.6),
    },
    Row {
        name: "camera 5x5 lines, 4.5.1 ZeroMQ",
        version: "4.5.1",
        api: "zmq",
        layout: &["--size", "5x5", "--seed", "7"],
        apply: &[],
        steer: "camera",
        target: (300.0, 0.6),
    },
    Row {
        name: "camera 5x5 lines, 4.5.1 legacy",
        version: "4.5.1",
        api: "legacy",
        layout: &["--size", "5x5", "--seed", "7"],
        apply: &[],
        steer: "camera",
        target: (300.0, 0.6),
    },
    Row {
        name: "camera 9x9 course maze, 4.10 ZeroMQ",
        version: "4.10.0",
        api: "zmq",
        layout: &["--seed", "42"],
        apply: &[],
        steer: "camera",
        target: (600.0, 0.6),
    },
    Row {
        name: "pose 9x9 course maze, 4.10 ZeroMQ",
        version: "4.10.0",
        api: "zmq",
        layout: &["--seed", "42"],
        apply: &[],
        steer: "pose",
        target: (60.0, 0.8),
    },
    Row {
        name: "pose 6x6 walls of 1 m, 4.10 ZeroMQ",
        version: "4.10.0",
        api: "zmq",
        layout: &[
            "--seed",
            "5",
            "--size",
            "6x6",
            "--style",
            "walls",
            "--cell-size",
            "1",
        ],
        apply: &["--create-missing"],
        steer: "pose",
        target: (600.0, 0.6),
    },
];

fn vrep_maze(args: &[String]) -> std::process::Output {
    Command::new(BIN)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("vrep-maze runs")
}

fn strings(words: &[&str]) -> Vec<String> {
    words.iter().map(|w| w.to_string()).collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs a row `runs` times; prints its medians.
fn bench_row(row: &Row, sim: &RealSim, dir: &Path, runs: usize) {
    let layout = dir.join(format!("{}.json", row.name.replace([' ', ','], "_")));
    let layout = layout.display().to_string();
    let mut generate = strings(&["generate"]);
    generate.extend(strings(row.layout));
    generate.extend(["-o".into(), layout.clone()]);
    assert!(vrep_maze(&generate).status.success());
    let port_number = match row.api {
        "legacy" => sim.legacy.expect("4.5.1 serves legacy"),
        _ => sim.zmq,
    };
    let port = [
        "--api".to_string(),
        row.api.into(),
        "--port".into(),
        port_number.to_string(),
    ];
    let mut apply = vec!["apply".to_string(), layout.clone()];
    apply.extend(port.clone());
    apply.extend(strings(row.apply));
    let applied = vrep_maze(&apply);
    assert!(
        applied.status.success(),
        "{}",
        String::from_utf8_lossy(&applied.stderr)
    );
    let (mut walls, mut spls, mut lines, mut reached) = (vec![], vec![], vec![], 0);
    for _ in 0..runs {
        let mut drive = vec!["drive".to_string(), layout.clone()];
        drive.extend(strings(&[
            "--wheels",
            "--start-simulation",
            "--json",
            "--steer",
            row.steer,
        ]));
        drive.extend(port.clone());
        let began = Instant::now();
        let out = vrep_maze(&drive);
        walls.push(began.elapsed().as_secs_f64());
        let report: Value = serde_json::from_slice(&out.stdout).unwrap_or(Value::Null);
        reached += usize::from(report["reached_end"] == true);
        spls.push(report["spl"].as_f64().unwrap_or(0.0));
        if let Some(m) = report["line"]["mean_distance_m"].as_f64() {
            lines.push(m);
        }
    }
    let wall = median(walls);
    let spl = median(spls);
    let line = if lines.is_empty() {
        String::from("-")
    } else {
        format!("{:.3} m", median(lines))
    };
    println!(
        "{:<40} reached {reached}/{runs}  wall {wall:>6.1} s (target {:>5.0}, ratio {:.2})  SPL {spl:.3} (target {:.1})  line {line}",
        row.name,
        row.target.0,
        wall / row.target.0,
        row.target.1
    );
}

/// The README's kinematic pair on the plain course scene: the report's completeness and SPL.
fn kinematic_pair(sims: &Path, dir: &Path) {
    let sim = RealSim::start(sims, "4.10.0");
    let layout = dir.join("kinematic.json").display().to_string();
    assert!(
        vrep_maze(&strings(&["generate", "--seed", "42", "-o", &layout]))
            .status
            .success()
    );
    let port = sim.zmq.to_string();
    assert!(
        vrep_maze(&strings(&[
            "apply", &layout, "--api", "zmq", "--port", &port
        ]))
        .status
        .success()
    );
    let mut driver = Command::new(BIN)
        .args(["drive", &layout, "--api", "zmq", "--port", &port])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("drive runs");
    std::thread::sleep(Duration::from_secs(1));
    let out = vrep_maze(&strings(&[
        "score",
        &layout,
        "--start-simulation",
        "--json",
        "--api",
        "zmq",
        "--port",
        &port,
    ]));
    let _ = driver.wait();
    let report: Value = serde_json::from_slice(&out.stdout).unwrap_or(Value::Null);
    println!(
        "{:<40} complete {}  SPL {}  samples {}  ({})",
        "kinematic pair, no --real-time, 4.10",
        report["complete"],
        report["spl"],
        report["samples"],
        report["incomplete_reason"]
    );
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let runs = args
        .iter()
        .position(|a| a == "--runs")
        .and_then(|i| args.get(i + 1))
        .and_then(|n| n.parse().ok())
        .unwrap_or(3);
    let filter: Vec<&String> = args
        .iter()
        .enumerate()
        .filter(|(i, a)| !a.starts_with("--") && (*i == 0 || args[i - 1] != "--runs"))
        .map(|(_, a)| a)
        .collect();
    let Some(sims) = real_sims_dir() else {
        println!("robot: set VREP_MAZE_REAL_SIMS to the folder of sim.sh (real builds only)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let wanted = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()));
    for version in ["4.10.0", "4.5.1"] {
        let rows: Vec<&Row> = ROWS
            .iter()
            .filter(|r| r.version == version && wanted(r.name))
            .collect();
        if rows.is_empty() {
            continue;
        }
        let sim = RealSim::start_with(&sims, version, &["--robot", "--display"]);
        for row in rows {
            bench_row(row, &sim, dir.path(), runs);
        }
    }
    if wanted("kinematic") {
        kinematic_pair(&sims, dir.path());
    }
}
