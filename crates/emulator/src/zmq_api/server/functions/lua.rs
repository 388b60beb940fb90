//! `sim.executeLuaCode(code)`: a real CoppeliaSim (4.5.1 and 4.10.0 alike) runs any Lua
//! program and answers `(true, value)`, or `(false, message)` when the program fails, as
//! measured: `return 1+1` answered `(true, 2)`, `error("boom")` `(false, '[string
//! "error("boom")"]:1: boom')`, `return sim.getShapeMesh(999999)` `(false, '1: in
//! sim.getShapeMesh: object does not exist.')` (`docs/measurements.md`, "Meshes read back in
//! one request"). The emulator runs no Lua: it answers the programs our client sends
//! ([`vrep_maze_core::coppelia::lua`]: reading meshes back, creating a batch of meshes;
//! [`calls`]: several calls in one request), the last two by making the calls the program
//! makes, and any other with a failure that says so.

use ciborium::Value;

use super::args::Args;
use super::{Ctx, Outcome, call_in, ret};
use crate::zmq_api::cbor::{self, float_array, int};
use vrep_maze_core::coppelia::lua::{self, CreateMeshes, LuaMesh, create::SHADING_ANGLE};
use vrep_maze_core::coppelia::{
    COLORCOMPONENT_AMBIENT_DIFFUSE, HANDLE_WORLD, OBJINTPARAM_VISIBILITY_LAYER,
    SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC,
};
use vrep_maze_wire::zmq_api::calls;

/// `sim.executeLuaCode(code)`.
pub(super) fn execute_lua_code(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let code = a.text(0)?;
    if let Some(handles) = lua::parse_read_meshes(code) {
        return read_meshes(ctx, handles);
    }
    if let Some(handles) = lua::parse_read_dressed(code) {
        return read_dressed(ctx, handles);
    }
    if let Some(batch) = lua::parse_create_meshes(code) {
        return create_meshes(ctx, &batch);
    }
    if let Some(each) = calls::parse_calls(code) {
        return make_calls(ctx, each);
    }
    failed("vrep-maze serve runs no Lua: it answers only vrep-maze's own mesh programs")
}

/// [`lua::read_meshes_code`]: every mesh packed as `sim.getShapeMesh` reads it.
fn read_meshes(ctx: &mut Ctx<'_>, handles: Vec<i32>) -> Result<Outcome, String> {
    let mut packed = Vec::with_capacity(handles.len() * 2);
    for h in handles {
        let Ok(object) = ctx.sim.scene.get(h) else {
            return failed("1: in sim.getShapeMesh: object does not exist.");
        };
        let Some(mesh) = object.shape_mesh() else {
            return failed("1: in sim.getShapeMesh: object is not a shape.");
        };
        packed.push(Value::Bytes(lua::pack_floats(&mesh.vertices)));
        packed.push(Value::Bytes(lua::pack_int32s(&mesh.indices)));
    }
    ret(vec![Value::Bool(true), Value::Array(packed)])
}

/// [`lua::read_dressed_code`]: every mesh as [`read_meshes`] packs it, then its world pose,
/// colour and visibility layer, each as the call the program makes answers it.
fn read_dressed(ctx: &mut Ctx<'_>, handles: Vec<i32>) -> Result<Outcome, String> {
    let mut out = Vec::with_capacity(handles.len() * lua::DRESSED_ENTRIES);
    for h in handles {
        match read_meshes(ctx, vec![h])? {
            Outcome::Ret(values) if values.first() == Some(&Value::Bool(true)) => {
                if let Some(Value::Array(triangles)) = values.into_iter().nth(1) {
                    out.extend(triangles);
                }
            }
            failure => return Ok(failure),
        }
        let hv = int(h.into());
        let calls = [
            (
                "sim.getObjectPose",
                vec![hv.clone(), int(HANDLE_WORLD.into())],
                0,
            ),
            (
                "sim.getShapeColor",
                vec![
                    hv.clone(),
                    Value::Text(String::new()),
                    int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
                ],
                1,
            ),
            (
                "sim.getObjectInt32Param",
                vec![hv, int(OBJINTPARAM_VISIBILITY_LAYER.into())],
                0,
            ),
        ];
        for (func, args, value) in calls {
            match succeeded(call_in(ctx, func, &args), func) {
                Ok(values) => out.push(values.into_iter().nth(value).unwrap_or(Value::Null)),
                Err(e) => return failed(&format!("1: {e}")),
            }
        }
    }
    ret(vec![Value::Bool(true), Value::Array(out)])
}

