//! What a survey finds over the ZeroMQ remote API: the objects drawing needs, their names,
//! types, parents and world poses, read in as few requests as the answers allow and
//! remembered for the connection (aliases, types, poses this connection set), and the
//! copies an interrupted run may have left at the scene root.

use std::collections::{HashMap, HashSet};

use ciborium::Value;

use super::{Known, LinePoses, WorldPose, ZmqBackend, alias_of, int_result, pose_of, record_calls};
use crate::draw::backend::{Backend, ObjectInfo};
use crate::draw::error::BackendError;
use crate::draw::mesh::parse_mesh_name;
use crate::draw::ownership;
use crate::draw::record::CopyRecord;
use crate::draw::survey::Traits;
use crate::zmq_api::cbor::{self, int};
use crate::zmq_api::{Outcome, ZmqError};
use vrep_maze_core::coppelia::{
    HANDLE_ALL, HANDLE_SCENE, HANDLE_WORLD, OBJECT_SHAPE_TYPE, OBJINTPARAM_VISIBILITY_LAYER,
};

/// A named object as a survey read it, with its type code.
type NamedInfo = (ObjectInfo, i32);

/// What a survey reads first ([`ZmqBackend::first_reads`]).
struct FirstReads {
    /// The named objects with their type codes.
    named: Vec<NamedInfo>,
    /// The maze dummy's first-level children that are shapes, and all of them (when the
    /// scene has the dummy).
    listed: Option<(Vec<i32>, Vec<i32>)>,
    /// The scene's root objects.
    roots: Vec<i32>,
    /// The copy record.
    record: CopyRecord,
}

/// The templates whose copies a survey looks for, with the copy record: how the copies
/// found are named and told from the user's objects.
struct Copies<'a> {
    /// The templates' aliases: the style's template first, then those of other styles.
    templates: Vec<&'a str>,
    /// The templates' handles by alias.
    handles: HashMap<&'a str, i32>,
    /// The templates' type codes by alias: a recorded copy must still be of its
    /// template's type.
    kinds: HashMap<&'a str, i32>,
    /// The copy record as read, brought up to date by [`ZmqBackend::collect`].
    record: CopyRecord,
    /// The copies of a template found in the maze (handle, alias): what the record holds
    /// once surveyed.
    present: Vec<(i32, String)>,
    /// How many copies of each template were named so far.
    numbered: Vec<u32>,
}

impl<'a> Copies<'a> {
    /// The templates of `known` (their types from `found`), and the copy `record`.
    fn new(known: &'a Known, found: &Traits, record: CopyRecord) -> Self {
        let templates: Vec<&str> = std::iter::once(known.line_alias.as_str())
            .chain(known.foreign_aliases.iter().map(String::as_str))
            .collect();
        let handles: HashMap<&str, i32> = known
            .named
            .iter()
            .filter(|(name, _)| templates.contains(&alias_of(name)))
            .map(|(name, h)| (alias_of(name), *h))
            .collect();
        let kinds: HashMap<&str, i32> = handles
            .iter()
            .filter_map(|(alias, h)| found.kinds.get(h).map(|k| (*alias, *k)))
            .collect();
        let numbered = vec![0; templates.len()];
        Self {
            templates,
            handles,
            kinds,
            record,
            present: Vec::new(),
            numbered,
        }
    }

    /// The name of an object of alias `alias`: the next copy's of its template
    /// (`/Line[k]`), or the alias of any other.
    fn copy_name(&mut self, alias: &str) -> String {
        match self.templates.iter().position(|t| *t == alias) {
            Some(t) => {
                self.numbered[t] += 1;
                format!("/{alias}[{}]", self.numbered[t])
            }
            None => alias.to_string(),
        }
    }

