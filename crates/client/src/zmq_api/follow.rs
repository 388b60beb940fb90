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

use super::cbor::{self, int};
use super::client::{Client, ZmqError, object_path};
use crate::held::Held;
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
}

impl<'a> ZmqFollower<'a> {
    /// Follows over `client`, closed when the follower is.
    pub fn new(client: Client) -> Self {
        Self::over(Held::Owned(client))
    }

    /// Follows over a drawing backend's client, left open ([`crate::draw::backend::Backend::follower`]).
    pub fn lent(client: &'a mut Client) -> Self {
        Self::over(Held::Lent(client))
    }

    fn over(client: Held<'a, Client>) -> Self {
        Self {
            client,
            handles: None,
            time: None,
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
}
