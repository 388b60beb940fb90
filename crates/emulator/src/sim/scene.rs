//! The scene: objects with handle, name, alias, type, parent, local pose, size and colour.

use std::collections::BTreeMap;
use vrep_maze_core::coppelia::names::{Naming, copy_parts};

use serde::{Deserialize, Serialize};

use super::index::Index;
use super::mesh::Mesh;
use super::object::{Object, ObjectType};
use vrep_maze_core::coppelia::frame::{Frame, position_euler};
use vrep_maze_core::coppelia::{HANDLE_PARENT, HANDLE_WORLD};

/// Errors of scene operations (each maps to a remote error on the wire).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimError {
    /// No object has this handle (never existed or removed).
    #[error("object handle {0} does not exist")]
    NoSuchHandle(i32),
    /// No object has this name or path.
    #[error("object '{0}' does not exist")]
    NoSuchName(String),
    /// The parent would create a cycle.
    #[error("object {child} cannot be made a child of {parent} (cycle)")]
    Cycle {
        /// The object being re-parented.
        child: i32,
        /// The requested parent.
        parent: i32,
    },
    /// A scene file could not be read.
    #[error("invalid scene file: {0}")]
    BadScene(String),
}

/// How pasted copies are named.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NamingMode {
    /// What CoppeliaSim 4.5.1 was observed to do: `Line` -> `Line0`, `Line1` -> `Line2`,
    /// counting up from the original's number suffix (or 0) to the first free name.
    #[default]
    Plain,
    /// The `Line#0`, `Line#1` form found in the CoppeliaSim 4.x core sources.
    Hash,
}

/// An in-memory scene. Lookups by name, alias, parent and copy number go through an index
/// kept beside the objects (never serialized: the JSON is the objects, the next handle and the
/// naming mode), so no operation scans the whole scene for one object.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(from = "SceneData")]
pub struct Scene {
    objects: BTreeMap<i32, Object>,
    next_handle: i32,
    /// Naming of pasted copies.
    pub naming: NamingMode,
    #[serde(skip)]
    index: Index,
}

/// What a scene's JSON holds; the index is rebuilt from it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneData {
    objects: BTreeMap<i32, Object>,
    next_handle: i32,
    naming: NamingMode,
}

impl From<SceneData> for Scene {
    fn from(d: SceneData) -> Scene {
        Scene {
            index: Index::build(d.objects.values()),
            objects: d.objects,
            next_handle: d.next_handle,
            naming: d.naming,
        }
    }
}

impl PartialEq for Scene {
    fn eq(&self, other: &Scene) -> bool {
        self.objects == other.objects
            && self.next_handle == other.next_handle
            && self.naming == other.naming
    }
}

impl Default for Scene {
    fn default() -> Self {
        Scene::empty()
    }
}

/// Arguments of [`Scene::add`] besides the name.
#[derive(Debug, Clone)]
pub struct NewObject {
    /// Object type.
    pub kind: ObjectType,
    /// Parent handle.
    pub parent: Option<i32>,
    /// Local position.
    pub position: [f64; 3],
    /// Local Euler angles.
    pub orientation: [f64; 3],
    /// Bounding-box size in metres (x, y, z); a plane has z = 0.
    pub size: [f64; 3],
    /// Ambient-diffuse colour as 8-bit RGB.
    pub colour: [u8; 3],
}

impl Scene {
    /// A scene without objects.
    pub fn empty() -> Scene {
        Scene {
            objects: BTreeMap::new(),
            next_handle: 10,
            naming: NamingMode::Plain,
            index: Index::default(),
        }
    }

    /// The course scene of `../shared/spec/course-scene.md` (the spec folder beside this
    /// repository), its objects where the real `course.ttt` of `../shared/coppeliasim/` has
    /// them (read back from a real 4.5.1): `Floor` (10 m x 10 m, grey here, white there), dummy
    /// `Maze` at the origin, green `Line` (0.6 x 0.1) at the origin at z 0.001, blue `Start`
    /// at (-4, -4) and red `End` at (4, 4) (1 x 1 at z 0.002).
    pub fn course() -> Scene {
        let mut s = Scene::empty();
        let shape = |position, size, colour| NewObject {
            kind: ObjectType::Shape,
            parent: None,
            position,
            orientation: [0.0; 3],
            size,
            colour,
        };
        s.add(
            "Floor",
            shape([0.0, 0.0, 0.0], [10.0, 10.0, 0.0], [128, 128, 128]),
        );
        s.add(
            "Maze",
            NewObject {
                kind: ObjectType::Dummy,
                size: [0.01; 3],
                ..shape([0.0; 3], [0.0; 3], [255, 255, 0])
            },
        );
        s.add(
            "Line",
            shape([0.0, 0.0, 0.001], [0.6, 0.1, 0.0], [0, 255, 0]),
        );
        s.add(
            "Start",
            shape([-4.0, -4.0, 0.002], [1.0, 1.0, 0.0], [0, 0, 255]),
        );
        s.add(
            "End",
            shape([4.0, 4.0, 0.002], [1.0, 1.0, 0.0], [255, 0, 0]),
        );
        s
    }

