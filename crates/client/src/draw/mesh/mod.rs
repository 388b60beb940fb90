//! Drawing a maze as a few mesh shapes instead of one copy of a template per line
//! (`apply --draw mesh`): [`vrep_maze_core::mesh`] computes the meshes from a layout, [`MeshDrawing`] is
//! the capability a backend offers to create, find and read them.
//!
//! Where the meshes live: under the maze dummy (`Maze`), a dummy named [`HOLDER`] holds
//! them, its frame on the Floor's; each mesh's frame is on the Floor's too, so its vertices
//! are Floor coordinates ([`vrep_maze_core::mesh`]). One path lookup (`Maze/MazeMeshes`) tells whether a
//! scene holds a mesh maze, so a copies-mode draw or a clear finds and removes one without
//! reading the name of every copy. Each mesh's name carries a fingerprint of what it holds
//! ([`mesh_name`]): a re-apply keeps the meshes whose fingerprint it would draw.

pub mod compare;
pub mod draw;

pub use draw::{apply, found, leftovers, verify, verify_read_only};
pub use vrep_maze_core::mesh::{
    HOLDER, MAX_TRIANGLES, MESH_PREFIX, MazeMesh, MeshKind, MeshMaze, Piece, mesh_name,
    parse_mesh_name,
};

use super::error::BackendError;
use super::names::ObjectNames;

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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshPlace {
    /// The maze dummy.
    pub parent: i32,
    /// The holder, if the scene has one.
    pub holder: Option<i32>,
    /// The floor.
    pub floor: i32,
    /// The floor's world pose (position, Euler angles) as this run's survey read it, if it
    /// did: a backend that needs it (the legacy API's model) is spared reading it again.
    pub floor_pose: Option<([f64; 3], [f64; 3])>,
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
    /// The dummy named [`HOLDER`] under the maze dummy, if the scene has one.
    pub holder: Option<i32>,
    /// The meshes of ours under the holder: named by [`parse_mesh_name`] (as a backend
    /// finds them, everything under it, until [`FoundMeshes::sorted`]).
    pub meshes: Vec<FoundMesh>,
    /// The user's objects under the holder: anything not named as a mesh of ours
    /// ([`FoundMeshes::sorted`]). Never removed; while there are any, the holder is the
    /// user's too ([`FoundMeshes::holder_is_ours`]).
    pub users: Vec<FoundMesh>,
    /// Objects at the scene root named like a mesh of ours ([`parse_mesh_name`]): moved out
    /// of the holder by the user, so theirs now. Never removed, never kept; reported.
    pub elsewhere: Vec<String>,
}

impl FoundMeshes {
    /// Sorts what a backend found under the holder: a mesh of ours is named by
    /// [`parse_mesh_name`] (a fingerprint no one types by chance), anything else (a cuboid
    /// put there by hand) is the user's.
    pub fn sorted(self) -> FoundMeshes {
        let (meshes, mut users): (Vec<FoundMesh>, Vec<FoundMesh>) = self
            .meshes
            .into_iter()
            .partition(|m| parse_mesh_name(&m.name).is_some());
        users.extend(self.users);
        FoundMeshes {
            holder: self.holder,
            meshes,
            users,
            elsewhere: self.elsewhere,
        }
    }

    /// `true` if the scene has a holder and it holds nothing but meshes of ours: a holder
    /// holding the user's objects (or the user's own dummy named [`HOLDER`]) is left with
    /// them.
    pub fn holder_is_ours(&self) -> bool {
        self.holder.is_some() && self.users.is_empty()
    }

    /// `true` if the scene holds a mesh maze of ours: a mesh, or a holder of ours.
    pub fn is_mesh_maze(&self) -> bool {
        !self.meshes.is_empty() || self.holder_is_ours()
    }

    /// What removing a mesh maze removes: our meshes, then the holder if it is ours.
    pub fn ours(&self) -> Vec<(i32, String)> {
        self.meshes
            .iter()
            .map(|m| (m.handle, m.name.clone()))
            .chain(
                self.holder
                    .filter(|_| self.holder_is_ours())
                    .map(|h| (h, HOLDER.to_string())),
            )
            .collect()
    }

