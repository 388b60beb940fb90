//! The [`RobotPort`] over the ZeroMQ remote API, both protocols. Stepping is the add-on's:
//! protocol 2 (4.6+) `sim.setStepping(true)` and a blocking `sim.step()` per step
//! (zmqRemoteApi@coppeliasim-v4.10.0-rev0 `ZMQ remote API server.lua:71-127`: the
//! simulation waits at every step for each client in stepping mode); protocol 1 (4.5.1) the
//! add-on's globals `setStepping(enable, uuid)` and `step(uuid)`, the main script held until
//! every stepping client stepped (`simAddOnZMQ remote API server.lua:177-229` at
//! coppeliasim-v4.5.1-rev4), and the step's end seen as the simulation time advancing. A
//! stop ends every client's stepping on both.

use std::time::{Duration, Instant};

use ciborium::Value;

use super::cbor::{self, float_array, int};
use super::client::object_path;
use super::client::{Client, ClientOptions, ZmqError};
use super::{Outcome, Protocol};
use crate::held::Held;
use crate::robot::{DRIVER_SIGNAL, Reading, RobotError, RobotNames, RobotPort, RobotSurvey};
use vrep_maze_core::coppelia::{
    BOOLPARAM_DYNAMICS_HANDLING_ENABLED, HANDLE_ALL, HANDLE_PARENT, INTPARAM_IDLE_FPS,
    SIMULATION_STOPPED,
};
use vrep_maze_core::robot::Pose;
use vrep_maze_core::robot::camera::{CameraModel, Image};
use vrep_maze_core::robot::wheels::{DiffDrive, Wheels};

/// `sim.objfloatparam_objbbox_min_x` .. `_max_z`: a shape's bounding box in its own frame.
const BBOX_PARAMS: [i64; 6] = [15, 16, 17, 18, 19, 20];
/// `sim.visionintparam_resolution_x` and `_y`.
const RESOLUTION_PARAMS: [i64; 2] = [1002, 1003];
/// `sim.visionfloatparam_perspective_angle`.
const VIEW_ANGLE_PARAM: i64 = 1004;
/// The integer signal holding the camera's explicit-handling flag as the user had it, while a
/// run has it changed (cleared when the run puts it back).
const CAMERA_FLAG_SIGNAL: &str = "vrepMaze.cameraFlag";
/// How long a protocol-1 step may take to show in the simulation time.
const STEP_TIMEOUT: Duration = Duration::from_secs(30);

/// Handles of the robot's parts, once surveyed.
#[derive(Debug, Clone, Copy)]
struct Parts {
    robot: i64,
    left: i64,
    right: i64,
    camera: Option<i64>,
    floor: i64,
}

/// A call as [`Client::call_all`] and [`Client::read_all`] take it.
type Call = (&'static str, Vec<Value>);

impl Parts {
    /// Both wheels' target velocities set to 0.
    fn wheels_stopped(&self) -> [Call; 2] {
        [self.left, self.right].map(|joint| {
            (
                "sim.setJointTargetVelocity",
                vec![int(joint), Value::Float(0.0)],
            )
        })
    }

    /// The robot at `pose` in the floor's frame, `height` above it, level.
    fn robot_at(&self, pose: Pose, height: f64) -> [Call; 2] {
        [
            (
                "sim.setObjectPosition",
                vec![
                    int(self.robot),
                    int(self.floor),
                    float_array(&[pose.x, pose.y, height]),
                ],
            ),
            (
                "sim.setObjectOrientation",
                vec![
                    int(self.robot),
                    int(self.floor),
                    float_array(&[0.0, 0.0, pose.yaw]),
                ],
            ),
        ]
    }
}

/// A wheeled robot driven over a ZeroMQ connection.
pub struct ZmqRobot<'a> {
    client: Option<Held<'a, Client>>,
    options: ClientOptions,
    /// The name protocol 1's stepping globals know this client by.
    uuid: String,
    parts: Option<Parts>,
    /// The camera's explicit-handling flag before the run, when this run changed it.
    camera_flag: Option<i64>,
    /// The robot's height above the floor, kept when it is placed.
    height: f64,
    /// The camera's resolution before [`ZmqRobot::set_camera_resolution`] changed it, put
    /// back by [`ZmqRobot::close`].
    resolution: Option<[i64; 2]>,
    /// The robot's parts as they rest on the stopped simulation, once
    /// [`ZmqRobot::remember_rest`] has read them.
    rest: Option<Rest>,
}

