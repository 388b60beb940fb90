//! The [`RobotPort`] over the legacy remote API (CoppeliaSim 4.5.1), the course's way:
//! `simxSynchronous(true)` and one `simxSynchronousTrigger` per step, the wheels by
//! `simxSetJointTargetVelocity`, odometry by `simxGetJointPosition`, the pose by
//! `simxGetObjectPosition` / `simxGetObjectOrientation` relative to the floor, and the camera
//! streamed (`simxGetVisionSensorImage`, streaming, then read from the inbox).
//!
//! A step's end is known from the simulation time the server stamps on every reply block
//! (`simxGetLastCmdTime`): the trigger's reply only says that the step may run, so the
//! readings after it are read again until their stamp is past the previous readings'
//! (spec `legacy-remote-api.md` 5.1, 7.3, 12.21). The image used is the streamed one stamped
//! with the readings' time. The legacy API reads no shape colour: the survey reports none.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use super::client::{Client, ClientError, ClientOptions, Reply};
use super::command::{Command, SimControl, decode_image, read_f32, read_f32x3, read_i32};
use crate::robot::{DRIVER_SIGNAL, Reading, RobotError, RobotNames, RobotPort, RobotSurvey};
use vrep_maze_core::coppelia::frame::frame;
use vrep_maze_core::coppelia::{INTPARAM_PROGRAM_VERSION, OBJFLOATPARAM_BBOX};
use vrep_maze_core::robot::Pose;
use vrep_maze_core::robot::camera::{CameraModel, Image};
use vrep_maze_core::robot::wheels::{DiffDrive, Wheels};

/// `sim_visionintparam_resolution_x` and `_y`.
const RESOLUTION_PARAMS: [i32; 2] = [1002, 1003];
/// `sim_visionfloatparam_perspective_angle`.
const VIEW_ANGLE_PARAM: i32 = 1004;
/// How long a step may take to show in the readings' simulation time.
const STEP_TIMEOUT: Duration = Duration::from_secs(30);
/// How long the simulation may take to stop.
const STOP_TIMEOUT: Duration = Duration::from_secs(10);

/// Handles of the robot's parts, once surveyed.
#[derive(Debug, Clone, Copy)]
struct Parts {
    robot: i32,
    left: i32,
    right: i32,
    camera: Option<i32>,
    floor: i32,
}

/// A wheeled robot driven over a legacy connection.
pub struct LegacyRobot {
    client: Option<Client>,
    /// Where the simulator is and how to connect, to reach it again should this connection
    /// be lost mid-run.
    reconnect: Option<(SocketAddr, ClientOptions)>,
    parts: Option<Parts>,
    /// The robot's height above the floor, kept when it is placed.
    height: f64,
    /// The wheels to set with the next step's trigger.
    wheels: Option<Wheels>,
    /// The simulation time of the latest readings, ms.
    last_ms: Option<i32>,
    /// The camera is read in this run.
    camera: bool,
    /// The image stream was started.
    streaming: bool,
}

fn lost(e: ClientError) -> RobotError {
    RobotError::Connection(e.to_string())
}

fn malformed(what: &str) -> RobotError {
    RobotError::Connection(format!("malformed reply to {what}"))
}

impl LegacyRobot {
    /// Drives over `client`, reaching the simulator again with `options` (and the client's
    /// address) should this connection be lost.
    pub fn new(client: Client, options: ClientOptions) -> Self {
        let reconnect = client.peer().map(|a| (a, options));
        Self {
            client: Some(client),
            reconnect,
            parts: None,
            height: 0.0,
            wheels: None,
            last_ms: None,
            camera: false,
            streaming: false,
        }
    }

    /// Closes the connection the way the official client leaves (`Err` if the simulator
    /// did not acknowledge it).
    pub fn close(mut self) -> Result<(), ClientError> {
        match self.client.take() {
            Some(client) => client.close(),
            None => Ok(()),
        }
    }

    fn client(&mut self) -> Result<&mut Client, RobotError> {
        self.client
            .as_mut()
            .ok_or_else(|| RobotError::Connection("the connection is closed".into()))
    }

    fn parts(&self) -> Result<Parts, RobotError> {
        self.parts
            .ok_or_else(|| RobotError::Scene("the robot was not surveyed".into()))
    }

