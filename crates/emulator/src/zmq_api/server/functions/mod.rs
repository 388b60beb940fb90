//! The functions the emulated server answers, over [`Simulator`]: one [`REGISTRY`] of handlers
//! by name, the [`call`] dispatcher, and the `zmqRemoteApi.info('sim')` map, whose function list
//! is derived from the registry.
//!
//! Handlers live in one unit per family: [`objects`] (finding, copying, removing, parenting),
//! [`poses`] (positions, orientations, poses), [`state`] (simulation state, integer parameters
//! and signals), [`authoring`] (creating, naming and dressing objects, saving the scene) and
//! [`shapes`] (mesh shapes: creating, reading back, merging) and [`models`] (model bases,
//! saving and loading XML models) and [`lua`] (the one Lua program our client sends).
//! Argument orders of both CoppeliaSim generations are accepted where they differ
//! (`sim.setObjectPosition(h, rel, pos)` up to 4.5, `(h, pos, rel)` from 4.6). Objects'
//! special properties and shape parameters live in [`Extras`], beside the protocol-neutral scene.

mod args;
mod authoring;
mod constants;
mod lua;
mod models;
mod objects;
mod poses;
mod shapes;
mod state;

use std::collections::HashMap;

use ciborium::Value;

use crate::sim::{ObjectType, Simulator};
use crate::zmq_api::cbor::{self, int};
use crate::zmq_api::message::Protocol;
use args::Args;
use constants::SIM_CONSTANTS;
use vrep_maze_core::coppelia::{
    SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC, SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE,
    SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};

/// Per-object properties the protocol-neutral scene does not model; kept by the server across
/// calls.
#[derive(Debug, Clone, Default)]
pub(super) struct Extras {
    /// Special-property bits set by `sim.setObjectSpecialProperty`, per handle.
    special: HashMap<i32, i32>,
    /// Shape parameters set by `sim.setObjectInt32Param`, per (handle, parameter).
    shape_params: HashMap<(i32, i32), i32>,
    /// Model properties set by `sim.setModelProperty` (or a loaded model base), per handle.
    model_property: HashMap<i32, i32>,
    /// Lines the simulator logs (its deprecation notes), taken by the server after each call.
    pub(super) notes: Vec<String>,
    /// The deprecation note of `sim.createMeshShape` was logged (4.10 logs it once).
    mesh_shape_noted: bool,
}

impl Extras {
    /// Special-property bits of an object (defaults: everything on for shapes, as CoppeliaSim's
    /// "Add > Primitive shape" with dynamics; nothing for dummies).
    fn special(&self, sim: &Simulator, handle: i32) -> Option<i32> {
        let o = sim.scene.get(handle).ok()?;
        Some(*self.special.get(&handle).unwrap_or(&match o.kind {
            ObjectType::Shape => {
                SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE
            }
            ObjectType::Dummy => 0,
        }))
    }

    /// A shape's integer parameter (static: 0, respondable: 1 by default); `None` for a
    /// parameter we do not model.
    fn shape_param(&self, handle: i32, param: i32) -> Option<i32> {
        let default = match param {
            SHAPEINTPARAM_STATIC => 0,
            SHAPEINTPARAM_RESPONDABLE => 1,
            _ => return None,
        };
        Some(*self.shape_params.get(&(handle, param)).unwrap_or(&default))
    }
}

/// The outcome of one function call.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Outcome {
    /// Return values.
    Ret(Vec<Value>),
    /// An error message (as the Lua error text).
    Err(String),
    /// Protocol 2 only: answer `_*wait*_` first, then these return values on `_*executed*_`.
    WaitThen(Vec<Value>),
}

/// What a handler works on: the scene, the properties the scene does not model, and the
/// protocol generation the server speaks (a few replies differ between them).
struct Ctx<'a> {
    sim: &'a mut Simulator,
    extras: &'a mut Extras,
    protocol: Protocol,
}

/// One function's implementation: return values, or the error text of a failed call.
type Handler = fn(&mut Ctx<'_>, &Args<'_>) -> Result<Outcome, String>;