/// [`calls::calls_code`]: each call made in turn, its failure answered as `pcall` gives a
/// C function's error inside a program (`-1: in sim.getObjectPose: object does not exist.`
/// on both real builds, `docs/measurements.md` "Calls made in one request").
fn make_calls(ctx: &mut Ctx<'_>, each: Vec<(String, Vec<Value>)>) -> Result<Outcome, String> {
    let outcomes = each
        .into_iter()
        .map(|(func, args)| match call_in(ctx, &func, &args) {
            Outcome::Ret(values) | Outcome::WaitThen(values) => Ok(values),
            Outcome::Err(e) if e == calls::no_such_function(&func) => Err(e),
            Outcome::Err(e) => Err(format!("-1: {e}")),
        })
        .collect();
    ret(calls::answer(outcomes))
}

/// [`lua::create_meshes_code`]: each mesh made and dressed by the calls the program makes;
/// on a failure, what it made is removed and the failure answered.
fn create_meshes(ctx: &mut Ctx<'_>, batch: &CreateMeshes<'_>) -> Result<Outcome, String> {
    let mut made = Vec::with_capacity(batch.meshes.len());
    for mesh in &batch.meshes {
        if let Err(e) = create_mesh(ctx, batch, mesh, &mut made) {
            if !made.is_empty() {
                let list = Value::Array(made.iter().map(|&h: &i32| int(h.into())).collect());
                call_in(ctx, "sim.removeObjects", &[list]);
            }
            return failed(&e);
        }
    }
    let handles = made.into_iter().map(|h| int(h.into())).collect();
    ret(vec![Value::Bool(true), Value::Array(handles)])
}

