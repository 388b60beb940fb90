//! The ZeroMQ remote API as a drawing backend: [`crate::draw::backend::Backend`] over [`Client`].
//!
//! Objects are found by path (`/Maze`, `/Line`); the earlier maze is the object tree under
//! the maze dummy (`sim.getObjectsInTree`), plus root objects that carry a template's alias
//! (copies pasted by an interrupted run, reported by their path `/Line[n]`). Each pose is
//! one `sim.setObjectPose` call; removals go in one `sim.removeObjects` call. The ZeroMQ API
//! has one call per object where the legacy API batches, so "one round trip" operations of
//! the trait cost one call per object; reads that do not depend on each other's answers are
//! made by one request ([`Client::read_all`]), writes sent together ([`Client::call_all`])
//! and served by one main-loop pass.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use ciborium::Value;
use nalgebra::{Quaternion, UnitQuaternion};

use super::cbor::{self, float_array, int};
use super::client::{Client, ClientOptions, Outcome, ZmqError, object_path};
use crate::draw::backend::{
    Authoring, Backend, BoundingBox, Edit, IdleRates, Lease, ObjectInfo, Survey,
};
use crate::draw::error::BackendError;
use crate::draw::record::CopyRecord;
use crate::draw::signals::{self, COPIES, SAVED_IDLE_FPS};
use crate::draw::survey::{SurveyHandles, SurveyNames};
use vrep_maze_core::coppelia::frame::{
    Frame, euler_from_rotation, frame, position_euler, rotation_from_euler,
};
use vrep_maze_core::coppelia::{
    HANDLE_ALL, HANDLE_WORLD, INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION, OBJECT_SHAPE_TYPE,
    OBJFLOATPARAM_BBOX, SIMULATION_STOPPED,
};
use vrep_maze_core::score::follow::Follower;

mod authoring;
mod lease;
mod mesh;
mod robot;
mod survey;

impl From<ZmqError> for BackendError {
    fn from(e: ZmqError) -> BackendError {
        match e {
            ZmqError::Remote { .. } => BackendError::Remote(e.to_string()),
            other => BackendError::Transport(other.to_string()),
        }
    }
}

/// What the last survey resolved, so [`Backend::objects`] can list the same objects.
#[derive(Debug, Clone, Default)]
struct Known {
    named: Vec<(String, i32)>,
    parent: Option<i32>,
    line_alias: String,
    /// Aliases of the other templates found in the scene (the other style's, the post's):
    /// the maze dummy's children carrying one are named after it, so a drawing can tell
    /// them from copies of its own template.
    foreign_aliases: Vec<String>,
}

/// A world pose: position and CoppeliaSim Euler angles.
type WorldPose = ([f64; 3], [f64; 3]);

/// Whether [`ZmqBackend::collect`] reads the poses of the maze's lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum LinePoses {
    /// Poses this connection set (and the simulator acknowledged), NaN for the others: a
    /// survey then reads no line one by one, and apply sets every line it does not know.
    Known,
    /// Poses this connection set, and a read of every other (verification).
    Read,
    /// Every pose read now.
    Fresh,
}

