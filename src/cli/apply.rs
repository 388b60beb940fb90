//! `vrep-maze apply`: draw a layout into CoppeliaSim over the legacy or the ZeroMQ remote API.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use anyhow::Context;

use super::progress::{Progress, Unit};
use super::usage::ensure_usage;

use super::connect::{Api, Connected, RawClient, connect, connect_client};
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::reports::{ApplyCounts, ApplyJson, REPORT_VERSION};
use super::say::{self, say};
use crate::draw::run::Authored;
use crate::draw::{self, ApplyOptions, Backend, DrawError, ObjectNames, Picture, RunError, Stage};

/// Where the simulator is and what its objects are called (shared by `apply` and `clear`).
#[derive(Debug, Clone, clap::Args)]
pub struct ConnectArgs {
    /// Host running CoppeliaSim (dotted IPv4 or a name).
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
    /// Remote API: `auto` (try legacy on 19997, then ZeroMQ on 23000; says which answered),
    /// `legacy` (CoppeliaSim up to 4.10) or `zmq` (4.3 and later, the only one from 4.11).
    #[arg(long, value_enum, default_value = "auto")]
    pub api: Api,
    /// Port of the remote API server, 1..65535 [default: 19997 for legacy, 23000 for zmq].
    #[arg(long, allow_negative_numbers = true, value_parser = clap::value_parser!(u16).range(1..))]
    pub port: Option<u16>,
    /// The floor: every layout coordinate is relative to it.
    #[arg(long, default_value = "Floor")]
    pub floor: String,
    /// The dummy every maze line becomes a child of.
    #[arg(long, default_value = "Maze")]
    pub parent: String,
    /// The line template (a green plane of the layout's `line.length` x `line.width`: 0.6 m x
    /// 0.1 m on the course).
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
    /// The start marker (a blue plane a cell wide: 1 m x 1 m on the course).
    #[arg(long, default_value = "Start")]
    pub start: String,
    /// The end marker (a red plane a cell wide: 1 m x 1 m on the course).
    #[arg(long, default_value = "End")]
    pub end: String,
    /// Seconds to keep trying to connect [default: 10; 75 for legacy when an earlier run
    /// ended with its session open, since CoppeliaSim may then refuse every connection for
    /// about a minute; auto tries legacy for at most 1.5 unless so] (more than 0, at most a day).
    #[arg(long, value_name = "SECS", value_parser = parse_timeout, allow_negative_numbers = true)]
    pub connect_timeout: Option<Duration>,
    /// Seconds to wait for each reply (more than 0, at most a day).
    #[arg(long, value_name = "SECS", default_value = "10", value_parser = parse_timeout, allow_negative_numbers = true)]
    pub timeout: Duration,
}

impl ConnectArgs {
    /// Whether `--api legacy` was asked (not the automatic choice).
    pub fn asks_legacy(&self) -> bool {
        self.api == Api::Legacy
    }

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

    /// Refuses two roles given one name, as conflicting options are: a usage error (exit 2)
    /// before anything is sent, with the draw error's hints.
    pub fn check_roles(&self) -> anyhow::Result<()> {
        self.names().check_roles().map_err(|e| {
            let message = super::remedies::message(&e);
            anyhow::Error::new(e).context(super::usage::UsageError(message.into()))
        })
    }

    /// Connects to the simulator over the chosen API, saying on standard error what it
    /// tries; with `auto` (and over ZeroMQ) says on standard output which API and version
    /// answered.
    pub fn connect(&self) -> anyhow::Result<Box<dyn Backend>> {
        Ok(self.connect_until(None)?.backend)
    }

    /// [`ConnectArgs::connect`], keeping the description of what answered (for `--json`),
    /// ending the connection wait at once when `stop` is set (Ctrl-C) with
    /// [`super::interrupt::Interrupted`].
    pub fn connect_until(
        &self,
        stop: Option<&std::sync::atomic::AtomicBool>,
    ) -> anyhow::Result<Connected> {
        self.check_host()?;
        for (role, name) in self.names().roles() {
            ensure_usage!(
                !name.trim().is_empty(),
                "{} needs the name of an object in the scene, not an empty one",
                super::remedies::option(role)
            );
        }
        let connected = connect(
            self.api,
            &self.host,
            self.port,
            self.timeout,
            self.connect_timeout,
            stop,
        )?;
        if self.api != Api::Legacy {
            say(format!("using the {}", connected.description))?;
        }
        Ok(connected)
    }

