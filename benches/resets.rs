//! Benchmark: a training loop's reset on one open [`Session`] (issue 29): at the user's idle
//! rate 0, a 9x9 mesh maze replaced by another (a new seed each reset), and a 16x16
//! micromouse wall maze (`generate --preset micromouse`) drawn as meshes replaced by another,
//! each `--resets N` times (default 200), against `vrep-maze serve --timing realistic` as
//! 4.5.1 (ZeroMQ protocol 1) and as 4.10 (protocol 2) and, when `VREP_MAZE_REAL_SIMS` names
//! the folder of `sim.sh`, the real builds beside it. Prints the median and 99th percentile
//! per reset, the objects drawing sees (the survey) and the simulator process's resident
//! memory (`serve`'s, or the real CoppeliaSim's) at the first reset and after the last (flat:
//! no leak).
//!
//!     cargo bench --bench resets                         # serve only, 200 resets a row
//!     cargo bench --bench resets -- --resets 1000        # the leak check
//!     VREP_MAZE_REAL_SIMS=/abs/path/shared/coppeliasim cargo bench --bench resets

#[path = "../tests/common/real_sim.rs"]
mod real_sim;

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use real_sim::{RealSim, real_sims_dir};
use vrep_maze::draw::{ApplyOptions, Backend, DrawMode, Job, Picture, Session};
use vrep_maze::layout::{Layout, read_layout};
use vrep_maze::legacy::LegacyBackend;
use vrep_maze::zmq_api::{ClientOptions, ZmqBackend};

/// The `vrep-maze` binary cargo built (it serves and generates).
const BIN: &str = env!("CARGO_BIN_EXE_vrep-maze");

/// A `serve` child as a version, killed when dropped.
struct Served {
    child: Child,
    zmq: u16,
}