/// A connected ZeroMQ remote API scene.
#[derive(Debug)]
pub struct ZmqBackend {
    client: Client,
    version: i32,
    known: Known,
    timeout: Duration,
    /// World poses of objects this connection placed or read, by handle. ZeroMQ has no
    /// batching, so reading a line costs as much as placing it; a pose the simulator
    /// acknowledged setting is not read back.
    poses: HashMap<i32, WorldPose>,
    /// Alias and type code of objects this connection read or pasted, by handle (an
    /// object's alias and type do not change while a run draws).
    traits: HashMap<i32, (String, i32)>,
    /// Aliases read without the type (root objects that are no template's copy).
    aliases: HashMap<i32, String>,
    /// The scene's record of the copies this tool pasted ([`CopyRecord`]), read once per
    /// connection, and whether it changed since it was last written.
    record: Option<CopyRecord>,
    record_changed: bool,
    /// An older version's copy record was read (under [`signals::COPIES`]'s old name): it is
    /// removed with the next write of the record.
    old_record: bool,
    /// An older version's record of the user's idle rate was read (under
    /// [`signals::SAVED_IDLE_FPS`]'s old name): deleting the record deletes it too.
    old_saved_rate: bool,
    /// `false` once the simulator did not keep the lease ([`Lease::unkept`]): the copy record
    /// is then neither read nor written.
    signals_kept: bool,
    /// The idle rates read with the version when connecting, the round trips made then and
    /// when: [`Backend::idle_rates`] takes them while no other call has been made since,
    /// within [`FIRST_RATES_FRESH`].
    first_rates: Option<(IdleRates, usize, Instant)>,
    /// Bounding-box extents and whether an object has children, of the objects a survey
    /// doubted ([`ZmqBackend::doubt`]) and their templates; emptied by each survey.
    extents: HashMap<i32, Option<[f64; 3]>>,
    children: HashMap<i32, bool>,
    /// Whether anything lies below the maze dummy's children (one call for the whole
    /// maze, made for the first doubted child of a survey).
    deep: Option<bool>,
    /// The root objects the last survey found named like a mesh of ours
    /// ([`crate::draw::mesh::FoundMeshes::elsewhere`]).
    root_meshes: Vec<String>,
}

fn alias_of(name: &str) -> &str {
    let last = name.rsplit('/').next().unwrap_or(name);
    last.split(['[', '{']).next().unwrap_or(last)
}

impl ZmqBackend {
    /// Connects (see [`Client::connect_with`]: the connection's own call and the first
    /// reads, [`ZmqBackend::first_calls`], wait for one main-loop pass).
    pub fn connect(options: &ClientOptions) -> Result<ZmqBackend, BackendError> {
        let (client, outcomes) = Client::connect_with(options, &ZmqBackend::first_calls())?;
        ZmqBackend::with_first(client, options.timeout, outcomes)
    }

    /// What a backend reads first: the program version (it decides the argument order of
    /// pose setters) and the idle rates ([`Backend::idle_rates`]).
    pub fn first_calls() -> Vec<(&'static str, Vec<Value>)> {
        vec![
            (
                "sim.getInt32Param",
                vec![int(INTPARAM_PROGRAM_VERSION.into())],
            ),
            idle_rate_call(),
            saved_rate_call(SAVED_IDLE_FPS.name),
            saved_rate_call(SAVED_IDLE_FPS.old),
        ]
    }

    /// The backend over `client`, from the outcomes of [`ZmqBackend::first_calls`].
    pub fn with_first(
        client: Client,
        timeout: Duration,
        outcomes: Vec<Outcome>,
    ) -> Result<ZmqBackend, BackendError> {
        let mut outcomes = outcomes.into_iter();
        let mut next = || outcomes.next().unwrap_or(Ok(vec![]));
        let version = int_result("sim.getInt32Param", next())?;
        let (rates, old_saved_rate) = idle_rates_of(next(), next(), next())?;
        let round_trips = client.stats().round_trips as usize;
        Ok(ZmqBackend {
            client,
            version,
            known: Known::default(),
            timeout,
            poses: HashMap::new(),
            traits: HashMap::new(),
            aliases: HashMap::new(),
            record: None,
            record_changed: false,
            old_record: false,
            old_saved_rate,
            signals_kept: true,
            first_rates: Some((rates, round_trips, Instant::now())),
            extents: HashMap::new(),
            children: HashMap::new(),
            deep: None,
            root_meshes: Vec::new(),
        })
    }

    /// The client (for counters and the protocol generation).
    pub fn client(&self) -> &Client {
        &self.client
    }

    fn call(&mut self, func: &str, args: Vec<Value>) -> Result<Vec<Value>, BackendError> {
        Ok(self.client.call(func, args)?)
    }

    /// The handle of a path, `None` if there is no such object ([`ZmqBackend::handles_of`]).
    fn handle_of(&mut self, path: &str) -> Result<Option<i32>, BackendError> {
        Ok(self.handles_of(&[path])?.into_iter().next().flatten())
    }