/// How the robot rests on the stopped simulation ([`ZmqRobot::remember_rest`]).
#[derive(Debug, Clone)]
struct Rest {
    /// Every part below the robot, in tree order.
    parts: Vec<RestingPart>,
    /// Whether the scene's physics engine runs (`sim.boolparam_dynamics_handling_enabled`).
    dynamics: bool,
}

/// A part of the robot as it rests on the stopped simulation.
#[derive(Debug, Clone, Copy)]
struct RestingPart {
    handle: i64,
    /// Its pose in its parent's frame: x, y, z, then the quaternion x, y, z, w.
    pose: [f64; 7],
    /// Its position, if it is a joint that has one (not a spherical joint).
    joint: Option<f64>,
    /// The pose its joint gives its child (`sim.getObjectChildPose`), if it is a joint: a
    /// spherical joint (the caster ball's) has no position, only this.
    child: Option<[f64; 7]>,
}

fn lost(e: ZmqError) -> RobotError {
    RobotError::Connection(e.to_string())
}

fn malformed(what: &str) -> RobotError {
    RobotError::Connection(format!("malformed reply to {what}"))
}

impl<'a> ZmqRobot<'a> {
    /// Drives over `client`, connected with `options` (kept to reach the simulator again
    /// to stop it, should this connection be lost mid-run).
    pub fn new(client: Client, options: ClientOptions) -> Self {
        Self::over(Held::Owned(client), options)
    }

    /// Drives over a drawing backend's client, left open ([`crate::draw::Backend::robot`]).
    pub fn lent(client: &'a mut Client) -> Self {
        let endpoint = client.endpoint().trim_start_matches("tcp://");
        let (host, port) = endpoint.rsplit_once(':').unwrap_or((endpoint, ""));
        let options = ClientOptions {
            host: host.trim_matches(['[', ']']).to_string(),
            port: port.parse().unwrap_or(0),
            ..ClientOptions::default()
        };
        Self::over(Held::Lent(client), options)
    }

    fn over(client: Held<'a, Client>, options: ClientOptions) -> Self {
        Self {
            client: Some(client),
            options,
            uuid: super::client::new_uuid(),
            parts: None,
            camera_flag: None,
            height: 0.0,
            resolution: None,
            rest: None,
        }
    }

    /// Reads how the robot rests on the stopped simulation, for [`ZmqRobot::put_back`]: each
    /// part's pose in its parent's frame, each joint's position and the pose it gives its
    /// child, and whether the physics engine runs (two requests, once: a later call does
    /// nothing). Call it after [`RobotPort::place`], before the simulation starts.
    pub fn remember_rest(&mut self) -> Result<(), RobotError> {
        if self.rest.is_some() {
            return Ok(());
        }
        let p = self.parts()?;
        // every type, the robot first
        let args = vec![int(p.robot), int(HANDLE_ALL.into()), int(0)];
        let got = self
            .client()?
            .call("sim.getObjectsInTree", args)
            .map_err(lost)?;
        let tree = got
            .first()
            .and_then(cbor::handles)
            .ok_or_else(|| malformed("sim.getObjectsInTree"))?;
        let parts: Vec<i64> = tree.into_iter().skip(1).map(i64::from).collect();
        let mut calls = vec![(
            "sim.getBoolParam",
            vec![int(BOOLPARAM_DYNAMICS_HANDLING_ENABLED.into())],
        )];
        for &h in &parts {
            calls.push(("sim.getObjectPose", vec![int(h), int(HANDLE_PARENT.into())]));
            calls.push(("sim.getJointPosition", vec![int(h)]));
            calls.push(("sim.getObjectChildPose", vec![int(h)]));
        }
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        let dynamics = got[0]
            .as_ref()
            .map_err(|e| RobotError::Scene(e.to_string()))?
            .first()
            .and_then(Value::as_bool)
            .ok_or_else(|| malformed("sim.getBoolParam"))?;
        let parts = parts
            .iter()
            .zip(got[1..].chunks(3))
            .map(|(&h, three)| {
                let pose = Self::numbers::<7>(&three[0], "sim.getObjectPose")?;
                // a part that is no joint refuses both joint reads; a spherical joint the first
                let joint = Self::number(&three[1], "sim.getJointPosition").ok();
                let child = Self::numbers::<7>(&three[2], "sim.getObjectChildPose").ok();
                Ok(RestingPart {
                    handle: h,
                    pose,
                    joint,
                    child,
                })
            })
            .collect::<Result<_, RobotError>>()?;
        self.rest = Some(Rest { parts, dynamics });
        Ok(())
    }