    /// The options of a fresh connection to where `client` is connected (its host and port,
    /// `--timeout`): a robot run stops the simulation over one when its own is lost.
    pub fn options_for(&self, client: &crate::zmq_api::Client) -> crate::zmq_api::ClientOptions {
        let port = client
            .endpoint()
            .rsplit(':')
            .next()
            .and_then(|p| p.parse().ok());
        crate::zmq_api::ClientOptions {
            host: self.host.clone(),
            port: port.unwrap_or(0),
            timeout: self.timeout,
            ..Default::default()
        }
    }

    /// Connects as [`ConnectArgs::connect_until`] does (the same waits, messages and hints)
    /// for a command that does not draw: the raw client of the API that answered.
    pub fn client_until(
        &self,
        stop: Option<&std::sync::atomic::AtomicBool>,
    ) -> anyhow::Result<RawClient> {
        self.check_host()?;
        connect_client(
            self.api,
            &self.host,
            self.port,
            self.timeout,
            self.connect_timeout,
            stop,
        )
    }

    /// `vrep-maze COMMAND` with the options of this connection that are not the defaults
    /// (host, API, port, names, timeouts), each word quoted for the shell: the command a
    /// hint shows, which reaches the same simulator and objects.
    pub fn command(&self, command: &str) -> String {
        let mut words = vec!["vrep-maze".to_string(), command.to_string()];
        let mut add = |option: &str, value: String| {
            words.push(option.to_string());
            words.push(super::escape::shell_word(&value).into_owned());
        };
        if self.host != "127.0.0.1" {
            add("--host", self.host.clone());
        }
        if self.api != Api::Auto {
            let api = clap::ValueEnum::to_possible_value(&self.api)
                .map(|v| v.get_name().to_string())
                .unwrap_or_default();
            add("--api", api);
        }
        if let Some(port) = self.port {
            add("--port", port.to_string());
        }
        let (names, defaults) = (self.names(), ObjectNames::default());
        for (role, name) in names.roles() {
            if name != defaults.name(role) {
                add(super::remedies::option(role), name.to_string());
            }
        }
        if let Some(wait) = self.connect_timeout {
            add("--connect-timeout", wait.as_secs_f64().to_string());
        }
        if self.timeout != Duration::from_secs(10) {
            add("--timeout", self.timeout.as_secs_f64().to_string());
        }
        words.join(" ")
    }

    /// Refuses an empty `--host`.
    fn check_host(&self) -> anyhow::Result<()> {
        ensure_usage!(
            !self.host.trim().is_empty(),
            "--host needs a host name or an IP address, not an empty one"
        );
        Ok(())
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
    /// Draw into a running simulation, leaving it running: the maze lasts until the
    /// simulation stops, when CoppeliaSim removes what was made while it ran (apply again
    /// then to have it back). For a new maze between a robot's runs without a restart.
    #[arg(long, conflicts_with = "stop_simulation")]
    pub while_running: bool,
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
    /// coloured like the template (seconds instead of minutes for big mazes): created by
    /// `sim.createMeshShape` over ZeroMQ, loaded as an XML model over the legacy API.
    #[arg(long, value_enum, default_value = "copies")]
    pub draw: DrawMode,
    /// ZeroMQ only: grow a `Floor` smaller than the layout's floor to its size
    /// (`sim.scaleObject`) instead of refusing; `clear` puts it back to its size before.
    #[arg(long)]
    pub resize_floor: bool,
    /// ZeroMQ only: save the scene afterwards to this path (on the simulator's machine).
    #[arg(long, value_name = "PATH")]
    pub save_scene: Option<String>,
    /// Print one JSON document on standard output (schema/apply-v1.schema.json).
    #[arg(long)]
    pub json: bool,
    /// The robot whose footprint is checked against the passages after the draw (a
    /// warning if it does not fit): its model's bounding box in the scene, the narrower
    /// horizontal side; nothing is said if the scene has no object of this name.
    #[arg(long, value_name = "NAME", default_value = "Robot")]
    pub robot: String,
    /// The robot's footprint width in metres, instead of reading it from the scene.
    #[arg(long, value_name = "M", value_parser = super::values::parse_metres, allow_negative_numbers = true)]
    pub robot_width: Option<f64>,
}

impl ApplyArgs {
    /// The robot the drawing is checked against (`--robot`, `--robot-width`).
    pub fn robot_check(&self) -> draw::robot::RobotCheck {
        draw::robot::RobotCheck {
            name: self.robot.clone(),
            width: self.robot_width,
        }
    }
}

/// How `apply` draws a maze (`--draw`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DrawMode {
    /// One copy of the template per line, wall or post.
    Copies,
    /// A few mesh shapes, one rectangle or box per straight run.
    Mesh,
}

