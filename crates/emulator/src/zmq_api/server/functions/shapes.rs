//! Mesh shapes: creating one from vertices and indices, reading a shape's mesh and bounding
//! box back (every shape: a created mesh, or the primitive a plane or cuboid is), merging
//! shapes. As CoppeliaSim 4.5.1 (coppeliaSimLib `simInternal.cpp`, tag
//! coppeliasim-v4.5.1-rev4): a new mesh is at the world origin with its vertices as given,
//! duplicate vertices merged; a mesh reads back relative to the shape's frame. 4.10 (protocol
//! 2) differs in two replies: `sim.getShapeBB` gives the box's pose too, and
//! `sim.createMeshShape` logs that it is deprecated (`../shared/spec/real-coppeliasim-4.10.md`
//! "Other API changes that matter").

use ciborium::Value;

use super::{Args, Ctx, Outcome, ret};
use crate::sim::{Mesh, MeshError, NewObject, ObjectType};
use crate::zmq_api::cbor::{float_array, int};
use crate::zmq_api::message::Protocol;

/// What 4.10 logs, once, at the first `sim.createMeshShape` (`../shared/spec/real-coppeliasim-4.10.md`
/// "Other API changes that matter").
const MESH_SHAPE_DEPRECATED: &str =
    "sim.createMeshShape: deprecated, please use sim.createShape instead";

/// `sim.createMeshShape(options, shadingAngle, vertices, indices)`: a grey shape named
/// `Shape` (`Shape0`, ...) at the world origin; bad vertices or indices are the errors
/// CoppeliaSim gives. Over protocol 2 the first call logs the deprecation note.
pub(super) fn create_mesh_shape(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    if ctx.protocol == Protocol::V2 && !ctx.extras.mesh_shape_noted {
        ctx.extras.mesh_shape_noted = true;
        ctx.extras.notes.push(MESH_SHAPE_DEPRECATED.into());
    }
    create_shape(ctx, a)
}

/// `sim.createShape(options, shadingAngle, vertices, indices, normals = nil, ...)`, on both
/// generations (4.5.1 has it too: coppeliaSimLib@coppeliasim-v4.5.1-rev4
/// `luaScriptFunctions.cpp:288`): the shape [`create_mesh_shape`] makes, at the identity
/// pose with its vertices as given (coppeliaSimLib@coppeliasim-v4.10.0-rev0
/// `simInternal.cpp:6304-6362`). There its bounding box is then re-fitted to the mesh
/// (`alignBB("mesh")`: measured on 4.10.0 on 2026-11-27, two flat rectangles 1 x 0.1 get the
/// sizes 0 x 0.1 x 1, the box turned -90 degrees about y); here it stays aligned with the
/// shape's frame, as `sim.createMeshShape`'s. No client of ours reads a created mesh's box.
/// Optional normals and textures are not modelled.
pub(super) fn create_shape(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    a.int(0)?;
    a.get(1)
        .and_then(crate::zmq_api::cbor::number)
        .ok_or_else(|| a.bad(1, "a number"))?;
    let (vertices, indices) = (a.floats(2)?, a.ints(3)?);
    let mesh = Mesh::new(vertices, indices).map_err(|e| match e {
        MeshError::BadVertices => format!("in {}: invalid vertices.", a.func),
        MeshError::BadIndices => format!("in {}: invalid indices.", a.func),
    })?;
    let scene = &mut ctx.sim.scene;
    let h = scene.create(
        "Shape",
        NewObject {
            kind: ObjectType::Shape,
            parent: None,
            position: [0.0; 3],
            orientation: [0.0; 3],
            size: [0.0; 3],
            colour: [204, 204, 204],
        },
    );
    scene.set_mesh(h, mesh).map_err(|_| a.no_object())?;
    ret(vec![int(h.into())])
}

/// The shape `h` of a call, or the error CoppeliaSim gives for a handle that is no shape.
fn shape<'s>(ctx: &'s Ctx<'_>, a: &Args<'_>, h: i32) -> Result<&'s crate::sim::Object, String> {
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    if o.kind != ObjectType::Shape {
        return Err(format!("in {}: object is not a shape.", a.func));
    }
    Ok(o)
}

