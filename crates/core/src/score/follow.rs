//! Following a robot while the simulation runs: the [`Follower`] port a connection to a
//! simulator implements (legacy: `vrep_maze_client::legacy::follow`, ZeroMQ:
//! `vrep_maze_client::zmq_api::follow`), and [`follow`], which waits for the simulation,
//! collects one [`Sample`] per simulation step it sees and decides when the run is over. It never
//! changes the scene; it starts and stops the simulation only when asked.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector3};

use super::{GradeOptions, Grader, Sample};

/// Why following failed or stopped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FollowError {
    /// The scene has no object of that name.
    #[error("the scene has no object named `{0}`")]
    NoSuchObject(String),
    /// The connection failed or a reply was malformed.
    #[error("{0}")]
    Connection(String),
}

impl FollowError {
    /// The connection failed: `error` as it says it.
    pub fn lost(error: impl std::fmt::Display) -> FollowError {
        FollowError::Connection(error.to_string())
    }

    /// The reply to `what` could not be understood.
    pub fn malformed(what: &str) -> FollowError {
        FollowError::Connection(format!("malformed reply to {what}"))
    }
}

/// What one look at the simulator found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Look {
    /// The robot's pose at a simulation step (maybe one already seen).
    Pose(Sample),
    /// The simulation runs (or is paused) but no pose has arrived yet.
    Nothing,
    /// The simulation is stopped.
    Stopped,
}

/// A connection that can watch one object's pose relative to another as the simulation
/// runs. Implementations read only; [`Follower::set_running`] is the one change they make.
pub trait Follower {
    /// Finds the robot and the floor by name; a missing one is [`FollowError::NoSuchObject`].
    fn find(&mut self, robot: &str, floor: &str) -> Result<(), FollowError>;
    /// Whether the simulation is running or paused (not stopped).
    fn is_running(&mut self) -> Result<bool, FollowError>;
    /// Starts (`true`) or stops (`false`) the simulation.
    fn set_running(&mut self, run: bool) -> Result<(), FollowError>;
    /// The robot's latest pose with the simulation time it was read at, or what keeps it
    /// from being known. Called about every [`POLL`].
    fn look(&mut self) -> Result<Look, FollowError>;
    /// Ends whatever the follower set up (streams) and closes the connection.
    fn close(self: Box<Self>);
    /// Whether the robot has joints (wheels) while no stepping driver has announced itself
    /// yet: `score --start-simulation` then waits a while for one ([`DRIVER_WAIT`]).
    /// Connections that cannot tell say `false`.
    fn awaits_driver(&mut self) -> Result<bool, FollowError> {
        Ok(false)
    }
    /// Joins the stepping of a driver that announced itself (`drive --wheels`), so that the
    /// simulation waits for this follower at every step and no step passes unseen; `false`
    /// when there is none (or the connection cannot step).
    fn join_driver(&mut self) -> Result<bool, FollowError> {
        Ok(false)
    }
    /// Lets a joined simulation advance one step, and waits for it.
    fn step(&mut self) -> Result<(), FollowError> {
        Ok(())
    }
    /// Leaves a joined driver's stepping (the driver goes on alone).
    fn leave(&mut self) -> Result<(), FollowError> {
        Ok(())
    }
}

/// How long `score --start-simulation` waits for a stepping driver to place a robot that has
/// wheels before it starts the simulation anyway (for a robot driven by a script of its own).
pub const DRIVER_WAIT: Duration = Duration::from_secs(10);

/// How often [`follow`] looks: well under one 50 ms simulation step, so no step is missed
/// where the protocol can show every step.
pub const POLL: Duration = Duration::from_millis(10);

/// When a run is over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Until {
    /// When the robot reaches `End` (or the simulation stops first: then incomplete).
    End,
    /// When the simulation stops.
    Stop,
}