    /// The course scene with a wall template and a post template as well: `Wall`, a dark
    /// grey cuboid of the wall defaults (1 m x 0.05 m x 0.2 m), standing beside the floor at
    /// (0, -6), and `Post`, one of 0.05 m x 0.05 m x 0.2 m (the default post) at (0, -6.3),
    /// so the scene takes line mazes and wall mazes with or without posts (`serve --scene
    /// course-walls`).
    pub fn course_walls() -> Scene {
        use vrep_maze_core::layout::walls::defaults;
        let mut s = Scene::course();
        let cuboid = |position: [f64; 2], size: [f64; 3]| NewObject {
            kind: ObjectType::Shape,
            parent: None,
            position: [position[0], position[1], size[2] / 2.0],
            orientation: [0.0; 3],
            size,
            colour: [77, 77, 77],
        };
        s.add(
            "Wall",
            cuboid(
                [0.0, -6.0],
                [defaults::LENGTH, defaults::THICKNESS, defaults::HEIGHT],
            ),
        );
        s.add(
            "Post",
            cuboid(
                [0.0, -6.3],
                [defaults::THICKNESS, defaults::THICKNESS, defaults::HEIGHT],
            ),
        );
        s
    }

    /// Reads a scene from JSON (the format of [`Scene::to_json`] or of a `--dump` file) and
    /// checks it: unknown fields, handles that disagree with their keys or reach the next free
    /// handle, unknown parents, parent cycles (an object its own ancestor), duplicate names,
    /// and non-finite or negative numbers are refused, naming the object and field.
    pub fn from_json(text: &str) -> Result<Scene, SimError> {
        /// A `--dump` file: the scene plus what viewers read (`world` poses).
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Dump {
            #[allow(dead_code)]
            format: Option<String>,
            #[allow(dead_code)]
            version: Option<u32>,
            scene: Scene,
            #[allow(dead_code)]
            world: Option<serde_json::Value>,
        }
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| SimError::BadScene(e.to_string()))?;
        let wrapped = value.get("scene").is_some();
        let scene = if wrapped {
            serde_json::from_value::<Dump>(value).map(|d| d.scene)
        } else {
            serde_json::from_value::<Scene>(value)
        }
        .map_err(|e| {
            let hint = if e.to_string().contains("null") {
                " (a number that is not finite is written as null)"
            } else {
                ""
            };
            SimError::BadScene(format!("{e}{hint}"))
        })?;
        scene.check()?;
        Ok(scene)
    }

    /// The consistency [`Scene::from_json`] requires (see there).
    fn check(&self) -> Result<(), SimError> {
        let bad = |o: &Object, what: String| {
            SimError::BadScene(format!("object '{}' (handle {}): {what}", o.name, o.handle))
        };
        let mut names = std::collections::HashSet::new();
        for (&key, o) in &self.objects {
            if key != o.handle {
                return Err(bad(o, format!("is stored under handle {key}")));
            }
            if o.handle >= self.next_handle {
                return Err(bad(
                    o,
                    format!("handle is not below next_handle {}", self.next_handle),
                ));
            }
            if !names.insert(o.name.as_str()) {
                return Err(bad(o, "its name is used by another object".into()));
            }
            for (field, values) in [
                ("position", o.position),
                ("orientation", o.orientation),
                ("size", o.size),
            ] {
                if let Some(i) = values.iter().position(|v| !v.is_finite()) {
                    return Err(bad(o, format!("{field}[{i}] is not a finite number")));
                }
            }
            if let Some(m) = &o.mesh
                && let Err(e) = Mesh::new(m.vertices.clone(), m.indices.clone())
            {
                return Err(bad(o, format!("mesh: {e}")));
            }
            if let Some(i) = o.size.iter().position(|v| *v < 0.0) {
                return Err(bad(o, format!("size[{i}] is negative")));
            }
            // walk up: more steps than objects means a cycle
            let mut parent = o.parent;
            let mut steps = 0;
            while let Some(p) = parent {
                let Some(up) = self.objects.get(&p) else {
                    return Err(bad(o, format!("has unknown parent {p}")));
                };
                steps += 1;
                if p == o.handle || steps > self.objects.len() {
                    return Err(bad(o, "is its own ancestor (a parent cycle)".into()));
                }
                parent = up.parent;
            }
        }
        Ok(())
    }

    /// Puts an object into the scene and its index.
    fn insert(&mut self, o: Object) {
        self.index.insert(&o);
        self.objects.insert(o.handle, o);
    }

    /// Adds an object with a fresh handle; the alias is the name (which no other object may
    /// have: names are unique in a scene).
    pub fn add(&mut self, name: &str, o: NewObject) -> i32 {
        let handle = self.next_handle;
        self.next_handle += 1;
        self.insert(Object {
            handle,
            name: name.to_string(),
            alias: name.to_string(),
            kind: o.kind,
            parent: o.parent,
            position: o.position,
            orientation: o.orientation,
            size: o.size,
            colour: o.colour,
            mesh: None,
            layer: None,
        });
        handle
    }

    /// Adds an object as a loaded model's object is added: its alias kept, its name the alias
    /// if no object has that name, else the name a pasted copy of it would get.
    pub fn add_loaded(&mut self, alias: &str, o: NewObject) -> i32 {
        let name = match self.index.named(alias) {
            None => alias.to_string(),
            Some(_) => self.copy_name(alias),
        };
        let handle = self.add(&name, o);
        self.rename(handle, None, Some(alias.to_string()));
        handle
    }

    /// Gives the shape `handle` the triangles `mesh` (relative to its frame) and, as its
    /// size, the extent of their bounding box.
    pub fn set_mesh(&mut self, handle: i32, mesh: Mesh) -> Result<(), SimError> {
        let o = self
            .objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?;
        let (min, max) = mesh.bounds();
        o.size = [0, 1, 2].map(|k| (max[k] - min[k]).max(0.0));
        o.mesh = Some(mesh);
        Ok(())
    }

    /// This scene with its `Floor` resized to `size` (x, y) metres: a floor that takes a
    /// maze larger than the course's 10 m (what a user makes by scaling the floor).
    pub fn with_floor(mut self, size: [f64; 2]) -> Scene {
        if let Ok(floor) = self.resolve("Floor") {
            let z = self.objects.get(&floor).map_or(0.0, |o| o.size[2]);
            let _ = self.set_size(floor, [size[0], size[1], z]);
        }
        self
    }

    /// Scales an object along its own x, y and z by `factors` (`sim.scaleObject`): its size
    /// and, for a mesh shape, its vertices; its pose stays. A dummy scales alike along all
    /// three, by the geometric mean of the factors: measured on the real 4.10 and 4.5.1
    /// (issue 38, `docs/measurements.md` "Scaling a dummy"), a 0.7231 m dummy scaled by
    /// 15 / 0.7231 along x and y and 1 along z read 5.46 m, which is 0.7231 times the cube
    /// root of the three factors' product (5.459); no other factors were measured.
    pub fn scale(&mut self, handle: i32, factors: [f64; 3]) -> Result<(), SimError> {
        let o = self
            .objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?;
        let factors = if o.kind == ObjectType::Dummy {
            [(factors[0] * factors[1] * factors[2]).cbrt(); 3]
        } else {
            factors
        };
        o.size = [0, 1, 2].map(|k| o.size[k] * factors[k]);
        if let Some(mesh) = &mut o.mesh {
            for v in mesh.vertices.chunks_exact_mut(3) {
                for k in 0..3 {
                    v[k] = (f64::from(v[k]) * factors[k]) as f32;
                }
            }
        }
        Ok(())
    }

    /// Sets an object's visibility layer bits (`sim.setObjectInt32Param(h, 10, bits)`; 0
    /// hides it).
    pub fn set_layer(&mut self, handle: i32, bits: i32) -> Result<(), SimError> {
        self.objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?
            .layer = Some(bits);
        Ok(())
    }

    /// Resizes an object (its bounding box; e.g. a template the user scaled).
    pub fn set_size(&mut self, handle: i32, size: [f64; 3]) -> Result<(), SimError> {
        let o = self
            .objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?;
        o.size = size;
        Ok(())
    }

    /// The object with this handle.
    pub fn get(&self, handle: i32) -> Result<&Object, SimError> {
        self.objects
            .get(&handle)
            .ok_or(SimError::NoSuchHandle(handle))
    }

    /// All objects in handle order.
    pub fn objects(&self) -> impl Iterator<Item = &Object> {
        self.objects.values()
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.objects.len()
    }

    /// True without objects.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty()
    }

    /// Children of `parent` (`None`: the objects without parent), in handle order.
    pub fn children(&self, parent: Option<i32>) -> impl Iterator<Item = i32> + '_ {
        self.index.children(parent)
    }

    /// How many children `parent` has (`None`: how many objects have no parent); O(1).
    pub fn child_count(&self, parent: Option<i32>) -> usize {
        self.index.child_count(parent)
    }

    /// Objects in hierarchy order: depth first from the roots, siblings in handle order.
    pub fn tree_order(&self) -> Vec<i32> {
        let mut out = Vec::with_capacity(self.objects.len());
        for root in self.children(None) {
            self.push_subtree(root, &mut out);
        }
        out
    }

    /// `base` and everything under it, depth first, siblings in handle order (the order of
    /// [`Scene::tree_order`]); empty if `base` does not exist.
    pub fn subtree(&self, base: i32) -> Vec<i32> {
        let mut out = vec![];
        if self.objects.contains_key(&base) {
            self.push_subtree(base, &mut out);
        }
        out
    }

    /// Depth first without recursion (a deep chain must not overflow the stack).
    fn push_subtree(&self, base: i32, out: &mut Vec<i32>) {
        let mut stack = vec![base];
        while let Some(h) = stack.pop() {
            out.push(h);
            let first = stack.len();
            stack.extend(self.children(Some(h)));
            stack[first..].reverse();
        }
    }

    fn is_descendant(&self, handle: i32, ancestor: i32) -> bool {
        let mut cur = self.objects.get(&handle).and_then(|o| o.parent);
        while let Some(p) = cur {
            if p == ancestor {
                return true;
            }
            cur = self.objects.get(&p).and_then(|o| o.parent);
        }
        false
    }

    /// Resolves a name like `simGetObjectHandle`: an exact object name (`Line`, `Line0`, or
    /// `Line#0` in hash naming), or an alias path `/Line`, `/Line[2]`, `/Line{2}`,
    /// `/Maze/Line`. As a real 4.5.1 resolves them (`../shared/spec/zmq-remote-api.md`,
    /// "Name resolution in 4.x"; measured with the template at the root and 159 copies under
    /// `Maze`): `alias{n}` is the n-th object of that alias in the scope, in handle order;
    /// `alias[n]` the n-th of one hierarchy level, the first level (nearest the scope) that
    /// has more than n of them (so `/Line[1]` is `/Maze/Line[1]` there); `alias` is both's
    /// first.
    pub fn resolve(&self, name: &str) -> Result<i32, SimError> {
        let missing = || SimError::NoSuchName(name.to_string());
        if let Some(path) = name.strip_prefix('/') {
            let mut scope: Option<i32> = None;
            for comp in path.split('/') {
                let (alias, index, level) = parse_path_component(comp).ok_or_else(missing)?;
                let matches: Vec<i32> = self
                    .index
                    .with_alias(alias)
                    .filter(|&h| scope.is_none_or(|s| self.is_descendant(h, s)))
                    .collect();
                let found = if level {
                    self.nth_of_a_level(&matches, index)
                } else {
                    matches.get(index).copied()
                };
                scope = Some(found.ok_or_else(missing)?);
            }
            scope.ok_or_else(missing)
        } else {
            self.index.named(name).ok_or_else(missing)
        }
    }

    /// The `n`-th of `matches` (handle order) among those of one hierarchy level: the
    /// levels by depth, the first that holds more than `n` of them.
    fn nth_of_a_level(&self, matches: &[i32], n: usize) -> Option<i32> {
        let mut levels: BTreeMap<usize, Vec<i32>> = BTreeMap::new();
        for &h in matches {
            levels.entry(self.depth(h)).or_default().push(h);
        }
        levels.values().find_map(|level| level.get(n).copied())
    }

    /// How many ancestors `handle` has (0 at the scene root).
    fn depth(&self, mut handle: i32) -> usize {
        let mut d = 0;
        while let Some(p) = self.objects.get(&handle).and_then(|o| o.parent) {
            d += 1;
            handle = p;
        }
        d
    }

    /// The path of an object: its ancestors' aliases then its own, e.g. `/Line[2]` or
    /// `/Maze/Line[1]`, where `[n]` (omitted for 0) counts the objects of the same alias, in
    /// handle order, at its hierarchy level (the root objects, or the parent's children).
    /// [`Scene::resolve`] maps it back to the object.
    pub fn path(&self, handle: i32) -> Result<String, SimError> {
        let o = self.get(handle)?;
        let mut chain = vec![];
        let mut cur = o.parent;
        while let Some(p) = cur {
            chain.push(self.get(p)?.alias.clone());
            cur = self.get(p)?.parent;
        }
        chain.reverse();
        let scope: Option<i32> = None;
        let mut scope = scope;
        let mut out = String::new();
        for alias in &chain {
            let first = self
                .index
                .with_alias(alias)
                .find(|&x| scope.is_none_or(|s| self.is_descendant(x, s)));
            scope = first;
            out.push('/');
            out.push_str(alias);
        }
        // counted within its hierarchy level, as [`Scene::resolve`] reads `[n]`
        let level = chain.len();
        let index = self
            .index
            .with_alias(&o.alias)
            .take_while(|&x| x <= handle)
            .filter(|&x| scope.is_none_or(|s| self.is_descendant(x, s)))
            .filter(|&x| self.depth(x) == level)
            .position(|x| x == handle)
            .unwrap_or(0);
        out.push('/');
        out.push_str(&o.alias);
        if index > 0 {
            out.push_str(&format!("[{index}]"));
        }
        Ok(out)
    }

    /// World frame of an object.
    pub fn world(&self, handle: i32) -> Result<Frame, SimError> {
        let o = self.get(handle)?;
        let local = o.local();
        match o.parent {
            Some(p) => Ok(self.world(p)? * local),
            None => Ok(local),
        }
    }

    /// The frame `relative_to` designates for `handle`: world (-1), the parent (-11) or an object.
    fn reference(&self, handle: i32, relative_to: i32) -> Result<Frame, SimError> {
        match relative_to {
            HANDLE_WORLD => Ok(Frame::identity()),
            HANDLE_PARENT => match self.get(handle)?.parent {
                Some(p) => self.world(p),
                None => Ok(Frame::identity()),
            },
            h => self.world(h),
        }
    }

    /// Pose of `handle` relative to `relative_to`, as (position, Euler angles).
    pub fn pose(&self, handle: i32, relative_to: i32) -> Result<([f64; 3], [f64; 3]), SimError> {
        let rel = self.reference(handle, relative_to)?;
        Ok(position_euler(&(rel.inverse() * self.world(handle)?)))
    }

    fn set_world(&mut self, handle: i32, world: Frame) -> Result<(), SimError> {
        let parent = match self.get(handle)?.parent {
            Some(p) => self.world(p)?,
            None => Frame::identity(),
        };
        let (p, e) = position_euler(&(parent.inverse() * world));
        let o = self
            .objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?;
        o.position = p;
        o.orientation = e;
        Ok(())
    }

    /// Sets the position relative to `relative_to`, keeping the orientation.
    pub fn set_position(
        &mut self,
        handle: i32,
        relative_to: i32,
        p: [f64; 3],
    ) -> Result<(), SimError> {
        let rel = self.reference(handle, relative_to)?;
        let mut world = self.world(handle)?;
        world.translation.vector = (rel * nalgebra::Point3::from(p)).coords;
        self.set_world(handle, world)
    }

    /// Sets the orientation relative to `relative_to`, keeping the position.
    pub fn set_orientation(
        &mut self,
        handle: i32,
        relative_to: i32,
        e: [f64; 3],
    ) -> Result<(), SimError> {
        let rel = self.reference(handle, relative_to)?;
        let mut world = self.world(handle)?;
        world.rotation = rel.rotation * vrep_maze_core::coppelia::frame::rotation_from_euler(e);
        self.set_world(handle, world)
    }

    /// Sets the parent (`None` = scene root). With `keep_in_place` the world pose is kept,
    /// otherwise the local pose is kept (and the object moves with its new parent).
    pub fn set_parent(
        &mut self,
        handle: i32,
        parent: Option<i32>,
        keep_in_place: bool,
    ) -> Result<(), SimError> {
        let world = self.world(handle)?;
        if let Some(p) = parent {
            self.get(p)?;
            if p == handle || self.is_descendant(p, handle) {
                return Err(SimError::Cycle {
                    child: handle,
                    parent: p,
                });
            }
        }
        let o = self
            .objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?;
        let old = std::mem::replace(&mut o.parent, parent);
        self.index.reparent(handle, old, parent);
        if keep_in_place {
            self.set_world(handle, world)?;
        }
        Ok(())
    }

    /// What a simulation's stop does to the scene it changed since `started` (the scene at
    /// its start), as the real 4.5.1 and 4.10 do it (`docs/measurements.md`, "What a stop
    /// undoes"; the spec's "edits made while running are undone" is too broad): objects made
    /// while it ran are removed, those it started with go back to their local pose;
    /// removals, colours, names and layers stay as they are.
    pub fn end_run(&mut self, started: &Scene) {
        let made: Vec<i32> = self
            .tree_order()
            .into_iter()
            .filter(|h| !started.objects.contains_key(h))
            .collect();
        for handle in made.into_iter().rev() {
            // a made object's children that the run started with move up, as a removal does
            let _ = self.remove(handle);
        }
        for (handle, then) in &started.objects {
            if let Some(o) = self.objects.get_mut(handle) {
                o.position = then.position;
                o.orientation = then.orientation;
            }
        }
    }

    /// Removes an object; its children move to its parent, keeping their world pose.
    pub fn remove(&mut self, handle: i32) -> Result<(), SimError> {
        let parent = self.get(handle)?.parent;
        let children: Vec<i32> = self.children(Some(handle)).collect();
        for c in children {
            self.set_parent(c, parent, true)?;
        }
        if let Some(o) = self.objects.remove(&handle) {
            self.index.remove(&o);
        }
        Ok(())
    }

    /// Copies and pastes objects, returning the new handles in order. Copies keep the world
    /// pose; a copy's parent is the copy of its original's parent when that was copied too,
    /// else none (pasted copies are parentless, as observed on CoppeliaSim 4.5.1).
    pub fn copy_paste(&mut self, handles: &[i32]) -> Result<Vec<i32>, SimError> {
        let mut unique: Vec<i32> = Vec::with_capacity(handles.len());
        // position of each original in `unique`
        let mut position: std::collections::HashMap<i32, usize> =
            std::collections::HashMap::with_capacity(handles.len());
        for &h in handles {
            self.get(h)?;
            if let std::collections::hash_map::Entry::Vacant(e) = position.entry(h) {
                e.insert(unique.len());
                unique.push(h);
            }
        }
        let worlds: Vec<Frame> = unique
            .iter()
            .map(|&h| self.world(h))
            .collect::<Result<_, _>>()?;
        let mut new = Vec::with_capacity(unique.len());
        // within one call, the copies of one base count on from the previous one
        let mut next: std::collections::HashMap<(String, &'static str), u64> =
            std::collections::HashMap::new();
        for (&h, world) in unique.iter().zip(&worlds) {
            let original = self.objects[&h].clone();
            let (base, sep, start) = self.copy_name_parts(&original.name);
            let key = (base, sep);
            let from = next.get(&key).copied().unwrap_or(0).max(start);
            let n = self.index.first_free(&key.0, sep, from);
            let name = format!("{}{sep}{n}", key.0);
            next.insert(key, n.saturating_add(1));
            let handle = self.next_handle;
            self.next_handle += 1;
            let (position, orientation) = position_euler(world);
            self.insert(Object {
                handle,
                name,
                parent: None,
                position,
                orientation,
                ..original
            });
            new.push(handle);
        }
        for (i, &h) in unique.iter().enumerate() {
            if let Some(p) = self.objects[&h].parent
                && let Some(&j) = position.get(&p)
            {
                self.set_parent(new[i], Some(new[j]), true)?;
            }
        }
        Ok(new)
    }

    /// Name a copy of `name` gets under the current naming mode.
    pub fn copy_name(&self, name: &str) -> String {
        let (base, sep, start) = self.copy_name_parts(name);
        format!("{base}{sep}{}", self.index.first_free(&base, sep, start))
    }

    /// (base, separator, first number to try) of the names of copies of `name`.
    fn copy_name_parts(&self, name: &str) -> (String, &'static str, u64) {
        let naming = match self.naming {
            NamingMode::Plain => Naming::Plain,
            NamingMode::Hash => Naming::Hash,
        };
        let (base, sep, start) = copy_parts(name, naming);
        (base.to_string(), sep, start)
    }

    /// JSON dump: the scene plus every object's world pose (for viewers).
    pub fn to_json(&self) -> serde_json::Value {
        let world: Vec<serde_json::Value> = self
            .objects
            .values()
            .map(|o| {
                let (p, e) = self
                    .pose(o.handle, HANDLE_WORLD)
                    .unwrap_or(([0.0; 3], [0.0; 3]));
                serde_json::json!({
                    "handle": o.handle, "name": o.name, "type": o.kind,
                    "parent": o.parent, "position": p, "orientation": e,
                    "size": o.size, "colour": o.colour,
                })
            })
            .collect();
        serde_json::json!({ "format": "vrep-maze scene", "version": 1, "scene": self, "world": world })
    }
}

