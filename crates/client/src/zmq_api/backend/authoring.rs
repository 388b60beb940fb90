//! [`Authoring`] over the ZeroMQ remote API: what the course scene has and this one lacks
//! created (the floor, the maze dummy, the templates, start and end: planes, cuboids, a
//! dummy), undone when one fails; the scene saved; an object scaled.

use ciborium::Value;

use super::{ZmqBackend, alias_of};
use crate::draw::backend::Authoring;
use crate::draw::error::BackendError;
use crate::draw::names::ObjectNames;
use crate::zmq_api::cbor::{float_array, int};
use crate::zmq_api::client::object_path;
use vrep_maze_core::coppelia::{
    COLORCOMPONENT_AMBIENT_DIFFUSE, HANDLE_WORLD, PRIMITIVESHAPE_CUBOID, PRIMITIVESHAPE_PLANE,
    SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC, SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE,
    SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};
use vrep_maze_core::layout::sizes::Sizes;

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
    /// A dummy of `size` metres named `alias`, in the world frame.
    pub(super) fn create_dummy(&mut self, size: f64, alias: &str) -> Result<i32, BackendError> {
        let h = self
            .client
            .call_int("sim.createDummy", vec![Value::Float(size)])?;
        self.call(
            "sim.setObjectAlias",
            vec![int(h.into()), Value::Text(alias.into())],
        )?;
        Ok(h)
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
        let special = (!floor).then_some(SPECIAL_RENDERABLE);
        let size = [size[0], size[1], 0.0];
        let h = self.primitive(PRIMITIVESHAPE_PLANE, size, colour, special, floor)?;
        self.place(h, name, relative_to, [0.0, 0.0, z])?;
        Ok(h)
    }

    /// A static primitive shape of `kind` and `size`, coloured, with the special properties
    /// `special` (the default ones when `None`), respondable or not.
    fn primitive(
        &mut self,
        kind: i32,
        size: [f64; 3],
        colour: [f64; 3],
        special: Option<i32>,
        respondable: bool,
    ) -> Result<i32, BackendError> {
        let h = self.client.call_int(
            "sim.createPrimitiveShape",
            vec![int(kind.into()), float_array(&size), int(0)],
        )?;
        self.dress(h, Value::Null, colour, special, respondable)?;
        Ok(h)
    }

    /// Dresses the new shape `h`, made here or as a mesh ([`super::mesh`]), by the same calls
    /// in the same order: its ambient-diffuse colour, its special properties `special` (the
    /// default ones when `None`), static, respondable or not. `colour_name` is
    /// `sim.setShapeColor`'s second argument: CoppeliaSim reads nil and `""` alike (the whole
    /// shape) on 4.5.1 and 4.10 (`../shared/spec/real-coppeliasim-4.5.1.md` measured `""`;
    /// `--create-missing` sends nil on both builds), so each caller keeps what it sent.
    pub(super) fn dress(
        &mut self,
        h: i32,
        colour_name: Value,
        colour: [f64; 3],
        special: Option<i32>,
        respondable: bool,
    ) -> Result<(), BackendError> {
        let hv = || int(h.into());
        self.call(
            "sim.setShapeColor",
            vec![
                hv(),
                colour_name,
                int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
                float_array(&colour),
            ],
        )?;
        if let Some(special) = special {
            self.call(
                "sim.setObjectSpecialProperty",
                vec![hv(), int(special.into())],
            )?;
        }
        for (param, on) in [
            (SHAPEINTPARAM_STATIC, true),
            (SHAPEINTPARAM_RESPONDABLE, respondable),
        ] {
            self.call(
                "sim.setObjectInt32Param",
                vec![hv(), int(param.into()), int(on.into())],
            )?;
        }
        Ok(())
    }

    /// A new object put at `position` in the frame `relative_to` and named `name`.
    fn place(
        &mut self,
        h: i32,
        name: &str,
        relative_to: i32,
        position: [f64; 3],
    ) -> Result<(), BackendError> {
        self.set_pose(h, relative_to, position, [0.0; 3])?;
        self.call(
            "sim.setObjectAlias",
            vec![int(h.into()), Value::Text(alias_of(name).into())],
        )?;
        Ok(())
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
            Make::Dummy => self.create_dummy(0.05, alias)?,
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
        let special =
            SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE;
        let grey = [0.3, 0.3, 0.3];
        let h = self.primitive(PRIMITIVESHAPE_CUBOID, size, grey, Some(special), true)?;
        self.place(h, name, relative_to, [at[0], at[1], size[2] / 2.0])?;
        Ok(h)
    }
}