impl From<DrawMode> for draw::DrawMode {
    fn from(mode: DrawMode) -> draw::DrawMode {
        match mode {
            DrawMode::Copies => draw::DrawMode::Copies,
            DrawMode::Mesh => draw::DrawMode::Mesh,
        }
    }
}

/// Runs `apply`.
pub fn run(args: ApplyArgs, bars: Progress) -> anyhow::Result<std::process::ExitCode> {
    say::set_json(args.json);
    ensure_usage!(
        args.save_scene
            .as_deref()
            .is_none_or(|path| !path.trim().is_empty()),
        "--save-scene needs the path of a scene file (on the simulator's machine, e.g. /tmp/maze.ttt), not an empty one"
    );
    let zmq_only = args.create_missing || args.save_scene.is_some();
    ensure_usage!(
        !zmq_only || args.scene.api != Api::Legacy,
        "--create-missing and --save-scene need the ZeroMQ remote API (--api zmq): the legacy API cannot create objects or save scenes"
    );
    ensure_usage!(
        !args.resize_floor || args.scene.api != Api::Legacy,
        "--resize-floor needs the ZeroMQ remote API (--api zmq): the legacy API cannot resize objects"
    );
    // two roles on one object: refused at once, before connecting
    args.scene.check_roles()?;
    let layout = crate::layout::read_layout(&args.layout)?;
    let job = args
        .job(&layout, None)
        .with_context(|| format!("{}: nothing was drawn", args.layout.display()))?;
    let words = Words::of(&job.picture);
    drive(&args, bars, job, words)
}

impl ApplyArgs {
    /// The one place `apply`'s options become a [`draw::Job`] (the command line's and
    /// Python's `apply`, a session's too): `layout` drawn the `--draw` way, with the object
    /// names, `--stop-simulation`, `--dry-run`, `--resize-floor`, `--create-missing` and
    /// `--save-scene`; `interrupt` is the flag Ctrl-C sets. Fails when the layout cannot be
    /// drawn ([`Picture::of`]).
    pub fn job<'a>(
        &self,
        layout: &'a crate::layout::Layout,
        interrupt: Option<Arc<AtomicBool>>,
    ) -> Result<draw::Job<'a>, crate::validate::Invalid> {
        Ok(draw::Job {
            layout,
            picture: Picture::of(layout, self.draw.into())?,
            options: ApplyOptions {
                names: self.scene.names(),
                stop_simulation: self.stop_simulation,
                while_running: self.while_running,
                dry_run: self.dry_run,
                resize_floor: self.resize_floor,
                interrupt,
                robot: self.robot_check(),
                ..Default::default()
            },
            create_missing: self.create_missing,
            save_scene: self.save_scene.clone(),
        })
    }
}

/// The words `apply` tells one draw mode's progress and outcome in.
struct Words {
    /// What the progress bar counts ("lines", "wall runs and posts", ...).
    what: &'static str,
    /// The bar's message while pasting.
    pasting: String,
    /// The bar's message while placing.
    placing: String,
    /// What "interrupted: N of M ..." counts, and what was done with them.
    interrupted: String,
    /// The last line of a real run: what was verified.
    verified: String,
}

