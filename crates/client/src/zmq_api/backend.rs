//! The ZeroMQ remote API as a drawing backend: [`crate::draw::Backend`] over [`Client`].
//!
//! Objects are found by path (`/Maze`, `/Line`); the earlier maze is the object tree under
//! the maze dummy (`sim.getObjectsInTree`), plus root objects that carry a template's alias
//! (copies pasted by an interrupted run, reported by their path `/Line[n]`). Each pose is
//! one `sim.setObjectPose` call; removals go in one `sim.removeObjects` call. The ZeroMQ API
//! has one call per object where the legacy API batches, so "one round trip" operations of
//! the trait cost one call per object; reads that do not depend on each other's answers are
//! made by one request ([`Client::read_all`]), writes sent together ([`Client::call_all`])
//! and served by one main-loop pass.

use std::collections::{HashMap, HashSet};
use std::time::{Duration, Instant};

use ciborium::Value;
use nalgebra::{Quaternion, UnitQuaternion};

use super::cbor::{self, float_array, int};
use super::client::{Client, ClientOptions, Outcome, ZmqError};
use crate::draw::plan;
use crate::draw::record::CopyRecord;
use crate::draw::signals::{self, COPIES, LEASE, SAVED_IDLE_FPS};
use crate::draw::{
    Authoring, Backend, BackendError, BoundingBox, Claimed, Edit, IdleRates, Lease, ObjectInfo,
    ObjectNames, Sizes, Survey, SurveyHandles, SurveyNames,
};
use vrep_maze_core::coppelia::frame::{
    Frame, euler_from_rotation, frame, position_euler, rotation_from_euler,
};
use vrep_maze_core::coppelia::{
    COLORCOMPONENT_AMBIENT_DIFFUSE, HANDLE_ALL, HANDLE_SCENE, HANDLE_WORLD, INTPARAM_IDLE_FPS,
    INTPARAM_PROGRAM_VERSION, OBJECT_SHAPE_TYPE, OBJFLOATPARAM_BBOX, PRIMITIVESHAPE_CUBOID,
    PRIMITIVESHAPE_PLANE, SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC, SIMULATION_STOPPED,
    SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};
use vrep_maze_core::score::follow::Follower;

mod mesh;

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
}

/// The path `sim.getObject` needs for a user-given name: names are aliases at the scene
/// root unless they already are paths (`/Maze/Line`, `./x`, `:x`).
pub fn object_path(name: &str) -> String {
    if name.starts_with(['/', '.', ':']) {
        name.to_string()
    } else {
        format!("/{name}")
    }
}

fn alias_of(name: &str) -> &str {
    let last = name.rsplit('/').next().unwrap_or(name);
    last.split(['[', '{']).next().unwrap_or(last)
}

/// A plane to create: size x, y; RGB colour (0..1); height above the floor.
type PlaneSpec = ([f64; 2], [f64; 3], f64);