/// Object creation and renaming, which only the ZeroMQ remote API can do (`createPrimitiveShape`,
/// `createDummy`, `setObjectAlias`, `setShapeColor`).
impl Scene {
    /// `base` if no object has that name (other than `except`), else `base0`, `base1`, ...:
    /// the names CoppeliaSim gives newly created objects.
    pub fn unique_name(&self, base: &str, except: Option<i32>) -> String {
        let taken = |n: &str| self.index.named(n).is_some_and(|h| Some(h) != except);
        if !taken(base) {
            return base.to_string();
        }
        (0u64..)
            .map(|n| format!("{base}{n}"))
            .find(|n| !taken(n))
            .unwrap_or_default()
    }

    /// Adds an object named `base` (made unique, see [`Scene::unique_name`]); alias `base`.
    pub fn create(&mut self, base: &str, o: NewObject) -> i32 {
        let name = self.unique_name(base, None);
        let handle = self.add(&name, o);
        self.rename(handle, None, Some(base.to_string()));
        handle
    }

    /// Sets the alias (characters outside `[A-Za-z0-9_]` become `_`) and renames the
    /// old-style name after it, made unique.
    pub fn set_alias(&mut self, handle: i32, alias: &str) -> Result<(), SimError> {
        self.get(handle)?;
        let clean: String = alias
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let name = self.unique_name(&clean, Some(handle));
        self.rename(handle, Some(name), Some(clean));
        Ok(())
    }

