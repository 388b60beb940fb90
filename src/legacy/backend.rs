//! The legacy remote API as a drawing backend: [`crate::draw::Backend`] over [`Client`].

use std::time::{Duration, Instant};

use super::client::{Client, ClientError, ClientOptions, Reply};
use super::command::{
    ALL_OBJECTS, Command, GroupData, SimControl, decode_handle_list, group, read_i32,
};
use crate::coppelia::{
    DEFAULT_IDLE_FPS, HANDLE_WORLD, INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION, OBJFLOATPARAM_BBOX,
};
use crate::draw::{
    Backend, BackendError, BoundingBox, Edit, IdleRates, ObjectInfo, SAVED_IDLE_FPS_SIGNAL, Survey,
};

mod mesh;

/// A connected legacy remote API scene. Dropping it closes the connection cleanly.
pub struct LegacyBackend {
    client: Option<Client>,
    timeout: Duration,
    /// `host:port` as the user gave it, for [`Backend::describe`].
    addr: String,
    /// The simulator runs on this machine (a loopback host): mesh models are loaded from a
    /// temporary file by its path instead of being sent with `simxTransferFile`.
    local: bool,
}

impl From<ClientError> for BackendError {
    fn from(e: ClientError) -> BackendError {
        BackendError::Transport(e.to_string())
    }
}

impl LegacyBackend {
    /// Connects to `host:port`, retrying for up to `timeout`, which is also the timeout of
    /// each request.
    pub fn connect(
        host: &str,
        port: u16,
        timeout: Duration,
    ) -> Result<LegacyBackend, BackendError> {
        let opts = ClientOptions {
            connect_timeout: timeout,
            reply_timeout: timeout,
            ..Default::default()
        };
        let addr = if host.contains(':') && !host.starts_with('[') {
            format!("[{host}]:{port}")
        } else {
            format!("{host}:{port}")
        };
        let client = Client::connect(&addr, opts)?;
        let local = host.eq_ignore_ascii_case("localhost")
            || host
                .trim_matches(['[', ']'])
                .parse::<std::net::IpAddr>()
                .is_ok_and(|ip| ip.is_loopback());
        Ok(LegacyBackend {
            client: Some(client),
            timeout,
            addr,
            local,
        })
    }

    /// Wraps a connected client to a simulator on this machine.
    pub fn new(client: Client, timeout: Duration) -> LegacyBackend {
        LegacyBackend {
            client: Some(client),
            timeout,
            addr: "a connected client".into(),
            local: true,
        }
    }

    /// Sends mesh models with `simxTransferFile` as for a simulator on another machine,
    /// even when it is on this one.
    pub fn transferring_models(mut self) -> LegacyBackend {
        self.local = false;
        self
    }

    fn client(&mut self) -> Result<&mut Client, BackendError> {
        self.client
            .as_mut()
            .ok_or_else(|| BackendError::Transport("connection already closed".into()))
    }

    fn call(&mut self, commands: &[Command]) -> Result<Vec<Reply>, BackendError> {
        Ok(self.client()?.call(commands)?)
    }
}

impl Drop for LegacyBackend {
    fn drop(&mut self) {
        if let Some(c) = self.client.take() {
            let _ = c.close();
        }
    }
}

fn group_commands() -> [Command; 3] {
    [group::NAMES, group::PARENTS, group::ABSOLUTE_POSES].map(|data_type| {
        Command::GetObjectGroupData {
            object_type: ALL_OBJECTS,
            data_type,
        }
    })
}

