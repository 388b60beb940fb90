//! `vrep-maze score`: follow a robot while the simulation runs and grade its run against
//! the maze (see [`crate::score`]). Reads only; starts and stops the simulation only with
//! `--start-simulation`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::{Context, Result};

use super::apply::ConnectArgs;
use super::connect::RawClient;
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::output::write_output;
use super::reports::ScoreJson;
use crate::layout::Layout;
use crate::legacy::follow::LegacyFollower;
use crate::score::follow::{FollowError, FollowOptions, Follower, Until, follow};
use crate::score::{DEFAULT_ROBOT_RADIUS, GradeOptions, Grader, Report, Sample, trajectory};
use crate::zmq_api::follow::ZmqFollower;

/// Exit code of a run that ended early (the simulation stopped before `End` with `--until
/// end`, the connection dropped, or `--timeout` passed), or was sampled too sparsely to
/// grade: the report is partial.
pub const INCOMPLETE_EXIT_CODE: u8 = 3;

/// Options of `score`.
#[derive(Debug, clap::Args)]
#[command(
    mut_arg("timeout", |a| a.long("reply-timeout").help("Seconds to wait for each reply (more than 0, at most a day)")),
    after_help = "Examples:\n  vrep-maze score maze.json                       # wait for the simulation, follow Robot to End\n  vrep-maze score maze.json --start-simulation --json > report.json\n  vrep-maze score maze.json --until stop --trajectory run.csv\n\nExit codes: 0 complete, 1 error (nothing followed), 2 usage, 3 incomplete (a partial report, or samples too far apart to grade), 130 interrupted."
)]
pub struct ScoreArgs {
    /// The layout the robot drives through.
    pub layout: PathBuf,
    /// The robot's object (its centre is graded).
    #[arg(long, default_value = "Robot")]
    pub robot: String,
    /// Where the simulator is and what its objects are called (as for `apply`).
    #[command(flatten)]
    pub scene: ConnectArgs,
    /// Start the simulation if it is stopped, and stop it when the run is over.
    #[arg(long)]
    pub start_simulation: bool,
    /// Wall-clock seconds for the whole run, waiting for the simulation to start included.
    #[arg(long = "timeout", value_name = "SECS", default_value_t = 600.0)]
    pub run_timeout: f64,
    /// When the run is over: when the robot reaches End, or when the simulation stops.
    #[arg(long, value_enum, default_value = "end")]
    pub until: Until,
    /// The robot's radius in metres, for wall contacts (wall mazes).
    #[arg(long, value_name = "M", default_value_t = DEFAULT_ROBOT_RADIUS)]
    pub robot_radius: f64,
    /// Side of End's square footprint in metres [default: the cell size, the course's 1 m
    /// marker].
    #[arg(long, value_name = "M")]
    pub end_size: Option<f64>,
    /// Print the report as JSON (schema: schema/score-report.schema.json).
    #[arg(long)]
    pub json: bool,
    /// Also write the followed trajectory here (CSV: t,x,y,yaw; `-` for standard output).
    #[arg(long, value_name = "run.csv")]
    pub trajectory: Option<PathBuf>,
}

/// A graded run: the report and the samples it was graded from.
#[derive(Debug, Clone)]
pub struct Scored {
    /// The grade, marked incomplete when the run ended early.
    pub report: Report,
    /// The robot's poses, one per simulation step seen (`Floor` frame).
    pub samples: Vec<Sample>,
}

impl ScoreArgs {
    /// Checks the options and `layout`, connects, follows the robot and grades its run
    /// (what `vrep-maze score` does before printing). `connected` is set once the
    /// connection is made; setting `interrupt` ends the run early (then incomplete).
    pub fn score(
        &self,
        layout: &Layout,
        interrupt: Arc<AtomicBool>,
        connected: &AtomicBool,
    ) -> Result<Scored> {
        let grader = self.grader(layout)?;
        let mut follower = connect(&self.scene, &interrupt)?;
        connected.store(true, Ordering::SeqCst);
        let scored = self.follow(follower.as_mut(), &grader, interrupt);
        follower.close();
        scored
    }

    /// As [`ScoreArgs::score`], over a follower already connected (a session's: it is left
    /// open); the connection options are not used.
    pub fn score_over(
        &self,
        follower: &mut dyn Follower,
        layout: &Layout,
        interrupt: Arc<AtomicBool>,
    ) -> Result<Scored> {
        let grader = self.grader(layout)?;
        self.follow(follower, &grader, interrupt)
    }

