//! A maze as a complete CoppeliaSim XML scene: the `Floor` (a plane of the layout's floor
//! size at the world origin, the layout's frame), the `Maze` dummy with the meshes of
//! [`super::simmodel`], the blue `Start` and red `End` markers (planes of one cell at their
//! poses), and for a line maze the green `Line` template where the first segment is (under
//! a mesh), so the scene is also a course scene `apply` draws into.

use super::simmodel::{MAZE_DUMMY, SPECIAL, maze_objects};
use crate::coppelia::xml::{
    Body, Document, FileKind, Mesh, Primitive, Shape, XmlObject, yaw_quaternion,
};
use crate::layout::{Layout, Pose};
use crate::mesh::MeshMaze;

/// Floor (0), Maze (1), MazeMeshes (2), the meshes, then Start, End and the Line template.
pub(super) fn document(layout: &Layout, maze: &MeshMaze) -> Document {
    let [fx, fy] = layout.floor.size;
    let floor_pose = Pose {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        yaw: 0.0,
    };
    let mut objects = vec![
        plane(0, "Floor", floor_pose, [fx, fy], [1.0, 1.0, 1.0]),
        XmlObject::dummy(1, None, "Maze", MAZE_DUMMY.0, MAZE_DUMMY.1),
    ];
    objects.extend(maze_objects(maze, 1, 2));
    let next = objects.len() as i32;
    let cell = layout.grid.cell_size;
    objects.push(plane(
        next,
        "Start",
        maze.start,
        [cell, cell],
        [0.0, 0.0, 1.0],
    ));
    objects.push(plane(
        next + 1,
        "End",
        maze.end,
        [cell, cell],
        [1.0, 0.0, 0.0],
    ));
    if let Some(pose) = maze.template {
        let size = [layout.line.length, layout.line.width];
        objects.push(plane(next + 2, "Line", pose, size, [0.0, 1.0, 0.0]));
    }
    Document {
        kind: FileKind::Scene,
        objects,
    }
}

/// A parentless plane of `size` centred on `pose`, as CoppeliaSim makes planes: static, not
/// respondable, collidable, measurable, detectable and renderable.
fn plane(handle: i32, alias: &str, pose: Pose, [sx, sy]: [f64; 2], colour: [f32; 3]) -> XmlObject {
    let (hx, hy) = ((sx / 2.0) as f32, (sy / 2.0) as f32);
    let mesh = Mesh {
        vertices: vec![
            [-hx, -hy, 0.0],
            [hx, -hy, 0.0],
            [hx, hy, 0.0],
            [-hx, hy, 0.0],
        ],
        indices: vec![0, 1, 2, 0, 2, 3],
    };
    XmlObject {
        handle,
        parent: None,
        alias: alias.to_string(),
        position: [pose.x, pose.y, pose.z],
        quaternion: yaw_quaternion(pose.yaw),
        model_base: false,
        special: SPECIAL,
        body: Body::Shape(Shape {
            mesh,
            colour,
            primitive: Primitive::Plane([sx, sy, 0.0001]),
            is_static: true,
            respondable: false,
        }),
    }
}