fn parse_objects(replies: &[Reply]) -> Result<Vec<ObjectInfo>, BackendError> {
    let bad = |what: &str| BackendError::Transport(format!("malformed group data reply ({what})"));
    if replies.iter().any(|r| r.remote_error) {
        return Err(BackendError::Remote(
            "reading the object list (group data) failed".into(),
        ));
    }
    let decode = |r: &Reply| GroupData::decode(&r.data).ok_or_else(|| bad("sizes"));
    let (names, parents, poses) = (
        decode(&replies[0])?,
        decode(&replies[1])?,
        decode(&replies[2])?,
    );
    let n = names.handles.len();
    if names.strings.len() != n
        || parents.ints.len() != n
        || poses.floats.len() != 6 * n
        || parents.handles != names.handles
        || poses.handles != names.handles
    {
        return Err(bad("counts"));
    }
    Ok((0..n)
        .map(|i| {
            let f = |k: usize| poses.floats[6 * i + k] as f64;
            ObjectInfo {
                handle: names.handles[i],
                name: names.strings[i].clone(),
                parent: (parents.ints[i] >= 0).then_some(parents.ints[i]),
                position: [f(0), f(1), f(2)],
                orientation: [f(3), f(4), f(5)],
            }
        })
        .collect())
}

/// Server time one request may take: well within any reply timeout, and short enough that a
/// progress bar moves every couple of seconds.
const REQUEST_SECONDS: f64 = 1.5;
/// The server's time per pasted and placed line, and its growth per object in the scene
/// (re-parenting rebuilds the new parent's child order and walks the parentless objects):
/// fitted to `../shared/spec/real-coppeliasim-4.5.1.md`, "Drawing cost on the server"
/// (30x30: 1.54 s, 60x60: 11.1 s; 100x100 over 60 s in one request).
const SECONDS_PER_LINE: f64 = 0.65e-3;
/// See [`SECONDS_PER_LINE`] (an upper bound: `Maze`'s children plus the parentless objects
/// are at most the objects in the scene).
const SECONDS_PER_LINE_PER_OBJECT: f64 = 127e-9;

impl Backend for LegacyBackend {
    fn idle_rates(&mut self) -> Result<IdleRates, BackendError> {
        let r = self.call(&[
            Command::GetIntParam(INTPARAM_IDLE_FPS),
            Command::GetIntSignal(SAVED_IDLE_FPS_SIGNAL.into()),
        ])?;
        let current = if r[0].remote_error {
            return Err(BackendError::Remote("reading the idle rate".into()));
        } else {
            read_i32(&r[0].data, 0).unwrap_or(DEFAULT_IDLE_FPS)
        };
        // no record: the signal does not exist, which the server reports as an error
        let saved = if r[1].remote_error {
            None
        } else {
            read_i32(&r[1].data, 0)
        };
        Ok(IdleRates { current, saved })
    }

    fn lines_per_request(&self, objects_in_scene: usize) -> usize {
        let per_line = SECONDS_PER_LINE + SECONDS_PER_LINE_PER_OBJECT * objects_in_scene as f64;
        (REQUEST_SECONDS / per_line) as usize
    }