    /// The options and `layout` checked, and the grader of runs through `layout`.
    fn grader(&self, layout: &Layout) -> Result<Grader> {
        // the maze's roles on one name are conflicting options here too
        self.scene.check_roles()?;
        super::usage::ensure_usage!(
            self.run_timeout.is_finite() && self.run_timeout > 0.0 && self.run_timeout <= 86_400.0,
            "--timeout must be a number of seconds, more than 0 and at most a day, got {}",
            self.run_timeout
        );
        super::usage::ensure_usage!(
            self.robot_radius.is_finite() && (0.0..=100.0).contains(&self.robot_radius),
            "--robot-radius must be in 0..=100 m, got {}",
            self.robot_radius
        );
        super::usage::ensure_usage!(
            self.end_size
                .is_none_or(|s| s.is_finite() && s > 0.0 && s <= 1000.0),
            "--end-size must be more than 0 and at most 1000 m"
        );
        crate::validate::checked(layout).context("nothing was scored")?;
        Grader::new(layout).map_err(|e| anyhow::anyhow!("{e}"))
    }

    /// Finds the robot, follows its run over `follower` and grades it.
    fn follow(
        &self,
        follower: &mut dyn Follower,
        grader: &Grader,
        interrupt: Arc<AtomicBool>,
    ) -> Result<Scored> {
        let grade = GradeOptions {
            robot_radius: self.robot_radius,
            end_size: self.end_size,
        };
        let options = FollowOptions {
            robot: self.robot.clone(),
            floor: self.scene.floor.clone(),
            until: self.until,
            timeout: Duration::from_secs_f64(self.run_timeout),
            start_simulation: self.start_simulation,
            interrupt: Some(interrupt),
            grade,
        };
        // a missing robot is said at once, before any wait for the simulation
        if let Err(e) = follower.find(&self.robot, &self.scene.floor) {
            return Err(missing_robot(e, &self.robot)).context("nothing was scored");
        }
        if !self.start_simulation {
            eprintln!(
                "waiting for the simulation to run (at most {} s) ...",
                self.run_timeout
            );
        }
        let followed = follow(follower, grader, &options).context("nothing was scored")?;
        let mut report = grader.grade(&followed.samples, &grade);
        report.followed(followed.incomplete, followed.wall_time_s);
        Ok(Scored {
            report,
            samples: followed.samples,
        })
    }
}

/// Runs `score`.
pub fn run(args: ScoreArgs) -> Result<ExitCode> {
    let layout = crate::layout::read_layout(&args.layout)?;
    let interrupt = Interrupt::install()?;
    let Scored { report, samples } = args
        .score(&layout, interrupt.shared(), &AtomicBool::new(false))
        .with_context(|| args.layout.display().to_string())?;
    if let Some(path) = &args.trajectory {
        let csv = trajectory::to_csv(&samples);
        write_output(Some(path), |w| w.write_all(csv.as_bytes()))?;
    }
    let text = if args.json {
        serde_json::to_string_pretty(&ScoreJson::of(&report))? + "\n"
    } else {
        describe(&report, &hints(&report))
    };
    write_output(None, |w| w.write_all(text.as_bytes()))?;
    Ok(exit_code(&report, &interrupt))
}

/// The exit code of a graded run: 0 complete, 130 interrupted, 3 otherwise (partial).
pub(super) fn exit_code(report: &Report, interrupt: &Interrupt) -> ExitCode {
    if report.complete {
        ExitCode::SUCCESS
    } else if interrupt.requested() {
        ExitCode::from(INTERRUPTED_EXIT_CODE)
    } else {
        ExitCode::from(INCOMPLETE_EXIT_CODE)
    }
}

/// `error` with what to do when it is the missing robot `robot`: name the robot, or give the
/// emulator one.
fn missing_robot(error: FollowError, robot: &str) -> anyhow::Error {
    match error {
        FollowError::NoSuchObject(name) if name == robot => super::hinted::hinted(
            FollowError::NoSuchObject(name),
            vec![
                "pass --robot NAME with the name of your robot's object in the scene".into(),
                "without a robot of your own: `vrep-maze drive LAYOUT --api zmq &` adds one named Robot at Start and drives it along the solution while the simulation runs (or `vrep-maze serve --robot PATH.csv` drives one along a path file)".into(),
            ],
        ),
        other => anyhow::Error::new(other),
    }
}