    /// The handles of `names` ([`object_path`]), `None` for a name with no object (-1 with
    /// `noError`, or an error from a simulator that does not know the `noError` option),
    /// the calls made by one request ([`Client::read_all`]).
    fn handles_of(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError> {
        Ok(self.handles_with(names, vec![])?.0)
    }

    /// [`ZmqBackend::handles_of`], with the calls `more` made in the same request; their
    /// outcomes come second.
    fn handles_with(
        &mut self,
        names: &[&str],
        more: Vec<(&'static str, Vec<Value>)>,
    ) -> Result<(Vec<Option<i32>>, Vec<Outcome>), BackendError> {
        let mut calls: Vec<(&str, Vec<Value>)> = names
            .iter()
            .map(|n| {
                let opts = cbor::map([("noError", Value::Bool(true))]);
                ("sim.getObject", vec![Value::Text(object_path(n)), opts])
            })
            .collect();
        calls.extend(more);
        let mut outcomes = self.client.read_all(&calls)?;
        let more = outcomes.split_off(names.len());
        let mut out = Vec::with_capacity(names.len());
        for outcome in outcomes {
            out.push(match outcome {
                Ok(values) => values.first().and_then(cbor::int32).filter(|&h| h >= 0),
                Err(_) => None,
            });
        }
        Ok((out, more))
    }

    fn handles_in(&mut self, base: i32, options: i32) -> Result<Vec<i32>, BackendError> {
        let v = self.client.call1(
            "sim.getObjectsInTree",
            vec![
                int(base.into()),
                int(HANDLE_ALL.into()),
                int(options.into()),
            ],
        )?;
        cbor::handles(&v).ok_or_else(|| {
            BackendError::Transport(format!(
                "sim.getObjectsInTree: not a handle list: {}",
                cbor::describe(&v)
            ))
        })
    }

    fn world_pose(&mut self, handle: i32) -> Result<([f64; 3], [f64; 3]), BackendError> {
        let values = self.call(
            "sim.getObjectPose",
            vec![int(handle.into()), int(HANDLE_WORLD.into())],
        )?;
        pose_of(handle, &values)
    }

    /// The bounding-box extents of `handle` (`None` if the simulator gives none), read once
    /// per survey.
    fn extents(&mut self, handle: i32) -> Result<Option<[f64; 3]>, BackendError> {
        if let Some(size) = self.extents.get(&handle) {
            return Ok(*size);
        }
        let size = self.sizes(&[handle])?.into_iter().next().flatten();
        self.extents.insert(handle, size);
        Ok(size)
    }

    /// The scene's copy record ([`signals::COPIES`], merged with an older version's under
    /// its old name, read together), read on first use (a simulator without string signals has none,
    /// nor one that does not keep signals).
    fn copy_record(&mut self) -> Result<CopyRecord, BackendError> {
        if let Some(r) = &self.record {
            return Ok(r.clone());
        }
        if !self.signals_kept {
            self.record = Some(CopyRecord::default());
            return Ok(CopyRecord::default());
        }
        let outcomes = self.client.read_all(&record_calls())?;
        self.record_from(outcomes)
    }

    /// The copy record from the outcomes of [`record_calls`], remembered for the connection.
    fn record_from(&mut self, outcomes: Vec<Outcome>) -> Result<CopyRecord, BackendError> {
        let mut texts = Vec::with_capacity(2);
        for outcome in outcomes {
            texts.push(match outcome {
                Ok(values) => match values.first() {
                    Some(Value::Text(t)) => Some(t.clone()),
                    Some(Value::Bytes(b)) => Some(String::from_utf8_lossy(b).into_owned()),
                    _ => None,
                },
                Err(ZmqError::Remote { .. }) => None,
                Err(e) => return Err(e.into()),
            });
        }
        let old = texts.pop().flatten();
        let new = texts.pop().flatten();
        self.old_record = old.is_some();
        // an older version's record moves to the new name with the next write
        self.record_changed |= old.is_some();
        let parse = |t: Option<String>| t.map(|t| CopyRecord::parse(&t)).unwrap_or_default();
        let record = parse(new).merged(parse(old));
        self.record = Some(record.clone());
        Ok(record)
    }

    /// Writes the copy record if it changed (a simulator without string signals only loses
    /// the record: later runs read aliases instead), and removes an older version's. The
    /// record is a `String`: CBOR text, valid UTF-8 ([`crate::draw::record`]).
    fn write_record(&mut self) -> Result<(), BackendError> {
        let Some(record) = self
            .record
            .as_ref()
            .filter(|_| self.record_changed && self.signals_kept)
        else {
            return Ok(());
        };
        let text: String = record.format();
        let mut calls = vec![(
            "sim.setStringSignal",
            vec![Value::Text(COPIES.name.into()), Value::Text(text)],
        )];
        if self.old_record {
            calls.push((
                "sim.clearStringSignal",
                vec![Value::Text(COPIES.old.into())],
            ));
        }
        for outcome in self.client.call_all(&calls)? {
            match outcome {
                Ok(_) | Err(ZmqError::Remote { .. }) => {}
                Err(e) => return Err(e.into()),
            }
        }
        self.record_changed = false;
        self.old_record = false;
        Ok(())
    }

    /// Records the world pose an acknowledged `sim.setObjectPose` gave `handle`.
    fn remember_pose(
        &mut self,
        handle: i32,
        relative_to: i32,
        position: [f64; 3],
        euler: [f64; 3],
    ) -> Result<(), BackendError> {
        let reference = match relative_to {
            HANDLE_WORLD => Frame::identity(),
            r => {
                let (p, e) = match self.poses.get(&r) {
                    Some(&pose) => pose,
                    None => {
                        let pose = self.world_pose(r)?;
                        self.poses.insert(r, pose);
                        pose
                    }
                };
                frame(p, e)
            }
        };
        let world = position_euler(&(reference * frame(position, euler)));
        self.poses.insert(handle, world);
        Ok(())
    }

    fn set_pose(
        &mut self,
        handle: i32,
        relative_to: i32,
        position: [f64; 3],
        euler: [f64; 3],
    ) -> Result<(), BackendError> {
        let q = rotation_from_euler(euler);
        let pose = float_array(&[position[0], position[1], position[2], q.i, q.j, q.k, q.w]);
        let (h, rel) = (int(handle.into()), int(relative_to.into()));
        let args = if self.version >= 40600 {
            vec![h, pose, rel]
        } else {
            vec![h, rel, pose]
        };
        self.call("sim.setObjectPose", args)?;
        Ok(())
    }

    fn remove(&mut self, handles: &[i32]) -> Result<(), BackendError> {
        let list = Value::Array(handles.iter().map(|h| int((*h).into())).collect());
        match self.client.call("sim.removeObjects", vec![list]) {
            Ok(_) => Ok(()),
            // before 4.5: one sim.removeObject per object
            Err(e) if e.is_no_such_function() => {
                for h in handles {
                    self.call("sim.removeObject", vec![int((*h).into())])?;
                }
                Ok(())
            }
            Err(e) => Err(e.into()),
        }
    }
}

/// The calls that read the copy record: its signal, then an older version's.
fn record_calls() -> [(&'static str, Vec<Value>); 2] {
    let call = |name: &str| ("sim.getStringSignal", vec![Value::Text(name.into())]);
    [call(COPIES.name), call(COPIES.old)]
}

/// How long the idle rates read when connecting stand for the scene's: a command draws at
/// once; a connection kept longer reads them again (the user may have changed the rate).
const FIRST_RATES_FRESH: Duration = Duration::from_secs(1);

/// The most copies one paste round makes over ZeroMQ (see `pieces_per_request`).
const ZMQ_PASTE_ROUND: usize = 1000;

impl Backend for ZmqBackend {
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError> {
        let asked = names.into_array();
        // the simulation's state rides in the request that finds the objects
        let state = vec![("sim.getSimulationState", vec![])];
        let (found, state) = self.handles_with(&asked, state)?;
        let state = int_result(
            "sim.getSimulationState",
            state.into_iter().next().unwrap_or(Ok(vec![])),
        )?;
        let found: [Option<i32>; 7] = found
            .try_into()
            .map_err(|_| BackendError::Transport("a handle missing from the survey".into()))?;
        let handles = SurveyHandles::from_array(found);
        let (_, optional_names) = names.needed_and_optional();
        let (_, optional_handles) = handles.needed_and_optional();
        self.known = Known {
            foreign_aliases: optional_names
                .iter()
                .zip(optional_handles)
                .filter(|(_, h)| h.is_some())
                .map(|(n, _)| alias_of(n).to_string())
                .collect(),
            named: asked
                .iter()
                .zip(found)
                .filter_map(|(n, h)| h.map(|h| (n.to_string(), h)))
                .collect(),
            parent: handles.parent,
            line_alias: alias_of(names.template).to_string(),
        };
        self.extents.clear();
        self.children.clear();
        self.deep = None;
        let (objects, traits) = if handles.needed_found() {
            self.collect(LinePoses::Known)?
        } else {
            Default::default()
        };
        Ok(Survey {
            handles,
            objects,
            simulation_running: state != SIMULATION_STOPPED,
            traits,
        })
    }

    fn idle_rates(&mut self) -> Result<IdleRates, BackendError> {
        if let Some((rates, round_trips, read)) = self.first_rates.take()
            && round_trips == self.round_trips()
            && read.elapsed() < FIRST_RATES_FRESH
        {
            return Ok(rates);
        }
        let mut outcomes = self
            .client
            .read_all(&[
                idle_rate_call(),
                saved_rate_call(SAVED_IDLE_FPS.name),
                saved_rate_call(SAVED_IDLE_FPS.old),
            ])?
            .into_iter();
        let mut next = || outcomes.next().unwrap_or(Ok(vec![]));
        let (rates, old) = idle_rates_of(next(), next(), next())?;
        self.old_saved_rate = old;
        Ok(rates)
    }

    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        Ok(self.collect(LinePoses::Read)?.0)
    }

    fn objects_from_scene(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        Ok(self.collect(LinePoses::Fresh)?.0)
    }

    /// Six calls an object, made by one request ([`Client::read_all`]).
    fn bounding_boxes(
        &mut self,
        handles: &[i32],
    ) -> Result<Vec<Option<BoundingBox>>, BackendError> {
        let calls: Vec<(&str, Vec<Value>)> = handles
            .iter()
            .flat_map(|&h| {
                (0..6).map(move |k| {
                    let param = OBJFLOATPARAM_BBOX + k;
                    (
                        "sim.getObjectFloatParam",
                        vec![int(h.into()), int(param.into())],
                    )
                })
            })
            .collect();
        let outcomes = self.client.read_all(&calls)?;
        Ok(outcomes
            .chunks(6)
            .map(|six| {
                let mut v = [0.0; 6];
                for (slot, outcome) in v.iter_mut().zip(six) {
                    // an object without the parameter (gone) has no box
                    *slot = outcome.as_ref().ok()?.first().and_then(cbor::number)?;
                }
                Some(BoundingBox {
                    min: [v[0], v[1], v[2]],
                    max: [v[3], v[4], v[5]],
                })
            })
            .collect())
    }

    /// A shape's size in one call (`sim.getShapeBB`), any other object's from its bounding
    /// box (six calls); all made by one request ([`Client::read_all`]).
    fn sizes(&mut self, handles: &[i32]) -> Result<Vec<Option<[f64; 3]>>, BackendError> {
        let shape = |b: &Self, h: &i32| b.traits.get(h).map(|t| t.1) == Some(OBJECT_SHAPE_TYPE);
        let shapes: Vec<i32> = handles.iter().copied().filter(|h| shape(self, h)).collect();
        let calls: Vec<(&str, Vec<Value>)> = shapes
            .iter()
            .map(|&h| ("sim.getShapeBB", vec![int(h.into())]))
            .collect();
        let mut sizes: HashMap<i32, Option<[f64; 3]>> = HashMap::new();
        for (h, outcome) in shapes.iter().zip(self.client.read_all(&calls)?) {
            if let Ok(values) = outcome {
                sizes.insert(*h, values.first().and_then(cbor::numbers::<3>));
            }
        }
        // the others, and a shape whose size the simulator would not give this way
        let rest: Vec<i32> = handles
            .iter()
            .copied()
            .filter(|h| !sizes.contains_key(h))
            .collect();
        for (h, b) in rest.iter().zip(self.bounding_boxes(&rest)?) {
            sizes.insert(*h, b.map(|b| b.size()));
        }
        Ok(handles
            .iter()
            .map(|h| sizes.get(h).copied().flatten())
            .collect())
    }

    /// One call a shape, made by one request ([`Client::read_all`]).
    fn shape_colours(
        &mut self,
        handles: &[i32],
    ) -> Result<Option<Vec<Option<[f64; 3]>>>, BackendError> {
        let calls: Vec<(&str, Vec<Value>)> = handles
            .iter()
            .map(|&h| mesh::shape_colour_call(h))
            .collect();
        let outcomes = self.client.read_all(&calls)?;
        Ok(Some(
            outcomes
                .iter()
                .map(|o| o.as_ref().ok().and_then(|v| mesh::colour_of(v)))
                .collect(),
        ))
    }

    /// One call a signal, made by one request ([`Client::read_all`]).
    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError> {
        let calls: Vec<(&str, Vec<Value>)> = names
            .iter()
            .map(|name| ("sim.getInt32Signal", vec![Value::Text(name.to_string())]))
            .collect();
        let mut out = Vec::with_capacity(names.len());
        for outcome in self.client.read_all(&calls)? {
            out.push(outcome?.first().and_then(cbor::int32));
        }
        Ok(out)
    }

    /// One call a signal, sent together ([`Client::call_all`]) and served in order.
    fn set_int_signals(&mut self, signals: &[(&str, Option<i32>)]) -> Result<(), BackendError> {
        let calls: Vec<(&str, Vec<Value>)> = signals
            .iter()
            .map(|(name, value)| {
                let name = Value::Text(name.to_string());
                match value {
                    Some(v) => ("sim.setInt32Signal", vec![name, int((*v).into())]),
                    None => ("sim.clearInt32Signal", vec![name]),
                }
            })
            .collect();
        for outcome in self.client.call_all(&calls)? {
            outcome?;
        }
        Ok(())
    }

    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        let mut out = Vec::with_capacity(groups.len());
        for g in groups {
            let list = Value::Array(g.iter().map(|h| int((*h).into())).collect());
            let v = self
                .client
                .call1("sim.copyPasteObjects", vec![list, int(0)])?;
            match cbor::handles(&v) {
                Some(new) if new.len() == g.len() => {
                    // a copy has its original's alias and type; a copy of a template (or
                    // of one of its copies) goes in the record
                    let record = self.record.get_or_insert_default();
                    for (source, copy) in g.iter().zip(&new) {
                        if let Some(t) = self.traits.get(source).cloned() {
                            let template = t.0 == self.known.line_alias
                                || self.known.foreign_aliases.contains(&t.0);
                            if template {
                                self.record_changed |= record.insert(*copy, &t.0);
                            }
                            self.traits.insert(*copy, t);
                        }
                    }
                    out.push(new)
                }
                _ => {
                    return Err(BackendError::Remote(format!(
                        "copy-paste of {} object(s) returned {}",
                        g.len(),
                        cbor::describe(&v)
                    )));
                }
            }
        }
        self.write_record()?;
        Ok(out)
    }

    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError> {
        // copies removed leave the record kept here, but that alone is not worth a call per
        // removal round: the scene's record keeps their handles, which name no object any
        // more (ignored, and dropped by the next run's survey)
        if let Some(record) = self.record.as_mut() {
            let removed = Edit::removed(edits);
            record.retain(|h| !removed.contains(&h));
        }
        self.write_record()?;
        let mut i = 0;
        while i < edits.len() {
            match edits[i] {
                Edit::SetParent {
                    handle,
                    parent,
                    keep_in_place,
                } => {
                    let p = int(parent.unwrap_or(HANDLE_WORLD).into());
                    self.call(
                        "sim.setObjectParent",
                        vec![int(handle.into()), p, Value::Bool(keep_in_place)],
                    )?;
                    if !keep_in_place {
                        // the local pose is kept, so the world pose moves with the parent
                        self.poses.remove(&handle);
                    }
                }
                Edit::SetPose {
                    handle,
                    relative_to,
                    position,
                    orientation,
                } => {
                    self.set_pose(handle, relative_to, position, orientation)?;
                    self.remember_pose(handle, relative_to, position, orientation)?;
                }
                Edit::Remove(_) => {
                    let run: Vec<i32> = edits[i..]
                        .iter()
                        .map_while(|e| {
                            if let Edit::Remove(h) = e {
                                Some(*h)
                            } else {
                                None
                            }
                        })
                        .collect();
                    i += run.len();
                    self.remove(&run)?;
                    for h in &run {
                        self.poses.remove(h);
                    }
                    continue;
                }
            }
            i += 1;
        }
        Ok(())
    }

    /// The record and the rate are two calls, sent together ([`Client::call_all`]: one
    /// main-loop pass over protocol 1) and ordered so that a cut between them never loses
    /// the user's rate: the record is written before the rate is lowered, and deleted only
    /// after the rate is restored (a stale record beside a set rate is ignored).
    /// Deleting the record deletes an older version's too ([`signals::SAVED_IDLE_FPS`]), if
    /// one was read: a call more after the rate is restored, which may wait for a pass.
    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError> {
        let name = |n: &str| Value::Text(n.into());
        let set_rate = (
            "sim.setInt32Param",
            vec![int(INTPARAM_IDLE_FPS.into()), int(fps.into())],
        );
        let (calls, rate_at) = match saved {
            Some(v) => (
                vec![
                    (
                        "sim.setInt32Signal",
                        vec![name(SAVED_IDLE_FPS.name), int(v.into())],
                    ),
                    set_rate,
                ],
                1,
            ),
            None => {
                let mut calls = vec![
                    set_rate,
                    ("sim.clearInt32Signal", vec![name(SAVED_IDLE_FPS.name)]),
                ];
                if std::mem::take(&mut self.old_saved_rate) {
                    calls.push(("sim.clearInt32Signal", vec![name(SAVED_IDLE_FPS.old)]));
                }
                (calls, 0)
            }
        };
        let outcomes = self.client.call_all(&calls)?;
        for (k, outcome) in outcomes.into_iter().enumerate() {
            match outcome {
                Ok(_) => {}
                // a simulator without integer signals only loses the crash record
                Err(_) if k != rate_at => {}
                Err(e) => return Err(e.into()),
            }
        }
        Ok(())
    }

    fn stop_simulation(&mut self) -> Result<(), BackendError> {
        let deadline = Instant::now() + self.timeout;
        self.call("sim.stopSimulation", vec![])?;
        while self.client.call_int("sim.getSimulationState", vec![])? != SIMULATION_STOPPED {
            if Instant::now() > deadline {
                return Err(BackendError::Remote("the simulation did not stop".into()));
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Ok(())
    }

    fn round_trips(&self) -> usize {
        self.client.stats().round_trips as usize
    }

    /// Each call is its own request, but a paste round's copies stay parentless until they
    /// are re-parented one by one, and CoppeliaSim 4.5.1 walks every parentless object on
    /// each such re-parenting (coppeliaSimLib@coppeliasim-v4.5.1-rev4
    /// `sceneObjectContainer.cpp:1133, 1146, 1281-1306`): rounds of at most 1,000 copies
    /// (`ZMQ_PASTE_ROUND`) keep that walk short (the pastes cost the same).
    fn pieces_per_request(&self, _objects_in_scene: usize) -> usize {
        ZMQ_PASTE_ROUND
    }

    fn remote_api(&self) -> Option<crate::draw::estimate::RemoteApi> {
        Some(crate::draw::estimate::RemoteApi::Zmq)
    }

    fn describe(&self) -> String {
        let v = self.version;
        let protocol = self
            .client
            .protocol()
            .map(|p| p.to_string())
            .unwrap_or_else(|| "?".into());
        format!(
            "ZeroMQ remote API at {}, protocol {protocol}, CoppeliaSim {}.{}.{}",
            self.client.endpoint(),
            v / 10000,
            v / 100 % 100,
            v % 100
        )
    }

    fn authoring(&mut self) -> Option<&mut dyn Authoring> {
        Some(self)
    }

    fn lease(&mut self) -> Option<&mut dyn Lease> {
        Some(self)
    }

    fn meshes(&mut self) -> Option<&mut dyn crate::draw::mesh::MeshDrawing> {
        Some(self)
    }

    fn model_box(&mut self, name: &str) -> Result<Option<BoundingBox>, BackendError> {
        self.read_model_box(name)
    }

    fn follower(&mut self) -> Option<Box<dyn Follower + '_>> {
        Some(Box::new(super::follow::ZmqFollower::lent(&mut self.client)))
    }

    fn robot(&mut self) -> Option<Box<dyn crate::robot::RobotPort + '_>> {
        Some(Box::new(super::robot::ZmqRobot::lent(&mut self.client)))
    }
}

/// `sim.getInt32Param(sim.intparam_idle_fps)`.
fn idle_rate_call() -> (&'static str, Vec<Value>) {
    ("sim.getInt32Param", vec![int(INTPARAM_IDLE_FPS.into())])
}

/// `sim.getInt32Signal(name)` of the user's idle rate recorded by an interrupted `apply`
/// ([`signals::SAVED_IDLE_FPS`]'s name or old name).
fn saved_rate_call(name: &str) -> (&'static str, Vec<Value>) {
    ("sim.getInt32Signal", vec![Value::Text(name.into())])
}

/// The one integer a call returned.
fn int_result(func: &str, outcome: Outcome) -> Result<i32, BackendError> {
    let values = outcome?;
    values
        .first()
        .and_then(cbor::int32)
        .ok_or_else(|| BackendError::Transport(format!("{func}: expected an integer reply")))
}

/// The idle rates from the replies of [`idle_rate_call`] and the two [`saved_rate_call`]s
/// (new name, then old: [`signals::newest`]), and whether an older version's record was
/// read. The record matters only while the rate is 0 (an interrupted run left it so); beside
/// a set rate it is stale. No record: the signal is not set (nil), or the simulator has no
/// integer signals.
fn idle_rates_of(
    current: Outcome,
    saved: Outcome,
    old: Outcome,
) -> Result<(IdleRates, bool), BackendError> {
    let current = int_result("sim.getInt32Param", current)?;
    let read = |outcome: Outcome| match outcome {
        Ok(values) => Ok(values.first().and_then(cbor::int32)),
        Err(ZmqError::Remote { .. }) => Ok(None),
        Err(e) => Err(BackendError::from(e)),
    };
    let (saved, old) = (read(saved)?, read(old)?);
    let old_read = old.is_some();
    let saved = signals::newest(saved, old).filter(|_| current == 0);
    Ok((IdleRates { current, saved }, old_read))
}

/// The world position and Euler angles in the reply of `sim.getObjectPose(handle, world)`
/// (x, y, z, then the quaternion x, y, z, w).
fn pose_of(handle: i32, values: &[Value]) -> Result<([f64; 3], [f64; 3]), BackendError> {
    let v = values.first().ok_or_else(|| {
        BackendError::Transport(format!(
            "sim.getObjectPose of object {handle}: no return value"
        ))
    })?;
    let p = cbor::numbers::<7>(v).ok_or_else(|| {
        BackendError::Transport(format!(
            "sim.getObjectPose of object {handle}: not 7 numbers: {}",
            cbor::describe(v)
        ))
    })?;
    let q = UnitQuaternion::from_quaternion(Quaternion::new(p[6], p[3], p[4], p[5]));
    Ok(([p[0], p[1], p[2]], euler_from_rotation(&q)))
}