    fn survey(&mut self, names: &[&str]) -> Result<Survey, BackendError> {
        let mut cmds: Vec<Command> = names
            .iter()
            .map(|n| Command::GetObjectHandle(n.to_string()))
            .collect();
        cmds.extend(group_commands());
        let r = self.call(&cmds)?;
        let k = names.len();
        let handles = r[..k]
            .iter()
            .map(|r| {
                if r.remote_error {
                    None
                } else {
                    read_i32(&r.data, 0).filter(|&h| h >= 0)
                }
            })
            .collect();
        let objects = parse_objects(&r[k..])?;
        let simulation_running = self.client()?.simulation_running().unwrap_or(false);
        Ok(Survey {
            handles,
            objects,
            simulation_running,
        })
    }

    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        let r = self.call(&group_commands())?;
        parse_objects(&r)
    }

    fn bounding_boxes(
        &mut self,
        handles: &[i32],
    ) -> Result<Vec<Option<BoundingBox>>, BackendError> {
        let cmds: Vec<Command> = handles
            .iter()
            .flat_map(|&handle| {
                (0..6).map(move |k| Command::GetObjectFloatParam {
                    handle,
                    param: OBJFLOATPARAM_BBOX + k,
                })
            })
            .collect();
        let r = self.call(&cmds)?;
        Ok(r.chunks(6)
            .map(|six| {
                let v: Option<Vec<f64>> = six
                    .iter()
                    .map(|r| {
                        let b = r.data.get(..4).filter(|_| !r.remote_error)?;
                        Some(f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64)
                    })
                    .collect();
                v.map(|v| BoundingBox {
                    min: [v[0], v[1], v[2]],
                    max: [v[3], v[4], v[5]],
                })
            })
            .collect())
    }

    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        let cmds: Vec<Command> = groups
            .iter()
            .map(|g| Command::CopyPaste(g.clone()))
            .collect();
        let r = self.call(&cmds)?;
        groups
            .iter()
            .zip(r)
            .map(|(g, r)| match decode_handle_list(&r.data) {
                Some(new) if !r.remote_error && new.len() == g.len() => Ok(new),
                _ => Err(BackendError::Remote(format!(
                    "copy-paste of {} object(s) failed",
                    g.len()
                ))),
            })
            .collect()
    }

    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError> {
        let mut cmds = Vec::with_capacity(edits.len() * 2);
        let mut what = Vec::with_capacity(edits.len() * 2);
        let f = |v: [f64; 3]| [v[0] as f32, v[1] as f32, v[2] as f32];
        for e in edits {
            match *e {
                Edit::SetParent {
                    handle,
                    parent,
                    keep_in_place,
                } => {
                    cmds.push(Command::SetObjectParent {
                        handle,
                        parent: parent.unwrap_or(HANDLE_WORLD),
                        keep_in_place,
                    });
                    what.push(format!("set the parent of object {handle}"));
                }
                Edit::SetPose {
                    handle,
                    relative_to,
                    position,
                    orientation,
                } => {
                    cmds.push(Command::SetPosition {
                        handle,
                        relative_to,
                        xyz: f(position),
                    });
                    cmds.push(Command::SetOrientation {
                        handle,
                        relative_to,
                        euler: f(orientation),
                    });
                    what.push(format!("set the position of object {handle}"));
                    what.push(format!("set the orientation of object {handle}"));
                }
                Edit::Remove(handle) => {
                    cmds.push(Command::RemoveObject(handle));
                    what.push(format!("remove object {handle}"));
                }
            }
        }
        let r = self.call(&cmds)?;
        let failed: Vec<&str> = r
            .iter()
            .zip(&what)
            .filter(|(r, _)| r.remote_error)
            .map(|(_, w)| w.as_str())
            .collect();
        if failed.is_empty() {
            Ok(())
        } else {
            Err(BackendError::Remote(format!(
                "{} of {} edits failed: {}",
                failed.len(),
                what.len(),
                failed.join("; ")
            )))
        }
    }

    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError> {
        let record = match saved {
            Some(v) => Command::SetIntSignal(SAVED_IDLE_FPS_SIGNAL.into(), v),
            None => Command::ClearIntSignal(SAVED_IDLE_FPS_SIGNAL.into()),
        };
        // record first: if setting the rate fails, the record still tells the next run
        let r = self.call(&[record, Command::SetIntParam(INTPARAM_IDLE_FPS, fps)])?;
        if r[1].remote_error {
            Err(BackendError::Remote(format!(
                "setting the idle rate to {fps} fps"
            )))
        } else {
            Ok(())
        }
    }

    fn stop_simulation(&mut self) -> Result<(), BackendError> {
        let deadline = Instant::now() + self.timeout;
        self.client()?
            .call1(Command::Simulation(SimControl::Stop))?;
        loop {
            // the state bit of a reply is stamped before the pass executes, so ask again
            let c = self.client()?;
            c.call1(Command::GetIntParam(INTPARAM_PROGRAM_VERSION))?;
            if c.simulation_running() == Some(false) {
                return Ok(());
            }
            if Instant::now() > deadline {
                return Err(BackendError::Remote("the simulation did not stop".into()));
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn round_trips(&self) -> usize {
        self.client.as_ref().map(Client::round_trips).unwrap_or(0)
    }

    fn describe(&self) -> String {
        format!("legacy remote API at {}", self.addr)
    }

    /// Sends the kill command (as `simxFinish` does) and closes the socket.
    fn meshes(&mut self) -> Option<&mut dyn crate::draw::mesh::MeshDrawing> {
        Some(self)
    }

    fn close(&mut self) -> Result<(), BackendError> {
        match self.client.take() {
            Some(c) => Ok(c.close()?),
            None => Ok(()),
        }
    }
}