/// Every function we answer, by full dotted name. The `sim.*` entries, in this order, are what
/// `zmqRemoteApi.info('sim')` advertises.
const REGISTRY: &[(&str, Handler)] = &[
    ("zmqRemoteApi.info", info),
    ("zmqRemoteApi.require", require),
    ("sim.getObject", objects::get_object),
    ("sim.getObjectAlias", objects::get_object_alias),
    ("sim.setObjectAlias", authoring::set_object_alias),
    ("sim.getObjectType", objects::get_object_type),
    ("sim.getObjectFloatParam", objects::get_object_float_param),
    ("sim.copyPasteObjects", objects::copy_paste_objects),
    ("sim.removeObjects", objects::remove_objects),
    ("sim.removeObject", objects::remove_object),
    ("sim.getObjectsInTree", objects::get_objects_in_tree),
    ("sim.getObjectParent", objects::get_object_parent),
    ("sim.setObjectParent", objects::set_object_parent),
    ("sim.setObjectPosition", poses::set_object_position),
    ("sim.getObjectPosition", poses::get_object_position),
    ("sim.setObjectOrientation", poses::set_object_orientation),
    ("sim.getObjectOrientation", poses::get_object_orientation),
    ("sim.setObjectPose", poses::set_object_pose),
    ("sim.getObjectPose", poses::get_object_pose),
    ("sim.getSimulationState", state::get_simulation_state),
    ("sim.getSimulationTime", state::get_simulation_time),
    ("sim.startSimulation", state::start_simulation),
    ("sim.stopSimulation", state::stop_simulation),
    ("sim.getInt32Param", state::get_int32_param),
    ("sim.setInt32Param", state::set_int32_param),
    ("sim.getInt32Signal", state::get_int32_signal),
    ("sim.setInt32Signal", state::set_int32_signal),
    ("sim.clearInt32Signal", state::clear_int32_signal),
    ("sim.getStringSignal", state::get_string_signal),
    ("sim.setStringSignal", state::set_string_signal),
    ("sim.clearStringSignal", state::clear_string_signal),
    (
        "sim.createPrimitiveShape",
        authoring::create_primitive_shape,
    ),
    ("sim.createDummy", authoring::create_dummy),
    ("sim.setShapeColor", authoring::set_shape_color),
    ("sim.getShapeColor", authoring::get_shape_color),
    (
        "sim.setObjectSpecialProperty",
        authoring::set_object_special_property,
    ),
    (
        "sim.getObjectSpecialProperty",
        authoring::get_object_special_property,
    ),
    ("sim.setObjectInt32Param", authoring::set_object_int32_param),
    ("sim.getObjectInt32Param", authoring::get_object_int32_param),
    ("sim.saveScene", authoring::save_scene),
    ("sim.createMeshShape", shapes::create_mesh_shape),
    ("sim.createShape", shapes::create_shape),
    ("sim.getShapeMesh", shapes::get_shape_mesh),
    ("sim.getShapeBB", shapes::get_shape_bb),
    ("sim.groupShapes", shapes::group_shapes),
    ("sim.scaleObject", shapes::scale_object),
    ("sim.setModelProperty", models::set_model_property),
    ("sim.getModelProperty", models::get_model_property),
    ("sim.saveModel", models::save_model),
    ("sim.loadModel", models::load_model),
    ("sim.executeLuaCode", lua::execute_lua_code),
];

/// Calls one function. `func` is the full dotted name (`sim.getObject`); a name the registry
/// lacks is `No such function: <func>`, as CoppeliaSim says it.
pub(super) fn call(
    sim: &mut Simulator,
    extras: &mut Extras,
    protocol: Protocol,
    func: &str,
    args: &[Value],
) -> Outcome {
    let mut ctx = Ctx {
        sim,
        extras,
        protocol,
    };
    call_in(&mut ctx, func, args)
}

/// Calls one function from within another (the calls of a Lua program, [`lua`]).
fn call_in(ctx: &mut Ctx<'_>, func: &str, args: &[Value]) -> Outcome {
    let Some((_, handler)) = REGISTRY.iter().find(|(name, _)| *name == func) else {
        return Outcome::Err(no_such_function(func));
    };
    handler(ctx, &Args::new(func, args)).unwrap_or_else(Outcome::Err)
}

fn no_such_function(func: &str) -> String {
    format!("No such function: {func}")
}

/// A call's return values.
fn ret(values: Vec<Value>) -> Result<Outcome, String> {
    Ok(Outcome::Ret(values))
}

/// The outcome of a call without return values.
fn nothing() -> Result<Outcome, String> {
    ret(vec![])
}

/// The `sim.*` functions we answer (short names, registry order): what
/// `zmqRemoteApi.info('sim')` advertises.
fn sim_functions() -> impl Iterator<Item = &'static str> {
    REGISTRY
        .iter()
        .filter_map(|(name, _)| name.strip_prefix("sim."))
}

/// The `zmqRemoteApi.info('sim')` map: `{fname: {func: {}}, cname: {const: v}}`, from which
/// the official clients build their `sim` object.
fn sim_info() -> Value {
    let mut pairs: Vec<(Value, Value)> = sim_functions()
        .map(|f| {
            (
                Value::Text(f.to_string()),
                cbor::map([("func", Value::Map(vec![]))]),
            )
        })
        .collect();
    pairs.extend(
        SIM_CONSTANTS
            .iter()
            .map(|(c, v)| (Value::Text(c.to_string()), cbor::map([("const", int(*v))]))),
    );
    Value::Map(pairs)
}

/// `zmqRemoteApi.info(module)`: the function and constant names of `sim`, our only module.
fn info(_: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    match a.text(0)? {
        "sim" => ret(vec![sim_info()]),
        other => Err(format!("in {}: no such module '{other}'", a.func)),
    }
}

