//! `vrep-maze serve`: an emulated CoppeliaSim speaking the legacy remote API, the ZeroMQ
//! remote API, or both over one shared scene.

use std::net::SocketAddr;
use std::path::PathBuf;

use anyhow::Context;

use super::hinted::hinted;
use super::stdout::outln;
use super::usage::ensure_usage;

use std::sync::Arc;

use crate::legacy::{ServerConfig, spawn};
use crate::sim::{NamingMode, RobotPath, Scene, Simulator, Timing};
use crate::zmq_api::{self, Protocol};

/// Serve an in-memory scene over the legacy and/or ZeroMQ remote API (no CoppeliaSim needed).
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  vrep-maze serve --scene course --dump scene.json &\n  vrep-maze apply maze.json\n  vrep-maze serve --api zmq --scene empty &\n  vrep-maze apply --api zmq --create-missing maze.json"
)]
pub struct ServeArgs {
    /// Which remote API to serve: `legacy` (port 19997), `zmq` (port 23000), or `both` from
    /// one shared scene.
    #[arg(long, value_enum, default_value = "legacy")]
    pub api: ServeApi,
    /// Port to listen on at 127.0.0.1, as every client's `--port` (0: a free one, printed)
    /// [default: 19997 for legacy and both, 23000 for zmq; or $VREP_MAZE_LEGACY_PORT,
    /// $VREP_MAZE_ZMQ_PORT]. With `--api both` it is the legacy port; the ZeroMQ one is
    /// `--zmq-port`.
    #[arg(long, conflicts_with = "listen")]
    pub port: Option<u16>,
    /// Address to listen on [default: 127.0.0.1 and the port of `--port`]. Loopback by
    /// default.
    #[arg(long)]
    pub listen: Option<SocketAddr>,
    /// With `--api both`: the ZeroMQ port at 127.0.0.1 (0: a free one, printed) [default:
    /// 23000 or $VREP_MAZE_ZMQ_PORT; a free one when `--port` or `--listen` moves the legacy
    /// port, so one flag never leaves the other API on a default a CoppeliaSim may hold].
    #[arg(long, conflicts_with = "zmq_listen")]
    pub zmq_port: Option<u16>,
    /// With `--api both`: the ZeroMQ address [default: 127.0.0.1 and the port of
    /// `--zmq-port`].
    #[arg(long)]
    pub zmq_listen: Option<SocketAddr>,
    /// ZeroMQ protocol generation: 1 (CoppeliaSim 4.3 to 4.5) or 2 (4.6 and later).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(1..=2))]
    pub protocol: u8,
    /// Scene to start from: `course` (Floor, Maze, Line, Start, End), `course-walls` (the
    /// course, a Wall cuboid and a Post cuboid), `empty`, or a JSON scene file (a `--dump`
    /// output).
    #[arg(long, default_value = "course")]
    pub scene: String,
    /// Add an object named `Robot` that, while the simulation runs, drives along this
    /// path file's waypoints (CSV with header `t,x,y,yaw`: simulation seconds, metres and
    /// radians relative to `Floor`, linear between waypoints), for `score` to follow.
    #[arg(long, value_name = "PATH.csv")]
    pub robot: Option<PathBuf>,
    /// Main-loop passes per second while the simulation is stopped (CoppeliaSim's default is
    /// 8; 0 = as fast as possible). Clients can change it (`sim_intparam_idle_fps`).
    #[arg(long, default_value_t = 8, allow_negative_numbers = true)]
    pub idle_fps: i32,
    /// Write the scene as JSON to this file after each legacy client disconnects and on exit
    /// (ZeroMQ: on exit).
    #[arg(long)]
    pub dump: Option<PathBuf>,
    /// Name pasted copies `Line0` (plain, as CoppeliaSim 4.5.1 does) or `Line#0` (hash).
    #[arg(long, value_enum, default_value = "plain")]
    pub naming: Naming,
    /// Log connections and protocol errors on stderr.
    #[arg(long, short)]
    pub verbose: bool,
    /// Log every received message and command block on stderr (protocol debugging).
    #[arg(long)]
    pub trace: bool,
    /// After any client leaves, refuse connections for this many milliseconds while the
    /// listening socket is re-created [default: 500 with realistic timing (CoppeliaSim's
    /// plugin sleeps 0.5 s before it binds the port again), 0 with instant].
    #[arg(long, value_name = "MS")]
    pub rebind_delay_ms: Option<u64>,
    /// `realistic`: take the time a real CoppeliaSim takes (4.5.1, or 4.10 with `--protocol
    /// 2`: modeled server work of each call, the legacy port's re-creation and TIME_WAIT); `instant`: none of them (the main
    /// loop still passes at the idle rate).
    #[arg(long, value_enum, default_value = "realistic")]
    pub timing: TimingMode,
    /// Legacy API: after a session whose server side closed first (after its reply to the
    /// kill command, or on the idle timeout) and whose client answered that close with its
    /// own instead of data or a reset, refuse every connection for this many seconds, as
    /// TCP's TIME_WAIT on the port does [default: 60 with realistic timing, 0 with instant].
    #[arg(long, value_name = "SECS")]
    pub reconnect_penalty: Option<f64>,
}

