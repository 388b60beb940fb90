//! `vrep-maze apply`: draw a layout into CoppeliaSim over the legacy or the ZeroMQ remote API.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::Context;

use super::ensure_usage;
use super::progress::{Progress, Unit};

use super::connect::{Api, connect};
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use crate::draw::{self, ApplyOptions, Backend, DrawError, Drawing, ObjectNames, Stage};

/// Where the simulator is and what its objects are called (shared by `apply` and `clear`).
#[derive(Debug, Clone, clap::Args)]
pub struct ConnectArgs {
    /// Host running CoppeliaSim (dotted IPv4 or a name).
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// Remote API: `legacy` (CoppeliaSim up to 4.10), `zmq` (4.3 and later, the only one from
    /// 4.11), or `auto` (try legacy on 19997, then ZeroMQ on 23000; prints which was used).
    #[arg(long, value_enum, default_value = "legacy")]
    pub api: Api,
    /// Port of the remote API server [default: 19997 for legacy, 23000 for zmq].
    #[arg(long, allow_negative_numbers = true)]
    pub port: Option<u16>,
    /// The floor: every layout coordinate is relative to it.
    #[arg(long, default_value = "Floor")]
    pub floor: String,
    /// The dummy every maze line becomes a child of.
    #[arg(long, default_value = "Maze")]
    pub parent: String,
    /// The line template (a 0.6 m x 0.1 m green plane).
    #[arg(long, default_value = "Line")]
    pub line: String,
    /// The wall template of wall mazes (a cuboid as long as a cell side; it stays where it is,
    /// every wall is a copy).
    #[arg(long, default_value = "Wall")]
    pub wall: String,
    /// The post template of wall mazes with posts (a cuboid as thick as the walls and as
    /// high; it stays where it is, every post is a copy).
    #[arg(long, default_value = "Post")]
    pub post: String,
    /// The start marker (a 1 m x 1 m blue plane).
    #[arg(long, default_value = "Start")]
    pub start: String,
    /// The end marker (a 1 m x 1 m red plane).
    #[arg(long, default_value = "End")]
    pub end: String,
    /// Seconds to keep trying to connect [default: 75 for legacy: CoppeliaSim refuses every
    /// connection for about a minute after a client left abruptly; 10 for zmq; auto tries
    /// legacy for at most 1.5] (more than 0, at most a day).
    #[arg(long, value_name = "SECS", value_parser = parse_timeout, allow_negative_numbers = true)]
    pub connect_timeout: Option<Duration>,
    /// Seconds to wait for each reply (more than 0, at most a day).
    #[arg(long, value_name = "SECS", default_value = "10", value_parser = parse_timeout, allow_negative_numbers = true)]
    pub timeout: Duration,
}

impl ConnectArgs {
    /// The object names.
    pub fn names(&self) -> ObjectNames {
        ObjectNames {
            floor: self.floor.clone(),
            parent: self.parent.clone(),
            line: self.line.clone(),
            start: self.start.clone(),
            end: self.end.clone(),
            wall: self.wall.clone(),
            post: self.post.clone(),
        }
    }

    /// Connects to the simulator over the chosen API, saying on standard error what it
    /// tries; with `auto` (and over ZeroMQ) says on standard output which API and version
    /// answered.
    pub fn connect(&self) -> anyhow::Result<Box<dyn Backend>> {
        let connected = connect(
            self.api,
            &self.host,
            self.port,
            self.timeout,
            self.connect_timeout,
        )?;
        if self.api != Api::Legacy {
            println!("using the {}", connected.description);
        }
        Ok(connected.backend)
    }
}

/// The longest `--timeout`: a day.
const MAX_TIMEOUT_SECONDS: f64 = 86_400.0;

/// `--timeout`: seconds, more than 0 and at most [`MAX_TIMEOUT_SECONDS`].
fn parse_timeout(text: &str) -> Result<Duration, String> {
    let seconds: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a number of seconds"))?;
    if seconds > 0.0 && seconds <= MAX_TIMEOUT_SECONDS {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(format!(
            "{text} is out of range: more than 0 and at most {MAX_TIMEOUT_SECONDS} seconds"
        ))
    }
}