/// A name `create_missing` can give a new object: its alias must be `[A-Za-z0-9_]+`.
fn check_alias(name: &str) -> Result<(), BackendError> {
    let alias = alias_of(name);
    if alias.is_empty()
        || !alias.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        || name.contains('[')
    {
        return Err(BackendError::Remote(format!(
            "cannot create `{name}`: a created object's name must be letters, digits and _ only"
        )));
    }
    Ok(())
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
        let calls: Vec<(&str, Vec<Value>)> = names
            .iter()
            .map(|n| {
                let opts = cbor::map([("noError", Value::Bool(true))]);
                ("sim.getObject", vec![Value::Text(object_path(n)), opts])
            })
            .collect();
        let mut out = Vec::with_capacity(names.len());
        for outcome in self.client.read_all(&calls)? {
            out.push(match outcome {
                Ok(values) => values.first().and_then(cbor::int32).filter(|&h| h >= 0),
                Err(_) => None,
            });
        }
        Ok(out)
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

    /// Objects (handle, name, parent) with their poses: from [`ZmqBackend::poses`] if known,
    /// else read (`Read`) or NaN (`Known`, never in place); `Fresh` reads every one. The reads
    /// are made by one request ([`Client::read_all`]).
    fn line_infos(
        &mut self,
        lines: Vec<(i32, String, Option<i32>)>,
        poses: LinePoses,
    ) -> Result<Vec<ObjectInfo>, BackendError> {
        let unknown = ([f64::NAN; 3], [f64::NAN; 3]);
        let read: Vec<i32> = lines
            .iter()
            .map(|(h, _, _)| *h)
            .filter(|h| match (self.poses.contains_key(h), poses) {
                (true, LinePoses::Known | LinePoses::Read) | (false, LinePoses::Known) => false,
                (_, LinePoses::Read | LinePoses::Fresh) => true,
            })
            .collect();
        let calls: Vec<(&str, Vec<Value>)> = read
            .iter()
            .map(|h| {
                let args = vec![int((*h).into()), int(HANDLE_WORLD.into())];
                ("sim.getObjectPose", args)
            })
            .collect();
        let mut read_now = HashMap::with_capacity(read.len());
        for (h, outcome) in read.iter().zip(self.client.read_all(&calls)?) {
            let pose = match outcome {
                Ok(values) => pose_of(*h, &values)?,
                // listed a moment ago, gone now (another run removed it): never in place
                Err(ZmqError::Remote { .. }) => unknown,
                Err(e) => return Err(e.into()),
            };
            read_now.insert(*h, pose);
        }
        Ok(lines
            .into_iter()
            .map(|(handle, name, parent)| {
                let (position, orientation) = read_now
                    .get(&handle)
                    .or_else(|| self.poses.get(&handle))
                    .copied()
                    .unwrap_or(unknown);
                ObjectInfo {
                    handle,
                    name,
                    parent,
                    position,
                    orientation,
                }
            })
            .collect())
    }

    /// Reads the aliases of `handles` not known yet, and the type codes of those whose `kind`
    /// is not given, in one request ([`Client::read_all`]): what [`ZmqBackend::traits`] and
    /// [`ZmqBackend::alias`] then find remembered (`with_types: false`: the aliases only). An
    /// object whose read fails is left unknown, for the one-by-one read to report.
    fn read_traits(
        &mut self,
        handles: &[(i32, Option<i32>)],
        with_types: bool,
    ) -> Result<(), BackendError> {
        let todo: Vec<(i32, Option<i32>)> = handles
            .iter()
            .copied()
            .filter(|(h, _)| {
                !self.traits.contains_key(h) && (with_types || !self.aliases.contains_key(h))
            })
            .collect();
        let mut calls: Vec<(&str, Vec<Value>)> = Vec::new();
        for (h, kind) in &todo {
            calls.push(("sim.getObjectAlias", vec![int((*h).into()), int(-1)]));
            if with_types && kind.is_none() {
                calls.push(("sim.getObjectType", vec![int((*h).into())]));
            }
        }
        let mut outcomes = self.client.read_all(&calls)?.into_iter();
        for (h, kind) in todo {
            let alias = outcomes.next().and_then(Result::ok);
            let alias = alias
                .as_ref()
                .and_then(|v| v.first())
                .map(|v| cbor::text(v).unwrap_or_default().to_string());
            let kind = match kind {
                Some(k) => Some(k),
                None if with_types => outcomes
                    .next()
                    .and_then(|o| int_result("sim.getObjectType", o).ok()),
                None => None,
            };
            match (alias, kind) {
                (Some(alias), Some(kind)) if with_types => {
                    self.traits.insert(h, (alias, kind));
                }
                (Some(alias), _) if !with_types => {
                    self.aliases.insert(h, alias);
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The named objects with their parents and world poses, and their type codes (a named
    /// object's alias is its name's last part: only its type is read, once), the calls sent
    /// in one request ([`Client::read_all`]).
    fn named_infos(
        &mut self,
        named: &[(String, i32)],
    ) -> Result<Vec<(ObjectInfo, i32)>, BackendError> {
        let mut calls: Vec<(&str, Vec<Value>)> = Vec::new();
        // one type read an object (two names may resolve to one object)
        let mut typed: HashSet<i32> = self.traits.keys().copied().collect();
        let mut read_type = Vec::with_capacity(named.len());
        for (_, h) in named {
            let handle = int((*h).into());
            calls.push(("sim.getObjectParent", vec![handle.clone()]));
            calls.push((
                "sim.getObjectPose",
                vec![handle.clone(), int(HANDLE_WORLD.into())],
            ));
            read_type.push(typed.insert(*h));
            if read_type[read_type.len() - 1] {
                calls.push(("sim.getObjectType", vec![handle]));
            }
        }
        let mut outcomes = self.client.read_all(&calls)?.into_iter();
        let mut next = || outcomes.next().unwrap_or(Ok(vec![]));
        let mut out = Vec::with_capacity(named.len());
        for ((name, h), read_type) in named.iter().zip(read_type) {
            let parent = int_result("sim.getObjectParent", next())?;
            let (position, orientation) = pose_of(*h, &next()?)?;
            if read_type {
                let kind = int_result("sim.getObjectType", next())?;
                self.traits.insert(*h, (alias_of(name).to_string(), kind));
            }
            self.poses.insert(*h, (position, orientation));
            let info = ObjectInfo {
                handle: *h,
                name: name.clone(),
                parent: (parent >= 0).then_some(parent),
                position,
                orientation,
            };
            out.push((info, self.traits[h].1));
        }
        Ok(out)
    }

    /// The alias and type code of `handle`: remembered (read before, or a copy this
    /// connection pasted), else read (`kind`, if given, is the type already known).
    fn traits(&mut self, handle: i32, kind: Option<i32>) -> Result<(String, i32), BackendError> {
        if let Some(t) = self.traits.get(&handle) {
            return Ok(t.clone());
        }
        let alias = self.alias(handle)?;
        let kind = match kind {
            Some(k) => k,
            None => self
                .client
                .call_int("sim.getObjectType", vec![int(handle.into())])?,
        };
        self.traits.insert(handle, (alias.clone(), kind));
        Ok((alias, kind))
    }

    /// The alias of `handle`: remembered, else read.
    fn alias(&mut self, handle: i32) -> Result<String, BackendError> {
        if let Some(alias) = self
            .traits
            .get(&handle)
            .map(|t| &t.0)
            .or_else(|| self.aliases.get(&handle))
        {
            return Ok(alias.clone());
        }
        let alias = self
            .client
            .call1("sim.getObjectAlias", vec![int(handle.into()), int(-1)])?;
        let alias = cbor::text(&alias).unwrap_or_default().to_string();
        self.aliases.insert(handle, alias.clone());
        Ok(alias)
    }

    /// The named objects (read), the maze dummy's children and root copies of the templates
    /// found (their poses as `poses` says), with what tells copies from the user's objects
    /// ([`plan::Traits`]). A child carrying a template's alias is named as a copy of it
    /// (`/Line[k]`), any other by its alias, so that only the templates' copies are taken
    /// for the maze's. A child the copy record names and of its template's type is known
    /// without reading its alias; one that is not recorded but named and typed like a copy
    /// is sized and asked for children ([`ZmqBackend::doubt`]: normally none). The record
    /// is then brought up to date (written with the next edit or paste). The poses this
    /// connection set for the maze dummy's children are trusted only while the dummy is
    /// where it was when they were set, at a finite pose (a child of a dummy at NaN is at
    /// NaN, whatever was set).
    fn collect(
        &mut self,
        poses: LinePoses,
    ) -> Result<(Vec<ObjectInfo>, plan::Traits), BackendError> {
        let known = self.known.clone();
        let mut out = Vec::new();
        let mut found = plan::Traits::default();
        let parent_before = known.parent.and_then(|p| self.poses.get(&p).copied());
        for (info, kind) in self.named_infos(&known.named)? {
            found.kinds.insert(info.handle, kind);
            out.push(info);
        }
        let parent_now = known.parent.and_then(|p| self.poses.get(&p).copied());
        let finite = |(p, e): WorldPose| p.iter().chain(&e).all(|x| x.is_finite());
        let distrust =
            parent_now.is_some_and(|now| !finite(now) || parent_before.is_some_and(|b| b != now));
        let mut seen: HashSet<i32> = known.named.iter().map(|(_, h)| *h).collect();
        let templates: Vec<&str> = std::iter::once(known.line_alias.as_str())
            .chain(known.foreign_aliases.iter().map(String::as_str))
            .collect();
        // the templates' handles and types by alias: a recorded copy must still be of its
        // template's type
        let template_handles: HashMap<&str, i32> = known
            .named
            .iter()
            .filter(|(name, _)| templates.contains(&alias_of(name)))
            .map(|(name, h)| (alias_of(name), *h))
            .collect();
        let template_kinds: HashMap<&str, i32> = template_handles
            .iter()
            .filter_map(|(alias, h)| found.kinds.get(h).map(|k| (*alias, *k)))
            .collect();
        let mut record = self.copy_record()?;
        // the record first: a named object it holds is one of our copies (refused as a
        // template or marker), a listed one of its template's type is ours
        found.recorded.extend(
            known
                .named
                .iter()
                .map(|(_, h)| *h)
                .filter(|h| record.get(*h).is_some()),
        );
        let mut present = Vec::new();
        let mut numbered = vec![0; templates.len()];
        let mut copy_name = |alias: &str| match templates.iter().position(|t| *t == alias) {
            Some(t) => {
                numbered[t] += 1;
                format!("/{alias}[{}]", numbered[t])
            }
            None => alias.to_string(),
        };
        // a copy of a template by alias and type, unless the record does not hold it and
        // what `doubt` reads of an object named and typed like a copy says otherwise
        let judge = |backend: &mut Self,
                     (h, tree): (i32, Option<(i32, &[i32])>),
                     name: &str,
                     alias: &str,
                     kind: i32,
                     found: &mut plan::Traits|
         -> Result<bool, BackendError> {
            let family = templates
                .iter()
                .find(|t| plan::is_copy_name(name, t) && template_kinds.get(*t) == Some(&kind));
            let template = family.and_then(|t| template_handles.get(t).copied());
            if let Some(template) = template.filter(|_| record.get(h) != Some(alias)) {
                backend.doubt(h, template, tree, found)?;
            }
            let of_type = template_kinds.get(alias) == Some(&kind);
            if of_type && record.get(h) == Some(alias) {
                found.recorded.insert(h);
            }
            Ok(of_type && !plan::contradicts_copy(found, h, template))
        };
        if let Some(parent) = known.parent {
            // options 3: first-level children only, without the dummy itself; the shapes
            // among them in one call, so only the other children's types are asked
            let shapes: HashSet<i32> = self
                .client
                .call1(
                    "sim.getObjectsInTree",
                    vec![int(parent.into()), int(OBJECT_SHAPE_TYPE.into()), int(3)],
                )
                .ok()
                .as_ref()
                .and_then(cbor::handles)
                .unwrap_or_default()
                .into_iter()
                .collect();
            let kids = self.handles_in(parent, 3)?;
            let shape = |h: i32| shapes.contains(&h).then_some(OBJECT_SHAPE_TYPE);
            let new_kids: Vec<i32> = kids.iter().copied().filter(|h| !seen.contains(h)).collect();
            for &h in &new_kids {
                // a recorded copy that is (still) of its template's type is known without
                // reading its alias
                if let (Some(alias), Some(kind)) = (record.get(h), shape(h))
                    && template_kinds.get(alias) == Some(&kind)
                    && !self.traits.contains_key(&h)
                {
                    self.traits.insert(h, (alias.to_string(), kind));
                }
            }
            // the others' aliases (and the non-shapes' types) together, not one by one
            let unknown: Vec<(i32, Option<i32>)> =
                new_kids.iter().map(|&h| (h, shape(h))).collect();
            self.read_traits(&unknown, true)?;
            let mut lines = Vec::new();
            for &h in &kids {
                if seen.insert(h) {
                    let (alias, kind) = self.traits(h, shape(h))?;
                    found.kinds.insert(h, kind);
                    let name = copy_name(&alias);
                    let tree = Some((parent, &kids[..]));
                    if judge(self, (h, tree), &name, &alias, kind, &mut found)? {
                        present.push((h, alias.clone()));
                    }
                    if distrust {
                        self.poses.remove(&h);
                    }
                    lines.push((h, name, Some(parent)));
                }
            }
            out.extend(self.line_infos(lines, poses)?);
        }
        // root objects carrying a template's alias: copies left parentless by an interrupted
        // run (of this style's template, or of another found in the scene, which a drawing
        // removes or, for posts, reuses). They are named `/Line[k]` whatever their path.
        let roots: Vec<i32> = self
            .handles_in(HANDLE_SCENE, 2)?
            .into_iter()
            .filter(|h| !seen.contains(h))
            .collect();
        let unknown: Vec<(i32, Option<i32>)> = roots.iter().map(|&h| (h, None)).collect();
        self.read_traits(&unknown, false)?;
        let mut lines = Vec::new();
        for h in roots {
            if seen.contains(&h) {
                continue;
            }
            // the type only of those carrying a template's alias
            if !templates.contains(&self.alias(h)?.as_str()) {
                continue;
            }
            let (alias, kind) = self.traits(h, None)?;
            let parent = self
                .client
                .call_int("sim.getObjectParent", vec![int(h.into())])?;
            if parent >= 0 {
                continue; // not a root object after all
            }
            seen.insert(h);
            found.kinds.insert(h, kind);
            let name = copy_name(&alias);
            // a copy at the root stays in the record if it is there (pasted by an
            // interrupted run), but none is added by its alias: the root also holds the
            // user's template when a name found one of our copies instead
            if judge(self, (h, None), &name, &alias, kind, &mut found)?
                && record.get(h) == Some(alias.as_str())
            {
                present.push((h, alias.clone()));
            }
            lines.push((h, name, None));
        }
        out.extend(self.line_infos(lines, poses)?);
        // the record now holds exactly the templates' copies in the maze: those read by
        // alias are added (a maze drawn without a record pays its reads once), handles no
        // longer there are dropped
        if known.parent.is_some() {
            // a named object the record holds stays in it: refused as a template or marker,
            // it is still our copy
            let mut changed = record
                .retain(|h| present.iter().any(|(p, _)| *p == h) || found.recorded.contains(&h));
            for (h, alias) in &present {
                changed |= record.insert(*h, alias);
            }
            self.record_changed |= changed;
        }
        self.record = Some(record);
        Ok((out, found))
    }

    /// Reads what tells `handle`, named and typed like a copy of `template` but not in the
    /// copy record, from a copy ([`plan::contradicts_copy`]) into `found`: its size and its
    /// template's (a shape's `sim.getShapeBB`, one call; other objects' bounding box, six)
    /// and whether it has children (`sim.getObjectsInTree`, one call, unless `tree`, the
    /// maze dummy and its children it is one of, shows nothing below them: one call for
    /// the whole maze). Read once per survey.
    fn doubt(
        &mut self,
        handle: i32,
        template: i32,
        tree: Option<(i32, &[i32])>,
        found: &mut plan::Traits,
    ) -> Result<(), BackendError> {
        for h in [template, handle] {
            if let Some(size) = self.extents(h)? {
                found.sizes.insert(h, size);
            }
        }
        // a shape's colour (one call each, the template's once a survey): a user's red copy
        // of `Line` is no line of the maze
        let shapes = [template, handle]
            .into_iter()
            .filter(|h| self.traits.get(h).map(|t| t.1) == Some(OBJECT_SHAPE_TYPE))
            .filter(|h| !found.colours.contains_key(h))
            .collect::<Vec<_>>();
        if !shapes.is_empty()
            && let Some(colours) = self.shape_colours(&shapes)?
        {
            for (h, c) in shapes.into_iter().zip(colours) {
                found.colours.extend(c.map(|c| (h, c)));
            }
        }
        let deep = match (tree, self.deep) {
            (None, _) => true,
            (Some(_), Some(deep)) => deep,
            (Some((parent, kids)), None) => {
                // options 1: the whole tree without the dummy
                let deep = self.handles_in(parent, 1)?.len() > kids.len();
                self.deep = Some(deep);
                deep
            }
        };
        let children = match self.children.get(&handle) {
            Some(&c) => c,
            None if !deep => false,
            None => {
                let c = !self.handles_in(handle, 3)?.is_empty();
                self.children.insert(handle, c);
                c
            }
        };
        if children {
            found.with_children.insert(handle);
        }
        Ok(())
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
        let call = |name: &str| ("sim.getStringSignal", vec![Value::Text(name.into())]);
        let mut texts = Vec::with_capacity(2);
        for outcome in self
            .client
            .read_all(&[call(COPIES.name), call(COPIES.old)])?
        {
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

    /// A static plane named `name`, coloured, at height `z` in the frame `relative_to`.
    /// Only a floor is respondable and detectable; markers are seen by cameras only.
    fn create_plane(
        &mut self,
        name: &str,
        size: [f64; 2],
        colour: [f64; 3],
        z: f64,
        relative_to: i32,
        floor: bool,
    ) -> Result<i32, BackendError> {
        let h = self.client.call_int(
            "sim.createPrimitiveShape",
            vec![
                int(PRIMITIVESHAPE_PLANE.into()),
                float_array(&[size[0], size[1], 0.0]),
                int(0),
            ],
        )?;
        let hv = || int(h.into());
        self.call(
            "sim.setShapeColor",
            vec![
                hv(),
                Value::Null,
                int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
                float_array(&colour),
            ],
        )?;
        if !floor {
            self.call(
                "sim.setObjectSpecialProperty",
                vec![hv(), int(SPECIAL_RENDERABLE.into())],
            )?;
        }
        self.call(
            "sim.setObjectInt32Param",
            vec![hv(), int(SHAPEINTPARAM_STATIC.into()), int(1)],
        )?;
        self.call(
            "sim.setObjectInt32Param",
            vec![
                hv(),
                int(SHAPEINTPARAM_RESPONDABLE.into()),
                int(floor.into()),
            ],
        )?;
        self.set_pose(h, relative_to, [0.0, 0.0, z], [0.0; 3])?;
        self.call(
            "sim.setObjectAlias",
            vec![hv(), Value::Text(alias_of(name).into())],
        )?;
        Ok(h)
    }
}

/// How long the idle rates read when connecting stand for the scene's: a command draws at
/// once; a connection kept longer reads them again (the user may have changed the rate).
const FIRST_RATES_FRESH: Duration = Duration::from_secs(1);

/// The most copies one paste round makes over ZeroMQ (see `lines_per_request`).
const ZMQ_PASTE_ROUND: usize = 1000;

impl Backend for ZmqBackend {
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError> {
        let asked = names.into_array();
        let found: [Option<i32>; 7] = self
            .handles_of(&asked)?
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
        let state = self.client.call_int("sim.getSimulationState", vec![])?;
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
            let removed: HashSet<i32> = edits
                .iter()
                .filter_map(|e| match e {
                    Edit::Remove(h) => Some(*h),
                    _ => None,
                })
                .collect();
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
    /// `sceneObjectContainer.cpp:1133, 1146, 1281-1306`): rounds of at most
    /// [`ZMQ_PASTE_ROUND`] copies keep that walk short (the pastes cost the same).
    fn lines_per_request(&self, _objects_in_scene: usize) -> usize {
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

    fn follower(&mut self) -> Option<Box<dyn Follower + '_>> {
        Some(Box::new(super::follow::ZmqFollower::lent(&mut self.client)))
    }
}

/// The lease is the integer signal [`signals::LEASE`] (a simulator without integer signals
/// answers with a remote error, and the run goes on unguarded).
impl Lease for ZmqBackend {
    /// Four calls sent together ([`Client::call_all`]: one main-loop pass over protocol 1):
    /// read the holder, write the token, remove an older version's lease (which stops an
    /// older run drawing now), read the token back.
    fn claim(&mut self, token: i32) -> Result<Claimed, BackendError> {
        let name = |n: &str| Value::Text(n.into());
        let calls = [
            ("sim.getInt32Signal", vec![name(LEASE.name)]),
            (
                "sim.setInt32Signal",
                vec![name(LEASE.name), int(token.into())],
            ),
            ("sim.clearInt32Signal", vec![name(LEASE.old)]),
            ("sim.getInt32Signal", vec![name(LEASE.name)]),
        ];
        let mut read = Vec::with_capacity(2);
        for (k, outcome) in self.client.call_all(&calls)?.into_iter().enumerate() {
            let values = outcome?;
            if k == 0 || k == 3 {
                read.push(values.first().and_then(cbor::int32));
            }
        }
        Ok(Claimed {
            previous: read[0],
            read_back: read[1],
        })
    }

    fn holder(&mut self) -> Result<Option<i32>, BackendError> {
        let name = Value::Text(LEASE.name.into());
        let values = self.call("sim.getInt32Signal", vec![name])?;
        Ok(values.first().and_then(cbor::int32))
    }

    fn release(&mut self) -> Result<(), BackendError> {
        let name = Value::Text(LEASE.name.into());
        self.call("sim.clearInt32Signal", vec![name])?;
        Ok(())
    }

    fn unkept(&mut self) {
        self.signals_kept = false;
        self.record = Some(CopyRecord::default());
        self.record_changed = false;
    }
}

impl Authoring for ZmqBackend {
    /// Creates the missing objects at the layout's `sizes`: the maze dummy, the line
    /// template (or for a wall maze the `Wall` template, a dark grey cuboid: static,
    /// respondable, collidable, measurable, detectable by proximity sensors, seen by cameras,
    /// standing 1 m beside the floor's south edge, and with posts the `Post` template, such
    /// a cuboid, 0.25 m south of it), start and end planes a cell wide (pure colours,
    /// static, not respondable, not collidable, not measurable, not detectable by proximity
    /// sensors, but seen by cameras), and a floor plane of the layout's floor when the
    /// scene has none. Returns the names created.
    fn create_missing(
        &mut self,
        names: &ObjectNames,
        sizes: &Sizes,
    ) -> Result<Vec<String>, BackendError> {
        self.create_course(names, sizes)
    }

    /// Saves the scene (`sim.saveScene`; the path is on the simulator's machine).
    fn save_scene(&mut self, path: &str) -> Result<(), BackendError> {
        self.call("sim.saveScene", vec![Value::Text(path.into())])?;
        Ok(())
    }

    fn scale(&mut self, handle: i32, factors: [f64; 3]) -> Result<(), BackendError> {
        let [x, y, z] = factors.map(Value::Float);
        self.call("sim.scaleObject", vec![int(handle.into()), x, y, z, int(0)])?;
        Ok(())
    }
}

/// An object `create_missing` makes.
enum Make {
    /// A floor plane of this size (x, y), respondable.
    Floor([f64; 2]),
    /// The maze dummy.
    Dummy,
    /// A plane: size, colour, height.
    Plane(PlaneSpec),
    /// A wall or post template: its size and where it stands on the floor (x, y).
    Cuboid([f64; 3], [f64; 2]),
}

impl ZmqBackend {
    /// Creates what the course scene has and this one lacks, at the layout's `sizes`: a
    /// floor, the maze dummy, the line template (or for a wall maze the wall template and
    /// the post template if the layout has posts), start and end.
    fn create_course(
        &mut self,
        names: &ObjectNames,
        sizes: &Sizes,
    ) -> Result<Vec<String>, BackendError> {
        let mut specs: Vec<(&str, Make)> = vec![(&names.floor, Make::Floor(sizes.floor))];
        specs.push((&names.parent, Make::Dummy));
        match sizes.wall {
            None => specs.push((
                &names.line,
                Make::Plane((sizes.line, [0.0, 1.0, 0.0], sizes.line_z)),
            )),
            Some(wall) => {
                // off the maze: 1 m beside the floor's south edge
                let beside = -sizes.floor[1] / 2.0 - 1.0;
                specs.push((&names.wall, Make::Cuboid(wall, [0.0, beside])));
                if let Some(post) = sizes.post {
                    let y = beside - (wall[1] + post[1]) / 2.0 - 0.25;
                    specs.push((&names.post, Make::Cuboid(post, [0.0, y])));
                }
            }
        }
        let [start_z, end_z] = sizes.marker_z;
        let cell = [sizes.cell, sizes.cell];
        specs.extend([
            (
                names.start.as_str(),
                Make::Plane((cell, [0.0, 0.0, 1.0], start_z)),
            ),
            (
                names.end.as_str(),
                Make::Plane((cell, [1.0, 0.0, 0.0], end_z)),
            ),
        ]);
        let names_asked: Vec<&str> = specs.iter().map(|(n, _)| *n).collect();
        let found = self.handles_of(&names_asked)?;
        let mut floor = found[0];
        // every name checked before anything is made: a failure leaves the scene as it was
        let mut missing = Vec::new();
        for ((name, shape), handle) in specs.into_iter().zip(&found) {
            if handle.is_some() {
                continue;
            }
            check_alias(name)?;
            let parent = name
                .rsplit_once('/')
                .map(|(p, _)| p)
                .filter(|p| !p.is_empty());
            if let Some(p) = parent {
                let made_first = missing
                    .iter()
                    .any(|(n, _, _): &(&str, Make, _)| object_path(n) == object_path(p));
                if !made_first && self.handle_of(p)?.is_none() {
                    return Err(BackendError::Remote(format!(
                        "cannot create `{name}`: `{p}` does not exist (nothing was created)"
                    )));
                }
            }
            missing.push((name, shape, parent));
        }
        let mut created: Vec<(String, i32)> = Vec::new();
        for (name, shape, parent) in missing {
            let h = match self.make(name, shape, &mut floor) {
                Ok(h) => h,
                Err(e) => return Err(self.undo_creation(&created, e)),
            };
            created.push((name.to_string(), h));
            if let Some(p) = parent
                && let Err(e) = self.parent_to(h, name, p)
            {
                return Err(self.undo_creation(&created, e));
            }
        }
        Ok(created.into_iter().map(|(n, _)| n).collect())
    }

    /// Makes one object of [`ZmqBackend::create_course`]: `shape` named `name`, on `floor`
    /// (which a new floor becomes).
    fn make(
        &mut self,
        name: &str,
        shape: Make,
        floor: &mut Option<i32>,
    ) -> Result<i32, BackendError> {
        let alias = alias_of(name);
        let h = match shape {
            Make::Floor(size) => {
                // a fresh CoppeliaSim scene has a floor; an empty `serve --scene empty` has none
                let h = self.create_plane(name, size, [0.5, 0.5, 0.5], 0.0, HANDLE_WORLD, true)?;
                *floor = Some(h);
                h
            }
            Make::Dummy => {
                let h = self
                    .client
                    .call_int("sim.createDummy", vec![Value::Float(0.05)])?;
                self.call(
                    "sim.setObjectAlias",
                    vec![int(h.into()), Value::Text(alias.into())],
                )?;
                h
            }
            Make::Plane((size, colour, z)) => {
                self.create_plane(name, size, colour, z, floor.unwrap_or(HANDLE_WORLD), false)?
            }
            Make::Cuboid(size, at) => {
                self.create_cuboid(name, size, at, floor.unwrap_or(HANDLE_WORLD))?
            }
        };
        Ok(h)
    }

    /// Puts the new object `h` (named `name`) under the object `parent` names.
    fn parent_to(&mut self, h: i32, name: &str, parent: &str) -> Result<(), BackendError> {
        let ph = self.handle_of(parent)?.ok_or_else(|| {
            BackendError::Remote(format!("cannot create `{name}`: `{parent}` does not exist"))
        })?;
        self.call(
            "sim.setObjectParent",
            vec![int(h.into()), int(ph.into()), Value::Bool(true)],
        )?;
        Ok(())
    }

    /// After `error` stopped a creation, removes the objects it had made (`created`) and
    /// says so, or says which are left if they could not be removed.
    fn undo_creation(&mut self, created: &[(String, i32)], error: BackendError) -> BackendError {
        if created.is_empty() {
            return error;
        }
        let handles: Vec<i32> = created.iter().map(|(_, h)| *h).collect();
        let names: Vec<&str> = created.iter().map(|(n, _)| n.as_str()).collect();
        let (status, text) = match self.remove(&handles) {
            Ok(()) => ("removed again", names.join(", ")),
            Err(e) => ("left in the scene", format!("{} ({e})", names.join(", "))),
        };
        let message = format!("{error}; what it had created was {status}: {text}");
        match error {
            BackendError::Transport(_) => BackendError::Transport(message),
            BackendError::Remote(_) => BackendError::Remote(message),
        }
    }

    /// The wall or post template `name`: a dark grey cuboid of `size`, static and
    /// respondable, sensed by every sensor, standing on the floor at `at` (x, y) in the
    /// frame `relative_to`.
    fn create_cuboid(
        &mut self,
        name: &str,
        size: [f64; 3],
        at: [f64; 2],
        relative_to: i32,
    ) -> Result<i32, BackendError> {
        let h = self.client.call_int(
            "sim.createPrimitiveShape",
            vec![
                int(PRIMITIVESHAPE_CUBOID.into()),
                float_array(&size),
                int(0),
            ],
        )?;
        let hv = || int(h.into());
        self.call(
            "sim.setShapeColor",
            vec![
                hv(),
                Value::Null,
                int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
                float_array(&[0.3, 0.3, 0.3]),
            ],
        )?;
        let special =
            SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE;
        self.call(
            "sim.setObjectSpecialProperty",
            vec![hv(), int(special.into())],
        )?;
        for param in [SHAPEINTPARAM_STATIC, SHAPEINTPARAM_RESPONDABLE] {
            self.call(
                "sim.setObjectInt32Param",
                vec![hv(), int(param.into()), int(1)],
            )?;
        }
        self.set_pose(h, relative_to, [at[0], at[1], size[2] / 2.0], [0.0; 3])?;
        self.call(
            "sim.setObjectAlias",
            vec![hv(), Value::Text(alias_of(name).into())],
        )?;
        Ok(h)
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
