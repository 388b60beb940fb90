//! `vrep-maze serve`: an emulated CoppeliaSim speaking the legacy remote API.

use std::net::SocketAddr;
use std::path::PathBuf;

use anyhow::Context;

use crate::legacy::{ServerConfig, spawn};
use crate::sim::{NamingMode, Scene, Simulator};

/// Serve an in-memory scene over the legacy remote API (no CoppeliaSim needed).
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Example:\n  vrep-maze serve --scene course --dump scene.json &\n  vrep-maze apply maze.json"
)]
pub struct ServeArgs {
    /// Address to listen on (loopback by default; the real simulator uses port 19997).
    #[arg(long, default_value = "127.0.0.1:19997")]
    pub listen: SocketAddr,
    /// Scene to start from: `course` (Floor, Maze, Line, Start, End), `empty`, or a JSON scene
    /// file (a `--dump` output).
    #[arg(long, default_value = "course")]
    pub scene: String,
    /// Main-loop passes per second while the simulation is stopped (CoppeliaSim's default is
    /// 8; 0 = as fast as possible). Clients can change it (`sim_intparam_idle_fps`).
    #[arg(long, default_value_t = 8)]
    pub idle_fps: i32,
    /// Write the scene as JSON to this file after each client disconnects and on exit.
    #[arg(long)]
    pub dump: Option<PathBuf>,
    /// Name pasted copies `Line0` (plain, as CoppeliaSim 4.5.1 does) or `Line#0` (hash).
    #[arg(long, value_enum, default_value = "plain")]
    pub naming: Naming,
    /// Log connections and protocol errors on stderr.
    #[arg(long, short)]
    pub verbose: bool,
}

/// Copy naming mode.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum Naming {
    /// `Line0`, `Line1`, ...
    Plain,
    /// `Line#0`, `Line#1`, ...
    Hash,
}

/// Runs the server until Ctrl-C / SIGTERM.
pub fn run(args: ServeArgs) -> anyhow::Result<std::process::ExitCode> {
    let mut scene = match args.scene.as_str() {
        "course" => Scene::course(),
        "empty" => Scene::empty(),
        file => {
            let text = std::fs::read_to_string(file)
                .with_context(|| format!("cannot read scene file {file}"))?;
            Scene::from_json(&text).with_context(|| format!("scene file {file}"))?
        }
    };
    scene.naming = match args.naming {
        Naming::Plain => NamingMode::Plain,
        Naming::Hash => NamingMode::Hash,
    };
    anyhow::ensure!(
        (0..=1000).contains(&args.idle_fps),
        "--idle-fps must be in 0..=1000, got {}",
        args.idle_fps
    );
    let config = ServerConfig {
        listen: args.listen,
        dump: args.dump,
        verbose: args.verbose,
        ..Default::default()
    };
    let (tx, rx) = std::sync::mpsc::channel();
    ctrlc::set_handler(move || {
        let _ = tx.send(());
    })
    .context("cannot install the Ctrl-C handler")?;
    let server = spawn(config, Simulator::new(scene, args.idle_fps)).with_context(|| {
        format!(
            "cannot listen on {} (port in use? try --listen 127.0.0.1:0)",
            args.listen
        )
    })?;
    println!(
        "vrep-maze serve: legacy remote API on {} (idle fps {})",
        server.local_addr(),
        args.idle_fps
    );
    let _ = rx.recv();
    let sim = server.shutdown();
    eprintln!("vrep-maze serve: stopped with {} objects", sim.scene.len());
    Ok(std::process::ExitCode::SUCCESS)
}