impl Words {
    /// The words of `picture`'s mode: `--draw copies` (one copy of a template per line,
    /// wall or post) or `--draw mesh` (a few mesh shapes, one rectangle or box per run).
    fn of(picture: &Picture) -> Words {
        match picture {
            Picture::Copies(drawing) => {
                let (what, noun) = match (drawing.style, drawing.posts.is_empty()) {
                    (crate::layout::Style::Lines, _) => ("lines", "line"),
                    (crate::layout::Style::Walls, true) => ("walls", "wall"),
                    (crate::layout::Style::Walls, false) => ("walls and posts", "wall, post"),
                };
                Words {
                    what,
                    pasting: format!("pasting {what}"),
                    placing: format!("placing {what}"),
                    interrupted: super::summary::interrupted_counts(picture),
                    verified: format!("verified: every {noun}, start and end in place"),
                }
            }
            Picture::Mesh(maze) => {
                let what = match maze.style {
                    crate::layout::Style::Lines => "line runs",
                    crate::layout::Style::Walls => "wall runs and posts",
                };
                Words {
                    what,
                    pasting: format!("creating the meshes of {what}"),
                    placing: format!("creating the meshes of {what}"),
                    interrupted: super::summary::interrupted_counts(picture),
                    verified: "verified: every mesh read back, start and end in place".into(),
                }
            }
        }
    }
}