    /// Whether object `h` (in `tree`, if a child) is a copy of a template by alias and
    /// type, unless the record does not hold it and what [`ZmqBackend::doubt`] reads of
    /// an object named and typed like a copy says otherwise.
    fn judge(
        &self,
        backend: &mut ZmqBackend,
        (h, tree): (i32, Option<(i32, &[i32])>),
        name: &str,
        alias: &str,
        kind: i32,
        found: &mut Traits,
    ) -> Result<bool, BackendError> {
        let family = self
            .templates
            .iter()
            .find(|t| ownership::is_copy_name(name, t) && self.kinds.get(*t) == Some(&kind));
        let template = family.and_then(|t| self.handles.get(t).copied());
        if let Some(template) = template.filter(|_| self.record.get(h) != Some(alias)) {
            backend.doubt(h, template, tree, found)?;
        }
        let of_type = self.kinds.get(alias) == Some(&kind);
        if of_type && self.record.get(h) == Some(alias) {
            found.recorded.insert(h);
        }
        Ok(of_type && !ownership::contradicts_copy(found, h, template))
    }
}

impl ZmqBackend {
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
    /// in one request ([`Client::read_all`]) with `more`, whose outcomes come second.
    fn named_infos(
        &mut self,
        named: &[(String, i32)],
        more: Vec<(&'static str, Vec<Value>)>,
    ) -> Result<(Vec<NamedInfo>, Vec<Outcome>), BackendError> {
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
        let asked = calls.len();
        calls.extend(more);
        let mut outcomes = self.client.read_all(&calls)?;
        let more = outcomes.split_off(asked);
        let mut outcomes = outcomes.into_iter();
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
        Ok((out, more))
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
    /// ([`Traits`]). A child carrying a template's alias is named as a copy of it
    /// (`/Line[k]`), any other by its alias, so that only the templates' copies are taken
    /// for the maze's. A child the copy record names and of its template's type is known
    /// without reading its alias; one that is not recorded but named and typed like a copy
    /// is sized and asked for children ([`ZmqBackend::doubt`]: normally none). The record
    /// is then brought up to date (written with the next edit or paste). The poses this
    /// connection set for the maze dummy's children are trusted only while the dummy is
    /// where it was when they were set, at a finite pose (a child of a dummy at NaN is at
    /// NaN, whatever was set).
    pub(super) fn collect(
        &mut self,
        poses: LinePoses,
    ) -> Result<(Vec<ObjectInfo>, Traits), BackendError> {
        let known = self.known.clone();
        let mut out = Vec::new();
        let mut found = Traits::default();
        let parent_before = known.parent.and_then(|p| self.poses.get(&p).copied());
        let FirstReads {
            named,
            listed,
            roots,
            record,
        } = self.first_reads(&known)?;
        for (info, kind) in named {
            found.kinds.insert(info.handle, kind);
            out.push(info);
        }
        let parent_now = known.parent.and_then(|p| self.poses.get(&p).copied());
        let finite = |(p, e): WorldPose| p.iter().chain(&e).all(|x| x.is_finite());
        let distrust =
            parent_now.is_some_and(|now| !finite(now) || parent_before.is_some_and(|b| b != now));
        let mut seen: HashSet<i32> = known.named.iter().map(|(_, h)| *h).collect();
        let mut copies = Copies::new(&known, &found, record);
        // the record first: a named object it holds is one of our copies (refused as a
        // template or marker), a listed one of its template's type is ours
        found.recorded.extend(
            known
                .named
                .iter()
                .map(|(_, h)| *h)
                .filter(|h| copies.record.get(*h).is_some()),
        );
        if let (Some(parent), Some(listed)) = (known.parent, listed) {
            let lines =
                self.children(parent, listed, &mut copies, distrust, &mut seen, &mut found)?;
            out.extend(self.line_infos(lines, poses)?);
        }
        let lines = self.roots(roots, &mut copies, &mut seen, &mut found)?;
        out.extend(self.line_infos(lines, poses)?);
        let Copies {
            mut record,
            present,
            ..
        } = copies;
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

    /// What [`ZmqBackend::collect`] reads first, in one request: the named objects, and riding
    /// with them the lists the survey walks (the maze dummy's shapes and children, the scene's
    /// roots) and the copy record when this connection has not read it yet.
    fn first_reads(&mut self, known: &Known) -> Result<FirstReads, BackendError> {
        let mut lists = Vec::new();
        if let Some(parent) = known.parent {
            // options 3: first-level children only, without the dummy itself; the shapes
            // among them listed too, so only the other children's types are asked
            lists.push(tree_call(parent, OBJECT_SHAPE_TYPE, 3));
            lists.push(tree_call(parent, HANDLE_ALL, 3));
        }
        lists.push(tree_call(HANDLE_SCENE, HANDLE_ALL, 2));
        let read_record = self.record.is_none() && self.signals_kept;
        if read_record {
            lists.extend(record_calls());
        }
        let (named, mut lists) = self.named_infos(&known.named, lists)?;
        let record = if read_record {
            let read = lists.split_off(lists.len().saturating_sub(2));
            self.record_from(read)?
        } else {
            self.copy_record()?
        };
        let mut lists = lists.into_iter();
        let mut next = || lists.next().unwrap_or(Ok(vec![]));
        let listed = match known.parent {
            Some(_) => {
                let shapes = handle_list(next()).unwrap_or_default();
                Some((shapes, handle_list(next())?))
            }
            None => None,
        };
        Ok(FirstReads {
            named,
            listed,
            roots: handle_list(next())?,
            record,
        })
    }

    /// The maze dummy `parent`'s first-level children not `seen` yet (`listed`: the shapes
    /// among them and all of them, as [`ZmqBackend::collect`] read them), named as
    /// [`ZmqBackend::collect`] says and judged by `copies` (their poses forgotten when
    /// `distrust`): (handle, name, parent) for [`ZmqBackend::line_infos`].
    fn children(
        &mut self,
        parent: i32,
        (shapes, kids): (Vec<i32>, Vec<i32>),
        copies: &mut Copies,
        distrust: bool,
        seen: &mut HashSet<i32>,
        found: &mut Traits,
    ) -> Result<Vec<(i32, String, Option<i32>)>, BackendError> {
        let shapes: HashSet<i32> = shapes.into_iter().collect();
        let shape = |h: i32| shapes.contains(&h).then_some(OBJECT_SHAPE_TYPE);
        let new_kids: Vec<i32> = kids.iter().copied().filter(|h| !seen.contains(h)).collect();
        for &h in &new_kids {
            // a recorded copy that is (still) of its template's type is known without
            // reading its alias
            if let (Some(alias), Some(kind)) = (copies.record.get(h), shape(h))
                && copies.kinds.get(alias) == Some(&kind)
                && !self.traits.contains_key(&h)
            {
                self.traits.insert(h, (alias.to_string(), kind));
            }
        }
        // the others' aliases (and the non-shapes' types) together, not one by one
        let unknown: Vec<(i32, Option<i32>)> = new_kids.iter().map(|&h| (h, shape(h))).collect();
        self.read_traits(&unknown, true)?;
        // the recorded copies are checked as new ones would be: size, colour, children
        let recorded: Vec<(i32, i32)> = new_kids
            .iter()
            .filter_map(|&h| {
                let (alias, kind) = self.traits.get(&h)?;
                let template = *copies.handles.get(alias.as_str())?;
                (copies.record.get(h) == Some(alias.as_str())
                    && copies.kinds.get(alias.as_str()) == Some(kind))
                .then_some((h, template))
            })
            .collect();
        self.check_recorded(parent, &kids, &recorded, found)?;
        let mut lines = Vec::new();
        for &h in &kids {
            if seen.insert(h) {
                let (alias, kind) = self.traits(h, shape(h))?;
                found.kinds.insert(h, kind);
                let name = copies.copy_name(&alias);
                let tree = Some((parent, &kids[..]));
                if copies.judge(self, (h, tree), &name, &alias, kind, found)? {
                    copies.present.push((h, alias.clone()));
                }
                if distrust {
                    self.poses.remove(&h);
                }
                lines.push((h, name, Some(parent)));
            }
        }
        Ok(lines)
    }

    /// Of the scene's `roots`, those not `seen` yet carrying a template's alias: copies left parentless by
    /// an interrupted run (of this style's template, or of another found in the scene,
    /// which a drawing removes or, for posts, reuses), judged by `copies`. They are named
    /// `/Line[k]` whatever their path. The root meshes are remembered on the way.
    fn roots(
        &mut self,
        roots: Vec<i32>,
        copies: &mut Copies,
        seen: &mut HashSet<i32>,
        found: &mut Traits,
    ) -> Result<Vec<(i32, String, Option<i32>)>, BackendError> {
        let roots: Vec<i32> = roots.into_iter().filter(|h| !seen.contains(h)).collect();
        let unknown: Vec<(i32, Option<i32>)> = roots.iter().map(|&h| (h, None)).collect();
        self.read_traits(&unknown, false)?;
        let mut lines = Vec::new();
        self.root_meshes.clear();
        self.recorded_roots_with_children(&roots, &copies.record, &copies.templates, found)?;
        for h in roots {
            if seen.contains(&h) {
                continue;
            }
            // the type only of those carrying a template's alias
            let alias = self.alias(h)?;
            if parse_mesh_name(&alias).is_some() {
                self.root_meshes.push(alias);
                continue;
            }
            if !copies.templates.contains(&alias.as_str()) {
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
            let name = copies.copy_name(&alias);
            // a copy at the root stays in the record if it is there (pasted by an
            // interrupted run), but none is added by its alias: the root also holds the
            // user's template when a name found one of our copies instead
            if copies.judge(self, (h, None), &name, &alias, kind, found)?
                && copies.record.get(h) == Some(alias.as_str())
            {
                copies.present.push((h, alias.clone()));
            }
            lines.push((h, name, None));
        }
        Ok(lines)
    }

    /// Marks the root objects among `roots` that the copy record holds (as a copy of one of
    /// `templates`) and that have children as such in `found` (the user's, then:
    /// [`ownership::contradicts_copy`]): their trees read by one request, and only when
    /// there are any (an interrupted run's parentless copies).
    fn recorded_roots_with_children(
        &mut self,
        roots: &[i32],
        record: &CopyRecord,
        templates: &[&str],
        found: &mut Traits,
    ) -> Result<(), BackendError> {
        let recorded: Vec<i32> = roots
            .iter()
            .copied()
            .filter(|&h| {
                let alias = self
                    .aliases
                    .get(&h)
                    .or_else(|| self.traits.get(&h).map(|t| &t.0));
                alias.is_some_and(|a| templates.contains(&a.as_str()) && record.get(h) == Some(a))
            })
            .collect();
        if recorded.is_empty() {
            return Ok(());
        }
        let calls: Vec<(&str, Vec<Value>)> = recorded
            .iter()
            .map(|&h| {
                let args = vec![int(h.into()), int(HANDLE_ALL.into()), int(3)];
                ("sim.getObjectsInTree", args)
            })
            .collect();
        for (h, outcome) in recorded.iter().zip(self.client.read_all(&calls)?) {
            let below = outcome
                .ok()
                .and_then(|v| v.first().and_then(cbor::handles))
                .unwrap_or_default();
            self.children.insert(*h, !below.is_empty());
            if !below.is_empty() {
                found.with_children.insert(*h);
            }
        }
        Ok(())
    }

    /// Reads what a copy pasted by this tool may have lost since (`recorded`: each copy the
    /// record holds under the maze dummy `parent`, and its template): its size, colour and
    /// visibility layer and its template's, and whether anything lies below it, in one
    /// request (the maze's whole tree, `sim.getObjectsInTree`, and a shape's
    /// `sim.getShapeBB`, `sim.getShapeColor` and `sim.getObjectInt32Param`; the
    /// parents of what lies below `kids`, the dummy's children, in a second only when
    /// something does). A copy with children is the user's
    /// ([`ownership::contradicts_copy`]), one of another size or colour spoiled
    /// (`Traits::spoiled`).
    fn check_recorded(
        &mut self,
        parent: i32,
        kids: &[i32],
        recorded: &[(i32, i32)],
        found: &mut Traits,
    ) -> Result<(), BackendError> {
        if recorded.is_empty() {
            return Ok(());
        }
        let mut sized: Vec<i32> = recorded.iter().map(|&(_, t)| t).collect();
        sized.sort_unstable();
        sized.dedup();
        sized.extend(recorded.iter().map(|&(c, _)| c));
        let tree = (
            "sim.getObjectsInTree",
            vec![int(parent.into()), int(HANDLE_ALL.into()), int(1)],
        );
        let mut calls = vec![tree];
        for &h in &sized {
            calls.push(("sim.getShapeBB", vec![int(h.into())]));
            calls.push(super::mesh::shape_colour_call(h));
            let layer = int(OBJINTPARAM_VISIBILITY_LAYER.into());
            calls.push(("sim.getObjectInt32Param", vec![int(h.into()), layer]));
        }
        let mut outcomes = self.client.read_all(&calls)?.into_iter();
        let below: Vec<i32> = match outcomes.next() {
            Some(Ok(values)) => values.first().and_then(cbor::handles).unwrap_or_default(),
            _ => Vec::new(),
        };
        for &h in &sized {
            let size = outcomes.next().and_then(Result::ok);
            let colour = outcomes.next().and_then(Result::ok);
            let layer = outcomes.next().and_then(Result::ok);
            if let Some(layer) = layer.and_then(|v| v.first().and_then(cbor::int32)) {
                found.layers.insert(h, layer);
            }
            if let Some(size) = size.and_then(|v| v.first().and_then(cbor::numbers::<3>)) {
                found.sizes.insert(h, size);
            }
            if let Some(colour) = colour.and_then(|v| super::mesh::colour_of(&v)) {
                found.colours.insert(h, colour);
            }
        }
        let kid_set: HashSet<i32> = kids.iter().copied().collect();
        let deeper: Vec<i32> = below.into_iter().filter(|h| !kid_set.contains(h)).collect();
        self.deep = Some(!deeper.is_empty());
        if !deeper.is_empty() {
            let calls: Vec<(&str, Vec<Value>)> = deeper
                .iter()
                .map(|&h| ("sim.getObjectParent", vec![int(h.into())]))
                .collect();
            let parents: HashSet<i32> = self
                .client
                .read_all(&calls)?
                .into_iter()
                .filter_map(|o| int_result("sim.getObjectParent", o).ok())
                .collect();
            for &h in kids {
                self.children.insert(h, parents.contains(&h));
            }
        }
        for &(copy, template) in recorded {
            if self.children.get(&copy) == Some(&true) {
                found.with_children.insert(copy);
            }
            if let Some(why) = ownership::spoiled(found, copy, template) {
                found.spoiled.insert(copy, why);
            }
        }
        Ok(())
    }

    /// Reads what tells `handle`, named and typed like a copy of `template` but not in the
    /// copy record, from a copy ([`ownership::contradicts_copy`]) into `found`: its size and its
    /// template's (a shape's `sim.getShapeBB`, one call; other objects' bounding box, six)
    /// and whether it has children (`sim.getObjectsInTree`, one call, unless `tree`, the
    /// maze dummy and its children it is one of, shows nothing below them: one call for
    /// the whole maze). Read once per survey.
    fn doubt(
        &mut self,
        handle: i32,
        template: i32,
        tree: Option<(i32, &[i32])>,
        found: &mut Traits,
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
}

/// `sim.getObjectsInTree(base, kind, options)`.
fn tree_call(base: i32, kind: i32, options: i32) -> (&'static str, Vec<Value>) {
    let args = vec![int(base.into()), int(kind.into()), int(options.into())];
    ("sim.getObjectsInTree", args)
}

/// The handles a `sim.getObjectsInTree` answered with.
fn handle_list(outcome: Outcome) -> Result<Vec<i32>, BackendError> {
    let values = outcome?;
    let first = values.first().unwrap_or(&Value::Null);
    cbor::handles(first).ok_or_else(|| {
        BackendError::Transport(format!(
            "sim.getObjectsInTree: not a handle list: {}",
            cbor::describe(first)
        ))
    })
}
