//! Following a robot over the legacy remote API, as the course handout's camera loop reads
//! its sensor: the pose is requested once in streaming mode (`simx_opmode_streaming`, every
//! main-loop pass, so every simulation step while the simulation runs) and then read from
//! the inbox (`simx_opmode_buffer`), each reply stamped with the simulation time it was
//! read at (`simxGetLastCmdTime`). A header-only message every look keeps the replies
//! coming, as the C client's communication thread does.

use super::client::Client;
use super::command::{Command, SimControl, read_f32x3, read_i32};
use crate::held::Held;
use vrep_maze_core::coppelia::frame::rotation_from_euler;
use vrep_maze_core::score::Sample;
use vrep_maze_core::score::follow::{FollowError, Follower, Look, heading};

/// A [`Follower`] over a legacy connection.
pub struct LegacyFollower<'a> {
    client: Held<'a, Client>,
    /// Robot and floor handles, once found.
    handles: Option<(i32, i32)>,
    /// The pose streams were requested.
    streaming: bool,
}

impl<'a> LegacyFollower<'a> {
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
            streaming: false,
        }
    }

    fn handle(&mut self, name: &str) -> Result<i32, FollowError> {
        let reply = self
            .client
            .call1(Command::GetObjectHandle(name.to_string()))
            .map_err(FollowError::lost)?;
        if reply.remote_error {
            return Err(FollowError::NoSuchObject(name.to_string()));
        }
        read_i32(&reply.data, 0).ok_or_else(|| FollowError::malformed("simxGetObjectHandle"))
    }

    fn streams(&self) -> Result<[Command; 2], FollowError> {
        let (handle, relative_to) = self
            .handles
            .ok_or_else(|| FollowError::Connection("the robot was not looked up".into()))?;
        Ok([
            Command::GetPosition {
                handle,
                relative_to,
            },
            Command::GetOrientation {
                handle,
                relative_to,
            },
        ])
    }
}

impl Follower for LegacyFollower<'_> {
    fn find(&mut self, robot: &str, floor: &str) -> Result<(), FollowError> {
        let robot = self.handle(robot)?;
        let floor = self.handle(floor)?;
        self.handles = Some((robot, floor));
        Ok(())
    }

    fn is_running(&mut self) -> Result<bool, FollowError> {
        self.client.poll().map_err(FollowError::lost)?;
        Ok(self.client.simulation_running().unwrap_or(false))
    }

    fn set_running(&mut self, run: bool) -> Result<(), FollowError> {
        let control = if run {
            SimControl::Start
        } else {
            SimControl::Stop
        };
        // a remote error only says it already was in that state
        self.client
            .call1(Command::Simulation(control))
            .map_err(FollowError::lost)?;
        Ok(())
    }

    fn look(&mut self) -> Result<Look, FollowError> {
        let [position, orientation] = self.streams()?;
        if self.streaming {
            self.client.poll().map_err(FollowError::lost)?;
        } else {
            self.client
                .stream(&[position.clone(), orientation.clone()], 0)
                .map_err(FollowError::lost)?;
            self.streaming = true;
        }
        if self.client.simulation_running() == Some(false) {
            return Ok(Look::Stopped);
        }
        let (Some((p, tp)), Some((e, te))) = (
            self.client.buffered(&position),
            self.client.buffered(&orientation),
        ) else {
            return Ok(Look::Nothing);
        };
        // both read in the same pass, while the simulation ran (0: stopped)
        if tp != te || tp <= 0 || p.remote_error || e.remote_error {
            return Ok(Look::Nothing);
        }
        let p = read_f32x3(&p.data, 0)
            .ok_or_else(|| FollowError::malformed("simxGetObjectPosition"))?;
        let e = read_f32x3(&e.data, 0)
            .ok_or_else(|| FollowError::malformed("simxGetObjectOrientation"))?;
        let rotation = rotation_from_euler(e.map(f64::from));
        Ok(Look::Pose(Sample {
            t: f64::from(tp) / 1000.0,
            x: f64::from(p[0]),
            y: f64::from(p[1]),
            yaw: heading(&rotation),
        }))
    }

    fn close(mut self: Box<Self>) {
        if self.streaming
            && let Ok(streams) = self.streams()
        {
            let _ = self.client.discontinue(&streams);
        }
        if let Some(client) = self.client.into_owned() {
            let _ = client.close();
        }
    }
}