impl Served {
    fn start(protocol: &str) -> Served {
        let mut child = Command::new(BIN)
            .args([
                "serve",
                "--timing",
                "realistic",
                "--api",
                "zmq",
                "--protocol",
            ])
            .args([protocol, "--idle-fps", "0", "--scene", "course-walls", "-q"])
            .args(["--listen", "127.0.0.1:0"])
            .stdout(Stdio::piped())
            .spawn()
            .unwrap();
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let zmq = line
            .split("127.0.0.1:")
            .nth(1)
            .and_then(|r| r.split_whitespace().next())
            .and_then(|p| p.parse().ok())
            .unwrap_or_else(|| panic!("serve printed {line:?}"));
        Served { child, zmq }
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Resident memory of process `pid` in MiB (Linux), if readable.
fn rss_mib(pid: Option<u32>) -> Option<f64> {
    let status = std::fs::read_to_string(format!("/proc/{}/status", pid?)).ok()?;
    let kb: f64 = status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()?;
    Some(kb / 1024.0)
}

/// `n` layouts made by `generate args --seed k`, k = 1..=n.
fn layouts(dir: &Path, args: &[&str], n: usize) -> Vec<Layout> {
    (1..=n)
        .map(|seed| {
            let file = dir.join(format!("{}-{seed}.json", args.join("")));
            let ok = Command::new(BIN)
                .arg("generate")
                .args(args)
                .args(["--seed", &seed.to_string(), "-o"])
                .arg(&file)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .unwrap();
            assert!(ok.success(), "generate {args:?}");
            read_layout(&file).unwrap()
        })
        .collect()
}

/// A mesh job for `layout`, creating what the scene lacks when `create`.
fn job(layout: &Layout, create: bool) -> Job<'_> {
    Job {
        layout,
        picture: Picture::of(layout, DrawMode::Mesh).unwrap(),
        options: ApplyOptions::default(),
        create_missing: create,
        save_scene: None,
    }
}

/// The `q` quantile of `times` (sorted in place), milliseconds.
fn quantile(times: &mut [Duration], q: f64) -> f64 {
    times.sort();
    let k = ((times.len() as f64 - 1.0) * q).round() as usize;
    times[k].as_secs_f64() * 1e3
}

/// Resets `session` through `mazes` (the first untimed, creating what is missing over
/// ZeroMQ) and
/// prints a row.
fn row(
    title: &str,
    sim: &str,
    session: &mut Session,
    mazes: &[Layout],
    pid: Option<u32>,
    target: f64,
) {
    // the legacy API creates nothing: the course scene has what a line maze needs
    let create = session.backend().unwrap().authoring().is_some();
    session.apply(&job(&mazes[0], create), &mut |_| {}).unwrap();
    let objects = |s: &mut Session| s.backend().unwrap().objects().unwrap().len();
    let (objects0, rss0) = (objects(session), rss_mib(pid));
    let mut times = Vec::with_capacity(mazes.len());
    for layout in &mazes[1..] {
        let job = job(layout, false);
        let t = Instant::now();
        session
            .apply(&job, &mut |_| {})
            .unwrap_or_else(|e| panic!("{title} on {sim}: {e}"));
        times.push(t.elapsed());
    }
    let (objects1, rss1) = (objects(session), rss_mib(pid));
    let median = quantile(&mut times, 0.5);
    let p99 = quantile(&mut times, 0.99);
    let rss = |r: Option<f64>| r.map_or("-".into(), |r| format!("{r:.1}"));
    println!(
        "{title:<28} {sim:<14} {median:>7.1} {p99:>7.1} {target:>7.0} {:>5} {objects0:>5}->{objects1:<5} {:>7}->{:<7}",
        if median <= target { "ok" } else { "MISS" },
        rss(rss0),
        rss(rss1),
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let resets: usize = args
        .iter()
        .position(|a| a == "--resets")
        .and_then(|k| args.get(k + 1)?.parse().ok())
        .unwrap_or(200);
    let dir = tempfile::tempdir().unwrap();
    // one maze more than resets: the first is drawn untimed
    let nine = layouts(dir.path(), &[], resets + 1);
    let mouse = layouts(dir.path(), &["--preset", "micromouse"], resets + 1);
    println!(
        "{:<28} {:<14} {:>7} {:>7} {:>7} {:>5} {:>12} {:>16}",
        "reset (one session, idle 0)",
        "simulator",
        "median",
        "p99",
        "target",
        "",
        "objects",
        "RSS MiB"
    );
    let connect = |port: u16| -> Session {
        let mut backend: Box<dyn Backend> = Box::new(
            ZmqBackend::connect(&ClientOptions {
                port,
                timeout: Duration::from_secs(30),
                ..Default::default()
            })
            .unwrap(),
        );
        // the user's idle rate 0
        backend.set_idle_fps(0, None).unwrap();
        Session::new(backend)
    };
    for (protocol, version) in [("1", "serve 4.5.1"), ("2", "serve 4.10.0")] {
        let served = Served::start(protocol);
        let mut session = connect(served.zmq);
        let pid = Some(served.child.id());
        row("mesh 9x9 by 9x9", version, &mut session, &nine, pid, 15.0);
        row(
            "micromouse walls (mesh)",
            version,
            &mut session,
            &mouse,
            pid,
            25.0,
        );
    }
    if let Some(sims) = real_sims_dir() {
        for version in ["4.5.1", "4.10.0"] {
            let real = RealSim::start(&sims, version);
            let mut session = connect(real.zmq);
            let name = format!("real {version}");
            let pid = real.pid();
            row("mesh 9x9 by 9x9", &name, &mut session, &nine, pid, 15.0);
            row(
                "micromouse walls (mesh)",
                &name,
                &mut session,
                &mouse,
                pid,
                25.0,
            );
            if let Some(port) = real.legacy {
                drop(session);
                let backend = LegacyBackend::connect("127.0.0.1", port, Duration::from_secs(30));
                let mut session = Session::new(Box::new(backend.unwrap()));
                let name = format!("real {version} legacy");
                row(
                    "mesh 9x9 by 9x9",
                    &name,
                    &mut session,
                    &nine,
                    real.pid(),
                    15.0,
                );
            }
        }
    }
}