/// How to follow a run.
#[derive(Debug, Clone)]
pub struct FollowOptions {
    /// The robot's object name.
    pub robot: String,
    /// The floor's object name (poses are relative to it).
    pub floor: String,
    /// When the run is over.
    pub until: Until,
    /// Wall-clock limit for the whole run, waiting for the simulation included.
    pub timeout: Duration,
    /// Start the simulation if it is stopped, and stop it when the run is over.
    pub start_simulation: bool,
    /// Set (e.g. by Ctrl-C) to end the run early; the report is then incomplete.
    pub interrupt: Option<Arc<AtomicBool>>,
    /// How the run is graded (the size of `End`'s footprint decides when it is reached).
    pub grade: GradeOptions,
}

/// A followed run: the samples, one per simulation step seen, and how it ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Followed {
    /// The robot's poses, by increasing simulation time.
    pub samples: Vec<Sample>,
    /// `None` if the run ended as `until` asks; else why it ended early.
    pub incomplete: Option<String>,
    /// Wall-clock seconds from the first sample to reaching `End` (or to the last sample).
    pub wall_time_s: Option<f64>,
}

/// Follows the robot of `options` on `follower`: finds it (an error before any waiting),
/// starts the simulation if asked, waits for it to run (an error if it does not within
/// the timeout: nothing was changed), then samples every step it sees until the run is
/// over. A simulation that stops early, a dropped connection, the timeout or an interrupt
/// end the run with a partial result.
pub fn follow(
    follower: &mut dyn Follower,
    grader: &Grader,
    options: &FollowOptions,
) -> Result<Followed, FollowError> {
    let deadline = Instant::now() + options.timeout;
    follower.find(&options.robot, &options.floor)?;
    let Started {
        joined,
        started_here,
    } = start_simulation(follower, options, deadline)?;
    let mut run = Run::default();
    let incomplete = sample_run(follower, grader, options, deadline, joined, &mut run);
    if joined {
        // a failure here changes nothing of the run seen; the driver's stop ends stepping
        let _ = follower.leave();
    }
    if started_here {
        // the run is over either way; a failure to stop is reported as one more reason
        if let Err(e) = follower.set_running(false) {
            let why = format!("the simulation could not be stopped: {e}");
            return Ok(run.finish(Some(
                incomplete.map_or(why.clone(), |i| format!("{i}; {why}")),
            )));
        }
    }
    Ok(run.finish(incomplete))
}

/// How [`start_simulation`] left the simulation.
struct Started {
    /// In step with a driver: every step is seen, and the driver stops the simulation.
    joined: bool,
    /// Started by this follower (without a driver): it stops the simulation at the end.
    started_here: bool,
}

/// Whether the interrupt of `options` was raised.
fn interrupted(options: &FollowOptions) -> bool {
    options
        .interrupt
        .as_ref()
        .is_some_and(|i| i.load(Ordering::SeqCst))
}

/// Gets the simulation running before `deadline`: waits a while for a driver to start it
/// if asked to start it, joins a driver's stepping, starts it if asked, then waits for it
/// to run (an error if it does not: nothing was changed).
fn start_simulation(
    follower: &mut dyn Follower,
    options: &FollowOptions,
    deadline: Instant,
) -> Result<Started, FollowError> {
    if options.start_simulation && !follower.is_running()? {
        let wait = (Instant::now() + DRIVER_WAIT).min(deadline);
        while follower.awaits_driver()? && Instant::now() < wait && !interrupted(options) {
            if follower.is_running()? {
                break;
            }
            std::thread::sleep(POLL * 5);
        }
    }
    // in step with a driver, every step is seen; the driver, not this follower, stops
    // the simulation at the end of its run
    let joined = follower.join_driver()?;
    let mut started_here = false;
    if options.start_simulation && !follower.is_running()? {
        follower.set_running(true)?;
        started_here = !joined;
    }
    while !follower.is_running()? {
        if Instant::now() >= deadline || interrupted(options) {
            return Err(FollowError::Connection(format!(
                "the simulation did not start within {} s; nothing was changed",
                options.timeout.as_secs_f64()
            )));
        }
        std::thread::sleep(POLL * 5);
    }
    Ok(Started {
        joined,
        started_here,
    })
}

