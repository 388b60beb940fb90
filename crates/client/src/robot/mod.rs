//! Driving the scene's wheeled robot by its motors, with physics, in stepping mode: the
//! [`RobotPort`] a connection implements (ZeroMQ: `zmq_api::robot`; legacy:
//! `legacy::robot`), and [`drive`], which runs one route with a [`Steer`] from
//! `vrep_maze_core::robot` deciding the wheels at every simulation step. The simulation
//! advances only when this client says so, so a run does not depend on the machine's pace
//! and the same maze gives the same run.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use vrep_maze_core::robot::camera::{CameraModel, Image};
use vrep_maze_core::robot::steer::{NOTHING_RENDERS, Observation, Steer};
use vrep_maze_core::robot::wheels::{DiffDrive, Wheels};
use vrep_maze_core::robot::{Pose, wrap};
use vrep_maze_core::score::Sample;

/// The names of the robot's parts in the scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RobotNames {
    /// The robot's base (its pose is the robot's).
    pub robot: String,
    /// The left wheel's joint.
    pub left_motor: String,
    /// The right wheel's joint.
    pub right_motor: String,
    /// The forward camera (a vision sensor).
    pub camera: String,
    /// The floor (poses are in its frame).
    pub floor: String,
    /// The line template (its colour is the lines' colour).
    pub line: String,
}

/// What the scene says of the robot before a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotSurvey {
    /// Wheel radius and track, read from the wheels' shapes and the joints' places.
    pub drive: DiffDrive,
    /// The camera, when the scene has one.
    pub camera: Option<CameraModel>,
    /// The lines' colour and the floor's (0..1), when they could be read.
    pub colours: Option<([f64; 3], [f64; 3])>,
    /// The robot's pose now.
    pub pose: Pose,
}

/// One simulation step's readings.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// Simulation time, seconds.
    pub time: f64,
    /// Left and right joint angles, radians.
    pub joints: [f64; 2],
    /// The robot's true pose (always read: it is what the run is graded by).
    pub pose: Pose,
    /// The camera's image, when asked for.
    pub image: Option<Image>,
}

/// Why a robot could not be driven.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RobotError {
    /// An object the run needs is missing, or is not what it must be.
    #[error("{0}")]
    Scene(String),
    /// The connection failed or a reply was malformed.
    #[error("{0}")]
    Connection(String),
}

/// A connection that can drive a wheeled robot in stepping mode.
pub trait RobotPort {
    /// Finds the robot's parts by `names` and reads its geometry.
    fn survey(&mut self, names: &RobotNames) -> Result<RobotSurvey, RobotError>;
    /// Puts the robot at `pose` (floor frame) on the stopped simulation.
    fn place(&mut self, pose: Pose) -> Result<(), RobotError>;
    /// Readies the run on the stopped simulation: stepping mode on, the camera spared
    /// rendering unless `camera` (it is read), and the driver announced by the signal
    /// [`DRIVER_SIGNAL`] so that a `score` joins the stepping and starts the simulation.
    fn prepare(&mut self, camera: bool) -> Result<(), RobotError>;
    /// One camera frame rendered now, on the stopped simulation, or `None` where this port
    /// cannot take one before the run (its frames come with the steps).
    fn still_frame(&mut self) -> Result<Option<Image>, RobotError> {
        Ok(None)
    }
    /// Starts the simulation.
    fn start_simulation(&mut self) -> Result<(), RobotError>;
    /// Whether the simulation runs (or is paused).
    fn is_running(&mut self) -> Result<bool, RobotError>;
    /// Reads this step's readings (the image when `image`).
    fn observe(&mut self, image: bool) -> Result<Reading, RobotError>;
    /// Sets the wheels' target velocities.
    fn actuate(&mut self, wheels: Wheels) -> Result<(), RobotError>;
    /// Lets the simulation advance one step and waits for it.
    fn step(&mut self) -> Result<(), RobotError>;
    /// Ends the run whatever happened: wheels stopped, simulation stopped, stepping off,
    /// the camera's handling as it was, the signal cleared. Tries a fresh connection when
    /// this one is lost.
    fn finish(&mut self) -> Result<(), RobotError>;
}