/// `sim.getShapeMesh(h)`: `(vertices, indices, normals)` relative to the shape's frame, one
/// normal (the face's) per index.
pub(super) fn get_shape_mesh(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let mesh = shape(ctx, a, h)?
        .shape_mesh()
        .ok_or_else(|| format!("in {}: object is not a shape.", a.func))?;
    let v = |k: i32| {
        let k = k as usize * 3;
        nalgebra::Vector3::new(
            f64::from(mesh.vertices[k]),
            f64::from(mesh.vertices[k + 1]),
            f64::from(mesh.vertices[k + 2]),
        )
    };
    let mut normals = Vec::with_capacity(mesh.indices.len() * 3);
    for t in mesh.indices.chunks_exact(3) {
        let n = (v(t[1]) - v(t[0])).cross(&(v(t[2]) - v(t[0])));
        let n = n.try_normalize(0.0).unwrap_or_default();
        for _ in 0..3 {
            normals.extend([n.x, n.y, n.z]);
        }
    }
    let vertices: Vec<f64> = mesh.vertices.iter().map(|&x| f64::from(x)).collect();
    let indices = Value::Array(mesh.indices.iter().map(|&i| int(i.into())).collect());
    ret(vec![float_array(&vertices), indices, float_array(&normals)])
}

/// `sim.getShapeBB(h)`: the size of the shape's bounding box (x, y, z); over protocol 2
/// also the box's pose in the shape's frame (x, y, z, qx, qy, qz, qw: its centre, unrotated
/// here), as 4.10 answers (`../shared/spec/real-coppeliasim-4.10.md` "Other API changes that
/// matter"; coppeliaSimLib@coppeliasim-v4.10.0-rev0 `luaScriptFunctions.cpp:11347-11378`).
pub(super) fn get_shape_bb(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let (min, max) = shape(ctx, a, h)?.bounding_box();
    let size = [0, 1, 2].map(|k| max[k] - min[k]);
    let mut values = vec![float_array(&size)];
    if ctx.protocol == Protocol::V2 {
        let centre = [0, 1, 2].map(|k| (max[k] + min[k]) / 2.0);
        values.push(float_array(&[
            centre[0], centre[1], centre[2], 0.0, 0.0, 0.0, 1.0,
        ]));
    }
    ret(values)
}

/// `sim.scaleObject(h, x, y, z, options = 0)`: the object grows or shrinks along its own
/// axes, its pose stays; returns 1. Measured on the real 4.5.1 (course.ttt's `Floor`, a 10 m
/// plane: `sim.getShapeBB` 10, 10, 0, then `sim.scaleObject(Floor, 4.5, 4.5, 1, 0)` answered
/// 1 and the box read 45, 45, 0 at the same position). A factor that is not a positive
/// number is refused.
pub(super) fn scale_object(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let factor = |i: usize| {
        a.get(i)
            .and_then(crate::zmq_api::cbor::number)
            .filter(|f| f.is_finite() && *f > 0.0)
            .ok_or_else(|| a.bad(i, "a positive number"))
    };
    let factors = [factor(1)?, factor(2)?, factor(3)?];
    ctx.sim.scene.scale(h, factors).map_err(|_| a.no_object())?;
    ret(vec![int(1)])
}

/// `sim.groupShapes(handles, merge = false)`: the shapes become one, the last listed (its
/// handle, name, parent and frame), holding every mesh expressed in its frame; the others
/// are removed. A merged shape and a grouped one read back the same mesh here. Fewer than
/// two shapes is CoppeliaSim's "not enough shapes" error.
pub(super) fn group_shapes(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let handles = a.handles(0)?;
    let mut shapes: Vec<i32> = Vec::new();
    for &h in &handles {
        let is_shape = ctx
            .sim
            .scene
            .get(h)
            .is_ok_and(|o| o.kind == ObjectType::Shape);
        if is_shape && !shapes.contains(&h) {
            shapes.push(h);
        }
    }
    let Some(&kept) = shapes.last().filter(|_| shapes.len() >= 2) else {
        return Err(format!("in {}: not enough shapes.", a.func));
    };
    let scene = &mut ctx.sim.scene;
    let into = scene.world(kept).map_err(|_| a.no_object())?.inverse();
    let (mut vertices, mut indices) = (Vec::new(), Vec::new());
    for &h in &shapes {
        let to_kept = into * scene.world(h).map_err(|_| a.no_object())?;
        let o = scene.get(h).map_err(|_| a.no_object())?;
        let mesh = o.shape_mesh().ok_or_else(|| a.no_object())?;
        let base = (vertices.len() / 3) as i32;
        for p in mesh.vertices.chunks_exact(3) {
            let p =
                to_kept * nalgebra::Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
            vertices.extend([p.x as f32, p.y as f32, p.z as f32]);
        }
        indices.extend(mesh.indices.iter().map(|i| base + i));
    }
    let merged = Mesh::new(vertices, indices).map_err(|e| format!("in {}: {e}.", a.func))?;
    for &h in &shapes[..shapes.len() - 1] {
        scene.remove(h).map_err(|_| a.no_object())?;
    }
    scene.set_mesh(kept, merged).map_err(|_| a.no_object())?;
    ret(vec![int(kept.into())])
}

