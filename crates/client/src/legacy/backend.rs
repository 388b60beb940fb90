//! The legacy remote API as a drawing backend: [`crate::draw::backend::Backend`] over [`Client`].

use std::collections::{HashMap, HashSet};
use std::time::{Duration, Instant};

use super::client::{Client, ClientError, ClientOptions, Reply};
use super::command::{
    ALL_OBJECTS, Command, GroupData, SimControl, decode_handle_list, group, read_i32,
};
use crate::draw::backend::{Backend, BoundingBox, Edit, IdleRates, ObjectInfo, Survey};
use crate::draw::error::BackendError;
use crate::draw::ownership::{self, is_copy_name};
use crate::draw::record::CopyRecord;
use crate::draw::signals::{self, COPIES, SAVED_IDLE_FPS};
use crate::draw::survey::Traits;
use crate::draw::survey::{SurveyHandles, SurveyNames};
use vrep_maze_core::coppelia::{
    DEFAULT_IDLE_FPS, HANDLE_WORLD, INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION, OBJFLOATPARAM_BBOX,
};
use vrep_maze_core::score::follow::Follower;

mod mesh;
mod robot;

/// A connected legacy remote API scene. Dropping it closes the connection cleanly.
pub struct LegacyBackend {
    client: Option<Client>,
    timeout: Duration,
    /// `host:port` as the user gave it, for [`Backend::describe`].
    addr: String,
    /// Run once the connection is closed cleanly (the simulator acknowledged the kill
    /// command), not when it ended any other way.
    on_clean_close: Option<Box<dyn FnOnce() + Send>>,
    /// The simulator runs on this machine (a loopback host): mesh models are loaded from a
    /// temporary file by its path instead of being sent with `simxTransferFile`.
    local: bool,
    /// The scene's record of the copies this tool pasted (read by the survey), whether it
    /// changed since, and the template alias of each object a paste may copy: the
    /// templates and their copies in the maze. Only the ZeroMQ backend needs the record (it
    /// cannot read names in a batch); this one keeps it true for it.
    record: CopyRecord,
    record_changed: bool,
    /// The survey read an older version's record (under [`signals::COPIES`]'s old name): it
    /// is emptied with the next write of the record (the legacy API cannot delete a string
    /// signal).
    old_record: bool,
    families: HashMap<i32, String>,
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
            on_clean_close: None,
            local,
            record: CopyRecord::default(),
            record_changed: false,
            old_record: false,
            families: HashMap::new(),
        })
    }

    /// Wraps a connected client to a simulator on this machine.
    pub fn new(client: Client, timeout: Duration) -> LegacyBackend {
        LegacyBackend {
            client: Some(client),
            timeout,
            addr: "a connected client".into(),
            on_clean_close: None,
            local: true,
            record: CopyRecord::default(),
            record_changed: false,
            old_record: false,
            families: HashMap::new(),
        }
    }

    /// Says where the client is connected (`host:port`, as [`Backend::describe`] names it:
    /// `legacy remote API at 127.0.0.1:19997`) instead of "a connected client".
    pub fn at(mut self, addr: impl Into<String>) -> LegacyBackend {
        self.addr = addr.into();
        self
    }

    /// Runs `then` once the connection is closed cleanly, by [`Backend::close`] or by
    /// dropping the backend (the simulator acknowledged the kill command and listens again
    /// within 0.5 s), not when the session ended any other way.
    pub fn on_clean_close(mut self, then: impl FnOnce() + Send + 'static) -> LegacyBackend {
        self.on_clean_close = Some(Box::new(then));
        self
    }

    /// Closes the client, if still open, and runs the clean-close action if it closed so.
    fn close_client(&mut self) -> Result<(), ClientError> {
        let Some(client) = self.client.take() else {
            return Ok(());
        };
        client.close()?;
        if let Some(then) = self.on_clean_close.take() {
            then();
        }
        Ok(())
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

    /// Learns from a survey which objects are the templates and their copies in the maze
    /// (named in a template's family and of its type, or recorded and of its type, and not
    /// contradicted by `traits`: [`ownership::contradicts_copy`]), and keeps `record` (the
    /// scene's) to those copies.
    fn learn_copies(
        &mut self,
        names: &SurveyNames<'_>,
        handles: &SurveyHandles,
        objects: &[ObjectInfo],
        traits: &Traits,
        mut record: CopyRecord,
    ) {
        self.families.clear();
        let templates = templates_of(names, handles);
        for (_, alias, h) in &templates {
            self.families.insert(*h, alias.clone());
        }
        let mut copies = HashMap::new();
        for (o, (name, alias, template)) in maze_objects(handles.parent, objects, &templates) {
            let of_type = kind_matches(traits, o.handle, *template);
            let named = is_copy_name(&o.name, name) || record.get(o.handle) == Some(alias);
            if of_type && named && !ownership::contradicts_copy(traits, o.handle, Some(*template)) {
                copies.insert(o.handle, alias.clone());
            }
        }
        // a named object the record holds stays in it: refused as a template or marker,
        // it is still our copy
        let mut changed =
            record.retain(|h| copies.contains_key(&h) || traits.recorded.contains(&h));
        for (h, alias) in &copies {
            changed |= record.insert(*h, alias);
        }
        self.families.extend(copies);
        self.record = record;
        self.record_changed = changed;
    }

    /// What tells the maze's copies from the user's objects named like them ([`Traits`]):
    /// `kinds`, plus the sizes and children of the objects named and typed like a
    /// template's copy that `record` does not hold (normally none: only a maze drawn by an
    /// older version, or a scene reloaded, since signals are not saved with it), of the
    /// copies it holds (a recorded copy scaled since is spoiled, one with children the
    /// user's), and of their templates. Sizes take six commands an object, in one request per
    /// [`SIZED_PER_REQUEST`] objects; children come with the survey's parents.
    fn traits(
        &mut self,
        names: &SurveyNames<'_>,
        handles: &SurveyHandles,
        objects: &[ObjectInfo],
        kinds: HashMap<i32, i32>,
        record: &CopyRecord,
    ) -> Result<Traits, BackendError> {
        let mut traits = Traits {
            kinds,
            ..Default::default()
        };
        let templates = templates_of(names, handles);
        // the record first: a named object it holds is one of our copies (refused as a
        // template or marker), a listed one of its template's type is ours
        traits.recorded = handles
            .into_array()
            .iter()
            .flatten()
            .copied()
            .filter(|h| record.get(*h).is_some())
            .collect();
        let mut doubtful = Vec::new();
        let mut sized: Vec<i32> = Vec::new();
        // the recorded copies are checked as new ones would be: size and children (this
        // API reads no colour)
        let mut recorded = Vec::new();
        for (o, (name, alias, template)) in maze_objects(handles.parent, objects, &templates) {
            if kind_matches(&traits, o.handle, *template) && record.get(o.handle) == Some(alias) {
                traits.recorded.insert(o.handle);
                recorded.push((o.handle, *template));
                if !sized.contains(template) {
                    sized.push(*template);
                }
            }
            if kind_matches(&traits, o.handle, *template)
                && is_copy_name(&o.name, name)
                && record.get(o.handle) != Some(alias)
            {
                doubtful.push(o.handle);
                if !sized.contains(template) {
                    sized.push(*template);
                }
            }
        }
        if doubtful.is_empty() && recorded.is_empty() {
            return Ok(traits);
        }
        let parents: HashSet<i32> = objects.iter().filter_map(|o| o.parent).collect();
        traits.with_children = doubtful
            .iter()
            .chain(recorded.iter().map(|(h, _)| h))
            .copied()
            .filter(|h| parents.contains(h))
            .collect();
        sized.extend(doubtful);
        sized.extend(recorded.iter().map(|(h, _)| *h));
        for chunk in sized.chunks(SIZED_PER_REQUEST) {
            for (h, b) in chunk.iter().zip(self.bounding_boxes(chunk)?) {
                if let Some(b) = b {
                    traits.sizes.insert(*h, b.size());
                }
            }
        }
        for (copy, template) in recorded {
            if let Some(why) = ownership::spoiled(&traits, copy, template) {
                traits.spoiled.insert(copy, why);
            }
        }
        Ok(traits)
    }

    fn call(&mut self, commands: &[Command]) -> Result<Vec<Reply>, BackendError> {
        Ok(self.client()?.call(commands)?)
    }
    /// The commands that store the copy record if it changed (or `edits` remove copies it
    /// holds, which it then drops), and delete an older version's record once.
    fn record_commands(&mut self, edits: &[Edit]) -> Vec<Command> {
        let mut cmds = Vec::new();
        let removed = Edit::removed(edits);
        let pruned = self.record.retain(|h| !removed.contains(&h));
        if std::mem::take(&mut self.record_changed) || pruned {
            // a String: valid UTF-8 ([`crate::draw::record`])
            let text: String = self.record.format();
            cmds.push(Command::SetStringSignal(
                COPIES.name.into(),
                text.into_bytes(),
            ));
            if std::mem::take(&mut self.old_record) {
                cmds.push(Command::SetStringSignal(COPIES.old.into(), vec![]));
            }
        }
        cmds
    }
}