/// The integer signal a stepping driver sets to 1 on the stopped simulation once the robot
/// is placed and stepping is on, and clears when it is done: a `score` that sees it joins
/// the stepping (so it sees every step) and may start the simulation.
pub const DRIVER_SIGNAL: &str = "vrepMaze.drive";

/// How a drive starts, ends and how long it may take.
#[derive(Debug, Clone)]
pub struct DriveOptions {
    /// Start the simulation (else wait for it to be started: by `score --start-simulation`,
    /// by the user, by a script).
    pub start_simulation: bool,
    /// Simulated seconds at most.
    pub sim_limit: f64,
    /// Wall-clock limit.
    pub wall_limit: Duration,
    /// Set (by Ctrl-C) to end the run early.
    pub interrupt: Option<Arc<AtomicBool>>,
}

/// A driven run: the robot's true poses at every step, and how it ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Driven {
    /// The true pose at every step, floor frame.
    pub samples: Vec<Sample>,
    /// `true` if the steer reached the end of its route.
    pub arrived: bool,
    /// Why the run ended early, if it did.
    pub stopped: Option<String>,
    /// Simulation steps made.
    pub steps: usize,
    /// Wall-clock seconds of the stepping.
    pub wall_time_s: f64,
    /// The steer's own belief of the pose at the end (camera: odometry and vision).
    pub belief: Option<Pose>,
}

/// Drives one route: places the robot at `start`, starts the simulation in stepping mode,
/// then at each step observes, lets `steer` decide and actuates, until the steer arrives,
/// a limit passes, an interrupt comes or the connection fails. The simulation is stopped
/// and stepping ended in every case (an error from that is returned only when the run
/// itself went well).
pub fn drive(
    port: &mut dyn RobotPort,
    steer: &mut dyn Steer,
    start: Pose,
    options: &DriveOptions,
) -> Result<Driven, RobotError> {
    port.place(start)?;
    let needs = steer.needs();
    let run = port
        .prepare(needs.image)
        .and_then(|()| dark_camera(port, needs.image))
        .and_then(|dark| match dark {
            Some(ended) => Ok(ended),
            None => started(port, options).and_then(|()| stepping(port, steer, options)),
        });
    let finished = port.finish();
    let driven = run?;
    finished?;
    Ok(driven)
}

/// The run, ended before it starts, when the camera is read and a frame taken on the
/// stopped simulation is all black: without a display a real 4.10 spends 4-5 s on each
/// frame, so the black frames the steer would wait out took 30-60 s and could pass the
/// client's reply timeout (`docs/measurements.md`, "A camera without a display").
fn dark_camera(port: &mut dyn RobotPort, camera: bool) -> Result<Option<Driven>, RobotError> {
    if !camera || !renders_nothing(port)? {
        return Ok(None);
    }
    let mut samples = Vec::new();
    add_sample(&mut samples, &port.observe(false)?);
    Ok(Some(Driven {
        samples,
        arrived: false,
        stopped: Some(NOTHING_RENDERS.into()),
        steps: 0,
        wall_time_s: 0.0,
        belief: None,
    }))
}

/// Whether a frame `port` takes on the stopped simulation ([`RobotPort::still_frame`]) is
/// all black: the camera renders nothing (`false` where the port cannot take one).
pub fn renders_nothing(port: &mut dyn RobotPort) -> Result<bool, RobotError> {
    Ok(port.still_frame()?.is_some_and(|frame| frame.is_black()))
}