    /// Puts the robot at `pose` (floor frame) while the simulation runs in stepping mode, so
    /// that a new episode needs no stop and start (15-20 ms and a first pass of 26 ms on the
    /// real 4.10, `docs/measurements.md`), in one request: the wheels stopped; the physics
    /// engine's world ended (dynamics handling off); the robot at `pose`, then every part
    /// and joint as [`ZmqRobot::remember_rest`] read them, every part's dynamics reset; and a
    /// fresh world made (dynamics handling on again, where the scene had it on). Episodes
    /// that begin so run alike to the last bit (`sim.resetDynamicObject` alone leaves the
    /// engine's state: episodes then differed by up to 7 mm); one that begins after a start
    /// differs from them unless this follows the start too. Returns `false` when the
    /// simulation was found stopped (by the user, say): then [`RobotPort::place`] and a start
    /// are the way.
    pub fn put_back(&mut self, pose: Pose) -> Result<bool, RobotError> {
        let p = self.parts()?;
        let Some(rest) = &self.rest else {
            return Err(RobotError::Scene(
                "the robot's resting pose was never read: place it on the stopped simulation first"
                    .into(),
            ));
        };
        let mut calls: Vec<Call> = vec![("sim.getSimulationState", vec![])];
        calls.extend(p.wheels_stopped());
        let dynamics = |on: bool| {
            (
                "sim.setBoolParam",
                vec![
                    int(BOOLPARAM_DYNAMICS_HANDLING_ENABLED.into()),
                    Value::Bool(on),
                ],
            )
        };
        if rest.dynamics {
            calls.push(dynamics(false));
        }
        // the robot first, then its parts in its frame: set after them, the robot's pose left
        // episodes that differed by 0.6-1.3 mm from one reset to the next (real 4.10)
        calls.extend(p.robot_at(pose, self.height));
        for part in &rest.parts {
            let local = vec![
                int(part.handle),
                int(HANDLE_PARENT.into()),
                float_array(&part.pose),
            ];
            calls.push(("sim.setObjectPose", local));
            if let Some(q) = part.joint {
                calls.push((
                    "sim.setJointPosition",
                    vec![int(part.handle), Value::Float(q)],
                ));
            }
            if let Some(child) = part.child {
                calls.push((
                    "sim.setObjectChildPose",
                    vec![int(part.handle), float_array(&child)],
                ));
            }
        }
        let reset = std::iter::once(p.robot).chain(rest.parts.iter().map(|r| r.handle));
        calls.extend(reset.map(|h| ("sim.resetDynamicObject", vec![int(h)])));
        if rest.dynamics {
            calls.push(dynamics(true));
        }
        // one program where the simulator runs it; made again, every call does the same
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        let state = Self::number(&got[0], "sim.getSimulationState")?;
        for outcome in got.into_iter().skip(1) {
            outcome.map_err(|e| RobotError::Scene(e.to_string()))?;
        }
        Ok(state as i64 != i64::from(SIMULATION_STOPPED))
    }