/// Samples every step seen into `run` (stepping the simulation when `joined` to a
/// driver) until the run is over: `None` if it ended as `options.until` asks, else why it
/// ended early.
fn sample_run(
    follower: &mut dyn Follower,
    grader: &Grader,
    options: &FollowOptions,
    deadline: Instant,
    joined: bool,
    run: &mut Run,
) -> Option<String> {
    loop {
        if interrupted(options) {
            break Some("interrupted".to_string());
        }
        if Instant::now() >= deadline {
            break Some(format!(
                "the timeout of {} s passed first",
                options.timeout.as_secs_f64()
            ));
        }
        match follower.look() {
            Err(e) => break Some(format!("connection lost: {e}")),
            Ok(Look::Stopped) => {
                break match options.until {
                    Until::Stop => None,
                    Until::End => {
                        Some("the simulation stopped before the robot reached End".into())
                    }
                };
            }
            Ok(Look::Nothing) => {}
            Ok(Look::Pose(sample)) => {
                if run.add(sample)
                    && options.until == Until::End
                    && grader.in_end_at(&sample, &options.grade)
                {
                    run.reached = Some(Instant::now());
                    break None;
                }
            }
        }
        if joined {
            if let Err(e) = follower.step() {
                break Some(format!("connection lost: {e}"));
            }
        } else {
            std::thread::sleep(POLL);
        }
    }
}

/// The samples gathered so far and the wall-clock times that matter.
#[derive(Debug, Default)]
struct Run {
    samples: Vec<Sample>,
    first: Option<Instant>,
    last: Option<Instant>,
    reached: Option<Instant>,
}

impl Run {
    /// Keeps `sample` if it is from a later simulation step than the last one kept.
    fn add(&mut self, sample: Sample) -> bool {
        if self.samples.last().is_some_and(|s| sample.t <= s.t) {
            return false;
        }
        let now = Instant::now();
        self.first.get_or_insert(now);
        self.last = Some(now);
        self.samples.push(sample);
        true
    }

    fn finish(self, incomplete: Option<String>) -> Followed {
        let wall = self
            .first
            .zip(self.reached.or(self.last))
            .map(|(a, b)| b.duration_since(a).as_secs_f64());
        Followed {
            samples: self.samples,
            incomplete,
            wall_time_s: wall,
        }
    }
}

