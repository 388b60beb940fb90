//! Following a robot over the ZeroMQ remote API. The cheapest reliable way: each look is
//! two calls, `sim.getObjectPose(robot, floor)` (position and orientation in one reply)
//! then `sim.getSimulationTime()`, and the time read after one pose is the time read
//! before the next. The add-on serves requests between simulation steps, so the pose's
//! step lies between the two times around it, and the sample is stamped with their
//! midpoint: exact when they agree (protocol 2, 4.6+, may serve several requests in one
//! pass) or are two steps apart (protocol 1, 4.5.1, serves one request per pass: the pose
//! is of the step between), else within half a step. At one request per pass the scorer
//! sees every second step (measured against the emulator: 54 samples over 5.5 s at
//! protocol 1, 80 at protocol 2, 107 over the legacy stream). Polling the state as well would
//! cost a third call per look, so `sim.getSimulationState()` is asked only when the time
//! stands at 0 or goes back (a stop). Streaming over ZeroMQ needs a script in the scene
//! and stepped mode changes how the simulation runs; this scorer changes neither.

use ciborium::Value;
use nalgebra::{Quaternion, UnitQuaternion};

use super::Protocol;
use super::backend::object_path;
use super::cbor::{self, int};
use super::client::{Client, ZmqError};
use crate::held::Held;
use crate::robot::DRIVER_SIGNAL;
use vrep_maze_core::coppelia::SIMULATION_STOPPED;
use vrep_maze_core::score::Sample;
use vrep_maze_core::score::follow::{FollowError, Follower, Look, heading};

/// A [`Follower`] over a ZeroMQ connection.
pub struct ZmqFollower<'a> {
    client: Held<'a, Client>,
    /// Robot and floor handles, once found.
    handles: Option<(i32, i32)>,
    /// The simulation time read last (the "before" of the next look).
    time: Option<f64>,
    /// The name protocol 1's stepping globals know this follower by, once it stepped.
    uuid: String,
}

impl<'a> ZmqFollower<'a> {
    /// Follows over `client`, closed when the follower is.
    pub fn new(client: Client) -> Self {
        Self::over(Held::Owned(client))
    }

    /// Follows over a drawing backend's client, left open ([`crate::draw::Backend::follower`]).
    pub fn lent(client: &'a mut Client) -> Self {
        Self::over(Held::Lent(client))
    }

    fn over(client: Held<'a, Client>) -> Self {
        Self {
            client,
            handles: None,
            time: None,
            uuid: super::client::new_uuid(),
        }
    }

    fn handle(&mut self, name: &str) -> Result<i32, FollowError> {
        let opts = cbor::map([("noError", Value::Bool(true))]);
        match self
            .client
            .call_int("sim.getObject", vec![Value::Text(object_path(name)), opts])
        {
            Ok(h) if h >= 0 => Ok(h),
            Ok(_) | Err(ZmqError::Remote { .. }) => {
                Err(FollowError::NoSuchObject(name.to_string()))
            }
            Err(e) => Err(FollowError::lost(e)),
        }
    }

    /// The driver's signal ([`DRIVER_SIGNAL`]), if set.
    fn driver_signal(&mut self) -> Result<Option<i64>, FollowError> {
        match self.client.call(
            "sim.getInt32Signal",
            vec![Value::Text(DRIVER_SIGNAL.into())],
        ) {
            Ok(values) => Ok(values.first().and_then(cbor::integer)),
            Err(ZmqError::Remote { .. }) => Ok(None),
            Err(e) => Err(FollowError::lost(e)),
        }
    }

    /// Stepping on or off, as the add-on of this protocol spells it.
    fn set_stepping(&mut self, on: bool) -> Result<(), FollowError> {
        let call = match self.client.protocol() {
            Some(Protocol::V1) => self.client.call(
                "setStepping",
                vec![Value::Bool(on), Value::Text(self.uuid.clone())],
            ),
            _ => self.client.call("sim.setStepping", vec![Value::Bool(on)]),
        };
        call.map(|_| ()).map_err(FollowError::lost)
    }

    fn time(&mut self) -> Result<f64, FollowError> {
        let v = self
            .client
            .call1("sim.getSimulationTime", vec![])
            .map_err(FollowError::lost)?;
        cbor::number(&v).ok_or_else(|| FollowError::malformed("sim.getSimulationTime"))
    }
}