    fn call(&mut self, commands: &[Command]) -> Result<Vec<Reply>, RobotError> {
        self.client()?.call(commands).map_err(lost)
    }

    /// The handles of `objects` (name, role), in one request; a scene error names the
    /// first one missing.
    fn handles(&mut self, objects: &[(&str, &str)]) -> Result<Vec<Option<i32>>, RobotError> {
        let commands: Vec<Command> = objects
            .iter()
            .map(|(name, _)| Command::GetObjectHandle(name.to_string()))
            .collect();
        let got = self.call(&commands)?;
        Ok(got
            .iter()
            .map(|r| read_i32(&r.data, 0).filter(|&h| !r.remote_error && h >= 0))
            .collect())
    }

    fn f32_of(reply: &Reply, what: &str) -> Result<f64, RobotError> {
        if reply.remote_error {
            return Err(RobotError::Scene(format!("the simulator refused {what}")));
        }
        read_f32(&reply.data, 0)
            .map(f64::from)
            .ok_or_else(|| malformed(what))
    }

    fn i32_of(reply: &Reply, what: &str) -> Result<i32, RobotError> {
        if reply.remote_error {
            return Err(RobotError::Scene(format!("the simulator refused {what}")));
        }
        read_i32(&reply.data, 0).ok_or_else(|| malformed(what))
    }

    fn xyz_of(reply: &Reply, what: &str) -> Result<[f64; 3], RobotError> {
        if reply.remote_error {
            return Err(RobotError::Scene(format!("the simulator refused {what}")));
        }
        read_f32x3(&reply.data, 0)
            .map(|v| v.map(f64::from))
            .ok_or_else(|| malformed(what))
    }

    /// The 3x4 row-major matrix of a position and CoppeliaSim Euler angles.
    fn matrix(position: [f64; 3], euler: [f64; 3]) -> [f64; 12] {
        let f = frame(position, euler);
        let r = f.rotation.to_rotation_matrix();
        let r = r.matrix();
        let t = f.translation.vector;
        [
            r[(0, 0)],
            r[(0, 1)],
            r[(0, 2)],
            t.x,
            r[(1, 0)],
            r[(1, 1)],
            r[(1, 2)],
            t.y,
            r[(2, 0)],
            r[(2, 1)],
            r[(2, 2)],
            t.z,
        ]
    }

    fn pose_of(position: [f64; 3], euler: [f64; 3]) -> Pose {
        let m = Self::matrix(position, euler);
        Pose {
            x: m[3],
            y: m[7],
            yaw: m[4].atan2(m[0]),
        }
    }

    /// A wheel's radius: half the larger side across the axle of the first shape under
    /// the joint (its bounding box, parameters 15..20).
    fn wheel_radius(&mut self, joint: i32, name: &str) -> Result<f64, RobotError> {
        let got = self.call(&[Command::GetObjectChild {
            handle: joint,
            index: 0,
        }])?;
        let wheel = read_i32(&got[0].data, 0).unwrap_or(-1);
        if wheel < 0 {
            return Err(RobotError::Scene(format!(
                "`{name}` has no wheel under it: give --wheel-radius"
            )));
        }
        let commands: Vec<Command> = (0..6)
            .map(|k| Command::GetObjectFloatParam {
                handle: wheel,
                param: OBJFLOATPARAM_BBOX + k,
            })
            .collect();
        let v: Vec<f64> = self
            .call(&commands)?
            .iter()
            .map(|r| Self::f32_of(r, "the wheel's bounding box"))
            .collect::<Result<_, _>>()?;
        Ok((v[3] - v[0]).max(v[4] - v[1]) / 2.0)
    }

