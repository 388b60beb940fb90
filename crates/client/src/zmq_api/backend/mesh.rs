//! [`MeshDrawing`] over the ZeroMQ remote API: a batch of meshes made and dressed by one
//! `sim.executeLuaCode` ([`lua::create`]), or where that fails `sim.createShape`
//! (`sim.createMeshShape` before 4.6) per mesh, dressed by the calls that dress a created
//! primitive shape (`ZmqBackend::dress`) and named; read back in one `sim.executeLuaCode`
//! ([`lua::read`]) or `sim.getShapeMesh` each.

use std::borrow::Cow;

use ciborium::Value;

use super::{ZmqBackend, int_result};
use crate::draw::error::BackendError;
use crate::draw::mesh::{
    FoundMesh, FoundMeshes, HOLDER, Look, MeshDrawing, MeshPlace, MeshReadback, NewMesh,
};
use crate::draw::names::ObjectNames;
use crate::zmq_api::cbor::{self, float_array, int};
use crate::zmq_api::client::object_path;
use crate::zmq_api::{Outcome, ZmqError};
use vrep_maze_core::coppelia::lua::{self, CreateMeshes, LuaMesh, create::SHADING_ANGLE};
use vrep_maze_core::coppelia::{COLORCOMPONENT_AMBIENT_DIFFUSE, OBJINTPARAM_VISIBILITY_LAYER};

/// The first program version whose add-on speaks protocol 2 (4.6.0): from it on meshes are
/// made with `sim.createShape`, since 4.10 logs that `sim.createMeshShape` is deprecated
/// (`../shared/spec/real-coppeliasim-4.10.md` "Other API changes that matter"). Both make the
/// same shape, at the identity pose with its vertices as given (coppeliaSimLib@coppeliasim-v4.10.0-rev0
/// `simInternal.cpp:6304-6408`); 4.5.1, where every timing was measured, keeps the older call.
const CREATE_SHAPE_SINCE: i32 = 40600;

/// Positions within this of the origin, and angles within this of zero, are the identity.
const IDENTITY: f64 = 1e-9;

/// The meshes of a [`lua::read_meshes_code`] answer, `(true, {v1, i1, ...})`: `None` for a
/// failure or an answer of another shape.
fn packed_meshes(values: &[Value], count: usize) -> Option<Vec<MeshReadback>> {
    let (Some(Value::Bool(true)), Some(Value::Array(packed))) = (values.first(), values.get(1))
    else {
        return None;
    };
    if packed.len() != 2 * count {
        return None;
    }
    packed
        .chunks_exact(2)
        .map(|pair| match pair {
            [Value::Bytes(v), Value::Bytes(i)] => Some(MeshReadback {
                vertices: Some(lua::unpack_floats(v)?),
                indices: Some(lua::unpack_int32s(i)?),
                ..Default::default()
            }),
            _ => None,
        })
        .collect()
}

/// The meshes of a [`lua::read_dressed_code`] answer, `(true, {v1, i1, pose1, colour1,
/// layer1, ...})`: `None` for a failure or an answer of another shape.
fn dressed_meshes(handles: &[i32], values: &[Value]) -> Option<Vec<MeshReadback>> {
    let (Some(Value::Bool(true)), Some(Value::Array(packed))) = (values.first(), values.get(1))
    else {
        return None;
    };
    if packed.len() != lua::DRESSED_ENTRIES * handles.len() {
        return None;
    }
    handles
        .iter()
        .zip(packed.chunks_exact(lua::DRESSED_ENTRIES))
        .map(|(&h, entries)| match entries {
            [Value::Bytes(v), Value::Bytes(i), pose, colour, layer] => Some(MeshReadback {
                vertices: Some(lua::unpack_floats(v)?),
                indices: Some(lua::unpack_int32s(i)?),
                bounding_box: None,
                colour: cbor::numbers::<3>(colour),
                pose: super::pose_of(h, std::slice::from_ref(pose)).ok()?,
                layer: cbor::int32(layer),
            }),
            _ => None,
        })
        .collect()
}

/// The handles in the answer of a [`lua::create_meshes_code`] program that made `count`
/// meshes, `(true, {h1, h2, ...})`; `None` for a failure (which the program undid).
fn created_handles(values: &[Value], count: usize) -> Result<Option<Vec<i32>>, BackendError> {
    match (values.first(), values.get(1)) {
        (Some(Value::Bool(true)), Some(Value::Array(handles))) if handles.len() == count => handles
            .iter()
            .map(|h| cbor::int32(h).map(Some))
            .collect::<Option<Option<Vec<i32>>>>()
            .ok_or_else(|| not_handles(values)),
        (Some(Value::Bool(false)), _) => Ok(None),
        _ => Err(not_handles(values)),
    }
}

fn not_handles(values: &[Value]) -> BackendError {
    BackendError::Transport(format!(
        "sim.executeLuaCode creating meshes: not their handles: {}",
        cbor::describe(&Value::Array(values.to_vec()))
    ))
}