/// How long the emulated server takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum TimingMode {
    /// What a real CoppeliaSim 4.5.1 takes.
    Realistic,
    /// No modeled costs, no re-creation delay, no TIME_WAIT.
    Instant,
}

/// Remote APIs `serve` can speak.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ServeApi {
    /// The legacy remote API.
    Legacy,
    /// The ZeroMQ remote API.
    Zmq,
    /// Both, over one shared scene.
    Both,
}

/// Copy naming mode.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum Naming {
    /// `Line0`, `Line1`, ...
    Plain,
    /// `Line#0`, `Line#1`, ...
    Hash,
}

/// The most bytes of a `--scene` file.
const MAX_SCENE_BYTES: usize = 1 << 30;

/// Runs the server until Ctrl-C / SIGTERM: the scene, the timing and the addresses from
/// the options (each refused as a usage error), then the servers.
pub fn run(args: ServeArgs) -> anyhow::Result<std::process::ExitCode> {
    let scene = scene(&args)?;
    ensure_usage!(
        (0..=1000).contains(&args.idle_fps),
        "--idle-fps must be in 0..=1000, got {}",
        args.idle_fps
    );
    let timing = timing(&args)?;
    let (legacy_listen, zmq_listen) = addresses(&args)?;
    let (tx, rx) = std::sync::mpsc::channel();
    ctrlc::set_handler(move || {
        let _ = tx.send(());
    })
    .context("cannot install the Ctrl-C handler")?;
    let mut sim = Simulator::new(scene, args.idle_fps);
    if let Some(path) = &args.robot {
        sim.robot = Some(robot_path(&mut sim.scene, path)?);
    }
    serve(&args, sim, timing, (legacy_listen, zmq_listen), &rx)?;
    Ok(std::process::ExitCode::SUCCESS)
}

/// `--scene` (the course, its wall maze, an empty scene or a file) named as `--naming` says.
fn scene(args: &ServeArgs) -> anyhow::Result<Scene> {
    let mut scene = match args.scene.as_str() {
        "course" => Scene::course(),
        "course-walls" => Scene::course_walls(),
        "empty" => Scene::empty(),
        file => {
            let text = super::input::read_text(
                std::path::Path::new(file),
                MAX_SCENE_BYTES,
                "a scene file",
                "a scene is read whole, so its size is bounded",
            )
            .with_context(|| format!("cannot read scene file {file}"))?;
            Scene::from_json(&text).with_context(|| format!("scene file {file}"))?
        }
    };
    scene.naming = match args.naming {
        Naming::Plain => NamingMode::Plain,
        Naming::Hash => NamingMode::Hash,
    };
    Ok(scene)
}