    /// One warning per object named like a mesh of ours outside the holder
    /// ([`FoundMeshes::elsewhere`]): left alone, and how to have it drawn again.
    pub fn elsewhere_warnings(&self, names: &ObjectNames) -> Vec<String> {
        self.elsewhere
            .iter()
            .map(|name| {
                format!(
                    "`{name}` at the scene root is named like a mesh of the maze but is not under `{}/{HOLDER}`: left alone (remove it if it is a leftover)",
                    names.parent
                )
            })
            .collect()
    }

    /// The names of what is left alone under the maze dummy: the holder, when it is the
    /// user's, and the user's objects under it.
    pub fn left_alone(&self) -> Vec<String> {
        let holder = (self.holder.is_some() && !self.holder_is_ours()).then(|| HOLDER.to_string());
        holder
            .into_iter()
            .chain(self.users.iter().map(|m| m.name.clone()))
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
    /// Visibility layer bits (0: hidden), if the API reads them (ZeroMQ).
    pub layer: Option<i32>,
}

/// What a backend must offer for `apply --draw mesh`, reached with
/// `Backend::meshes`. ZeroMQ creates meshes with `sim.createMeshShape`; the legacy
/// API, which cannot create shapes, loads them as a CoppeliaSim XML model.
pub trait MeshDrawing {
    /// How the template `handle` looks: its colour and special properties.
    fn look(&mut self, template: i32) -> Result<Look, BackendError>;
    /// The holder under the maze dummy `parent` (named [`HOLDER`]) and what it holds; empty
    /// when the scene has none. `names` are the scene's object names; `surveyed` is the
    /// holder a survey just found among `parent`'s children, if it did.
    fn find(
        &mut self,
        names: &ObjectNames,
        parent: i32,
        surveyed: Option<i32>,
    ) -> Result<FoundMeshes, BackendError>;
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
    /// Reads the meshes `handles` back (as [`MeshDrawing::read`]), in order; a backend that
    /// can reads them whole in one request (ZeroMQ: triangles, pose, colour and layer).
    fn read_all(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        handles.iter().map(|&h| self.read(h)).collect()
    }
    /// Reads back the triangles of the meshes `handles` (as [`MeshDrawing::read_shape`]), in
    /// order; a backend that can reads them in one request.
    fn read_shapes(&mut self, handles: &[i32]) -> Result<Vec<MeshReadback>, BackendError> {
        handles.iter().map(|&h| self.read_shape(h)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn under(handle: i32, name: &str) -> FoundMesh {
        FoundMesh {
            handle,
            name: name.into(),
            parent: Some(9),
        }
    }

    #[test]
    fn only_our_mesh_names_are_ours_and_a_holder_with_the_users_objects_is_theirs() {
        let ours = mesh_name(MeshKind::Lines, 0x0123_4567_89ab_cdef);
        let found = |meshes: Vec<FoundMesh>| {
            FoundMeshes {
                holder: Some(9),
                meshes,
                users: Vec::new(),
                elsewhere: Vec::new(),
            }
            .sorted()
        };
        let mixed = found(vec![under(10, &ours), under(11, "Cuboid")]);
        assert_eq!(mixed.meshes, vec![under(10, &ours)]);
        assert!(!mixed.holder_is_ours() && mixed.is_mesh_maze());
        assert_eq!(mixed.ours(), vec![(10, ours.clone())]);
        assert_eq!(
            mixed.left_alone(),
            vec![HOLDER.to_string(), "Cuboid".into()]
        );
        let users = found(vec![under(11, "Cuboid")]);
        assert!(!users.is_mesh_maze() && users.ours().is_empty());
        let mesh_maze = found(vec![under(10, &ours)]);
        assert_eq!(
            mesh_maze.ours(),
            vec![(10, ours.clone()), (9, HOLDER.to_string())]
        );
        assert!(mesh_maze.left_alone().is_empty());
        // an empty holder is ours (an interrupted mesh draw); no holder is no mesh maze
        assert!(found(vec![]).is_mesh_maze());
        assert!(!FoundMeshes::default().is_mesh_maze());
    }
}