#[cfg(test)]
mod tests {
    use super::super::testing::{ret1, run, run_on};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use crate::zmq_api::cbor;
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    fn floats(v: &[f64]) -> Value {
        float_array(v)
    }

    fn ints(v: &[i64]) -> Value {
        Value::Array(v.iter().map(|&i| int(i)).collect())
    }

    /// Two 1 m x 0.1 m rectangles side by side, sharing an edge: 8 vertices given.
    fn two_rects() -> (Value, Value) {
        let v = [
            0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.5, 0.1, 0.0, 0.0, 0.1, 0.0, //
            0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.1, 0.0, 0.5, 0.1, 0.0,
        ];
        (floats(&v), ints(&[0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7]))
    }

    #[test]
    fn a_mesh_is_created_at_the_origin_and_reads_back_relative_to_its_frame() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let (v, i) = two_rects();
        let h = ret1(run(
            &mut sim,
            "sim.createMeshShape",
            vec![int(0), Value::Float(0.5), v, i],
        ));
        let h32 = cbor::int32(&h).unwrap();
        assert_eq!(sim.scene.get(h32).unwrap().name, "Shape");
        let Outcome::Ret(bb) = run(&mut sim, "sim.getShapeBB", vec![h.clone()]) else {
            panic!()
        };
        assert_eq!(
            cbor::numbers::<3>(&bb[0]),
            Some([1.0, 0.1, 0.0].map(|x: f64| f64::from(x as f32)))
        );
        // protocol 2: and the box's pose, its centre in the shape's frame
        let pose = cbor::numbers::<7>(&bb[1]).unwrap();
        assert!(
            (pose[0] - 0.5).abs() < 1e-6 && (pose[1] - 0.05).abs() < 1e-6,
            "{pose:?}"
        );
        assert_eq!(pose[3..], [0.0, 0.0, 0.0, 1.0]);
        run(
            &mut sim,
            "sim.setObjectPosition",
            vec![h.clone(), floats(&[3.0, 2.0, 1.0]), int(-1)],
        );
        let Outcome::Ret(mesh) = run(&mut sim, "sim.getShapeMesh", vec![h.clone()]) else {
            panic!()
        };
        // duplicates merged: 6 vertices, 4 triangles, normals up
        assert_eq!(cbor::array(&mesh[0]).unwrap().len(), 18);
        assert_eq!(cbor::array(&mesh[1]).unwrap().len(), 12);
        let normals = cbor::array(&mesh[2]).unwrap();
        assert_eq!(normals.len(), 36);
        assert_eq!(cbor::number(&normals[2]), Some(1.0));
        let xs: Vec<f64> = cbor::array(&mesh[0])
            .unwrap()
            .iter()
            .map(|x| cbor::number(x).unwrap())
            .collect();
        assert!(
            xs.iter().all(|x| *x <= 1.0),
            "relative to the shape, not the world"
        );
    }

    #[test]
    fn the_line_template_reads_back_as_its_plane() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let line = int(sim.scene.resolve("Line").unwrap().into());
        let Outcome::Ret(mesh) = run(&mut sim, "sim.getShapeMesh", vec![line.clone()]) else {
            panic!()
        };
        let v: Vec<f64> = cbor::array(&mesh[0])
            .unwrap()
            .iter()
            .map(|x| cbor::number(x).unwrap())
            .collect();
        assert_eq!(v.len(), 12);
        assert!(v.chunks(3).all(|p| (p[0].abs() - 0.3).abs() < 1e-6
            && (p[1].abs() - 0.05).abs() < 1e-6
            && p[2] == 0.0));
        // protocol 1 (4.5.1): the sizes only
        let bb = ret1(run_on(&mut sim, Protocol::V1, "sim.getShapeBB", vec![line]));
        let bb = cbor::numbers::<3>(&bb).unwrap();
        assert!((bb[0] - 0.6).abs() < 1e-9 && (bb[1] - 0.1).abs() < 1e-9 && bb[2] == 0.0);
    }

    #[test]
    fn a_scaled_floor_grows_along_x_and_y_and_stays_where_it_is() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let floor = int(sim.scene.resolve("Floor").unwrap().into());
        let before = sim
            .scene
            .get(sim.scene.resolve("Floor").unwrap())
            .unwrap()
            .position;
        let scaled = run(
            &mut sim,
            "sim.scaleObject",
            vec![
                floor.clone(),
                floats(&[4.5]),
                Value::Float(4.5),
                Value::Float(1.0),
            ],
        );
        assert!(matches!(scaled, Outcome::Err(_)), "a factor is a number");
        let one = ret1(run(
            &mut sim,
            "sim.scaleObject",
            vec![
                floor.clone(),
                Value::Float(4.5),
                Value::Float(4.5),
                Value::Float(1.0),
                int(0),
            ],
        ));
        assert_eq!(cbor::number(&one), Some(1.0));
        let bb = ret1(run_on(
            &mut sim,
            Protocol::V1,
            "sim.getShapeBB",
            vec![floor],
        ));
        assert_eq!(cbor::numbers::<3>(&bb), Some([45.0, 45.0, 0.0]));
        let h = sim.scene.resolve("Floor").unwrap();
        assert_eq!(sim.scene.get(h).unwrap().position, before);
    }

    #[test]
    fn bad_meshes_and_handles_are_clear_errors() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let maze = int(sim.scene.resolve("Maze").unwrap().into());
        let cases = [
            (
                "sim.createMeshShape",
                vec![
                    int(0),
                    Value::Float(0.0),
                    floats(&[0.0; 9]),
                    ints(&[0, 1, 3]),
                ],
                "invalid indices",
            ),
            (
                "sim.createMeshShape",
                vec![
                    int(0),
                    Value::Float(0.0),
                    floats(&[0.0; 8]),
                    ints(&[0, 1, 1]),
                ],
                "invalid vertices",
            ),
            (
                "sim.createMeshShape",
                vec![
                    int(0),
                    Value::Float(0.0),
                    Value::Text("x".into()),
                    ints(&[0, 1, 2]),
                ],
                "argument 3",
            ),
            ("sim.getShapeMesh", vec![maze.clone()], "not a shape"),
            ("sim.getShapeBB", vec![int(999)], "does not exist"),
            ("sim.groupShapes", vec![ints(&[10])], "not enough shapes"),
        ];
        for (func, args, text) in cases {
            match run(&mut sim, func, args) {
                Outcome::Err(e) => assert!(e.contains(text), "{func}: {e}"),
                other => panic!("{func}: {other:?}"),
            }
        }
    }

    #[test]
    fn create_shape_is_create_mesh_shape_without_the_deprecation_note() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut extras = super::super::Extras::default();
        let mut create = |protocol, func| {
            let (v, i) = two_rects();
            let args = [int(0), Value::Float(0.5), v, i];
            let h = ret1(super::super::call(
                &mut sim,
                &mut extras,
                protocol,
                func,
                &args,
            ));
            (cbor::int32(&h).unwrap(), std::mem::take(&mut extras.notes))
        };
        let (a, notes) = create(Protocol::V2, "sim.createShape");
        assert!(notes.is_empty());
        let (_, notes) = create(Protocol::V1, "sim.createMeshShape");
        assert!(notes.is_empty(), "4.5.1 logs nothing");
        let (_, notes) = create(Protocol::V2, "sim.createMeshShape");
        assert_eq!(notes, [MESH_SHAPE_DEPRECATED]);
        let (b, notes) = create(Protocol::V2, "sim.createMeshShape");
        assert!(notes.is_empty(), "logged once");
        let mesh = |h: i32| {
            sim.scene
                .get(h)
                .unwrap()
                .shape_mesh()
                .map(|m| m.into_owned())
        };
        assert_eq!(mesh(a), mesh(b));
        assert_eq!(sim.scene.get(a).unwrap().position, [0.0; 3]);
    }

    #[test]
    fn merging_keeps_the_last_shape_with_every_triangle() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let (v, i) = two_rects();
        let a = ret1(run(
            &mut sim,
            "sim.createMeshShape",
            vec![int(0), Value::Float(0.0), v, i],
        ));
        let b = int(sim.scene.resolve("Start").unwrap().into());
        let kept = ret1(run(
            &mut sim,
            "sim.groupShapes",
            vec![Value::Array(vec![a.clone(), b.clone()]), Value::Bool(true)],
        ));
        assert_eq!(kept, b);
        assert!(sim.scene.get(cbor::int32(&a).unwrap()).is_err());
        let Outcome::Ret(mesh) = run(&mut sim, "sim.getShapeMesh", vec![b]) else {
            panic!()
        };
        assert_eq!(cbor::array(&mesh[1]).unwrap().len(), 12 + 6);
    }
}