/// `--timing` at the `--protocol`'s build, with `--reconnect-penalty`.
fn timing(args: &ServeArgs) -> anyhow::Result<Timing> {
    let mut timing = match args.timing {
        // protocol 2 is served as 4.10 (`../shared/spec/real-coppeliasim-4.10.md`), whose
        // meshes cost more (`docs/measurements.md` "Mesh calls on the real builds")
        TimingMode::Realistic if args.protocol == 2 => Timing::realistic_v4_10(),
        TimingMode::Realistic => Timing::realistic(),
        TimingMode::Instant => Timing::instant(),
    };
    if let Some(secs) = args.reconnect_penalty {
        ensure_usage!(
            secs.is_finite() && (0.0..=86_400.0).contains(&secs),
            "--reconnect-penalty must be a number of seconds in 0..=86400, got {secs}"
        );
        timing.reconnect_penalty = std::time::Duration::from_secs_f64(secs);
    }
    Ok(timing)
}

/// Where the legacy and the ZeroMQ servers listen: `--listen` or `--port` (at 127.0.0.1),
/// `--zmq-listen` or `--zmq-port` beside the legacy one (a free port when only the legacy one
/// moved), else the environment's or the default ports.
fn addresses(args: &ServeArgs) -> anyhow::Result<(SocketAddr, SocketAddr)> {
    let loopback = |port| SocketAddr::from(([127, 0, 0, 1], port));
    let listen = args.listen.or(args.port.map(loopback));
    let legacy_listen = match listen {
        Some(a) => a,
        None => loopback(super::connect::legacy_port()?),
    };
    let zmq_listen = match args.api {
        // the legacy port moved and the ZeroMQ one not named: a free one beside it
        ServeApi::Both => args
            .zmq_listen
            .or(args.zmq_port.map(loopback))
            .or(listen.map(|a| SocketAddr::new(a.ip(), 0))),
        _ => listen,
    };
    let zmq_listen = match zmq_listen {
        Some(a) => a,
        None => loopback(super::connect::zmq_port()?),
    };
    ensure_usage!(
        args.zmq_listen.is_none() || args.api == ServeApi::Both,
        "--zmq-listen is for --api both; use --listen with --api zmq"
    );
    ensure_usage!(
        args.zmq_port.is_none() || args.api == ServeApi::Both,
        "--zmq-port is for --api both; use --port with --api zmq"
    );
    Ok((legacy_listen, zmq_listen))
}

/// Serves `sim` over `--api` at the addresses (legacy, ZeroMQ) until `stop` receives,
/// announcing each server once all listen, and says how many objects the scene held.
fn serve(
    args: &ServeArgs,
    sim: Simulator,
    timing: Timing,
    (legacy_listen, zmq_listen): (SocketAddr, SocketAddr),
    stop: &std::sync::mpsc::Receiver<()>,
) -> anyhow::Result<()> {
    let (config, zmq_config) = configs(args, timing, (legacy_listen, zmq_listen));
    let zmq_line = |s: &zmq_api::ServerHandle| {
        outln!(
            "vrep-maze serve: ZeroMQ remote API (protocol {}) on {} (idle fps {})",
            args.protocol,
            s.local_addr(),
            args.idle_fps
        )
    };
    match args.api {
        ServeApi::Zmq => {
            let server = zmq_api::spawn(zmq_config, sim)
                .map_err(|e| cannot_listen(zmq_listen, "--port", &e))?;
            zmq_line(&server)?;
            let _ = stop.recv();
            let n = server.with_sim(|s| s.scene.len());
            server.shutdown();
            eprintln!("vrep-maze serve: stopped with {n} objects");
        }
        ServeApi::Legacy | ServeApi::Both => {
            let server =
                spawn(config, sim).map_err(|e| cannot_listen(legacy_listen, "--port", &e))?;
            let server = Arc::new(server);
            // both listen before either is announced: a refused port leaves no half server
            let zmq = if args.api == ServeApi::Both {
                let option = if args.zmq_listen.is_some() {
                    "--zmq-listen"
                } else {
                    "--zmq-port"
                };
                let z = zmq_api::spawn_shared(zmq_config, server.clone())
                    .map_err(|e| cannot_listen(zmq_listen, option, &e))?;
                Some(z)
            } else {
                None
            };
            outln!(
                "vrep-maze serve: legacy remote API on {} (idle fps {})",
                server.local_addr(),
                args.idle_fps
            )?;
            if let Some(z) = &zmq {
                zmq_line(z)?;
            }
            let _ = stop.recv();
            if let Some(z) = zmq {
                z.shutdown();
            }
            let server = Arc::try_unwrap(server)
                .map_err(|_| anyhow::anyhow!("the legacy server is still shared at shutdown"))?;
            let sim = server.shutdown();
            eprintln!("vrep-maze serve: stopped with {} objects", sim.scene.len());
        }
    }
    Ok(())
}

