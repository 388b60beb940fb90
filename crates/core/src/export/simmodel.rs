//! A maze as a CoppeliaSim XML model: the `Maze` dummy (the model base, at the world origin)
//! holding the `MazeMeshes` dummy and under it the meshes, as `apply --draw mesh` draws them
//! (each mesh's frame on the parent's, its vertices in the layout's frame, its name carrying
//! its fingerprint). Lines: the `Line` template's green, not respondable; walls and posts:
//! dark grey, respondable; all static, collidable, measurable, detectable and renderable.

use crate::coppelia::xml::{Document, FileKind, Mesh, XmlObject};
use crate::coppelia::{
    SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};
use crate::mesh::{HOLDER, MazeMesh, MeshKind, MeshMaze};

/// The special properties of every mesh (those of the course scene's `Line`).
pub(super) const SPECIAL: i32 =
    SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE;
/// The `Maze` dummy's size and colour in the course scene.
pub(super) const MAZE_DUMMY: (f64, [f32; 3]) = (0.05, [1.0, 0.8, 0.55]);
/// The colour of line meshes (the course scene's `Line`).
const LINE_GREEN: [f32; 3] = [0.0, 1.0, 0.0];
/// The colour of wall and post meshes (the emulator's `Wall` template, 77/255 grey).
const WALL_GREY: [f32; 3] = [0.302, 0.302, 0.302];

/// The model: `Maze` (handle 0, the base), `MazeMeshes` (1), the meshes (2, 3, ...).
pub(super) fn document(maze: &MeshMaze) -> Document {
    let mut base = XmlObject::dummy(0, None, "Maze", MAZE_DUMMY.0, MAZE_DUMMY.1);
    base.model_base = true;
    let mut objects = vec![base];
    objects.extend(maze_objects(maze, 0, 1));
    Document {
        kind: FileKind::Model,
        objects,
    }
}

/// The holder dummy (handle `first`, under `parent`) and the meshes under it.
pub(super) fn maze_objects(maze: &MeshMaze, parent: i32, first: i32) -> Vec<XmlObject> {
    let mut out = vec![XmlObject::dummy(
        first,
        Some(parent),
        HOLDER,
        0.01,
        MAZE_DUMMY.1,
    )];
    for (handle, m) in (first + 1..).zip(&maze.meshes) {
        out.push(mesh_object(handle, first, m));
    }
    out
}

fn mesh_object(handle: i32, parent: i32, m: &MazeMesh) -> XmlObject {
    let colour = match m.kind {
        MeshKind::Lines => LINE_GREEN,
        MeshKind::Walls | MeshKind::Posts => WALL_GREY,
    };
    let mesh = Mesh::from_flat(&m.vertices, &m.indices)
        .expect("the mesh geometry makes triples and indices in range");
    XmlObject::static_mesh(
        handle,
        Some(parent),
        &m.name(),
        mesh,
        (colour, SPECIAL),
        m.kind.respondable(),
    )
}