/// Draw a layout into a running CoppeliaSim (legacy or ZeroMQ remote API, simulation stopped).
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Example:\n  vrep-maze generate --seed 42 --algo prim -o m.json\n  vrep-maze apply m.json\n  vrep-maze apply m.json --port 19997 --line GreenLine --stop-simulation"
)]
pub struct ApplyArgs {
    /// Layout JSON written by `vrep-maze generate` (`-` reads standard input).
    pub layout: PathBuf,
    /// Connection and object names.
    #[command(flatten)]
    pub scene: ConnectArgs,
    /// Stop a running simulation first (changes made while it runs would be lost).
    #[arg(long)]
    pub stop_simulation: bool,
    /// Only show what would change.
    #[arg(long)]
    pub dry_run: bool,
    /// ZeroMQ only: create missing scene objects first (Floor, the Maze dummy, the Line,
    /// Start and End planes; for a wall maze the Wall cuboid instead of Line, and a Post
    /// cuboid if it has posts), so a brand-new scene needs no manual set-up.
    #[arg(long)]
    pub create_missing: bool,
    /// How the maze is drawn: `copies` pastes one copy of the template per line (or wall),
    /// `mesh` draws every straight run as one rectangle (or box) in a few mesh shapes,
    /// coloured like the template (ZeroMQ API; seconds instead of minutes for big mazes).
    #[arg(long, value_enum, default_value = "copies")]
    pub draw: DrawMode,
    /// ZeroMQ only: save the scene afterwards to this path (on the simulator's machine).
    #[arg(long, value_name = "PATH")]
    pub save_scene: Option<String>,
}

/// How `apply` draws a maze (`--draw`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DrawMode {
    /// One copy of the template per line, wall or post.
    Copies,
    /// A few mesh shapes, one rectangle or box per straight run.
    Mesh,
}

