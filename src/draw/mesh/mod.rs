//! Drawing a maze as a few mesh shapes instead of one copy of a template per line
//! (`apply --draw mesh`): [`geometry`] computes the meshes from a layout, [`MeshDrawing`] is
//! the capability a backend offers to create, find and read them.
//!
//! Where the meshes live: under the maze dummy (`Maze`), a dummy named [`HOLDER`] holds
//! them, its frame on the Floor's; each mesh's frame is on the Floor's too, so its vertices
//! are Floor coordinates ([`geometry`]). One path lookup (`Maze/MazeMeshes`) tells whether a
//! scene holds a mesh maze, so a copies-mode draw or a clear finds and removes one without
//! reading the name of every copy. Each mesh's name carries a fingerprint of what it holds
//! ([`geometry::mesh_name`]): a re-apply keeps the meshes whose fingerprint it would draw.

pub mod compare;
pub mod draw;
pub mod geometry;

pub use draw::{apply, found, leftovers, verify, verify_read_only};
pub use geometry::{
    MAX_TRIANGLES, MESH_PREFIX, MazeMesh, MeshKind, MeshMaze, Piece, mesh_name, parse_mesh_name,
};

use super::{BackendError, ObjectNames};

/// The alias of the dummy under the maze dummy that holds a mesh maze's meshes.
pub const HOLDER: &str = "MazeMeshes";

/// How a template looks, copied onto the meshes drawn in its stead.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Ambient-diffuse colour, RGB 0..1 (`sim.getShapeColor(h, "", 0)`).
    pub colour: [f64; 3],
    /// Special-property bits (collidable, measurable, detectable, renderable).
    pub special: i32,
}

/// One mesh to create.
#[derive(Debug, Clone, Copy)]
pub struct NewMesh<'a> {
    /// Name and alias ([`MazeMesh::name`]).
    pub name: &'a str,
    /// x, y, z per vertex, in the Floor frame.
    pub vertices: &'a [f32],
    /// Three vertex indices per triangle.
    pub indices: &'a [i32],
    /// Colour and special properties.
    pub look: Look,
    /// Respondable (walls, posts) or not (lines); every mesh is static.
    pub respondable: bool,
}

/// Where new meshes go: the holder (created under `parent` when `None`) and the Floor, whose
/// frame every mesh (and the holder) takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshPlace {
    /// The maze dummy.
    pub parent: i32,
    /// The holder, if the scene has one.
    pub holder: Option<i32>,
    /// The floor.
    pub floor: i32,
}

/// A mesh of ours found in the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct FoundMesh {
    /// Its handle.
    pub handle: i32,
    /// Its name (alias).
    pub name: String,
    /// Its parent.
    pub parent: Option<i32>,
}

/// The holder and what it holds.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FoundMeshes {
    /// The holder dummy, if the scene has one under the maze dummy.
    pub holder: Option<i32>,
    /// Every object under the holder: meshes of ours are named by
    /// [`parse_mesh_name`]; anything else was put there by hand.
    pub meshes: Vec<FoundMesh>,
}

impl FoundMeshes {
    /// The holder and everything under it: what removing a mesh maze removes.
    pub fn all_handles(&self) -> Vec<i32> {
        self.meshes
            .iter()
            .map(|m| m.handle)
            .chain(self.holder)
            .collect()
    }
}

/// A mesh read back: what the API can tell.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MeshReadback {
    /// x, y, z per vertex relative to the shape's frame, if the API reads meshes (ZeroMQ:
    /// `sim.getShapeMesh`; CoppeliaSim merges duplicate vertices, so these need not be the
    /// vertices given, only the same triangles).
    pub vertices: Option<Vec<f32>>,
    /// Three vertex indices per triangle, with `vertices`.
    pub indices: Option<Vec<i32>>,
    /// Bounding box relative to the shape's frame, min and max corners, if the API reads it.
    pub bounding_box: Option<([f64; 3], [f64; 3])>,
    /// Ambient-diffuse colour, if the API reads it.
    pub colour: Option<[f64; 3]>,
    /// World position and Euler angles of the shape's frame.
    pub pose: ([f64; 3], [f64; 3]),
}

/// What a backend must offer for `apply --draw mesh`, reached with
/// [`super::Backend::meshes`]. ZeroMQ creates meshes with `sim.createMeshShape`; the legacy
/// API, which cannot create shapes, loads them as a CoppeliaSim XML model.
pub trait MeshDrawing {
    /// How the template `handle` looks: its colour and special properties.
    fn look(&mut self, template: i32) -> Result<Look, BackendError>;
    /// The holder under the maze dummy `parent` (named [`HOLDER`]) and what it holds; empty
    /// when the scene has none. `names` are the scene's object names.
    fn find(&mut self, names: &ObjectNames, parent: i32) -> Result<FoundMeshes, BackendError>;
    /// Creates `meshes` (each static, with its look and respondability, named, its frame on
    /// the Floor's) under the holder of `place`, creating the holder first if there is none.
    /// Returns the holder and the new meshes' handles, in order.
    fn create(
        &mut self,
        place: &MeshPlace,
        meshes: &[NewMesh<'_>],
    ) -> Result<(i32, Vec<i32>), BackendError>;
    /// Reads a mesh back.
    fn read(&mut self, handle: i32) -> Result<MeshReadback, BackendError>;
    /// Reads back only a mesh's triangles (or bounding box), what `apply` checks of the
    /// meshes it has just created and dressed; by default all of [`MeshDrawing::read`].
    fn read_shape(&mut self, handle: i32) -> Result<MeshReadback, BackendError> {
        self.read(handle)
    }
}
