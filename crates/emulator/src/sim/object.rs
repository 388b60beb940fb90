//! One scene object ([`Object`]: handle, names, type, parent, local pose, size, colour,
//! mesh) and its type; the scene ([`super::scene`]) and its name index (the private
//! `sim::index`) both stand on it.

use serde::{Deserialize, Serialize};

use super::mesh::Mesh;
use vrep_maze_core::coppelia::frame::{Frame, frame};

/// Object types we model, with CoppeliaSim's `sim_object_*_type` codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ObjectType {
    /// A shape (planes, the floor): code 0.
    Shape,
    /// A dummy (the `Maze` anchor): code 4.
    Dummy,
}

impl ObjectType {
    /// CoppeliaSim's numeric type code.
    pub fn code(self) -> i32 {
        match self {
            ObjectType::Shape => vrep_maze_core::coppelia::OBJECT_SHAPE_TYPE,
            ObjectType::Dummy => vrep_maze_core::coppelia::OBJECT_DUMMY_TYPE,
        }
    }
}

/// One scene object. The pose is local (relative to the parent, or the world without parent).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Unique handle; handles only increase and are never reused.
    pub handle: i32,
    /// Old-style unique name (what `simxGetObjectHandle` and group data type 0 see).
    pub name: String,
    /// Alias (path component); copies keep the original's alias.
    pub alias: String,
    /// Object type.
    #[serde(rename = "type")]
    pub kind: ObjectType,
    /// Parent handle, `None` at the scene root.
    pub parent: Option<i32>,
    /// Position relative to the parent (metres).
    pub position: [f64; 3],
    /// Euler angles relative to the parent (radians, CoppeliaSim convention).
    pub orientation: [f64; 3],
    /// Bounding size x, y, z (metres).
    pub size: [f64; 3],
    /// Colour as RGB bytes.
    pub colour: [u8; 3],
    /// A shape's triangles relative to its frame, when they are not the primitive its
    /// `size` makes ([`Mesh::primitive`]): meshes created or loaded, merged groups.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<Mesh>,
    /// The visibility layer bits set by `sim.setObjectInt32Param(h, 10, bits)`, `None` for
    /// the type's default ([`Object::layer`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layer: Option<i32>,
}

impl Object {
    /// A shape's triangles relative to its frame: its own mesh, or the primitive of its
    /// size (a plane when the z size is 0, else a cuboid). `None` for a dummy.
    pub fn shape_mesh(&self) -> Option<std::borrow::Cow<'_, Mesh>> {
        match (self.kind, &self.mesh) {
            (ObjectType::Dummy, _) => None,
            (ObjectType::Shape, Some(m)) => Some(std::borrow::Cow::Borrowed(m)),
            (ObjectType::Shape, None) => Some(std::borrow::Cow::Owned(Mesh::primitive(self.size))),
        }
    }

    /// The visibility layer bits (`sim_objintparam_visibility_layer`): as set, else a new
    /// shape's 1 or a new dummy's 4, as both real builds answer
    /// ([`vrep_maze_core::coppelia::OBJINTPARAM_VISIBILITY_LAYER`]).
    pub fn layer(&self) -> i32 {
        self.layer.unwrap_or(match self.kind {
            ObjectType::Shape => vrep_maze_core::coppelia::SHAPE_LAYER,
            ObjectType::Dummy => vrep_maze_core::coppelia::DUMMY_LAYER,
        })
    }

    /// The bounding box relative to the object's frame, min and max corners: its mesh's,
    /// or `size` centred on the frame.
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        match &self.mesh {
            Some(m) => m.bounds(),
            None => (self.size.map(|s| -s / 2.0), self.size.map(|s| s / 2.0)),
        }
    }

    /// The local frame (relative to the parent).
    pub fn local(&self) -> Frame {
        frame(self.position, self.orientation)
    }

    /// Object float parameter `param` as `sim.getObjectFloatParam` gives it, `None` for one
    /// the emulator does not model. 15..20 are the bounding box (min x, y, z, then max x, y,
    /// z) as half-extents about the box's centre, whatever the shape's frame: the course's
    /// `Line` plane gives -0.3, -0.05, 0, 0.3, 0.05, 0, and so does a mesh whose vertices lie
    /// off its frame, made by `sim.createMeshShape` or loaded from an XML model alike
    /// (`../shared/spec/real-coppeliasim-4.5.1.md`, "Meshes on the real 4.5.1": a 27.05 m row
    /// of posts gives -13.525..13.525; the XML-loaded meshes of `apply --api legacy --draw
    /// mesh` measured the same on 2026-11-27).
    pub fn float_param(&self, param: i32) -> Option<f64> {
        let k = usize::try_from(param.checked_sub(vrep_maze_core::coppelia::OBJFLOATPARAM_BBOX)?)
            .ok()?;
        let (min, max) = self.bounding_box();
        let half = [0, 1, 2].map(|i| (max[i] - min[i]) / 2.0);
        // `+ 0.0` turns the -0 of an empty extent into 0, as CoppeliaSim answers
        match k {
            0..=2 => Some(-half[k] + 0.0),
            3..=5 => Some(half[k - 3] + 0.0),
            _ => None,
        }
    }
}