/// Runs `apply`.
pub fn run(args: ApplyArgs, bars: Progress) -> anyhow::Result<std::process::ExitCode> {
    if args.draw == DrawMode::Mesh {
        return run_mesh(args, bars);
    }
    let layout = crate::layout::read_layout(&args.layout)?;
    let drawing = Drawing::try_from(&layout)
        .with_context(|| format!("{}: nothing was drawn", args.layout.display()))?;
    let mut opts = ApplyOptions {
        names: args.scene.names(),
        stop_simulation: args.stop_simulation,
        dry_run: args.dry_run,
        ..Default::default()
    };
    let zmq_only = args.create_missing || args.save_scene.is_some();
    ensure_usage!(
        !zmq_only || args.scene.api != Api::Legacy,
        "--create-missing and --save-scene need the ZeroMQ remote API (--api zmq): the legacy API cannot create objects or save scenes"
    );
    let interrupt = Interrupt::install()?;
    opts.interrupt = Some(interrupt.shared());
    let mut backend = args.scene.connect()?;
    if interrupt.requested() {
        let _ = backend.close();
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    if args.create_missing && !args.dry_run {
        let Some(authoring) = backend.authoring() else {
            anyhow::bail!(
                "--create-missing needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
            );
        };
        let created = draw::create_missing_for(authoring, &opts.names, &layout)
            .context("creating the missing scene objects")?;
        if !created.is_empty() {
            println!("created {}", created.join(", "));
        }
    }
    let what = match (drawing.style, drawing.posts.is_empty()) {
        (crate::layout::Style::Walls, false) => "walls and posts",
        (style, _) => style.name(),
    };
    let bar = bars.bar(
        "reading the scene",
        drawing.copies() as u64,
        Unit::Items(what),
    );
    let mut progress = |stage: Stage| match stage {
        Stage::Surveyed => bar.set_message("reading the scene"),
        Stage::Pasting { .. } => bar.set_message(format!("pasting {what}")),
        Stage::Placing { done, .. } => {
            bar.set_message(format!("placing {what}"));
            bar.set_position(done as u64);
        }
        Stage::Verifying => bar.set_message("verifying"),
    };
    let result = draw::apply(backend.as_mut(), &drawing, &opts, &mut progress);
    bar.finish_and_clear();
    if let Err(DrawError::Interrupted { placed, total }) = &result {
        // the run stopped between requests and restored the idle rate; closing the way the
        // official client does spares the user the simulator's one-minute refusal
        let closed = backend.close();
        eprintln!(
            "interrupted: {placed} of {total} copies placed; the idle rate is restored{}",
            if closed.is_ok() {
                " and the connection closed cleanly"
            } else {
                ""
            }
        );
        eprintln!(
            "  hint: run the same apply again to finish the maze, or vrep-maze clear to remove it"
        );
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    let report = result.with_context(|| format!("drawing {}", args.layout.display()))?;
    if let Some(path) = &args.save_scene
        && !args.dry_run
    {
        let Some(authoring) = backend.authoring() else {
            anyhow::bail!(
                "--save-scene needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
            );
        };
        authoring
            .save_scene(path)
            .with_context(|| format!("saving the scene to {path}"))?;
        println!("saved the scene to {path} (on the simulator's machine)");
    }
    let _ = backend.close();
    if report.stopped_simulation {
        println!("stopped the simulation first");
    }
    println!("{report}");
    if !report.dry_run {
        let noun = match (drawing.style, drawing.posts.is_empty()) {
            (crate::layout::Style::Lines, _) => "line",
            (crate::layout::Style::Walls, true) => "wall",
            (crate::layout::Style::Walls, false) => "wall, post",
        };
        println!("verified: every {noun}, start and end in place");
    }
    Ok(std::process::ExitCode::SUCCESS)
}

/// Runs `apply --draw mesh`.
fn run_mesh(args: ApplyArgs, bars: Progress) -> anyhow::Result<std::process::ExitCode> {
    let layout = crate::layout::read_layout(&args.layout)?;
    let maze = draw::mesh::MeshMaze::try_from(&layout)
        .with_context(|| format!("{}: nothing was drawn", args.layout.display()))?;
    let mut opts = ApplyOptions {
        names: args.scene.names(),
        stop_simulation: args.stop_simulation,
        dry_run: args.dry_run,
        ..Default::default()
    };
    let interrupt = Interrupt::install()?;
    opts.interrupt = Some(interrupt.shared());
    let mut backend = args.scene.connect()?;
    if interrupt.requested() {
        let _ = backend.close();
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    if args.create_missing && !args.dry_run {
        let Some(authoring) = backend.authoring() else {
            anyhow::bail!(
                "--create-missing needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
            );
        };
        let created = draw::create_missing_for(authoring, &opts.names, &layout)
            .context("creating the missing scene objects")?;
        if !created.is_empty() {
            println!("created {}", created.join(", "));
        }
    }
    let what = match maze.style {
        crate::layout::Style::Lines => "line runs",
        crate::layout::Style::Walls => "wall runs and posts",
    };
    let bar = bars.bar("reading the scene", maze.pieces() as u64, Unit::Items(what));
    let mut progress = |stage: Stage| match stage {
        Stage::Surveyed => bar.set_message("reading the scene"),
        Stage::Pasting { .. } | Stage::Placing { .. } => {
            if let Stage::Placing { done, .. } = stage {
                bar.set_position(done as u64);
            }
            bar.set_message(format!("creating the meshes of {what}"));
        }
        Stage::Verifying => bar.set_message("verifying"),
    };
    let result = draw::mesh::apply(backend.as_mut(), &maze, &opts, &mut progress);
    bar.finish_and_clear();
    if let Err(DrawError::Interrupted { placed, total }) = &result {
        let closed = backend.close();
        eprintln!(
            "interrupted: {placed} of {total} {what} drawn; the idle rate is restored{}",
            if closed.is_ok() {
                " and the connection closed cleanly"
            } else {
                ""
            }
        );
        eprintln!(
            "  hint: run the same apply again to finish the maze, or vrep-maze clear to remove it"
        );
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    let report = result.with_context(|| format!("drawing {}", args.layout.display()))?;
    if let Some(path) = &args.save_scene
        && !args.dry_run
    {
        let Some(authoring) = backend.authoring() else {
            anyhow::bail!(
                "--save-scene needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
            );
        };
        authoring
            .save_scene(path)
            .with_context(|| format!("saving the scene to {path}"))?;
        println!("saved the scene to {path} (on the simulator's machine)");
    }
    let _ = backend.close();
    if report.stopped_simulation {
        println!("stopped the simulation first");
    }
    println!("{report}");
    if !report.dry_run {
        println!("verified: every mesh read back, start and end in place");
    }
    Ok(std::process::ExitCode::SUCCESS)
}