    fn camera_model(&mut self, camera: i32, robot: i32) -> Result<CameraModel, RobotError> {
        let got = self.call(&[
            Command::GetObjectIntParam {
                handle: camera,
                param: RESOLUTION_PARAMS[0],
            },
            Command::GetObjectIntParam {
                handle: camera,
                param: RESOLUTION_PARAMS[1],
            },
            Command::GetObjectFloatParam {
                handle: camera,
                param: VIEW_ANGLE_PARAM,
            },
            Command::GetPosition {
                handle: camera,
                relative_to: robot,
            },
            Command::GetOrientation {
                handle: camera,
                relative_to: robot,
            },
        ])?;
        let width = Self::i32_of(&got[0], "the camera's resolution")?;
        let height = Self::i32_of(&got[1], "the camera's resolution")?;
        if width <= 0 || height <= 0 {
            return Err(RobotError::Scene(format!(
                "the camera's resolution reads {width} x {height}: is it a vision sensor?"
            )));
        }
        let view_angle = Self::f32_of(&got[2], "the camera's view angle")?;
        let position = Self::xyz_of(&got[3], "the camera's position")?;
        let euler = Self::xyz_of(&got[4], "the camera's orientation")?;
        Ok(CameraModel {
            width: width as usize,
            height: height as usize,
            view_angle,
            mount: Self::matrix(position, euler),
            floor_z: -self.height,
        })
    }

    /// The readings' commands: both joints' angles, the robot's position and orientation
    /// on the floor.
    fn reading_commands(p: Parts) -> [Command; 4] {
        [
            Command::GetJointPosition(p.left),
            Command::GetJointPosition(p.right),
            Command::GetPosition {
                handle: p.robot,
                relative_to: p.floor,
            },
            Command::GetOrientation {
                handle: p.robot,
                relative_to: p.floor,
            },
        ]
    }

    fn image_command(camera: i32) -> Command {
        Command::GetVisionSensorImage {
            handle: camera,
            greyscale: false,
        }
    }

    /// The streamed image stamped `at_ms` or later, polling for it.
    fn image_at(&mut self, camera: i32, at_ms: i32) -> Result<Image, RobotError> {
        let command = Self::image_command(camera);
        let deadline = Instant::now() + STEP_TIMEOUT;
        loop {
            let client = self.client()?;
            if let Some((reply, stamp)) = client.buffered(&command)
                && stamp >= at_ms
            {
                if reply.remote_error {
                    return Err(RobotError::Scene(
                        "the simulator refused the camera's image (simxGetVisionSensorImage)"
                            .into(),
                    ));
                }
                let (w, h, rgb) = decode_image(&reply.data, 3)
                    .ok_or_else(|| malformed("simxGetVisionSensorImage"))?;
                return Image::new(w, h, rgb.to_vec()).map_err(RobotError::Connection);
            }
            if Instant::now() >= deadline {
                return Err(RobotError::Connection(format!(
                    "no camera image of the simulation time {:.3} s came within {} s",
                    f64::from(at_ms) / 1000.0,
                    STEP_TIMEOUT.as_secs()
                )));
            }
            client.poll().map_err(lost)?;
        }
    }