impl Drop for LegacyBackend {
    fn drop(&mut self) {
        let _ = self.close_client();
    }
}

/// Objects sized in one request while telling copies from the user's objects (six
/// commands each: about 0.2 MB a request).
const SIZED_PER_REQUEST: usize = 1000;

/// The templates a survey asked for and found (the style's, the other style's, the post
/// template): name, alias, handle.
fn templates_of<'n>(
    names: &SurveyNames<'n>,
    handles: &SurveyHandles,
) -> Vec<(&'n str, String, i32)> {
    names
        .templates()
        .into_iter()
        .zip(handles.templates())
        .filter_map(|(n, h)| h.map(|h| (n, ownership::family(n).to_string(), h)))
        .collect()
}

/// The objects that may be a template's copy in the maze (children of the maze dummy
/// `parent` and parentless objects, but not the templates; none without a maze dummy), each
/// paired with each of `templates`: callers test the family.
fn maze_objects<'a, 't>(
    parent: Option<i32>,
    objects: &'a [ObjectInfo],
    templates: &'t [(&str, String, i32)],
) -> impl Iterator<Item = (&'a ObjectInfo, &'t (&'t str, String, i32))> {
    objects
        .iter()
        .filter(move |o| {
            parent.is_some()
                && (o.parent == parent || o.parent.is_none())
                && !templates.iter().any(|t| t.2 == o.handle)
        })
        .flat_map(move |o| templates.iter().map(move |t| (o, t)))
}

/// `true` if `handle` and `template` are both of a known and the same type.
fn kind_matches(traits: &Traits, handle: i32, template: i32) -> bool {
    let kind = |h: i32| traits.kinds.get(&h);
    kind(handle).is_some() && kind(handle) == kind(template)
}

fn group_commands() -> [Command; 3] {
    group_data_commands([group::NAMES, group::PARENTS, group::ABSOLUTE_POSES])
}

fn group_data_commands<const N: usize>(data_types: [i32; N]) -> [Command; N] {
    data_types.map(|data_type| Command::GetObjectGroupData {
        object_type: ALL_OBJECTS,
        data_type,
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

/// Appends the commands of `edits` to `cmds` (the floats as `f32`); what each does, in
/// order, for an error message.
fn edit_commands(edits: &[Edit], cmds: &mut Vec<Command>) -> Vec<String> {
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
    what
}

impl Backend for LegacyBackend {
    fn idle_rates(&mut self) -> Result<IdleRates, BackendError> {
        let r = self.call(&[
            Command::GetIntParam(INTPARAM_IDLE_FPS),
            Command::GetIntSignal(SAVED_IDLE_FPS.name.into()),
            Command::GetIntSignal(SAVED_IDLE_FPS.old.into()),
        ])?;
        let current = if r[0].remote_error {
            return Err(BackendError::Remote("reading the idle rate".into()));
        } else {
            read_i32(&r[0].data, 0).unwrap_or(DEFAULT_IDLE_FPS)
        };
        // no record: the signal does not exist, which the server reports as an error
        let saved_in = |r: &crate::legacy::client::Reply| {
            (!r.remote_error).then(|| read_i32(&r.data, 0)).flatten()
        };
        let saved = signals::newest(saved_in(&r[1]), saved_in(&r[2]));
        Ok(IdleRates { current, saved })
    }

    /// Sized by the shared cost model (`vrep_maze_core::coppelia::cost`: pasting and re-parenting
    /// grow with the objects in the scene).
    fn pieces_per_request(&self, objects_in_scene: usize) -> usize {
        crate::draw::estimate::legacy_pieces_per_request(objects_in_scene)
    }

    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError> {
        let asked = names.into_array();
        let mut cmds: Vec<Command> = asked
            .iter()
            .map(|n| Command::GetObjectHandle(n.to_string()))
            .collect();
        cmds.extend(group_commands());
        cmds.extend(group_data_commands([group::TYPES]));
        cmds.push(Command::GetStringSignal(COPIES.name.into()));
        cmds.push(Command::GetStringSignal(COPIES.old.into()));
        let r = self.call(&cmds)?;
        let k = asked.len();
        // an unset signal (or a simulator without string signals) is a remote error
        let text = |at: usize| {
            r.get(at)
                .filter(|r| !r.remote_error)
                .map(|r| String::from_utf8_lossy(&r.data).into_owned())
        };
        let old = text(k + 5).filter(|t| !t.is_empty());
        let new = text(k + 4);
        // an older version's record moves to the new name with the next edits
        let moved = old.is_some();
        self.old_record = old.is_some();
        let parse = |t: Option<String>| t.map(|t| CopyRecord::parse(&t)).unwrap_or_default();
        let record = parse(new).merged(parse(old));
        let types = &r[k + 3];
        let kinds = match GroupData::decode(&types.data) {
            Some(g) if !types.remote_error && g.ints.len() == g.handles.len() => {
                g.handles.into_iter().zip(g.ints).collect()
            }
            _ => {
                return Err(BackendError::Transport(
                    "malformed group data reply (types)".into(),
                ));
            }
        };
        let handle = |r: &Reply| {
            if r.remote_error {
                None
            } else {
                read_i32(&r.data, 0).filter(|&h| h >= 0)
            }
        };
        let handles = SurveyHandles::from_array(std::array::from_fn(|i| handle(&r[i])));
        let objects = parse_objects(&r[k..k + 3])?;
        // the simulation state of the survey's own reply (a second request may follow)
        let simulation_running = self.client()?.simulation_running().unwrap_or(false);
        let traits = self.traits(names, &handles, &objects, kinds, &record)?;
        self.learn_copies(names, &handles, &objects, &traits, record);
        self.record_changed |= moved;
        Ok(Survey {
            handles,
            objects,
            simulation_running,
            traits,
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
            .flat_map(|&h| bounding_box_commands(h))
            .collect();
        let r = self.call(&cmds)?;
        Ok(r.chunks(6).map(bounding_box_of).collect())
    }

    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError> {
        let cmds: Vec<Command> = names
            .iter()
            .map(|n| Command::GetIntSignal(n.to_string()))
            .collect();
        // a signal that does not exist is reported as an error
        Ok(self
            .call(&cmds)?
            .iter()
            .map(|r| (!r.remote_error).then(|| read_i32(&r.data, 0)).flatten())
            .collect())
    }

    fn set_int_signals(&mut self, signals: &[(&str, Option<i32>)]) -> Result<(), BackendError> {
        let cmds: Vec<Command> = signals
            .iter()
            .map(|(name, value)| match value {
                Some(v) => Command::SetIntSignal(name.to_string(), *v),
                None => Command::ClearIntSignal(name.to_string()),
            })
            .collect();
        if self.call(&cmds)?.iter().any(|r| r.remote_error) {
            return Err(BackendError::Remote("setting integer signals".into()));
        }
        Ok(())
    }

    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        let cmds: Vec<Command> = groups
            .iter()
            .map(|g| Command::CopyPaste(g.clone()))
            .collect();
        let r = self.call(&cmds)?;
        let pasted = groups
            .iter()
            .zip(r)
            .map(|(g, r)| match decode_handle_list(&r.data) {
                Some(new) if !r.remote_error && new.len() == g.len() => Ok(new),
                _ => Err(BackendError::Remote(format!(
                    "copy-paste of {} object(s) failed",
                    g.len()
                ))),
            })
            .collect::<Result<Vec<Vec<i32>>, BackendError>>()?;
        // a copy of a template or of its copy is the template's: recorded, written with the
        // next edits (which re-parent it)
        for (g, new) in groups.iter().zip(&pasted) {
            for (source, copy) in g.iter().zip(new) {
                if let Some(alias) = self.families.get(source).cloned() {
                    self.record_changed |= self.record.insert(*copy, &alias);
                    self.families.insert(*copy, alias);
                }
            }
        }
        Ok(pasted)
    }

    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError> {
        // the changed copy record rides with the edits, without the copies they remove: no
        // request of its own
        let mut cmds = self.record_commands(edits);
        let record = cmds.len();
        let what = edit_commands(edits, &mut cmds);
        let r = self.call(&cmds)?;
        // a simulator without string signals only loses the record
        let failed: Vec<&str> = r[record..]
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
        // deleting the record deletes an older version's too
        let mut cmds = match saved {
            Some(v) => vec![Command::SetIntSignal(SAVED_IDLE_FPS.name.into(), v)],
            None => vec![
                Command::ClearIntSignal(SAVED_IDLE_FPS.name.into()),
                Command::ClearIntSignal(SAVED_IDLE_FPS.old.into()),
            ],
        };
        // record first: if setting the rate fails, the record still tells the next run
        cmds.push(Command::SetIntParam(INTPARAM_IDLE_FPS, fps));
        let r = self.call(&cmds)?;
        if r.last().is_none_or(|r| r.remote_error) {
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

    fn remote_api(&self) -> Option<crate::draw::estimate::RemoteApi> {
        Some(crate::draw::estimate::RemoteApi::Legacy)
    }

    fn describe(&self) -> String {
        format!("legacy remote API at {}", self.addr)
    }

    fn meshes(&mut self) -> Option<&mut dyn crate::draw::mesh::MeshDrawing> {
        Some(self)
    }

    fn model_box(&mut self, name: &str) -> Result<Option<BoundingBox>, BackendError> {
        self.read_model_box(name)
    }

    fn follower(&mut self) -> Option<Box<dyn Follower + '_>> {
        let client = self.client.as_mut()?;
        Some(Box::new(super::follow::LegacyFollower::lent(client)))
    }

    /// Ends the session as `simxFinish` does ([`Client::close`]).
    fn close(&mut self) -> Result<(), BackendError> {
        Ok(self.close_client()?)
    }
}

/// The six float parameters (15-20) that make `handle`'s bounding box.
pub(super) fn bounding_box_commands(handle: i32) -> impl Iterator<Item = Command> {
    (0..6).map(move |k| Command::GetObjectFloatParam {
        handle,
        param: OBJFLOATPARAM_BBOX + k,
    })
}

/// The bounding box the six replies to [`bounding_box_commands`] give; `None` if any failed.
pub(super) fn bounding_box_of(six: &[Reply]) -> Option<BoundingBox> {
    let v: Option<Vec<f64>> = six
        .iter()
        .map(|r| {
            let b = r.data.get(..4).filter(|_| !r.remote_error)?;
            Some(f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64)
        })
        .collect();
    let v = v.filter(|v| v.len() == 6)?;
    Some(BoundingBox {
        min: [v[0], v[1], v[2]],
        max: [v[3], v[4], v[5]],
    })
}