/// Runs `apply` after the usage checks: connects (Ctrl-C ends the wait), runs the job
/// ([`draw::run`]: creates the missing objects if asked, draws, saves the scene if asked)
/// with a progress bar and says what was done (`--json`: one document).
fn drive(
    args: &ApplyArgs,
    bars: Progress,
    mut job: draw::Job<'_>,
    words: Words,
) -> anyhow::Result<std::process::ExitCode> {
    let interrupt = Interrupt::install()?;
    job.options.interrupt = Some(interrupt.shared());
    let Connected {
        mut backend,
        description: connection,
    } = args.scene.connect_until(Some(interrupt.flag()))?;
    if interrupt.requested() {
        let _ = backend.close();
        return Ok(std::process::ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    let bar = bars.bar(
        "reading the scene",
        job.picture.pieces() as u64,
        Unit::Items(words.what),
    );
    let api = backend.remote_api();
    let dry_run = args.dry_run;
    let mut said = Ok(());
    let mut progress = |stage: Stage| match stage {
        Stage::Created(created) => {
            if !created.is_empty() {
                said = say(format!("created {}", created.join(", ")));
            }
        }
        Stage::Surveyed => bar.set_message("reading the scene"),
        Stage::Planned(work) => {
            let warning = api.and_then(|api| draw::estimate::slow_draw_warning(api, &work));
            if let Some(line) = warning.filter(|_| !bars.quiet() && !dry_run) {
                let line = super::wording::worded(&line);
                bar.suspend(|| eprintln!("{line}"));
            }
        }
        Stage::Pasting { .. } => bar.set_message(words.pasting.clone()),
        Stage::Placing { done, .. } => {
            bar.set_message(words.placing.clone());
            bar.set_position(done as u64);
        }
        Stage::Verifying => bar.set_message("verifying"),
    };
    let result = draw::run(backend.as_mut(), &job, &mut progress);
    bar.finish_and_clear();
    said?;
    // over ZeroMQ the missing objects can be made, in either draw mode: their hints say so
    let can_create = backend.authoring().is_some() && !args.create_missing;
    if let Err(RunError::Draw(DrawError::Interrupted { placed, total })) = &result {
        // the run stopped between requests and restored the idle rate; closing the way the
        // official client does spares the user the simulator's one-minute refusal
        let closed = backend.close().is_ok();
        return Ok(say_interrupted(args, &words, (*placed, *total), closed));
    }
    let done = result.map_err(|e| run_error(e, &args.layout, can_create))?;
    let report = &done.drawn;
    for warning in &report.warnings {
        eprintln!("warning: {}", super::escape::escaped(warning));
    }
    if let Some(path) = &done.saved_scene {
        say(format!(
            "saved the scene to {path} (on the simulator's machine)"
        ))?;
    }
    let _ = backend.close();
    say_done(args, &job.options.names.parent, &words, connection, done)?;
    Ok(std::process::ExitCode::SUCCESS)
}

/// What an interrupted apply says on standard error: how far it got (`placed` of `total`),
/// whether the connection `closed` cleanly, and how to finish or undo it.
fn say_interrupted(
    args: &ApplyArgs,
    words: &Words,
    (placed, total): (usize, usize),
    closed: bool,
) -> std::process::ExitCode {
    eprintln!(
        "interrupted: {placed} of {total} {}; the idle rate is restored{}",
        words.interrupted,
        if closed {
            " and the connection closed cleanly"
        } else {
            ""
        }
    );
    eprintln!(
        "  hint: run the same apply again to finish the maze, or {} to remove it",
        super::escape::escaped(&args.scene.command("clear"))
    );
    std::process::ExitCode::from(INTERRUPTED_EXIT_CODE)
}

/// What a finished apply says once the connection is closed: a stopped simulation, a grown
/// floor, the summary line, the user's objects left alone under `parent`, what was verified,
/// and with `--json` the document.
fn say_done(
    args: &ApplyArgs,
    parent: &str,
    words: &Words,
    connection: String,
    done: draw::Report,
) -> anyhow::Result<()> {
    let report = &done.drawn;
    if report.stopped_simulation {
        say("stopped the simulation first")?;
    } else if report.simulation_running && !report.dry_run {
        say("drawn into the running simulation: CoppeliaSim removes it when the simulation stops")?;
    }
    if let Some(line) = &report.floor {
        say(line)?;
    }
    say(super::summary::apply_line(report))?;
    if let Some(line) = draw::left_alone_line(&report.left_alone, parent) {
        say(line)?;
    }
    if !report.dry_run {
        say(&words.verified)?;
    }
    if args.json {
        say::document(&apply_json(args, connection, done))?;
    }
    Ok(())
}

/// A failed [`draw::run`] in the command line's words; with `can_create`, missing objects'
/// hints offer `--create-missing` after the first.
fn run_error(e: RunError, layout: &std::path::Path, can_create: bool) -> anyhow::Error {
    let drawing = || format!("drawing {}", layout.display());
    match e {
        RunError::NoAuthoring(Authored::CreateMissing) => anyhow::anyhow!(
            "--create-missing needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
        ),
        RunError::NoAuthoring(Authored::SaveScene) => anyhow::anyhow!(
            "--save-scene needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
        ),
        RunError::Create(e) => anyhow::Error::new(e).context("creating the missing scene objects"),
        RunError::Draw(e @ DrawError::Missing { .. }) if can_create => {
            let mut hints = super::remedies::hints(&e);
            hints.insert(
                1,
                "or pass --create-missing: over the ZeroMQ API vrep-maze creates them with the layout's sizes and the course's colours".into(),
            );
            super::hinted::hinted(super::remedies::message(&e), hints).context(drawing())
        }
        RunError::Draw(e) => anyhow::Error::new(e).context(drawing()),
        RunError::Save { path, source } => {
            anyhow::Error::new(source).context(format!("saving the scene to {path}"))
        }
    }
}

/// The `--json` document of a finished apply (either draw mode).
fn apply_json(args: &ApplyArgs, connection: String, done: draw::Report) -> ApplyJson {
    let report = &done.drawn;
    ApplyJson {
        format: "vrep-maze/apply".into(),
        version: REPORT_VERSION,
        layout: args.layout.display().to_string(),
        connection,
        style: report.style,
        counts: ApplyCounts::of(report),
        seconds: report.elapsed.as_secs_f64(),
        stopped_simulation: report.stopped_simulation,
        dry_run: report.dry_run,
        verified: !report.dry_run,
        created: done.created,
        saved_scene: done.saved_scene,
    }
}

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::super::{Cli, Command};
    use super::*;

    /// The connection options of `clear` as parsed from `words`.
    fn parsed(words: &[&str]) -> ConnectArgs {
        match Cli::try_parse_from(words).unwrap().command {
            Command::Clear(args) => args.scene,
            _ => unreachable!(),
        }
    }

    #[test]
    fn the_command_a_hint_shows_reaches_the_same_simulator_and_objects() {
        let words = [
            "vrep-maze",
            "clear",
            "--api",
            "zmq",
            "--port",
            "23160",
            "--parent",
            "MyMaze",
            "--timeout",
            "2.5",
        ];
        let scene = parsed(&words);
        let command = scene.command("clear");
        assert_eq!(command, words.join(" "));
        let again = parsed(&command.split(' ').collect::<Vec<_>>());
        assert_eq!(again.command("clear"), command);
        assert_eq!(
            parsed(&["vrep-maze", "clear"]).command("clear"),
            "vrep-maze clear"
        );
        let spaced = parsed(&["vrep-maze", "clear", "--line", "Green line"]);
        assert_eq!(
            spaced.command("clear"),
            "vrep-maze clear --line 'Green line'"
        );
    }
}