/// Connects a follower over the API `args` chooses (auto: legacy briefly, then ZeroMQ), as
/// `apply` connects; setting `stop` (Ctrl-C) ends the connection wait.
fn connect(args: &ConnectArgs, stop: &AtomicBool) -> Result<Box<dyn Follower>> {
    Ok(match args.client_until(Some(stop))? {
        RawClient::Legacy(client) => Box::new(LegacyFollower::new(client)),
        RawClient::Zmq(client) => Box::new(ZmqFollower::new(client)),
    })
}

impl ScoreJson {
    /// The `--json` document of `report`, with its hints.
    pub fn of(report: &Report) -> ScoreJson {
        ScoreJson {
            report: report.clone(),
            hints: hints(report),
        }
    }
}

/// What to do so that a run like the one `report` grades can be graded: for one sampled too
/// sparsely, a robot that moves in steps the scorer sees.
fn hints(report: &Report) -> Vec<String> {
    if report.sampling.is_dense() {
        return Vec::new();
    }
    vec![
        "`vrep-maze drive` moves its robot by remote calls, which a simulator without real time outruns (a headless CoppeliaSim by some 300 times): run it with --real-time".into(),
        "or drive a robot by its wheels in stepping mode (`vrep-maze drive --wheels`), where the simulation waits for its controller at every step".into(),
    ]
}

/// The report for a terminal, with `hints` (what to do about it) last.
pub(super) fn describe(r: &Report, hints: &[String]) -> String {
    use std::fmt::Write as _;
    let m = |v: f64| format!("{v:.3} m");
    let mut s = String::new();
    let _ = match &r.incomplete_reason {
        None => writeln!(s, "run: complete"),
        Some(why) => writeln!(s, "run: INCOMPLETE ({why})"),
    };
    let _ = match (r.time_s, r.wall_time_s) {
        (Some(t), Some(w)) => writeln!(
            s,
            "reached End: yes, at {t:.2} s simulation time ({w:.1} s wall time)"
        ),
        (Some(t), None) => writeln!(s, "reached End: yes, at {t:.2} s simulation time"),
        _ => writeln!(s, "reached End: no"),
    };
    let to_end = r
        .path_to_end_m
        .map_or(String::new(), |p| format!(" ({} to End)", m(p)));
    let shortest = match (r.shortest_length_m, r.start_cell) {
        (Some(l), Some([x, y])) => format!("shortest {} from cell ({x},{y})", m(l)),
        _ => "shortest unknown (the robot started outside the maze)".into(),
    };
    let _ = writeln!(s, "path: {} driven{to_end}; {shortest}", m(r.path_length_m));
    let _ = match r.spl {
        Some(spl) => writeln!(s, "SPL: {spl:.3}"),
        None if !r.sampling.is_dense() => writeln!(s, "SPL: none (sampled too sparsely to grade)"),
        None => writeln!(s, "SPL: unknown"),
    };
    let _ = writeln!(
        s,
        "cells: {} visited, {} revisits",
        r.cells_visited, r.cells_revisited
    );
    if let Some(l) = &r.line {
        let _ = writeln!(
            s,
            "line: {} mean, {} max from the line; {:.2} s more than half a line width off it",
            m(l.mean_distance_m),
            m(l.max_distance_m),
            l.time_off_line_s
        );
    }
    if let Some(w) = &r.walls {
        let _ = writeln!(
            s,
            "walls: closest approach {} (robot radius {}), {} contact(s)",
            m(w.closest_approach_m),
            m(w.robot_radius_m),
            w.contacts
        );
    }
    let span = match (r.first_time_s, r.last_time_s) {
        (Some(a), Some(b)) => format!(" (t = {a:.2} .. {b:.2} s)"),
        _ => String::new(),
    };
    let apart = match r.sampling.largest_jump_at_s {
        Some(_) => format!(", at most {} apart", m(r.sampling.largest_jump_m)),
        None => String::new(),
    };
    let _ = writeln!(
        s,
        "samples: {}{span}{apart}; {} off the floor, {} off the grid",
        r.samples, r.samples_off_floor, r.samples_off_grid
    );
    for hint in hints {
        let _ = writeln!(s, "hint: {hint}");
    }
    s
}