impl Follower for ZmqFollower<'_> {
    fn find(&mut self, robot: &str, floor: &str) -> Result<(), FollowError> {
        let robot = self.handle(robot)?;
        let floor = self.handle(floor)?;
        self.handles = Some((robot, floor));
        Ok(())
    }

    fn is_running(&mut self) -> Result<bool, FollowError> {
        let state = self
            .client
            .call_int("sim.getSimulationState", vec![])
            .map_err(FollowError::lost)?;
        Ok(state != SIMULATION_STOPPED)
    }

    fn set_running(&mut self, run: bool) -> Result<(), FollowError> {
        let func = if run {
            "sim.startSimulation"
        } else {
            "sim.stopSimulation"
        };
        self.client.call(func, vec![]).map_err(FollowError::lost)?;
        Ok(())
    }

    fn look(&mut self) -> Result<Look, FollowError> {
        let (robot, floor) = self
            .handles
            .ok_or_else(|| FollowError::Connection("the robot was not looked up".into()))?;
        let before = match self.time {
            Some(t) => t,
            None => self.time()?,
        };
        let pose = self
            .client
            .call1(
                "sim.getObjectPose",
                vec![int(robot.into()), int(floor.into())],
            )
            .map_err(FollowError::lost)?;
        let after = self.time()?;
        self.time = Some(after);
        if (after <= 0.0 || after < before) && !self.is_running()? {
            return Ok(Look::Stopped);
        }
        if after < before {
            // stopped and started again between two looks: the followed run is over
            return Ok(Look::Stopped);
        }
        if after <= 0.0 {
            return Ok(Look::Nothing);
        }
        let p =
            cbor::numbers::<7>(&pose).ok_or_else(|| FollowError::malformed("sim.getObjectPose"))?;
        let rotation = UnitQuaternion::from_quaternion(Quaternion::new(p[6], p[3], p[4], p[5]));
        Ok(Look::Pose(Sample {
            t: (before + after) / 2.0,
            x: p[0],
            y: p[1],
            yaw: heading(&rotation),
        }))
    }

    fn close(self: Box<Self>) {
        if let Some(client) = self.client.into_owned() {
            client.close();
        }
    }

    fn awaits_driver(&mut self) -> Result<bool, FollowError> {
        let Some((robot, _)) = self.handles else {
            return Ok(false);
        };
        if self.driver_signal()?.is_some() {
            return Ok(false);
        }
        // sim.object_joint_type (1) under the robot: wheels something must drive
        match self.client.call(
            "sim.getObjectsInTree",
            vec![int(robot.into()), int(1), int(0)],
        ) {
            Ok(values) => Ok(values
                .first()
                .and_then(cbor::array)
                .is_some_and(|joints| !joints.is_empty())),
            Err(ZmqError::Remote { .. }) => Ok(false),
            Err(e) => Err(FollowError::lost(e)),
        }
    }

    fn join_driver(&mut self) -> Result<bool, FollowError> {
        if self.driver_signal()? != Some(1) {
            return Ok(false);
        }
        self.set_stepping(true)?;
        Ok(true)
    }

    fn step(&mut self) -> Result<(), FollowError> {
        // the next look reads the time anew: the step moved it
        self.time = None;
        match self.client.protocol() {
            Some(Protocol::V1) => {
                let before = self.time()?;
                self.client
                    .call("step", vec![Value::Text(self.uuid.clone())])
                    .map_err(FollowError::lost)?;
                // the step shows as the time advancing, unless the simulation stopped
                let deadline = std::time::Instant::now() + STEP_WAIT;
                while self.time()? <= before && self.is_running()? {
                    if std::time::Instant::now() >= deadline {
                        return Err(FollowError::Connection(format!(
                            "the simulation did not advance within {} s of a step",
                            STEP_WAIT.as_secs()
                        )));
                    }
                }
                Ok(())
            }
            _ => self
                .client
                .call("sim.step", vec![])
                .map(|_| ())
                .map_err(FollowError::lost),
        }
    }

    fn leave(&mut self) -> Result<(), FollowError> {
        self.set_stepping(false)
    }
}

/// How long a protocol-1 step may take to show in the simulation time.
const STEP_WAIT: std::time::Duration = std::time::Duration::from_secs(30);
