//! The two ways `drive --wheels` steers, behind one [`Steer`] trait: [`PoseSteer`] follows
//! the solution from the simulator's ground truth; [`CameraSteer`] does the course's exercise
//! from the camera and the wheels' joint angles alone (odometry, kept on the lines by what
//! the camera sees, see [`super::localize`]), never reading where the robot really is.

use super::camera::{CameraModel, Image, LineColour};
use super::localize::LineMap;
use super::route::{Follower, Gains, Leg};
use super::wheels::{DiffDrive, Wheels};
use super::{Pose, wrap};

/// What the robot's sensors gave at one simulation step.
#[derive(Debug, Clone, PartialEq)]
pub struct Observation {
    /// Simulation time, seconds.
    pub time: f64,
    /// The left and right wheel joints' angles, radians (cyclic joints wrap).
    pub joints: [f64; 2],
    /// The robot's true pose in the floor frame: given only to a steer whose
    /// [`Needs::pose`] is set.
    pub pose: Option<Pose>,
    /// The camera's image: given only to a steer whose [`Needs::image`] is set.
    pub image: Option<Image>,
}

/// What a steer reads besides the joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Needs {
    /// The true pose.
    pub pose: bool,
    /// The camera image.
    pub image: bool,
}

/// A way of steering: one decision a simulation step.
pub trait Steer {
    /// What it reads.
    fn needs(&self) -> Needs;
    /// The wheel speeds for the next step. An error when the observation lacks what
    /// [`Steer::needs`] says, or when the robot cannot go on (a camera that sees nothing).
    fn decide(&mut self, observation: &Observation) -> Result<Wheels, String>;
    /// `true` once the end of the route is reached (by the steer's own reckoning).
    fn arrived(&self) -> bool;
    /// Where the steer believes the robot is.
    fn belief(&self) -> Option<Pose>;
}

/// Follows the route on the simulator's ground truth.
#[derive(Debug, Clone)]
pub struct PoseSteer {
    follower: Follower,
    last: Option<Pose>,
}

impl PoseSteer {
    /// A steer over `legs` for the robot `drive`.
    pub fn new(legs: Vec<Leg>, drive: DiffDrive, gains: Gains) -> Self {
        Self {
            follower: Follower::new(legs, drive, gains),
            last: None,
        }
    }
}

impl Steer for PoseSteer {
    fn needs(&self) -> Needs {
        Needs {
            pose: true,
            image: false,
        }
    }

    fn decide(&mut self, observation: &Observation) -> Result<Wheels, String> {
        let pose = observation
            .pose
            .ok_or("steering by pose needs the robot's pose")?;
        self.last = Some(pose);
        Ok(self.follower.wheels(pose))
    }

    fn arrived(&self) -> bool {
        self.follower.arrived()
    }

    fn belief(&self) -> Option<Pose> {
        self.last
    }
}

/// Everything [`CameraSteer`] needs to see the lines.
#[derive(Debug, Clone)]
pub struct Eye {
    /// The camera.
    pub camera: CameraModel,
    /// Which pixels are line.
    pub colour: LineColour,
    /// The drawn lines, as the map.
    pub map: LineMap,
}

/// Follows the route from odometry, corrected by the lines the camera sees.
#[derive(Debug, Clone)]
pub struct CameraSteer {
    follower: Follower,
    drive: DiffDrive,
    eye: Eye,
    /// The floor points of the pixels it looks at, worked out once.
    table: Vec<(usize, usize, [f64; 2])>,
    estimate: Pose,
    joints: Option<[f64; 2]>,
    /// Frames in a row in which no line pixel was seen.
    blind: usize,
    /// Frames in a row that were all black.
    black: usize,
}

/// Every how many pixels (across and up) the image is looked at: 64 x 64 of the course's
/// 256 x 256 camera.
const STRIDE: usize = 4;

/// How far ahead of the robot's centre the camera is read, metres: farther, a degree of
/// the body's pitch moves a floor point by centimetres.
const RANGE: f64 = 0.7;

/// Black frames in a row after which the camera is taken to render nothing.
const BLACK_LIMIT: usize = 5;

/// Why a run steered by camera ends when the camera renders nothing (a headless CoppeliaSim
/// without a display gives all-black images).
pub const NOTHING_RENDERS: &str = "the camera image is all black: nothing renders (start CoppeliaSim with a display; `sim.sh start ... --display` for the headless builds)";

/// Frames in a row without a line pixel after which the robot stops: it lost the maze.
const BLIND_LIMIT: usize = 100;

impl CameraSteer {
    /// A steer over `legs` for the robot `drive`, starting at `start` (where it was placed).
    pub fn new(legs: Vec<Leg>, drive: DiffDrive, gains: Gains, eye: Eye, start: Pose) -> Self {
        let table = eye.camera.ground_table(STRIDE, RANGE);
        Self {
            follower: Follower::new(legs, drive, gains),
            drive,
            eye,
            table,
            estimate: start,
            joints: None,
            blind: 0,
            black: 0,
        }
    }

    /// The floor points (robot frame) of the line pixels of `image`.
    pub fn line_points(&self, image: &Image) -> Vec<[f64; 2]> {
        self.table
            .iter()
            .filter(|(i, j, _)| *i < image.width && *j < image.height)
            .filter(|(i, j, _)| self.eye.colour.is_line(image.pixel(*i, *j)))
            .map(|(_, _, p)| *p)
            .collect()
    }
}

impl Steer for CameraSteer {
    fn needs(&self) -> Needs {
        Needs {
            pose: false,
            image: true,
        }
    }

    fn decide(&mut self, observation: &Observation) -> Result<Wheels, String> {
        let image = observation
            .image
            .as_ref()
            .ok_or("steering by camera needs the camera image")?;
        let [left, right] = observation.joints;
        if let Some([l0, r0]) = self.joints {
            self.estimate = self
                .drive
                .odometry(self.estimate, wrap(left - l0), wrap(right - r0));
        }
        self.joints = Some([left, right]);
        if image.is_black() {
            // the frame before the first render is black too (the simulation just started)
            self.black += 1;
            if self.black >= BLACK_LIMIT {
                return Err(NOTHING_RENDERS.into());
            }
            return Ok(Wheels::default());
        }
        self.black = 0;
        let points = self.line_points(image);
        if points.is_empty() {
            self.blind += 1;
            if self.blind >= BLIND_LIMIT {
                return Err(format!(
                    "the camera has seen no line for {BLIND_LIMIT} steps: the robot lost the maze"
                ));
            }
        } else {
            self.blind = 0;
            self.estimate = self.eye.map.correct(self.estimate, &points);
        }
        Ok(self.follower.wheels(self.estimate))
    }

    fn arrived(&self) -> bool {
        self.follower.arrived()
    }

    fn belief(&self) -> Option<Pose> {
        Some(self.estimate)
    }
}