/// One mesh of a batch, its handle pushed to `made` as soon as it exists.
fn create_mesh(
    ctx: &mut Ctx<'_>,
    batch: &CreateMeshes<'_>,
    mesh: &LuaMesh<'_>,
    made: &mut Vec<i32>,
) -> Result<(), String> {
    let (create, pose) = if batch.since_4_6 {
        ("sim.createShape", [1, 2])
    } else {
        ("sim.createMeshShape", [2, 1])
    };
    let vertices: Vec<f64> = mesh.vertices.iter().map(|&v| f64::from(v)).collect();
    let indices = mesh.indices.iter().map(|&i| int(i.into())).collect();
    let args = [
        int(0),
        Value::Float(SHADING_ANGLE),
        float_array(&vertices),
        Value::Array(indices),
    ];
    let values = succeeded(call_in(ctx, create, &args), create)?;
    let h = values
        .first()
        .and_then(cbor::int32)
        .ok_or_else(|| format!("in {create}: no handle"))?;
    made.push(h);
    let hv = int(h.into());
    let mut calls = vec![
        (
            "sim.setShapeColor",
            vec![
                hv.clone(),
                Value::Text(String::new()),
                int(COLORCOMPONENT_AMBIENT_DIFFUSE.into()),
                float_array(&mesh.colour),
            ],
        ),
        (
            "sim.setObjectSpecialProperty",
            vec![hv.clone(), int(mesh.special.into())],
        ),
        (
            "sim.setObjectInt32Param",
            vec![hv.clone(), int(SHAPEINTPARAM_STATIC.into()), int(1)],
        ),
        (
            "sim.setObjectInt32Param",
            vec![
                hv.clone(),
                int(SHAPEINTPARAM_RESPONDABLE.into()),
                int(mesh.respondable.into()),
            ],
        ),
        (
            "sim.setObjectAlias",
            vec![hv.clone(), Value::Text(mesh.name.to_string())],
        ),
    ];
    if let Some(floor) = batch.floor {
        let mut args = vec![hv.clone(), Value::Null, Value::Null];
        args[pose[0]] = float_array(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        args[pose[1]] = int(floor.into());
        calls.push(("sim.setObjectPose", args));
    }
    calls.push((
        "sim.setObjectParent",
        vec![hv, int(batch.holder.into()), Value::Bool(true)],
    ));
    for (func, args) in calls {
        succeeded(call_in(ctx, func, &args), func)?;
    }
    Ok(())
}

/// A call's return values, or its failure as the program reports it.
fn succeeded(outcome: Outcome, func: &str) -> Result<Vec<Value>, String> {
    match outcome {
        Outcome::Ret(values) | Outcome::WaitThen(values) => Ok(values),
        Outcome::Err(e) => Err(format!("in {func}: {e}")),
    }
}

/// The answer of a program that failed with `message`.
fn failed(message: &str) -> Result<Outcome, String> {
    ret(vec![Value::Bool(false), Value::Text(message.into())])
}

#[cfg(test)]
mod tests {
    use std::borrow::Cow;

    use super::super::testing::{ret1, run};
    use super::super::{Extras, call};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use crate::zmq_api::message::Protocol;
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    fn execute(sim: &mut Simulator, code: String) -> Vec<Value> {
        match run(sim, "sim.executeLuaCode", vec![Value::Text(code)]) {
            Outcome::Ret(values) => values,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn our_program_answers_every_mesh_packed_as_get_shape_mesh_reads_it() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let vertices = [0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 1.5, -0.25, 0.0];
        let made = ret1(run(
            &mut sim,
            "sim.createMeshShape",
            vec![
                int(0),
                Value::Float(0.5),
                float_array(&vertices),
                Value::Array(vec![int(0), int(1), int(2)]),
            ],
        ));
        let mesh = cbor::int32(&made).unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        let answer = execute(&mut sim, lua::read_meshes_code(&[mesh, line]));
        assert_eq!(answer[0], Value::Bool(true));
        let Value::Array(packed) = &answer[1] else {
            panic!("{answer:?}")
        };
        assert_eq!(packed.len(), 4);
        let Value::Bytes(v) = &packed[0] else {
            panic!()
        };
        assert_eq!(lua::unpack_floats(v).unwrap(), vertices.map(|x| x as f32));
        let Value::Bytes(i) = &packed[1] else {
            panic!()
        };
        assert_eq!(lua::unpack_int32s(i).unwrap(), [0, 1, 2]);
        // the template, a primitive plane, reads back as the mesh its size makes
        let Value::Bytes(plane) = &packed[3] else {
            panic!()
        };
        assert_eq!(lua::unpack_int32s(plane).unwrap().len(), 6);
    }

    #[test]
    fn other_programs_and_bad_handles_fail_as_lua_does() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let maze = sim.scene.resolve("Maze").unwrap();
        for (code, says) in [
            ("return 1+1".to_string(), "runs no Lua"),
            (lua::read_meshes_code(&[999_999]), "object does not exist"),
            (lua::read_meshes_code(&[maze]), "not a shape"),
        ] {
            let answer = execute(&mut sim, code);
            assert_eq!(answer[0], Value::Bool(false));
            let text = cbor::text(&answer[1]).unwrap();
            assert!(text.contains(says), "{text}");
        }
    }

    /// A batch of two meshes under a new holder, the floor's frame not the world's.
    fn batch(sim: &mut Simulator, since_4_6: bool) -> CreateMeshes<'static> {
        let holder = cbor::int32(&ret1(run(sim, "sim.createDummy", vec![Value::Float(0.01)])));
        let floor = sim.scene.resolve("Floor").unwrap();
        let mesh = |name: &str, z: f32, respondable| LuaMesh {
            name: Cow::Owned(name.into()),
            vertices: Cow::Owned(vec![0.0, 0.0, z, 1.5, 0.0, z, 1.5, -0.25, z, 0.0, -0.25, z]),
            indices: Cow::Owned(vec![0, 1, 2, 0, 2, 3]),
            colour: [0.1, 0.8, 0.2],
            special: 176,
            respondable,
        };
        CreateMeshes {
            since_4_6,
            holder: holder.unwrap(),
            floor: Some(floor),
            meshes: vec![
                mesh("MazeMesh_l_1", 0.001, false),
                mesh("MazeMesh_w_2", 0.1, true),
            ],
        }
    }

    /// What the remote API reads of object `h`: alias, parent, pose, mesh, colour, special
    /// properties, static and respondable.
    fn seen(sim: &mut Simulator, extras: &mut Extras, h: i32) -> Vec<Outcome> {
        let hv = || int(h.into());
        let calls: [(&str, Vec<Value>); 8] = [
            ("sim.getObjectAlias", vec![hv()]),
            ("sim.getObjectParent", vec![hv()]),
            ("sim.getObjectPose", vec![hv(), int(-1)]),
            ("sim.getShapeMesh", vec![hv()]),
            (
                "sim.getShapeColor",
                vec![hv(), Value::Text(String::new()), int(0)],
            ),
            ("sim.getObjectSpecialProperty", vec![hv()]),
            (
                "sim.getObjectInt32Param",
                vec![hv(), int(SHAPEINTPARAM_STATIC.into())],
            ),
            (
                "sim.getObjectInt32Param",
                vec![hv(), int(SHAPEINTPARAM_RESPONDABLE.into())],
            ),
        ];
        calls
            .into_iter()
            .map(|(f, a)| call(sim, extras, Protocol::V2, f, &a))
            .collect()
    }

    #[test]
    fn a_batch_made_by_our_program_is_what_the_separate_calls_make() {
        for since_4_6 in [true, false] {
            let protocol = if since_4_6 {
                Protocol::V2
            } else {
                Protocol::V1
            };
            let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
            // the floor away from the world frame, so the pose call counts
            let floor = sim.scene.resolve("Floor").unwrap();
            let pose = float_array(&[0.5, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
            let args = if since_4_6 {
                vec![int(floor.into()), pose, int(-1)]
            } else {
                vec![int(floor.into()), int(-1), pose]
            };
            let mut extras = Extras::default();
            call(&mut sim, &mut extras, protocol, "sim.setObjectPose", &args);
            let mut by_calls = sim.clone();
            let b = batch(&mut sim, since_4_6);
            assert_eq!(batch(&mut by_calls, since_4_6).holder, b.holder);
            let code = Value::Text(lua::create_meshes_code(&b));
            let answer = call(
                &mut sim,
                &mut extras,
                protocol,
                "sim.executeLuaCode",
                &[code],
            );
            let Outcome::Ret(values) = answer else {
                panic!("{answer:?}")
            };
            assert_eq!(values[0], Value::Bool(true), "{values:?}");
            let made = cbor::handles(&values[1]).unwrap();
            assert_eq!(made.len(), 2);
            let mut calls_extras = extras.clone();
            let mut separate = vec![];
            for m in &b.meshes {
                create_mesh(
                    &mut Ctx {
                        sim: &mut by_calls,
                        extras: &mut calls_extras,
                        protocol,
                    },
                    &b,
                    m,
                    &mut separate,
                )
                .unwrap();
            }
            assert_eq!(made, separate);
            for &h in &made {
                let program = seen(&mut sim, &mut extras, h);
                assert_eq!(program, seen(&mut by_calls, &mut calls_extras, h));
                // dressed: under the holder, in the floor's frame, respondable as asked
                assert_eq!(program[1], Outcome::Ret(vec![int(b.holder.into())]));
            }
            let position = |o: &Outcome| match o {
                Outcome::Ret(v) => cbor::numbers::<7>(&v[0]).unwrap()[..3].to_vec(),
                other => panic!("{other:?}"),
            };
            assert_eq!(
                position(&seen(&mut sim, &mut extras, made[0])[2]),
                [0.5, -1.0, 0.0]
            );
            assert_eq!(
                seen(&mut sim, &mut extras, made[1])[7],
                Outcome::Ret(vec![int(1)])
            );
        }
    }

    #[test]
    fn a_batch_that_fails_midway_leaves_nothing_behind() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut b = batch(&mut sim, true);
        b.holder = 999_999;
        let before = sim.scene.len();
        let answer = execute(&mut sim, lua::create_meshes_code(&b));
        assert_eq!(answer[0], Value::Bool(false));
        let text = cbor::text(&answer[1]).unwrap();
        assert!(text.contains("sim.setObjectParent"), "{text}");
        assert_eq!(sim.scene.len(), before);
    }
}