/// The heading of a rotation: the angle of its x axis projected on the floor, radians in
/// (-pi, pi] (the robot's yaw when it stands upright).
pub fn heading(rotation: &UnitQuaternion<f64>) -> f64 {
    let x = rotation * Vector3::x();
    x.y.atan2(x.x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;
    use std::collections::VecDeque;

    /// A follower that plays back scripted looks; `running` until the script says stopped.
    struct Script {
        looks: VecDeque<Result<Look, FollowError>>,
        running: bool,
        starts: Vec<bool>,
        has_robot: bool,
    }

    impl Follower for Script {
        fn find(&mut self, robot: &str, _: &str) -> Result<(), FollowError> {
            if self.has_robot {
                Ok(())
            } else {
                Err(FollowError::NoSuchObject(robot.into()))
            }
        }
        fn is_running(&mut self) -> Result<bool, FollowError> {
            Ok(self.running)
        }
        fn set_running(&mut self, run: bool) -> Result<(), FollowError> {
            self.starts.push(run);
            self.running = run;
            Ok(())
        }
        fn look(&mut self) -> Result<Look, FollowError> {
            let look = self.looks.pop_front().unwrap_or(Ok(Look::Stopped));
            if look == Ok(Look::Stopped) {
                self.running = false;
            }
            look
        }
        fn close(self: Box<Self>) {}
    }

    fn script(looks: Vec<Result<Look, FollowError>>, running: bool) -> Script {
        Script {
            looks: looks.into(),
            running,
            starts: vec![],
            has_robot: true,
        }
    }

    /// The 3 x 1 course maze: cells at floor x = -1, 0, 1; End's footprint from x = 0.5.
    fn grader() -> Grader {
        let grid = Grid::new(3, 1).unwrap();
        Grader::new(&build_layout(&GenerateSpec::course(grid, Algorithm::Dfs, 1)).unwrap()).unwrap()
    }

    fn at(t: f64, x: f64) -> Result<Look, FollowError> {
        Ok(Look::Pose(Sample {
            t,
            x,
            y: 0.0,
            yaw: 0.0,
        }))
    }

    fn options(until: Until, start: bool) -> FollowOptions {
        FollowOptions {
            robot: "Robot".into(),
            floor: "Floor".into(),
            until,
            timeout: Duration::from_secs(30),
            start_simulation: start,
            interrupt: None,
            grade: GradeOptions::default(),
        }
    }

    #[test]
    fn until_end_stops_at_the_first_sample_inside_end_and_skips_repeated_steps() {
        let looks = vec![
            Ok(Look::Nothing),
            at(0.05, -1.0),
            at(0.05, -1.0),
            at(0.1, 0.0),
            at(0.15, 0.6),
            at(0.2, 1.0),
        ];
        let mut f = script(looks, false);
        let run = follow(&mut f, &grader(), &options(Until::End, true)).unwrap();
        assert_eq!(run.incomplete, None);
        let times: Vec<f64> = run.samples.iter().map(|s| s.t).collect();
        assert_eq!(times, [0.05, 0.1, 0.15]);
        assert_eq!(f.starts, [true, false], "started, then stopped, as asked");
        assert!(run.wall_time_s.is_some());
    }

    #[test]
    fn a_stop_before_end_is_incomplete_with_until_end_and_complete_with_until_stop() {
        for (until, incomplete) in [(Until::End, true), (Until::Stop, false)] {
            let mut f = script(vec![at(0.05, -1.0), at(0.1, -0.5), Ok(Look::Stopped)], true);
            let run = follow(&mut f, &grader(), &options(until, false)).unwrap();
            assert_eq!(run.samples.len(), 2);
            assert_eq!(run.incomplete.is_some(), incomplete, "{until:?}: {run:?}");
            assert!(
                f.starts.is_empty(),
                "a simulation it did not start is left alone"
            );
        }
    }

    #[test]
    fn a_dropped_connection_keeps_the_samples_and_says_why() {
        let looks = vec![
            at(0.05, -1.0),
            Err(FollowError::Connection(
                "the simulator closed the connection".into(),
            )),
        ];
        let run = follow(
            &mut script(looks, true),
            &grader(),
            &options(Until::End, false),
        )
        .unwrap();
        assert_eq!(run.samples.len(), 1);
        assert!(run.incomplete.unwrap().contains("closed the connection"));
    }

    #[test]
    fn a_missing_robot_is_an_error_before_any_waiting() {
        let mut f = script(vec![], false);
        f.has_robot = false;
        let e = follow(&mut f, &grader(), &options(Until::End, true)).unwrap_err();
        assert_eq!(e, FollowError::NoSuchObject("Robot".into()));
        assert!(f.starts.is_empty(), "nothing was started");
    }

    #[test]
    fn a_simulation_that_never_starts_is_an_error() {
        let mut f = script(vec![], false);
        let interrupt = Arc::new(AtomicBool::new(true));
        let opts = FollowOptions {
            interrupt: Some(interrupt),
            ..options(Until::End, false)
        };
        let e = follow(&mut f, &grader(), &opts).unwrap_err();
        assert!(e.to_string().contains("did not start"), "{e}");
    }

    #[test]
    fn the_heading_is_the_yaw_of_an_upright_robot() {
        let q = UnitQuaternion::from_euler_angles(0.0, 0.0, 2.5);
        assert!((heading(&q) - 2.5).abs() < 1e-12);
    }
}
