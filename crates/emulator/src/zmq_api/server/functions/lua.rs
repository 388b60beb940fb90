//! `sim.executeLuaCode(code)`: a real CoppeliaSim (4.5.1 and 4.10.0 alike) runs any Lua
//! program and answers `(true, value)`, or `(false, message)` when the program fails, as
//! measured: `return 1+1` answered `(true, 2)`, `error("boom")` `(false, '[string
//! "error("boom")"]:1: boom')`, `return sim.getShapeMesh(999999)` `(false, '1: in
//! sim.getShapeMesh: object does not exist.')` (`docs/measurements.md`, "Meshes read back in
//! one request"). The emulator runs no Lua: it answers the one program our client sends
//! ([`vrep_maze_core::coppelia::lua`]), and any other with a failure that says so.

use ciborium::Value;

use super::args::Args;
use super::{Ctx, Outcome, ret};
use vrep_maze_core::coppelia::lua;

/// `sim.executeLuaCode(code)`.
pub(super) fn execute_lua_code(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let code = a.text(0)?;
    let Some(handles) = lua::parse_read_meshes(code) else {
        return failed("vrep-maze serve runs no Lua: it answers only vrep-maze's mesh read-back");
    };
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

/// The answer of a program that failed with `message`.
fn failed(message: &str) -> Result<Outcome, String> {
    ret(vec![Value::Bool(false), Value::Text(message.into())])
}

#[cfg(test)]
mod tests {
    use super::super::testing::{ret1, run};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use crate::zmq_api::cbor::{self, float_array, int};
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
}