    /// Wheels stopped, stepping off, the simulation stopped (and waited for), the image
    /// stream ended, over `client`.
    fn tidy(client: &mut Client, parts: Option<Parts>) -> Result<(), RobotError> {
        let mut commands = vec![];
        if let Some(p) = parts {
            for joint in [p.left, p.right] {
                commands.push(Command::SetJointTargetVelocity {
                    handle: joint,
                    velocity: 0.0,
                });
            }
        }
        // stepping off first: a stop then runs its last pass without waiting for a trigger
        commands.push(Command::Synchronous(false));
        commands.push(Command::ClearIntSignal(DRIVER_SIGNAL.into()));
        commands.push(Command::Simulation(SimControl::Stop));
        client.call(&commands).map_err(lost)?;
        if let Some(cam) = parts.and_then(|p| p.camera) {
            client
                .discontinue(&[Self::image_command(cam)])
                .map_err(lost)?;
        }
        let deadline = Instant::now() + STOP_TIMEOUT;
        loop {
            client
                .call1(Command::GetIntParam(INTPARAM_PROGRAM_VERSION))
                .map_err(lost)?;
            if client.simulation_running() == Some(false) {
                return Ok(());
            }
            if Instant::now() >= deadline {
                return Err(RobotError::Connection(format!(
                    "the simulation did not stop within {} s",
                    STOP_TIMEOUT.as_secs()
                )));
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

impl RobotPort for LegacyRobot {
    fn survey(&mut self, names: &RobotNames) -> Result<RobotSurvey, RobotError> {
        let roles = [
            (names.robot.as_str(), "the robot"),
            (names.left_motor.as_str(), "the left wheel's joint"),
            (names.right_motor.as_str(), "the right wheel's joint"),
            (names.floor.as_str(), "the floor"),
            (names.camera.as_str(), "the camera"),
        ];
        let found = self.handles(&roles)?;
        let required = |k: usize| {
            found[k].ok_or_else(|| {
                RobotError::Scene(format!(
                    "the scene has no object named `{}` ({})",
                    roles[k].0, roles[k].1
                ))
            })
        };
        let (robot, left, right, floor) = (required(0)?, required(1)?, required(2)?, required(3)?);
        let camera = found[4];
        let got = self.call(&[
            Command::GetPosition {
                handle: left,
                relative_to: robot,
            },
            Command::GetPosition {
                handle: right,
                relative_to: robot,
            },
            Command::GetPosition {
                handle: robot,
                relative_to: floor,
            },
            Command::GetOrientation {
                handle: robot,
                relative_to: floor,
            },
        ])?;
        let l = Self::xyz_of(&got[0], "the left joint's position")?;
        let r = Self::xyz_of(&got[1], "the right joint's position")?;
        let position = Self::xyz_of(&got[2], "the robot's position")?;
        let euler = Self::xyz_of(&got[3], "the robot's orientation")?;
        self.height = position[2];
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
        Ok(RobotSurvey {
            drive,
            camera,
            colours: None,
            pose: Self::pose_of(position, euler),
        })
    }

    fn place(&mut self, pose: Pose) -> Result<(), RobotError> {
        let p = self.parts()?;
        let height = self.height;
        let client = self.client()?;
        client
            .call1(Command::GetIntParam(INTPARAM_PROGRAM_VERSION))
            .map_err(lost)?;
        if client.simulation_running() != Some(false) {
            return Err(RobotError::Scene(
                "the simulation is running: stop it first (the robot is placed on a stopped simulation)".into(),
            ));
        }
        let got = client
            .call(&[
                Command::SetPosition {
                    handle: p.robot,
                    relative_to: p.floor,
                    xyz: [pose.x as f32, pose.y as f32, height as f32],
                },
                Command::SetOrientation {
                    handle: p.robot,
                    relative_to: p.floor,
                    euler: [0.0, 0.0, pose.yaw as f32],
                },
                Command::SetJointTargetVelocity {
                    handle: p.left,
                    velocity: 0.0,
                },
                Command::SetJointTargetVelocity {
                    handle: p.right,
                    velocity: 0.0,
                },
            ])
            .map_err(lost)?;
        if got.iter().any(|r| r.remote_error) {
            return Err(RobotError::Scene(
                "the simulator refused to place the robot or stop its wheels".into(),
            ));
        }
        Ok(())
    }

    fn prepare(&mut self, camera: bool) -> Result<(), RobotError> {
        let p = self.parts()?;
        if camera && p.camera.is_none() {
            return Err(RobotError::Scene("the robot has no camera".into()));
        }
        let got = self.call(&[Command::Synchronous(true)])?;
        if got[0].remote_error {
            return Err(RobotError::Scene(
                "the simulator refused synchronous mode on this port: enable it in remoteApiConnections.txt (portIndex1_syncSimTrigger = true)".into(),
            ));
        }
        self.last_ms = None;
        self.wheels = None;
        self.camera = camera;
        self.call(&[Command::SetIntSignal(DRIVER_SIGNAL.into(), 1)])?;
        Ok(())
    }

    fn start_simulation(&mut self) -> Result<(), RobotError> {
        let got = self.call(&[Command::Simulation(SimControl::Start)])?;
        if got[0].remote_error {
            return Err(RobotError::Scene(
                "the simulator refused to start the simulation".into(),
            ));
        }
        Ok(())
    }

    fn is_running(&mut self) -> Result<bool, RobotError> {
        let client = self.client()?;
        client
            .call1(Command::GetIntParam(INTPARAM_PROGRAM_VERSION))
            .map_err(lost)?;
        Ok(client.simulation_running() == Some(true))
    }

    fn observe(&mut self, image: bool) -> Result<Reading, RobotError> {
        let p = self.parts()?;
        let commands = Self::reading_commands(p);
        let deadline = Instant::now() + STEP_TIMEOUT;
        let mut reads = 0usize;
        let got = loop {
            let got = self.call(&commands)?;
            reads += 1;
            let stamp = got[0].sim_time;
            if self.last_ms.is_none_or(|last| stamp > last) {
                break got;
            }
            if Instant::now() >= deadline {
                return Err(RobotError::Connection(format!(
                    "the simulation did not advance within {} s of a step",
                    STEP_TIMEOUT.as_secs()
                )));
            }
        };
        let stamp = got[0].sim_time;
        self.last_ms = Some(stamp);
        let joints = [
            Self::f32_of(&got[0], "simxGetJointPosition")?,
            Self::f32_of(&got[1], "simxGetJointPosition")?,
        ];
        let pose = Self::pose_of(
            Self::xyz_of(&got[2], "simxGetObjectPosition")?,
            Self::xyz_of(&got[3], "simxGetObjectOrientation")?,
        );
        let image = match (image && self.camera, p.camera) {
            (true, Some(cam)) => {
                if !self.streaming {
                    // every main-loop pass, as the course's loop streams it
                    self.client()?
                        .stream(&[Self::image_command(cam)], 0)
                        .map_err(lost)?;
                    self.streaming = true;
                }
                Some(self.image_at(cam, stamp)?)
            }
            _ => None,
        };
        if std::env::var_os("VREP_MAZE_TRACE").is_some() {
            eprintln!(
                "legacy robot: readings at {:.3} s after {reads} read(s)",
                f64::from(stamp) / 1000.0
            );
        }
        Ok(Reading {
            time: f64::from(stamp) / 1000.0,
            joints,
            pose,
            image,
        })
    }

    fn actuate(&mut self, wheels: Wheels) -> Result<(), RobotError> {
        // sent with the next step's trigger, in its message: executed in the same pass
        self.wheels = Some(wheels);
        Ok(())
    }

    fn step(&mut self) -> Result<(), RobotError> {
        let p = self.parts()?;
        let mut commands = vec![];
        if let Some(w) = self.wheels.take() {
            commands.push(Command::SetJointTargetVelocity {
                handle: p.left,
                velocity: w.left as f32,
            });
            commands.push(Command::SetJointTargetVelocity {
                handle: p.right,
                velocity: w.right as f32,
            });
        }
        commands.push(Command::SynchronousTrigger);
        let got = self.call(&commands)?;
        if got.iter().any(|r| r.remote_error) {
            return Err(RobotError::Connection(
                "the simulator refused the wheels or the step trigger (simulation stopped, or synchronous mode ended?)".into(),
            ));
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), RobotError> {
        let parts = self.parts;
        self.streaming = false;
        self.camera = false;
        let first = match self.client.as_mut() {
            Some(client) => Self::tidy(client, parts),
            None => Err(RobotError::Connection("the connection is closed".into())),
        };
        if first.is_ok() {
            return Ok(());
        }
        // the connection is lost: a fresh one stops the simulation (synchronous mode ended
        // with the lost connection)
        let Some((addr, options)) = self.reconnect.clone() else {
            return first;
        };
        if let Some(old) = self.client.take() {
            let _ = old.close();
        }
        let mut fresh = Client::connect(addr, options).map_err(lost)?;
        let done = Self::tidy(&mut fresh, parts);
        let _ = fresh.close();
        done
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn poses_and_mounts_read_coppeliasim_euler_angles() {
        let p = LegacyRobot::pose_of([1.0, -2.0, 0.06], [0.0, 0.0, 2.0]);
        assert!(
            (p.x - 1.0).abs() < 1e-12 && (p.y + 2.0).abs() < 1e-12,
            "{p:?}"
        );
        assert!((p.yaw - 2.0).abs() < 1e-12, "{p:?}");
        // alpha turns about x first: R = Rx(90 degrees), rows [1 0 0], [0 0 -1], [0 1 0]
        let m = LegacyRobot::matrix([0.1, 0.0, 0.05], [FRAC_PI_2, 0.0, 0.0]);
        let want = [1.0, 0.0, 0.0, 0.1, 0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, 0.05];
        assert!(
            m.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12),
            "{m:?}"
        );
    }
}