    /// Gives an object a new name and/or alias, keeping the index in step.
    fn rename(&mut self, handle: i32, name: Option<String>, alias: Option<String>) {
        let Some(mut o) = self.objects.remove(&handle) else {
            return;
        };
        self.index.remove(&o);
        if let Some(n) = name {
            o.name = n;
        }
        if let Some(a) = alias {
            o.alias = a;
        }
        self.insert(o);
    }

    /// Sets an object's colour.
    pub fn set_colour(&mut self, handle: i32, colour: [u8; 3]) -> Result<(), SimError> {
        self.objects
            .get_mut(&handle)
            .ok_or(SimError::NoSuchHandle(handle))?
            .colour = colour;
        Ok(())
    }
}

/// A path component: its alias, index and whether the index counts within a hierarchy
/// level (`Line[2]`, and a bare `Line`) or the whole scope (`Line{2}`).
fn parse_path_component(comp: &str) -> Option<(&str, usize, bool)> {
    if comp.is_empty() {
        return None;
    }
    if let Some((alias, n)) = comp.strip_suffix(']').and_then(|c| c.split_once('[')) {
        return Some((alias, n.parse().ok()?, true));
    }
    if let Some((alias, n)) = comp.strip_suffix('}').and_then(|c| c.split_once('{')) {
        return Some((alias, n.parse().ok()?, false));
    }
    Some((comp, 0, true))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(s: &Scene, hs: &[i32]) -> Vec<String> {
        hs.iter().map(|h| s.get(*h).unwrap().name.clone()).collect()
    }

    #[test]
    fn a_mesh_off_its_frame_gives_its_box_as_half_extents_about_its_centre() {
        let s = Scene::course();
        let line = s.resolve("Line").unwrap();
        let mut o = s.get(line).unwrap().clone();
        // a 2 x 1 m rectangle whose corner is the frame's origin, 3 m along x
        let vertices = vec![3.0, 0.0, 0.0, 5.0, 0.0, 0.0, 5.0, 1.0, 0.0, 3.0, 1.0, 0.0];
        o.mesh = Some(Mesh::new(vertices, vec![0, 1, 2, 0, 2, 3]).unwrap());
        assert_eq!(o.bounding_box(), ([3.0, 0.0, 0.0], [5.0, 1.0, 0.0]));
        let got: Vec<f64> = (15..=20).map(|p| o.float_param(p).unwrap()).collect();
        assert_eq!(got, [-1.0, -0.5, 0.0, 1.0, 0.5, 0.0]);
    }

    #[test]
    fn a_dummy_scales_alike_along_every_axis_a_shape_along_each() {
        let mut s = Scene::course();
        let maze = s.resolve("Maze").unwrap();
        let floor = s.resolve("Floor").unwrap();
        s.set_size(maze, [0.7231; 3]).unwrap();
        let f = 15.0 / 0.7231;
        s.scale(maze, [f, f, 1.0]).unwrap();
        // issue 38's measurement: 5.46 m, not 15 m
        let size = s.get(maze).unwrap().size;
        assert!(size.iter().all(|v| (v - 5.459).abs() < 1e-3), "{size:?}");
        s.scale(floor, [1.5, 2.0, 1.0]).unwrap();
        assert_eq!(s.get(floor).unwrap().size, [15.0, 20.0, 0.0]);
    }

    #[test]
    fn paths_resolve_as_a_real_4_5_1_resolves_them() {
        let mut s = Scene::course();
        let line = s.resolve("Line").unwrap();
        let maze = s.resolve("Maze").unwrap();
        let copies: Vec<i32> = (0..3).map(|_| s.copy_paste(&[line]).unwrap()[0]).collect();
        for &c in &copies {
            s.set_parent(c, Some(maze), true).unwrap();
        }
        // measured on 4.5.1 with the template at the root and 159 copies under Maze
        assert_eq!(s.resolve("/Line").unwrap(), line);
        assert_eq!(s.resolve("/Line[0]").unwrap(), line);
        assert_eq!(s.resolve("/Line[1]").unwrap(), copies[1]);
        assert_eq!(s.resolve("/Line[2]").unwrap(), copies[2]);
        assert!(s.resolve("/Line[3]").is_err());
        assert_eq!(s.resolve("/Line{1}").unwrap(), copies[0]);
        assert_eq!(s.resolve("/Line{3}").unwrap(), copies[2]);
        assert!(s.resolve("/Line{4}").is_err());
        assert_eq!(s.resolve("/Maze/Line").unwrap(), copies[0]);
        assert_eq!(s.resolve("/Maze/Line{2}").unwrap(), copies[2]);
        for &h in copies.iter().chain([&line]) {
            assert_eq!(s.resolve(&s.path(h).unwrap()).unwrap(), h);
        }
    }

    #[test]
    fn observed_copy_naming() {
        let mut s = Scene::course();
        let line = s.resolve("Line").unwrap();
        let start = s.resolve("Start").unwrap();
        let c = s.copy_paste(&[line, line]).unwrap();
        assert_eq!(names(&s, &c), ["Line0"]);
        let c1 = s.copy_paste(&[line]).unwrap();
        assert_eq!(names(&s, &c1), ["Line1"]);
        s.remove(c[0]).unwrap();
        let again = s.copy_paste(&[line]).unwrap();
        assert_eq!(names(&s, &again), ["Line0"]);
        assert!(again[0] > c1[0], "handles are never reused");
        let of1 = s.copy_paste(&[c1[0]]).unwrap();
        assert_eq!(names(&s, &of1), ["Line2"]);
        let both = s.copy_paste(&[line, start]).unwrap();
        assert_eq!(names(&s, &both), ["Line3", "Start0"]);
        assert_eq!(s.get(both[0]).unwrap().alias, "Line");
        assert_eq!(s.path(c1[0]).unwrap(), "/Line[1]");
        assert_eq!(s.path(again[0]).unwrap(), "/Line[2]");
        assert_eq!(s.resolve("/Line[2]").unwrap(), again[0]);
        assert_eq!(s.resolve("/Line").unwrap(), line);
        assert!(s.resolve("Line#0").is_err());
    }

    /// The names, paths and orders the scene's index gives, against a scan of every object
    /// (what the scene did before it had an index), over random edits in both naming modes.
    #[test]
    fn the_index_answers_what_a_full_scan_answers() {
        use vrep_maze_core::rng::MazeRng;
        for (seed, naming) in [(1u64, NamingMode::Plain), (2, NamingMode::Hash)] {
            let mut rng = MazeRng::from_seed(seed);
            let mut s = Scene::course();
            s.naming = naming;
            for step in 0..200 {
                let hs: Vec<i32> = s.objects().map(|o| o.handle).collect();
                let pick = |rng: &mut MazeRng| hs[rng.index(hs.len())];
                match rng.below(6) {
                    0 | 1 => {
                        let picked: Vec<i32> =
                            (0..1 + rng.below(3)).map(|_| pick(&mut rng)).collect();
                        // reference: lowest free name counting on from the previous one
                        let want: Vec<String> = {
                            let mut taken: std::collections::HashSet<String> =
                                s.objects().map(|o| o.name.clone()).collect();
                            let mut next = std::collections::HashMap::new();
                            let mut seen = vec![];
                            let mut out = vec![];
                            for h in &picked {
                                if seen.contains(h) {
                                    continue;
                                }
                                seen.push(*h);
                                let (base, sep, start) =
                                    s.copy_name_parts(&s.get(*h).unwrap().name);
                                let from = next
                                    .get(&(base.clone(), sep))
                                    .copied()
                                    .unwrap_or(0)
                                    .max(start);
                                let n = (from..)
                                    .find(|n| !taken.contains(&format!("{base}{sep}{n}")))
                                    .unwrap();
                                next.insert((base.clone(), sep), n + 1);
                                taken.insert(format!("{base}{sep}{n}"));
                                out.push(format!("{base}{sep}{n}"));
                            }
                            out
                        };
                        let new = s.copy_paste(&picked).unwrap();
                        assert_eq!(names(&s, &new), want, "step {step}");
                    }
                    2 if s.len() > 3 => s.remove(pick(&mut rng)).unwrap(),
                    3 => {
                        let (h, p) = (pick(&mut rng), pick(&mut rng));
                        let _ = s.set_parent(h, (rng.below(4) > 0).then_some(p), true);
                    }
                    4 => {
                        let alias = ["Line", "Line7", "Wall", "Line#2", "x"][rng.index(5)];
                        s.set_alias(pick(&mut rng), alias).unwrap();
                    }
                    _ => {
                        let base = ["Line", "Plane", "Line0"][rng.index(3)];
                        let want = if s.objects().any(|o| o.name == base) {
                            (0u64..)
                                .map(|n| format!("{base}{n}"))
                                .find(|n| s.objects().all(|o| &o.name != n))
                                .unwrap()
                        } else {
                            base.to_string()
                        };
                        let h = s.create(
                            base,
                            NewObject {
                                kind: ObjectType::Shape,
                                parent: None,
                                position: [0.0; 3],
                                orientation: [0.0; 3],
                                size: [1.0; 3],
                                colour: [0; 3],
                            },
                        );
                        assert_eq!(s.get(h).unwrap().name, want);
                    }
                }
                if step % 5 != 0 {
                    continue;
                }
                // names and paths resolve to their objects; copy names are the first free
                for o in s.objects() {
                    assert_eq!(s.resolve(&o.name).unwrap(), o.handle);
                    let path = s.path(o.handle).unwrap();
                    let (base, sep, start) = s.copy_name_parts(&o.name);
                    let first = (start..)
                        .map(|n| format!("{base}{sep}{n}"))
                        .find(|n| s.objects().all(|x| &x.name != n))
                        .unwrap();
                    assert_eq!(s.copy_name(&o.name), first);
                    if s.get(o.handle).unwrap().parent.is_none() {
                        assert_eq!(s.resolve(&path).unwrap(), o.handle, "{path}");
                    }
                }
                // tree order: depth first from the roots, siblings in handle order
                let mut want = vec![];
                fn visit(s: &Scene, parent: Option<i32>, out: &mut Vec<i32>) {
                    for o in s.objects().filter(|o| o.parent == parent) {
                        out.push(o.handle);
                        visit(s, Some(o.handle), out);
                    }
                }
                visit(&s, None, &mut want);
                assert_eq!(s.tree_order(), want);
                assert_eq!(
                    s.child_count(None),
                    s.objects().filter(|o| o.parent.is_none()).count()
                );
                // a scene read back has the same index
                let back = Scene::from_json(&s.to_json().to_string()).unwrap();
                assert_eq!(back, s);
                assert_eq!(back.tree_order(), want);
            }
        }
    }

    #[test]
    fn hash_copy_naming() {
        let mut s = Scene::course();
        s.naming = NamingMode::Hash;
        let line = s.resolve("Line").unwrap();
        let a = s.copy_paste(&[line]).unwrap();
        let b = s.copy_paste(&[a[0]]).unwrap();
        assert_eq!(names(&s, &a), ["Line#0"]);
        assert_eq!(names(&s, &b), ["Line#1"]);
        assert_eq!(s.resolve("Line#1").unwrap(), b[0]);
    }

    #[test]
    fn copies_are_parentless_and_keep_world_pose() {
        let mut s = Scene::course();
        let (maze, line) = (s.resolve("Maze").unwrap(), s.resolve("Line").unwrap());
        s.set_position(maze, HANDLE_WORLD, [1.0, 1.0, 0.0]).unwrap();
        s.set_parent(line, Some(maze), true).unwrap();
        let before = s.pose(line, HANDLE_WORLD).unwrap();
        let c = s.copy_paste(&[line]).unwrap()[0];
        assert_eq!(s.get(c).unwrap().parent, None);
        assert_eq!(s.pose(c, HANDLE_WORLD).unwrap(), before);
    }

    #[test]
    fn relative_poses_with_rotation() {
        let mut s = Scene::course();
        let (a, b) = (s.resolve("Start").unwrap(), s.resolve("End").unwrap());
        s.set_position(a, HANDLE_WORLD, [1.0, 2.0, 0.001]).unwrap();
        s.set_orientation(a, HANDLE_WORLD, [0.0, 0.0, std::f64::consts::FRAC_PI_2])
            .unwrap();
        s.set_position(b, a, [0.5, 0.0, 0.0]).unwrap();
        s.set_orientation(b, a, [0.1, 0.2, 0.3]).unwrap();
        let (p, e) = s.pose(b, HANDLE_WORLD).unwrap();
        let near = |x: [f64; 3], y: [f64; 3]| x.iter().zip(y).all(|(a, b)| (a - b).abs() < 1e-4);
        assert!(
            near(p, [1.0, 2.5, 0.001]) && near(e, [-0.2010, 0.0980, 1.8907]),
            "{p:?} {e:?}"
        );
        assert!(near(s.pose(a, b).unwrap().0, [-0.4681, 0.1448, -0.0993]));
        // keep-in-place off keeps the local pose: the world pose changes
        s.set_parent(b, Some(a), false).unwrap();
        assert!(near(s.pose(b, HANDLE_PARENT).unwrap().0, [1.0, 2.5, 0.001]));
        assert!(!near(s.pose(b, HANDLE_WORLD).unwrap().0, [1.0, 2.5, 0.001]));
        assert!(matches!(
            s.set_parent(a, Some(b), true),
            Err(SimError::Cycle { .. })
        ));
    }

    #[test]
    fn remove_twice_fails_and_json_round_trips() {
        let mut s = Scene::course();
        let end = s.resolve("End").unwrap();
        s.remove(end).unwrap();
        assert_eq!(s.remove(end), Err(SimError::NoSuchHandle(end)));
        let text = s.to_json().to_string();
        assert_eq!(Scene::from_json(&text).unwrap(), s);
    }

    #[test]
    fn broken_scene_files_are_refused_naming_object_and_field() {
        let good = Scene::course().to_json();
        assert!(Scene::from_json(&good.to_string()).is_ok());
        let maze = Scene::course().resolve("Maze").unwrap().to_string();
        let line = Scene::course().resolve("Line").unwrap().to_string();
        let edit = |f: &dyn Fn(&mut serde_json::Value)| {
            let mut v = good.clone();
            f(&mut v);
            Scene::from_json(&v.to_string()).unwrap_err().to_string()
        };
        let objects = |v: &mut serde_json::Value| v["scene"]["objects"].clone();
        type Change<'a> = Box<dyn Fn(&mut serde_json::Value) + 'a>;
        let cases: Vec<(&str, Change)> = vec![
            (
                "its own ancestor",
                Box::new(|v| {
                    v["scene"]["objects"][&maze]["parent"] =
                        serde_json::json!(maze.parse::<i32>().unwrap());
                }),
            ),
            (
                "its own ancestor",
                Box::new(|v| {
                    // Maze -> Line -> Maze
                    v["scene"]["objects"][&maze]["parent"] =
                        serde_json::json!(line.parse::<i32>().unwrap());
                    v["scene"]["objects"][&line]["parent"] =
                        serde_json::json!(maze.parse::<i32>().unwrap());
                }),
            ),
            (
                "is stored under handle",
                Box::new(|v| {
                    let mut o = objects(v);
                    o[&line]["handle"] = serde_json::json!(999);
                    v["scene"]["objects"] = o;
                }),
            ),
            (
                "not finite",
                Box::new(|v| {
                    v["scene"]["objects"][&line]["position"][0] = serde_json::Value::Null;
                }),
            ),
            (
                "unknown field",
                Box::new(|v| {
                    v["scene"]["objects"][&line]["colour_name"] = serde_json::json!("green");
                }),
            ),
            (
                "used by another object",
                Box::new(|v| {
                    v["scene"]["objects"][&line]["name"] = serde_json::json!("Maze");
                }),
            ),
            (
                "negative",
                Box::new(|v| {
                    v["scene"]["objects"][&line]["size"][1] = serde_json::json!(-1.0);
                }),
            ),
        ];
        for (needle, change) in cases {
            let message = edit(&*change);
            assert!(message.contains(needle), "{needle}: {message}");
            assert!(message.len() < 300, "{message}");
        }
    }
}