    /// Sets the simulator's idle rate (`sim.intparam_idle_fps`: main-loop passes a second
    /// while the simulation is stopped; 0, no sleep between passes, makes a stop and a
    /// start take a few ms instead of a few passes of 125 ms at the default 8); returns the
    /// rate before, for the caller to put back.
    pub fn set_idle_rate(&mut self, fps: i32) -> Result<i32, RobotError> {
        let param = int(INTPARAM_IDLE_FPS.into());
        let client = self.client()?;
        let before = client
            .call_int("sim.getInt32Param", vec![param.clone()])
            .map_err(lost)?;
        client
            .call("sim.setInt32Param", vec![param, int(fps.into())])
            .map_err(lost)?;
        Ok(before)
    }

    /// Renders the surveyed camera at `width` x `height` pixels from now on (its
    /// resolution parameters; the simulation stopped), the resolution before kept for
    /// [`ZmqRobot::close`] to put back. Returns the camera model at the new resolution.
    pub fn set_camera_resolution(
        &mut self,
        width: u32,
        height: u32,
    ) -> Result<CameraModel, RobotError> {
        let p = self.parts()?;
        let cam = p
            .camera
            .ok_or_else(|| RobotError::Scene("the robot has no camera".into()))?;
        let model = self.camera_model(cam, p.robot)?;
        let before = [model.width as i64, model.height as i64];
        let calls: Vec<(&str, Vec<Value>)> = RESOLUTION_PARAMS
            .iter()
            .zip([width, height])
            .map(|(&param, n)| {
                let args = vec![int(cam), int(param), int(n.into())];
                ("sim.setObjectInt32Param", args)
            })
            .collect();
        for outcome in self.client()?.call_all(&calls).map_err(lost)? {
            outcome.map_err(|e| RobotError::Scene(format!("the camera's resolution: {e}")))?;
        }
        self.resolution.get_or_insert(before);
        self.camera_model(cam, p.robot)
    }

    /// Closes the connection if it is its own (a lent one stays open), the camera's
    /// resolution put back first if this robot changed it.
    pub fn close(mut self) {
        if let (Some(before), Ok(p)) = (self.resolution.take(), self.parts())
            && let (Some(cam), Some(client)) = (p.camera, self.client.as_deref_mut())
        {
            for (param, n) in RESOLUTION_PARAMS.iter().zip(before) {
                let _ = client.call(
                    "sim.setObjectInt32Param",
                    vec![int(cam), int(*param), int(n)],
                );
            }
        }
        if let Some(client) = self.client.take().and_then(Held::into_owned) {
            client.close();
        }
    }

    fn client(&mut self) -> Result<&mut Client, RobotError> {
        self.client
            .as_deref_mut()
            .ok_or_else(|| RobotError::Connection("the connection is closed".into()))
    }

    fn parts(&self) -> Result<Parts, RobotError> {
        self.parts
            .ok_or_else(|| RobotError::Scene("the robot was not surveyed".into()))
    }

    fn protocol(&mut self) -> Result<Protocol, RobotError> {
        Ok(self.client()?.protocol().unwrap_or(Protocol::V2))
    }

    /// The handle of the object `name`, or a scene error naming it and its `role`.
    fn handle(&mut self, name: &str, role: &str) -> Result<i64, RobotError> {
        let opts = cbor::map([("noError", Value::Bool(true))]);
        match self
            .client()?
            .call_int("sim.getObject", vec![Value::Text(object_path(name)), opts])
        {
            Ok(h) if h >= 0 => Ok(h.into()),
            Ok(_) | Err(ZmqError::Remote { .. }) => Err(RobotError::Scene(format!(
                "the scene has no object named `{name}` ({role})"
            ))),
            Err(e) => Err(lost(e)),
        }
    }