/// `zmqRemoteApi.require(module)`: loads `sim` (protocol 2 only; protocol-1 servers, 4.3 to
/// 4.5, have no `require` because `sim` is a global there).
fn require(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    if ctx.protocol == Protocol::V1 {
        return Err(no_such_function(a.func));
    }
    match a.text(0)? {
        "sim" | "sim-1" => nothing(),
        other => Err(format!("in {}: module '{other}' not found", a.func)),
    }
}

/// Helpers for the units' tests.
#[cfg(test)]
mod testing {
    use super::*;

    /// Calls `func` over protocol 2 with fresh [`Extras`].
    pub(super) fn run(sim: &mut Simulator, func: &str, args: Vec<Value>) -> Outcome {
        run_on(sim, Protocol::V2, func, args)
    }

    /// Calls `func` over `protocol` with fresh [`Extras`].
    pub(super) fn run_on(
        sim: &mut Simulator,
        protocol: Protocol,
        func: &str,
        args: Vec<Value>,
    ) -> Outcome {
        call(sim, &mut Extras::default(), protocol, func, &args)
    }

    /// The single return value of a successful call.
    pub(super) fn ret1(o: Outcome) -> Value {
        match o {
            Outcome::Ret(mut v) if v.len() == 1 => v.remove(0),
            other => panic!("{other:?}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::testing::run;
    use super::*;
    use crate::sim::Scene;
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    /// Identifiers following `prefix` in `text` and followed by `end`.
    fn names_between(text: &str, prefix: &str, end: char) -> HashSet<String> {
        text.match_indices(prefix)
            .filter(|(i, _)| {
                // `sim.` must start a name, not end one (`xsim.`)
                !text[..*i]
                    .chars()
                    .next_back()
                    .is_some_and(|c| c.is_alphanumeric() || c == '_')
            })
            .filter_map(|(i, _)| {
                let rest = &text[i + prefix.len()..];
                let len = rest
                    .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                rest[len..]
                    .starts_with(end)
                    .then(|| rest[..len].to_string())
            })
            .filter(|n| !n.is_empty())
            .collect()
    }

    #[test]
    fn every_function_our_client_and_the_official_one_call_is_registered() {
        let ours = names_between(
            include_str!("../../../../../client/src/zmq_api/backend.rs"),
            "\"sim.",
            '"',
        );
        let script = include_str!("../../../../../../tests/conformance/zmq_official_client.py");
        let official = names_between(script, "sim.", '(');
        assert!(
            ours.len() >= 20 && official.len() >= 20,
            "{ours:?} {official:?}"
        );
        let registered: HashSet<&str> = sim_functions().collect();
        let missing: Vec<&String> = ours
            .iter()
            .chain(&official)
            .filter(|n| !registered.contains(n.as_str()))
            .collect();
        assert!(missing.is_empty(), "not in the registry: {missing:?}");
        // constants the official client reads (`sim.handle_world`) are advertised too
        let constants: HashSet<&str> = SIM_CONSTANTS.iter().map(|(c, _)| *c).collect();
        let used = names_between(script, "sim.", ' ')
            .into_iter()
            .chain(names_between(script, "sim.", ','))
            .chain(names_between(script, "sim.", ')'))
            .filter(|n| n.contains('_'));
        let unknown: Vec<String> = used.filter(|c| !constants.contains(c.as_str())).collect();
        assert!(unknown.is_empty(), "not in SIM_CONSTANTS: {unknown:?}");
    }

    #[test]
    fn registry_and_advertised_names_are_unique() {
        let mut seen = HashSet::new();
        for (name, _) in REGISTRY {
            assert!(seen.insert(*name), "{name} registered twice");
        }
        let advertised: Vec<&str> = sim_functions().collect();
        assert_eq!(advertised.len(), REGISTRY.len() - 2, "{advertised:?}");
        let mut names = HashSet::new();
        for (c, _) in SIM_CONSTANTS {
            assert!(names.insert(*c), "{c} listed twice");
        }
        for f in advertised {
            assert!(names.insert(f), "{f} is both a function and a constant");
        }
    }

    #[test]
    fn unknown_functions_are_no_such_function() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        assert_eq!(
            run(&mut sim, "sim.nope", vec![]),
            Outcome::Err("No such function: sim.nope".into())
        );
        assert_eq!(
            run(&mut sim, "os.execute", vec![]),
            Outcome::Err("No such function: os.execute".into())
        );
    }

    #[test]
    fn protocol_1_has_no_require_but_has_info() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut x = Extras::default();
        let req = call(
            &mut sim,
            &mut x,
            Protocol::V1,
            "zmqRemoteApi.require",
            &[Value::Text("sim".into())],
        );
        assert_eq!(
            req,
            Outcome::Err("No such function: zmqRemoteApi.require".into())
        );
        assert!(matches!(
            call(
                &mut sim,
                &mut x,
                Protocol::V1,
                "zmqRemoteApi.info",
                &[Value::Text("sim".into())]
            ),
            Outcome::Ret(_)
        ));
    }
}