/// The legacy and the ZeroMQ servers' configurations: where each listens, `--dump`,
/// `--verbose`, `--trace`, the protocol and the timing.
fn configs(
    args: &ServeArgs,
    timing: Timing,
    (legacy_listen, zmq_listen): (SocketAddr, SocketAddr),
) -> (ServerConfig, zmq_api::ServerConfig) {
    let zmq_config = zmq_api::ServerConfig {
        listen: zmq_listen,
        protocol: if args.protocol == 1 {
            Protocol::V1
        } else {
            Protocol::V2
        },
        dump: if args.api == ServeApi::Zmq {
            args.dump.clone()
        } else {
            None
        },
        verbose: args.verbose,
        timing,
        ..Default::default()
    };
    let config = ServerConfig {
        listen: legacy_listen,
        dump: args.dump.clone(),
        verbose: args.verbose || args.trace,
        trace: args.trace,
        rebind_delay: std::time::Duration::from_millis(args.rebind_delay_ms.unwrap_or(
            match args.timing {
                // spec real-coppeliasim-4.5.1.md, "Why the legacy port refuses for a minute:
                // TIME_WAIT": `Sleep(500)` before the plugin binds the port again
                TimingMode::Realistic => 500,
                TimingMode::Instant => 0,
            },
        )),
        timing,
        ..Default::default()
    };
    (config, zmq_config)
}

/// The error of a server that could not listen on `addr`: one line, and when the port is
/// taken (a CoppeliaSim or another `serve` listens there) the hint to move it with `option`.
fn cannot_listen(addr: SocketAddr, option: &str, error: &dyn std::fmt::Display) -> anyhow::Error {
    let error = error.to_string();
    let taken = error.to_lowercase().contains("in use");
    let message = if taken {
        format!("cannot listen on {addr}: something already listens there ({error})")
    } else {
        format!("cannot listen on {addr}: {error}")
    };
    let example = match option {
        "--port" | "--zmq-port" => format!("{option} 0"),
        _ => format!("{option} {}:0", addr.ip()),
    };
    let mut hints = Vec::new();
    if taken {
        hints.push(format!(
            "a CoppeliaSim (or another `vrep-maze serve`) may hold it: use that one, stop it, or serve on another port with {option} (`{example}` picks a free one and prints it); clients then need the same --port"
        ));
    }
    hinted(message, hints)
}

/// Reads a `--robot` path file and adds its robot to `scene`.
fn robot_path(scene: &mut Scene, path: &std::path::Path) -> anyhow::Result<RobotPath> {
    let text = super::input::read_trajectory_text(path)
        .with_context(|| format!("cannot read the robot path {}", path.display()))?;
    let waypoints = crate::score::trajectory::parse_csv(&text)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    ensure_usage!(
        !waypoints.is_empty(),
        "{}: the robot path has no waypoints",
        path.display()
    );
    ensure_usage!(
        scene.resolve(ROBOT_NAME).is_err(),
        "--robot: the scene already has an object named {ROBOT_NAME}"
    );
    RobotPath::add_to(scene, ROBOT_NAME, waypoints).map_err(|e| anyhow::anyhow!("--robot: {e}"))
}

/// The name of the object `serve --robot` adds (the course robot's body).
pub const ROBOT_NAME: &str = "Robot";