    fn numbers<const N: usize>(outcome: &Outcome, what: &str) -> Result<[f64; N], RobotError> {
        match outcome {
            Ok(values) => values
                .first()
                .and_then(cbor::numbers::<N>)
                .ok_or_else(|| malformed(what)),
            Err(e) => Err(RobotError::Connection(e.to_string())),
        }
    }

    fn number(outcome: &Outcome, what: &str) -> Result<f64, RobotError> {
        match outcome {
            Ok(values) => values
                .first()
                .and_then(cbor::number)
                .ok_or_else(|| malformed(what)),
            Err(e) => Err(RobotError::Connection(e.to_string())),
        }
    }

    /// A wheel's radius: half the larger side across the axle of the first shape under
    /// the joint.
    fn wheel_radius(&mut self, joint: i64, name: &str) -> Result<f64, RobotError> {
        let wheel = self
            .client()?
            .call_int("sim.getObjectChild", vec![int(joint), int(0)])
            .map_err(lost)?;
        if wheel < 0 {
            return Err(RobotError::Scene(format!(
                "`{name}` has no wheel under it: give --wheel-radius"
            )));
        }
        let calls: Vec<(&str, Vec<Value>)> = BBOX_PARAMS
            .iter()
            .map(|&p| ("sim.getObjectFloatParam", vec![int(wheel.into()), int(p)]))
            .collect();
        let box_ = self.client()?.read_all(&calls).map_err(lost)?;
        let v: Vec<f64> = box_
            .iter()
            .map(|o| Self::number(o, "sim.getObjectFloatParam"))
            .collect::<Result<_, _>>()?;
        Ok((v[3] - v[0]).max(v[4] - v[1]) / 2.0)
    }

    fn camera_model(&mut self, camera: i64, robot: i64) -> Result<CameraModel, RobotError> {
        let calls = vec![
            (
                "sim.getObjectInt32Param",
                vec![int(camera), int(RESOLUTION_PARAMS[0])],
            ),
            (
                "sim.getObjectInt32Param",
                vec![int(camera), int(RESOLUTION_PARAMS[1])],
            ),
            (
                "sim.getObjectFloatParam",
                vec![int(camera), int(VIEW_ANGLE_PARAM)],
            ),
            ("sim.getObjectMatrix", vec![int(camera), int(robot)]),
        ];
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        let width = Self::number(&got[0], "the camera's resolution")? as usize;
        let height = Self::number(&got[1], "the camera's resolution")? as usize;
        let view_angle = Self::number(&got[2], "the camera's view angle")?;
        let mount = Self::numbers::<12>(&got[3], "sim.getObjectMatrix")?;
        Ok(CameraModel {
            width,
            height,
            view_angle,
            mount,
            floor_z: -self.height,
        })
    }

    /// A shape's colour (ambient-diffuse), if it can be read.
    fn colour(&mut self, shape: i64) -> Option<[f64; 3]> {
        let got = self
            .client()
            .ok()?
            .call("sim.getShapeColor", vec![int(shape), Value::Null, int(0)])
            .ok()?;
        got.get(1).and_then(cbor::numbers::<3>)
    }

    fn pose_of(matrix: &[f64; 12]) -> Pose {
        Pose {
            x: matrix[3],
            y: matrix[7],
            yaw: matrix[4].atan2(matrix[0]),
        }
    }

    /// The image `sim.getVisionSensorImg` answered `got` with.
    fn image_of(got: &[Value]) -> Result<Image, RobotError> {
        let bytes = match got.first() {
            Some(Value::Bytes(b)) => b.clone(),
            Some(Value::Text(t)) => t.as_bytes().to_vec(),
            _ => return Err(malformed("sim.getVisionSensorImg")),
        };
        let [w, h] = got
            .get(1)
            .and_then(cbor::numbers::<2>)
            .ok_or_else(|| malformed("sim.getVisionSensorImg"))?;
        Image::new(w as usize, h as usize, bytes).map_err(RobotError::Connection)
    }