impl ZmqBackend {
    /// `meshes` made, dressed, put in the floor's frame and under `holder` by one
    /// `sim.executeLuaCode` ([`lua::create`]: about half the time of the separate calls);
    /// `None` where the simulator could not run it (a failure the program undid, or no such
    /// function), and the separate calls then name what fails.
    fn created_in_one_request(
        &mut self,
        floor: i32,
        holder: i32,
        meshes: &[NewMesh<'_>],
    ) -> Result<Option<Vec<i32>>, BackendError> {
        let batch = CreateMeshes {
            since_4_6: self.version >= CREATE_SHAPE_SINCE,
            holder,
            floor: (!self.floor_is_world(floor)).then_some(floor),
            meshes: meshes
                .iter()
                .map(|m| LuaMesh {
                    name: Cow::Borrowed(m.name),
                    vertices: Cow::Borrowed(m.vertices),
                    indices: Cow::Borrowed(m.indices),
                    colour: m.look.colour,
                    special: m.look.special,
                    respondable: m.respondable,
                })
                .collect(),
        };
        let code = Value::Text(lua::create_meshes_code(&batch));
        match self.client.call("sim.executeLuaCode", vec![code]) {
            Ok(values) => created_handles(&values, meshes.len()),
            Err(ZmqError::Remote { .. }) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// `shape` with the colour, world pose and visibility layer of the mesh `handle`.
    fn dressed(&mut self, handle: i32, shape: MeshReadback) -> Result<MeshReadback, BackendError> {
        let (func, args) = shape_colour_call(handle);
        let colour = colour_of(&self.call(func, args)?);
        let pose = self.world_pose(handle)?;
        let layer = self.client.call_int(
            "sim.getObjectInt32Param",
            vec![int(handle.into()), int(OBJINTPARAM_VISIBILITY_LAYER.into())],
        )?;
        Ok(MeshReadback {
            colour,
            pose,
            layer: Some(layer),
            ..shape
        })
    }

    /// Whether the floor's world pose, as last read, is the world frame: a new mesh (at the
    /// world origin) is then on the floor already and needs no pose call.
    fn floor_is_world(&self, floor: i32) -> bool {
        self.poses
            .get(&floor)
            .is_some_and(|(p, e)| p.iter().chain(e).all(|x| x.abs() <= IDENTITY))
    }

    /// Puts a new object's frame on the floor's (unless it is there, the world's) and under
    /// `parent`, keeping it in place.
    fn settle(&mut self, h: i32, floor: i32, parent: i32) -> Result<(), BackendError> {
        if !self.floor_is_world(floor) {
            self.set_pose(h, floor, [0.0; 3], [0.0; 3])?;
        }
        self.call(
            "sim.setObjectParent",
            vec![int(h.into()), int(parent.into()), Value::Bool(true)],
        )?;
        Ok(())
    }
}

/// `sim.getShapeColor(h, "", 0)`: the ambient-diffuse colour of the shape `handle`.
pub(super) fn shape_colour_call(handle: i32) -> (&'static str, Vec<Value>) {
    (
        "sim.getShapeColor",
        vec![
            int(handle.into()),
            Value::Text(String::new()),
            int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
        ],
    )
}

/// The colour in the reply of [`shape_colour_call`] (`[1, [r, g, b]]`).
pub(super) fn colour_of(values: &[Value]) -> Option<[f64; 3]> {
    values.get(1).and_then(cbor::numbers::<3>)
}

impl MeshDrawing for ZmqBackend {
    /// The colour and the special properties, read by one request.
    fn look(&mut self, template: i32) -> Result<Look, BackendError> {
        let calls = [
            shape_colour_call(template),
            ("sim.getObjectSpecialProperty", vec![int(template.into())]),
        ];
        let [colour, special]: [Outcome; 2] = self
            .client
            .read_all(&calls)?
            .try_into()
            .map_err(|_| BackendError::Transport("a reply missing from a look".into()))?;
        let colour = colour.ok().and_then(|v| colour_of(&v)).ok_or_else(|| {
            BackendError::Transport(format!("sim.getShapeColor of {template}: no colour"))
        })?;
        let special = int_result("sim.getObjectSpecialProperty", special)?;
        Ok(Look { colour, special })
    }

    /// The holder's children and their aliases; the holder by its path unless `surveyed`.
    fn find(
        &mut self,
        names: &ObjectNames,
        _parent: i32,
        surveyed: Option<i32>,
    ) -> Result<FoundMeshes, BackendError> {
        let path = format!("{}/{HOLDER}", object_path(&names.parent));
        let elsewhere = self.root_meshes.clone();
        let holder = match surveyed {
            Some(h) => Some(h),
            None => self.handle_of(&path)?,
        };
        let Some(holder) = holder else {
            return Ok(FoundMeshes {
                elsewhere,
                ..Default::default()
            });
        };
        // options 3: the holder's children, without the holder itself (removing the holder
        // removes them; anything deeper moves up to its parent, as CoppeliaSim does); their
        // aliases in one request
        let children = self.handles_in(holder, 3)?;
        let calls: Vec<(&str, Vec<Value>)> = children
            .iter()
            .map(|&h| ("sim.getObjectAlias", vec![int(h.into()), int(-1)]))
            .collect();
        let aliases = self.client.read_all(&calls)?;
        let mut meshes = Vec::with_capacity(children.len());
        for (h, alias) in children.into_iter().zip(aliases) {
            let v = alias?;
            let name = v.first().and_then(cbor::text).ok_or_else(|| {
                BackendError::Transport(format!(
                    "sim.getObjectAlias of {h}: not a text: {}",
                    v.first().map_or("nothing".into(), cbor::describe)
                ))
            })?;
            meshes.push(FoundMesh {
                handle: h,
                name: name.to_string(),
                parent: Some(holder),
            });
        }
        Ok(FoundMeshes {
            holder: Some(holder),
            meshes,
            users: Vec::new(),
            elsewhere,
        })
    }

    fn create(
        &mut self,
        place: &MeshPlace,
        meshes: &[NewMesh<'_>],
    ) -> Result<(i32, Vec<i32>), BackendError> {
        let holder = match place.holder {
            Some(h) => h,
            None => {
                let h = self.create_dummy(0.01, HOLDER)?;
                self.settle(h, place.floor, place.parent)?;
                h
            }
        };
        if let Some(created) = self.created_in_one_request(place.floor, holder, meshes)? {
            return Ok((holder, created));
        }
        let mut created = Vec::with_capacity(meshes.len());
        for mesh in meshes {
            let vertices: Vec<f64> = mesh.vertices.iter().map(|&v| f64::from(v)).collect();
            let indices = Value::Array(mesh.indices.iter().map(|&i| int(i.into())).collect());
            let create = if self.version >= CREATE_SHAPE_SINCE {
                "sim.createShape"
            } else {
                "sim.createMeshShape"
            };
            let h = self.client.call_int(
                create,
                vec![
                    int(0),
                    Value::Float(SHADING_ANGLE),
                    float_array(&vertices),
                    indices,
                ],
            )?;
            self.dress(
                h,
                Value::Text(String::new()),
                mesh.look.colour,
                Some(mesh.look.special),
                mesh.respondable,
            )?;
            self.call(
                "sim.setObjectAlias",
                vec![int(h.into()), Value::Text(mesh.name.into())],
            )?;
            self.settle(h, place.floor, holder)?;
            created.push(h);
        }
        Ok((holder, created))
    }

    fn read(&mut self, handle: i32) -> Result<MeshReadback, BackendError> {
        let shape = self.read_shape(handle)?;
        self.dressed(handle, shape)
    }

    /// Every mesh whole in one `sim.executeLuaCode` ([`lua::read_dressed_code`]); where
    /// that fails, [`MeshDrawing::read_shapes`] and a few calls each.
    fn read_all(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        if handles.is_empty() {
            return Ok(Vec::new());
        }
        let code = Value::Text(lua::read_dressed_code(handles));
        match self.client.call("sim.executeLuaCode", vec![code]) {
            Ok(values) => {
                if let Some(meshes) = dressed_meshes(handles, &values) {
                    return Ok(meshes);
                }
            }
            Err(ZmqError::Remote { .. }) => {}
            Err(e) => return Err(e.into()),
        }
        let shapes = self.read_shapes(handles)?;
        handles
            .iter()
            .zip(shapes)
            .map(|(&h, shape)| self.dressed(h, shape))
            .collect()
    }

    /// Every mesh's triangles in one `sim.executeLuaCode` ([`lua::read_meshes_code`]); where
    /// that fails (a simulator without the function, a handle that is no shape), one
    /// `sim.getShapeMesh` each, which names the mesh at fault.
    fn read_shapes(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        if !handles.is_empty() {
            let code = Value::Text(lua::read_meshes_code(handles));
            match self.client.call("sim.executeLuaCode", vec![code]) {
                Ok(values) => {
                    if let Some(shapes) = packed_meshes(&values, handles.len()) {
                        return Ok(shapes);
                    }
                }
                Err(ZmqError::Remote { .. }) => {}
                Err(e) => return Err(e.into()),
            }
        }
        handles.iter().map(|&h| self.read_shape(h)).collect()
    }

    /// `sim.getShapeMesh` alone; the pose is left at the origin.
    fn read_shape(&mut self, handle: i32) -> Result<MeshReadback, BackendError> {
        let values = self.call("sim.getShapeMesh", vec![int(handle.into())])?;
        let floats = |v: Option<&Value>| -> Option<Vec<f32>> {
            cbor::array(v?)?
                .iter()
                .map(|x| cbor::number(x).map(|f| f as f32))
                .collect()
        };
        let vertices = floats(values.first());
        let indices = values
            .get(1)
            .and_then(cbor::array)
            .and_then(|v| v.iter().map(cbor::int32).collect::<Option<Vec<i32>>>());
        if vertices.is_none() || indices.is_none() {
            return Err(BackendError::Transport(format!(
                "sim.getShapeMesh of {handle}: not vertices and indices"
            )));
        }
        Ok(MeshReadback {
            vertices,
            indices,
            ..Default::default()
        })
    }
}