/// Starts the simulation, or waits for it to start.
fn started(port: &mut dyn RobotPort, options: &DriveOptions) -> Result<(), RobotError> {
    if options.start_simulation {
        return port.start_simulation();
    }
    let began = Instant::now();
    while !port.is_running()? {
        if interrupted(options) {
            return Err(RobotError::Scene(
                "interrupted before the simulation started".into(),
            ));
        }
        if began.elapsed() >= options.wall_limit {
            return Err(RobotError::Scene(format!(
                "the simulation did not start within {} s",
                options.wall_limit.as_secs_f64()
            )));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    Ok(())
}

fn interrupted(options: &DriveOptions) -> bool {
    options
        .interrupt
        .as_ref()
        .is_some_and(|i| i.load(Ordering::SeqCst))
}

/// Adds the pose of `reading` to `samples` unless its time is not past the last one's.
fn add_sample(samples: &mut Vec<Sample>, reading: &Reading) {
    if samples.last().is_none_or(|s| reading.time > s.t) {
        samples.push(Sample {
            t: reading.time,
            x: reading.pose.x,
            y: reading.pose.y,
            yaw: reading.pose.yaw,
        });
    }
}

/// Which limit of `options` passed, if one did, at simulation `time` of a run that
/// began at `began`: the simulation limit, then the wall-clock timeout.
fn limit_passed(time: f64, began: Instant, options: &DriveOptions) -> Option<String> {
    if time >= options.sim_limit {
        return Some(format!(
            "the simulation limit of {} s passed first",
            options.sim_limit
        ));
    }
    if began.elapsed() >= options.wall_limit {
        return Some(format!(
            "the timeout of {} s passed first",
            options.wall_limit.as_secs_f64()
        ));
    }
    None
}

/// The stepping loop of [`drive`], on a started simulation.
fn stepping(
    port: &mut dyn RobotPort,
    steer: &mut dyn Steer,
    options: &DriveOptions,
) -> Result<Driven, RobotError> {
    let needs = steer.needs();
    let trace = std::env::var_os("VREP_MAZE_TRACE").is_some();
    let began = Instant::now();
    let mut samples: Vec<Sample> = Vec::new();
    let mut steps = 0usize;
    // what the last actuation and step took, for VREP_MAZE_TRACE
    let (mut last_actuate, mut last_step) = (0.0, 0.0);
    let stopped = loop {
        if interrupted(options) {
            break Some("interrupted".to_string());
        }
        let observing = Instant::now();
        let reading = match port.observe(needs.image) {
            Ok(r) => r,
            Err(e) => break Some(format!("the connection failed: {e}")),
        };
        if steps > 0 && samples.last().is_some_and(|s| reading.time < s.t) {
            break Some("the simulation was stopped by someone else".to_string());
        }
        add_sample(&mut samples, &reading);
        let observation = Observation {
            time: reading.time,
            joints: reading.joints,
            pose: needs.pose.then_some(reading.pose),
            image: reading.image,
        };
        let deciding = Instant::now();
        let wheels = match steer.decide(&observation) {
            Ok(w) => w,
            Err(why) => break Some(why),
        };
        if trace {
            eprintln!(
                "robot: step {steps} at {:.3} s observed in {:.1} ms, decided in {:.1} ms, last actuate {:.1} ms, last step {:.1} ms: wheels {:.2} {:.2}, belief {:?}, truth {:?}",
                reading.time,
                (deciding - observing).as_secs_f64() * 1000.0,
                deciding.elapsed().as_secs_f64() * 1000.0,
                last_actuate * 1000.0,
                last_step * 1000.0,
                wheels.left,
                wheels.right,
                steer.belief(),
                reading.pose
            );
        }
        if steer.arrived() {
            break None;
        }
        if let Some(why) = limit_passed(reading.time, began, options) {
            break Some(why);
        }
        let actuating = Instant::now();
        if let Err(e) = port.actuate(wheels) {
            break Some(format!("the connection failed: {e}"));
        }
        let stepping = Instant::now();
        if let Err(e) = port.step() {
            break Some(format!("the connection failed: {e}"));
        }
        last_actuate = (stepping - actuating).as_secs_f64();
        last_step = stepping.elapsed().as_secs_f64();
        steps += 1;
    };
    Ok(Driven {
        arrived: stopped.is_none() && steer.arrived(),
        stopped,
        samples,
        steps,
        wall_time_s: began.elapsed().as_secs_f64(),
        belief: steer.belief(),
    })
}

/// The heading that faces the first leg of a route from `from` (0 when it has none).
pub fn facing(from: [f64; 2], to: Option<[f64; 2]>) -> f64 {
    to.map_or(0.0, |t| wrap((t[1] - from[1]).atan2(t[0] - from[0])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use vrep_maze_core::generate::Algorithm;
    use vrep_maze_core::layout::solution::solve;
    use vrep_maze_core::layout::{GenerateSpec, Layout, build_layout, passages};
    use vrep_maze_core::maze::Grid;
    use vrep_maze_core::robot::camera::LineColour;
    use vrep_maze_core::robot::localize::LineMap;
    use vrep_maze_core::robot::route::{Gains, legs};
    use vrep_maze_core::robot::steer::{CameraSteer, Eye, PoseSteer};

    const COURSE: DiffDrive = DiffDrive {
        wheel_radius: 0.04,
        track: 0.18,
    };

    /// A world without a simulator: the robot moves by its wheels with 3 % slip on the
    /// right wheel (so odometry drifts), its camera (64 x 64, the course camera's mount)
    /// renders the layout's lines green on a grey floor.
    struct World {
        map: LineMap,
        camera: CameraModel,
        pose: Pose,
        joints: [f64; 2],
        wheels: Wheels,
        time: f64,
        running: bool,
        finished: bool,
        /// Whether the camera renders (else its images are black: no display).
        renders: bool,
        /// Whether the simulation was ever started.
        started: bool,
    }

    impl World {
        fn new(layout: &Layout) -> Self {
            Self {
                map: LineMap::of(layout).unwrap(),
                camera: CameraModel {
                    width: 64,
                    height: 64,
                    view_angle: 60f64.to_radians(),
                    mount: [
                        0.0, 0.5, 0.866_025, 0.105, 1.0, 0.0, 0.0, 0.0, 0.0, 0.866_025, -0.5, 0.04,
                    ],
                    floor_z: -0.06,
                },
                pose: Pose::default(),
                joints: [0.0; 2],
                wheels: Wheels::default(),
                time: 0.0,
                running: false,
                finished: false,
                renders: true,
                started: false,
            }
        }

        fn render(&self) -> Image {
            if !self.renders {
                return Image::new(64, 64, vec![0; 64 * 64 * 3]).unwrap();
            }
            let mut rgb = Vec::with_capacity(64 * 64 * 3);
            for j in 0..64 {
                for i in 0..64 {
                    let on = self
                        .camera
                        .ground(i, j)
                        .is_some_and(|p| self.map.on_lines(self.pose, &[p]) == Some(1.0));
                    rgb.extend(if on { [0, 51, 0] } else { [51, 51, 51] });
                }
            }
            Image::new(64, 64, rgb).unwrap()
        }
    }

    impl RobotPort for World {
        fn survey(&mut self, _: &RobotNames) -> Result<RobotSurvey, RobotError> {
            Ok(RobotSurvey {
                drive: COURSE,
                camera: Some(self.camera.clone()),
                colours: Some(([0.0, 1.0, 0.0], [1.0, 1.0, 1.0])),
                pose: self.pose,
            })
        }
        fn place(&mut self, pose: Pose) -> Result<(), RobotError> {
            self.pose = pose;
            Ok(())
        }
        fn prepare(&mut self, _: bool) -> Result<(), RobotError> {
            Ok(())
        }
        fn still_frame(&mut self) -> Result<Option<Image>, RobotError> {
            Ok(Some(self.render()))
        }
        fn start_simulation(&mut self) -> Result<(), RobotError> {
            self.running = true;
            self.started = true;
            Ok(())
        }
        fn is_running(&mut self) -> Result<bool, RobotError> {
            Ok(self.running)
        }
        fn observe(&mut self, image: bool) -> Result<Reading, RobotError> {
            Ok(Reading {
                time: self.time,
                joints: self.joints.map(wrap),
                pose: self.pose,
                image: image.then(|| self.render()),
            })
        }
        fn actuate(&mut self, wheels: Wheels) -> Result<(), RobotError> {
            self.wheels = wheels;
            Ok(())
        }
        fn step(&mut self) -> Result<(), RobotError> {
            let dt = 0.05;
            let (left, right) = (self.wheels.left * dt, self.wheels.right * dt * 0.97);
            self.pose = COURSE.odometry(self.pose, left, right);
            self.joints[0] += left;
            self.joints[1] += self.wheels.right * dt;
            self.time += dt;
            Ok(())
        }
        fn finish(&mut self) -> Result<(), RobotError> {
            self.running = false;
            self.finished = true;
            Ok(())
        }
    }

    fn maze_3x3() -> Layout {
        build_layout(&GenerateSpec::course(
            Grid::new(3, 3).unwrap(),
            Algorithm::Dfs,
            42,
        ))
        .unwrap()
    }

    fn options() -> DriveOptions {
        DriveOptions {
            start_simulation: true,
            sim_limit: 300.0,
            wall_limit: Duration::from_secs(600),
            interrupt: None,
        }
    }

    /// The route and where the robot starts on it.
    fn route(layout: &Layout) -> (Vec<vrep_maze_core::robot::route::Leg>, Pose) {
        let grid = Grid::new(3, 3).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let path = solve(layout, &maze, None).unwrap();
        let legs = legs(&path.waypoints);
        let first = path.waypoints[0];
        let yaw = facing([first.x, first.y], legs.first().map(|l| l.to));
        (
            legs,
            Pose {
                x: first.x,
                y: first.y,
                yaw,
            },
        )
    }

    #[test]
    fn steering_by_pose_reaches_the_end_and_the_run_is_stopped() {
        let layout = maze_3x3();
        let (legs, start) = route(&layout);
        let end = legs.last().unwrap().to;
        let mut world = World::new(&layout);
        let mut steer = PoseSteer::new(legs, COURSE, Gains::default());
        let driven = drive(&mut world, &mut steer, start, &options()).unwrap();
        assert!(driven.arrived, "{:?}", driven.stopped);
        assert!((world.pose.x - end[0]).hypot(world.pose.y - end[1]) < 0.05);
        assert_eq!(driven.samples.len(), driven.steps + 1);
        assert!(world.finished && !world.running);
    }

    /// With a slipping wheel, odometry alone would drift off the lines; the camera keeps
    /// the belief, and so the robot, on them.
    #[test]
    fn steering_by_camera_keeps_to_the_lines_with_a_slipping_wheel() {
        let layout = maze_3x3();
        let (legs, start) = route(&layout);
        let end = legs.last().unwrap().to;
        let mut world = World::new(&layout);
        let eye = Eye {
            camera: world.camera.clone(),
            colour: LineColour::new([0.0, 1.0, 0.0], [1.0, 1.0, 1.0]).unwrap(),
            map: LineMap::of(&layout).unwrap(),
        };
        let gains = Gains {
            speed: 0.3,
            ..Gains::default()
        };
        let mut steer = CameraSteer::new(legs.clone(), COURSE, gains, eye, start);
        let driven = drive(&mut world, &mut steer, start, &options()).unwrap();
        assert!(driven.arrived, "{:?}", driven.stopped);
        assert!(
            (world.pose.x - end[0]).hypot(world.pose.y - end[1]) < 0.1,
            "ended at {:?}, the end is {end:?}",
            world.pose
        );
        let map = LineMap::of(&layout).unwrap();
        let off = driven
            .samples
            .iter()
            .filter(|s| {
                let at = Pose {
                    x: s.x,
                    y: s.y,
                    yaw: s.yaw,
                };
                map.on_lines(at, &[[0.0, 0.0]]) != Some(1.0)
            })
            .count();
        assert!(
            off * 20 < driven.samples.len(),
            "{off} of {} samples off the lines",
            driven.samples.len()
        );
    }

    #[test]
    fn an_interrupt_ends_the_run_and_still_stops_the_simulation() {
        let layout = maze_3x3();
        let (legs, start) = route(&layout);
        let mut world = World::new(&layout);
        let mut steer = PoseSteer::new(legs, COURSE, Gains::default());
        let options = DriveOptions {
            interrupt: Some(Arc::new(AtomicBool::new(true))),
            ..options()
        };
        let driven = drive(&mut world, &mut steer, start, &options).unwrap();
        assert_eq!(driven.stopped.as_deref(), Some("interrupted"));
        assert!(!driven.arrived);
        assert!(world.finished && !world.running);
    }

    #[test]
    fn a_camera_that_renders_nothing_ends_the_run_before_the_simulation_starts() {
        let layout = maze_3x3();
        let (legs, start) = route(&layout);
        let mut world = World::new(&layout);
        world.renders = false;
        let eye = Eye {
            camera: world.camera.clone(),
            colour: LineColour::new([0.0, 1.0, 0.0], [1.0, 1.0, 1.0]).unwrap(),
            map: LineMap::of(&layout).unwrap(),
        };
        let mut steer = CameraSteer::new(legs, COURSE, Gains::default(), eye, start);
        let driven = drive(&mut world, &mut steer, start, &options()).unwrap();
        assert_eq!(driven.stopped.as_deref(), Some(NOTHING_RENDERS));
        assert_eq!((driven.steps, driven.samples.len()), (0, 1));
        assert!(!driven.arrived && !world.started && world.finished);
    }
}