    /// Stops the simulation over `client` and waits until it is stopped.
    fn stop_over(client: &mut Client) -> Result<(), ZmqError> {
        client.call("sim.stopSimulation", vec![])?;
        let deadline = Instant::now() + Duration::from_secs(10);
        while client.call_int("sim.getSimulationState", vec![])? != SIMULATION_STOPPED
            && Instant::now() < deadline
        {
            // a stop takes a few main-loop passes (about 40 ms on 4.10 at idle rate 0)
            std::thread::sleep(Duration::from_millis(2));
        }
        Ok(())
    }

    fn set_stepping(&mut self, on: bool) -> Result<(), RobotError> {
        let protocol = self.protocol()?;
        let uuid = self.uuid.clone();
        let client = self.client()?;
        match protocol {
            Protocol::V1 => client.call("setStepping", vec![Value::Bool(on), Value::Text(uuid)]),
            Protocol::V2 => client.call("sim.setStepping", vec![Value::Bool(on)]),
        }
        .map(|_| ())
        .map_err(lost)
    }
}

impl RobotPort for ZmqRobot<'_> {
    fn survey(&mut self, names: &RobotNames) -> Result<RobotSurvey, RobotError> {
        let robot = self.handle(&names.robot, "the robot")?;
        let left = self.handle(&names.left_motor, "the left wheel's joint")?;
        let right = self.handle(&names.right_motor, "the right wheel's joint")?;
        let floor = self.handle(&names.floor, "the floor")?;
        let camera = self.handle(&names.camera, "the camera").ok();
        let line = self.handle(&names.line, "the line template").ok();
        let calls = vec![
            ("sim.getObjectPosition", vec![int(left), int(robot)]),
            ("sim.getObjectPosition", vec![int(right), int(robot)]),
            ("sim.getObjectMatrix", vec![int(robot), int(floor)]),
        ];
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        let l = Self::numbers::<3>(&got[0], "sim.getObjectPosition")?;
        let r = Self::numbers::<3>(&got[1], "sim.getObjectPosition")?;
        let m = Self::numbers::<12>(&got[2], "sim.getObjectMatrix")?;
        self.height = m[11];
        let track = (l[0] - r[0]).hypot(l[1] - r[1]);
        let radius = self.wheel_radius(left, &names.left_motor)?;
        let drive = DiffDrive::new(radius, track).map_err(|e| {
            RobotError::Scene(format!(
                "`{}` and `{}`: {e}; give --wheel-radius and --track",
                names.left_motor, names.right_motor
            ))
        })?;
        self.parts = Some(Parts {
            robot,
            left,
            right,
            camera,
            floor,
        });
        let camera = match camera {
            Some(c) => Some(self.camera_model(c, robot)?),
            None => None,
        };
        let colours = line.and_then(|l| self.colour(l)).zip(self.colour(floor));
        Ok(RobotSurvey {
            drive,
            camera,
            colours,
            pose: Self::pose_of(&m),
        })
    }

    fn place(&mut self, pose: Pose) -> Result<(), RobotError> {
        let p = self.parts()?;
        let height = self.height;
        let client = self.client()?;
        let state = client
            .call_int("sim.getSimulationState", vec![])
            .map_err(lost)?;
        if state != SIMULATION_STOPPED {
            return Err(RobotError::Scene(
                "the simulation is running: stop it first (the robot is placed on a stopped simulation)".into(),
            ));
        }
        let mut calls = p.robot_at(pose, height).to_vec();
        calls.extend(p.wheels_stopped());
        for outcome in client.call_all(&calls).map_err(lost)? {
            outcome.map_err(|e| RobotError::Scene(e.to_string()))?;
        }
        Ok(())
    }

    fn prepare(&mut self, camera: bool) -> Result<(), RobotError> {
        let p = self.parts()?;
        if let Some(cam) = p.camera {
            // a camera not read is spared rendering (30 ms a frame with a display); the flag
            // the user had is kept in a signal until it is put back, so a run that was
            // killed before its end leaves the next one the user's flag, not ours
            let got = self
                .client()?
                .read_all(&[
                    ("sim.getExplicitHandling", vec![int(cam)]),
                    (
                        "sim.getInt32Signal",
                        vec![Value::Text(CAMERA_FLAG_SIGNAL.into())],
                    ),
                ])
                .map_err(lost)?;
            let current = Self::number(&got[0], "sim.getExplicitHandling")? as i64;
            let saved = got[1]
                .as_ref()
                .ok()
                .and_then(|v| v.first())
                .and_then(cbor::int32);
            let flag = saved.map_or(current, i64::from);
            let wanted = if camera { flag } else { 1 };
            if current != wanted {
                let calls = vec![
                    (
                        "sim.setInt32Signal",
                        vec![Value::Text(CAMERA_FLAG_SIGNAL.into()), int(flag)],
                    ),
                    ("sim.setExplicitHandling", vec![int(cam), int(wanted)]),
                ];
                for outcome in self.client()?.call_all(&calls).map_err(lost)? {
                    outcome.map_err(lost)?;
                }
            }
            if current != wanted || saved.is_some() {
                self.camera_flag = Some(flag);
            }
            if camera && flag != 0 {
                return Err(RobotError::Scene(
                    "the camera is tagged for explicit handling, so it renders only when a script asks: untag it (sim.setExplicitHandling(camera, 0))".into(),
                ));
            }
        } else if camera {
            return Err(RobotError::Scene("the robot has no camera".into()));
        }
        self.set_stepping(true)?;
        self.client()?
            .call(
                "sim.setInt32Signal",
                vec![Value::Text(DRIVER_SIGNAL.into()), int(1)],
            )
            .map_err(lost)?;
        Ok(())
    }

    /// A frame rendered on demand: the camera tagged for explicit handling, handled, read,
    /// and untagged again, in one request (one idle pass on 4.5.1; 15-135 ms on the real
    /// 4.10 with a display, 4-5 s without one). `None` when the simulator refuses a call.
    fn still_frame(&mut self) -> Result<Option<Image>, RobotError> {
        let Some(cam) = self.parts()?.camera else {
            return Ok(None);
        };
        // a camera run has the camera untagged (`prepare` refuses one tagged by the user)
        let calls = [
            ("sim.setExplicitHandling", vec![int(cam), int(1)]),
            ("sim.handleVisionSensor", vec![int(cam)]),
            ("sim.getVisionSensorImg", vec![int(cam)]),
            ("sim.setExplicitHandling", vec![int(cam), int(0)]),
        ];
        // the calls run in order under one program where the simulator runs it, so the
        // camera is untagged even when this client dies waiting
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        match &got[..] {
            [Ok(_), Ok(_), Ok(image), Ok(_)] => Self::image_of(image).map(Some),
            _ => Ok(None),
        }
    }

    fn start_simulation(&mut self) -> Result<(), RobotError> {
        self.client()?
            .call("sim.startSimulation", vec![])
            .map_err(lost)?;
        Ok(())
    }

    fn is_running(&mut self) -> Result<bool, RobotError> {
        let state = self
            .client()?
            .call_int("sim.getSimulationState", vec![])
            .map_err(lost)?;
        Ok(state != SIMULATION_STOPPED)
    }

    fn observe(&mut self, image: bool) -> Result<Reading, RobotError> {
        let p = self.parts()?;
        let calls = vec![
            ("sim.getSimulationTime", vec![]),
            ("sim.getJointPosition", vec![int(p.left)]),
            ("sim.getJointPosition", vec![int(p.right)]),
            ("sim.getObjectMatrix", vec![int(p.robot), int(p.floor)]),
        ];
        let got = self.client()?.read_all(&calls).map_err(lost)?;
        let time = Self::number(&got[0], "sim.getSimulationTime")?;
        let joints = [
            Self::number(&got[1], "sim.getJointPosition")?,
            Self::number(&got[2], "sim.getJointPosition")?,
        ];
        let pose = Self::pose_of(&Self::numbers::<12>(&got[3], "sim.getObjectMatrix")?);
        let image = match (image, p.camera) {
            (true, Some(cam)) => {
                let got = self
                    .client()?
                    .call("sim.getVisionSensorImg", vec![int(cam)])
                    .map_err(lost)?;
                Some(Self::image_of(&got)?)
            }
            _ => None,
        };
        Ok(Reading {
            time,
            joints,
            pose,
            image,
        })
    }

    fn actuate(&mut self, wheels: Wheels) -> Result<(), RobotError> {
        let p = self.parts()?;
        let calls = vec![
            (
                "sim.setJointTargetVelocity",
                vec![int(p.left), Value::Float(wheels.left)],
            ),
            (
                "sim.setJointTargetVelocity",
                vec![int(p.right), Value::Float(wheels.right)],
            ),
        ];
        for outcome in self.client()?.call_all(&calls).map_err(lost)? {
            outcome.map_err(|e| RobotError::Connection(e.to_string()))?;
        }
        Ok(())
    }

    fn step(&mut self) -> Result<(), RobotError> {
        match self.protocol()? {
            Protocol::V2 => {
                self.client()?.call("sim.step", vec![]).map_err(lost)?;
            }
            Protocol::V1 => {
                let uuid = self.uuid.clone();
                let client = self.client()?;
                let before = client
                    .call1("sim.getSimulationTime", vec![])
                    .map_err(lost)?;
                let before =
                    cbor::number(&before).ok_or_else(|| malformed("sim.getSimulationTime"))?;
                client.call("step", vec![Value::Text(uuid)]).map_err(lost)?;
                let deadline = Instant::now() + STEP_TIMEOUT;
                loop {
                    let now = client
                        .call1("sim.getSimulationTime", vec![])
                        .map_err(lost)?;
                    if cbor::number(&now).is_some_and(|t| t > before) {
                        break;
                    }
                    if Instant::now() >= deadline {
                        return Err(RobotError::Connection(format!(
                            "the simulation did not advance within {} s of a step",
                            STEP_TIMEOUT.as_secs()
                        )));
                    }
                }
            }
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), RobotError> {
        let parts = self.parts;
        let restore = self.camera_flag.take();
        let tidy = |client: &mut Client| -> Result<(), RobotError> {
            Self::tidy(client, parts, restore).map_err(lost)
        };
        // stepping off first: the stop then waits for no step (median 34 against 65 ms on
        // the real 4.10, on a loaded 2-core machine)
        let first = match self.set_stepping(false) {
            Ok(()) => match self.client.as_deref_mut() {
                Some(client) => tidy(client),
                None => Err(RobotError::Connection("the connection is closed".into())),
            },
            Err(e) => Err(e),
        };
        if first.is_ok() {
            return Ok(());
        }
        // the connection is lost (or stuck in a step): a fresh one stops the simulation,
        // which ends every client's stepping
        let mut fresh = Client::connect(&self.options).map_err(lost)?;
        let done = tidy(&mut fresh);
        fresh.close();
        done
    }
}

impl ZmqRobot<'_> {
    /// Wheels stopped, the signal cleared, the simulation stopped (sent together, then
    /// waited for), the camera's handling put back.
    fn tidy(
        client: &mut Client,
        parts: Option<Parts>,
        restore: Option<i64>,
    ) -> Result<(), ZmqError> {
        let mut calls: Vec<Call> = Vec::new();
        if let Some(p) = parts {
            calls.extend(p.wheels_stopped());
        }
        let signal = vec![Value::Text(DRIVER_SIGNAL.into())];
        calls.push(("sim.clearInt32Signal", signal));
        for outcome in client.call_all(&calls)? {
            outcome?;
        }
        Self::stop_over(client)?;
        if let (Some(p), Some(flag)) = (parts, restore)
            && let Some(cam) = p.camera
        {
            client.call("sim.setExplicitHandling", vec![int(cam), int(flag)])?;
            let signal = vec![Value::Text(CAMERA_FLAG_SIGNAL.into())];
            client.call("sim.clearInt32Signal", signal)?;
        }
        Ok(())
    }
}
