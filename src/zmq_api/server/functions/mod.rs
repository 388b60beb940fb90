//! The `sim.*` functions an emulated ZeroMQ remote API server answers, over [`Simulator`].
//!
//! Argument orders of both CoppeliaSim generations are accepted where they differ
//! (`sim.setObjectPosition(h, rel, pos)` up to 4.5, `(h, pos, rel)` from 4.6). Objects'
//! special properties and shape parameters live in [`Extras`], beside the protocol-neutral scene.

use std::collections::HashMap;

use ciborium::Value;
use nalgebra::{Quaternion, UnitQuaternion};

use crate::coppelia::frame::{euler_from_rotation, rotation_from_euler};
use crate::coppelia::{
    HANDLE_ALL, HANDLE_PARENT, HANDLE_SCENE, HANDLE_WORLD, INTPARAM_IDLE_FPS,
    INTPARAM_PROGRAM_VERSION, SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC, SPECIAL_COLLIDABLE,
    SPECIAL_DETECTABLE, SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
};
use crate::sim::{NewObject, ObjectType, SimState, Simulator};
use crate::zmq_api::cbor::{self, float_array, int};
use crate::zmq_api::message::Protocol;

/// The program version a protocol-2 server reports (CoppeliaSim 4.10.0); a protocol-1
/// server reports the scene model's 4.5.1.
pub const PROGRAM_VERSION_V2: i32 = 41000;

/// Per-object properties the protocol-neutral scene does not model.
#[derive(Debug, Clone, Default)]
pub struct Extras {
    special: HashMap<i32, i32>,
    shape_params: HashMap<(i32, i32), i32>,
}

impl Extras {
    /// Special-property bits of an object (defaults: everything on for shapes, as CoppeliaSim's
    /// "Add > Primitive shape" with dynamics; nothing for dummies).
    pub fn special(&self, sim: &Simulator, handle: i32) -> Option<i32> {
        let o = sim.scene.get(handle).ok()?;
        Some(*self.special.get(&handle).unwrap_or(&match o.kind {
            ObjectType::Shape => {
                SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE
            }
            ObjectType::Dummy => 0,
        }))
    }

    /// A shape's integer parameter (static: 0, respondable: 1 by default).
    pub fn shape_param(&self, handle: i32, param: i32) -> Option<i32> {
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
pub enum Outcome {
    /// Return values.
    Ret(Vec<Value>),
    /// An error message (as the Lua error text).
    Err(String),
    /// Protocol 2 only: answer `_*wait*_` first, then these return values on `_*executed*_`.
    WaitThen(Vec<Value>),
}

/// Every `sim.*` function we answer (also what `zmqRemoteApi.info('sim')` lists).
pub const SIM_FUNCTIONS: &[&str] = &[
    "getObject",
    "getObjectAlias",
    "setObjectAlias",
    "getObjectType",
    "copyPasteObjects",
    "removeObjects",
    "removeObject",
    "getObjectsInTree",
    "getObjectParent",
    "setObjectParent",
    "setObjectPosition",
    "getObjectPosition",
    "setObjectOrientation",
    "getObjectOrientation",
    "setObjectPose",
    "getObjectPose",
    "getSimulationState",
    "startSimulation",
    "stopSimulation",
    "getInt32Param",
    "setInt32Param",
    "getInt32Signal",
    "setInt32Signal",
    "clearInt32Signal",
    "createPrimitiveShape",
    "createDummy",
    "setShapeColor",
    "getShapeColor",
    "setObjectSpecialProperty",
    "getObjectSpecialProperty",
    "setObjectInt32Param",
    "getObjectInt32Param",
    "saveScene",
];

/// Constants `zmqRemoteApi.info('sim')` lists.
pub const SIM_CONSTANTS: &[(&str, i64)] = &[
    ("handle_world", HANDLE_WORLD as i64),
    ("handle_all", HANDLE_ALL as i64),
    ("handle_parent", HANDLE_PARENT as i64),
    ("handle_scene", HANDLE_SCENE as i64),
    ("intparam_program_version", INTPARAM_PROGRAM_VERSION as i64),
    ("intparam_idle_fps", INTPARAM_IDLE_FPS as i64),
    ("primitiveshape_plane", 1),
    ("primitiveshape_disc", 2),
    ("primitiveshape_cuboid", 3),
    ("primitiveshape_spheroid", 4),
    ("primitiveshape_cylinder", 5),
    ("object_shape_type", 0),
    ("object_dummy_type", 4),
    ("simulation_stopped", 0),
    ("simulation_paused", 8),
    ("simulation_advancing_running", 17),
    ("colorcomponent_ambient_diffuse", 0),
    ("shapeintparam_static", SHAPEINTPARAM_STATIC as i64),
    (
        "shapeintparam_respondable",
        SHAPEINTPARAM_RESPONDABLE as i64,
    ),
    (
        "objectspecialproperty_collidable",
        SPECIAL_COLLIDABLE as i64,
    ),
    (
        "objectspecialproperty_measurable",
        SPECIAL_MEASURABLE as i64,
    ),
    (
        "objectspecialproperty_detectable",
        SPECIAL_DETECTABLE as i64,
    ),
    (
        "objectspecialproperty_renderable",
        SPECIAL_RENDERABLE as i64,
    ),
];

/// The `zmqRemoteApi.info('sim')` map: `{fname: {func: {}}, cname: {const: v}}`.
pub fn sim_info() -> Value {
    let mut pairs: Vec<(Value, Value)> = SIM_FUNCTIONS
        .iter()
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

/// Reads positional arguments with CoppeliaSim-like error texts.
struct Args<'a> {
    func: &'a str,
    args: &'a [Value],
}

impl Args<'_> {
    fn bad(&self, i: usize, what: &str) -> String {
        format!(
            "in {}: argument {} is not correct (expected {what}).",
            self.func,
            i + 1
        )
    }

    fn get(&self, i: usize) -> Option<&Value> {
        self.args.get(i).filter(|v| !matches!(v, Value::Null))
    }

    fn int(&self, i: usize) -> Result<i32, String> {
        self.get(i)
            .and_then(cbor::int32)
            .ok_or_else(|| self.bad(i, "an integer"))
    }

    fn int_or(&self, i: usize, default: i32) -> Result<i32, String> {
        if self.get(i).is_none() {
            Ok(default)
        } else {
            self.int(i)
        }
    }

    fn text(&self, i: usize) -> Result<&str, String> {
        self.get(i)
            .and_then(cbor::text)
            .ok_or_else(|| self.bad(i, "a string"))
    }

    fn vec3(&self, i: usize) -> Result<[f64; 3], String> {
        self.get(i)
            .and_then(cbor::numbers::<3>)
            .ok_or_else(|| self.bad(i, "a table of 3 numbers"))
    }

    fn handles(&self, i: usize) -> Result<Vec<i32>, String> {
        self.get(i)
            .and_then(cbor::handles)
            .ok_or_else(|| self.bad(i, "a table of handles"))
    }

    fn is_table(&self, i: usize) -> bool {
        matches!(self.get(i), Some(Value::Array(_)))
    }
}

const NO_OBJECT: &str = "object does not exist.";

fn no_object(func: &str) -> String {
    format!("in {func}: {NO_OBJECT}")
}

/// Calls one function. `func` is the full dotted name (`sim.getObject`).
pub fn call(
    sim: &mut Simulator,
    extras: &mut Extras,
    protocol: Protocol,
    func: &str,
    args: &[Value],
) -> Outcome {
    match dispatch(sim, extras, protocol, func, args) {
        Ok(o) => o,
        Err(e) => Outcome::Err(e),
    }
}

fn ret(values: Vec<Value>) -> Result<Outcome, String> {
    Ok(Outcome::Ret(values))
}

fn dispatch(
    sim: &mut Simulator,
    extras: &mut Extras,
    protocol: Protocol,
    func: &str,
    args: &[Value],
) -> Result<Outcome, String> {
    let a = Args { func, args };
    let nofunc = || Err(format!("No such function: {func}"));
    if func == "zmqRemoteApi.info" {
        return match a.text(0)? {
            "sim" => ret(vec![sim_info()]),
            other => Err(format!("in zmqRemoteApi.info: no such module '{other}'")),
        };
    }
    if func == "zmqRemoteApi.require" {
        // protocol 1 servers (4.3-4.5) have no require: `sim` is a global there
        if protocol == Protocol::V1 {
            return nofunc();
        }
        return match a.text(0)? {
            "sim" | "sim-1" => ret(vec![]),
            other => Err(format!(
                "in zmqRemoteApi.require: module '{other}' not found"
            )),
        };
    }
    let Some(name) = func.strip_prefix("sim.") else {
        return nofunc();
    };
    let nothing = || ret(vec![]);
    let scene_err = |_| no_object(func);
    match name {
        "getObject" => {
            let path = a.text(0)?;
            let opts = a.get(1);
            let no_error = opts
                .and_then(|o| cbor::get(o, "noError"))
                .and_then(cbor::boolean)
                .unwrap_or(false);
            let index = opts
                .and_then(|o| cbor::get(o, "index"))
                .and_then(cbor::integer);
            let full = match index {
                Some(i) if i > 0 => format!("{path}[{i}]"),
                _ => path.to_string(),
            };
            match sim.scene.resolve(&full) {
                Ok(h) => ret(vec![int(h.into())]),
                Err(_) if no_error => ret(vec![int(-1)]),
                Err(_) => Err(format!("in {func}: object does not exist: {full}")),
            }
        }
        "getObjectAlias" => {
            let h = a.int(0)?;
            let opt = a.int_or(1, -1)?;
            let o = sim.scene.get(h).map_err(scene_err)?;
            let s = match opt {
                -1 => o.alias.clone(),
                0 => {
                    let path = sim.scene.path(h).map_err(scene_err)?;
                    let idx = path
                        .rsplit_once('[')
                        .map(|(_, n)| n.trim_end_matches(']').to_string());
                    format!("{}[{}]", o.alias, idx.unwrap_or_else(|| "0".into()))
                }
                _ => sim.scene.path(h).map_err(scene_err)?,
            };
            ret(vec![Value::Text(s)])
        }
        "setObjectAlias" => {
            let (h, alias) = (a.int(0)?, a.text(1)?);
            sim.scene.set_alias(h, alias).map_err(scene_err)?;
            nothing()
        }
        "getObjectType" => {
            let h = a.int(0)?;
            ret(vec![int(sim
                .scene
                .get(h)
                .map_err(scene_err)?
                .kind
                .code()
                .into())])
        }
        "copyPasteObjects" => {
            let hs = a.handles(0)?;
            let new = sim.scene.copy_paste(&hs).map_err(scene_err)?;
            ret(vec![Value::Array(
                new.into_iter().map(|h| int(h.into())).collect(),
            )])
        }
        "removeObjects" => {
            let hs = a.handles(0)?;
            if let Some(bad) = hs.iter().find(|h| sim.scene.get(**h).is_err()) {
                return Err(format!("in {func}: {NO_OBJECT} (handle {bad})"));
            }
            for h in hs {
                // a handle listed twice is already gone: like CoppeliaSim, ignore it
                let _ = sim.scene.remove(h);
                extras.special.remove(&h);
            }
            nothing()
        }
        "removeObject" => {
            let h = a.int(0)?;
            sim.scene.remove(h).map_err(scene_err)?;
            nothing()
        }
        "getObjectsInTree" => {
            let base = a.int(0)?;
            let kind = a.int_or(1, HANDLE_ALL)?;
            let options = a.int_or(2, 0)?;
            let order = sim.scene.tree_order();
            let scene = &sim.scene;
            let in_tree = |h: i32| -> bool {
                if base == HANDLE_SCENE {
                    return options & 2 == 0 || scene.get(h).is_ok_and(|o| o.parent.is_none());
                }
                if h == base {
                    return options & 1 == 0;
                }
                let parent = scene.get(h).ok().and_then(|o| o.parent);
                if options & 2 != 0 {
                    return parent == Some(base);
                }
                let mut cur = parent;
                while let Some(p) = cur {
                    if p == base {
                        return true;
                    }
                    cur = scene.get(p).ok().and_then(|o| o.parent);
                }
                false
            };
            if base != HANDLE_SCENE {
                scene.get(base).map_err(scene_err)?;
            }
            let hs: Vec<Value> = order
                .into_iter()
                .filter(|&h| in_tree(h))
                .filter(|&h| {
                    kind == HANDLE_ALL || scene.get(h).is_ok_and(|o| o.kind.code() == kind)
                })
                .map(|h| int(h.into()))
                .collect();
            ret(vec![Value::Array(hs)])
        }
        "getObjectParent" => {
            let h = a.int(0)?;
            ret(vec![int(sim
                .scene
                .get(h)
                .map_err(scene_err)?
                .parent
                .unwrap_or(HANDLE_WORLD)
                .into())])
        }
        "setObjectParent" => {
            let (h, p) = (a.int(0)?, a.int(1)?);
            let keep = a.get(2).and_then(cbor::boolean).unwrap_or(true);
            let parent = (p != HANDLE_WORLD).then_some(p);
            sim.scene
                .set_parent(h, parent, keep)
                .map_err(|e| format!("in {func}: {e}"))?;
            nothing()
        }
        "setObjectPosition" | "setObjectOrientation" => {
            let h = a.int(0)?;
            // 4.5: (h, rel, v); 4.6+: (h, v, rel = world)
            let (rel, v) = if a.is_table(1) {
                (a.int_or(2, HANDLE_WORLD)?, a.vec3(1)?)
            } else {
                (a.int(1)?, a.vec3(2)?)
            };
            let r = if name == "setObjectPosition" {
                sim.scene.set_position(h, rel, v)
            } else {
                sim.scene.set_orientation(h, rel, v)
            };
            r.map_err(scene_err)?;
            nothing()
        }
        "getObjectPosition" | "getObjectOrientation" => {
            let (h, rel) = (a.int(0)?, a.int_or(1, HANDLE_WORLD)?);
            let (p, e) = sim.scene.pose(h, rel).map_err(scene_err)?;
            ret(vec![float_array(if name == "getObjectPosition" {
                &p
            } else {
                &e
            })])
        }
        "setObjectPose" => {
            let h = a.int(0)?;
            let (rel, pose) = if a.is_table(1) {
                (a.int_or(2, HANDLE_WORLD)?, 1)
            } else {
                (a.int(1)?, 2)
            };
            let p = a
                .get(pose)
                .and_then(cbor::numbers::<7>)
                .ok_or_else(|| a.bad(pose, "a table of 7 numbers"))?;
            let q = UnitQuaternion::from_quaternion(Quaternion::new(p[6], p[3], p[4], p[5]));
            sim.scene
                .set_orientation(h, rel, euler_from_rotation(&q))
                .map_err(scene_err)?;
            sim.scene
                .set_position(h, rel, [p[0], p[1], p[2]])
                .map_err(scene_err)?;
            nothing()
        }
        "getObjectPose" => {
            let (h, rel) = (a.int(0)?, a.int_or(1, HANDLE_WORLD)?);
            let (p, e) = sim.scene.pose(h, rel).map_err(scene_err)?;
            let q = rotation_from_euler(e);
            ret(vec![float_array(&[p[0], p[1], p[2], q.i, q.j, q.k, q.w])])
        }
        "getSimulationState" => ret(vec![int(match sim.state {
            SimState::Stopped => 0,
            SimState::Paused => 8,
            SimState::Running => 17,
        })]),
        "startSimulation" => {
            sim.start();
            nothing()
        }
        "stopSimulation" => {
            let was_running = sim.stop();
            if was_running && protocol == Protocol::V2 {
                // the add-on makes stopping a blocking call: the client waits through `_*wait*_`
                Ok(Outcome::WaitThen(vec![]))
            } else {
                nothing()
            }
        }
        "getInt32Signal" => {
            let value = sim.int_signals.get(a.text(0)?).copied();
            ret(vec![value.map_or(Value::Null, |v| int(v.into()))])
        }
        "setInt32Signal" => {
            let (name, value) = (a.text(0)?, a.int(1)?);
            sim.int_signals.insert(name.to_string(), value);
            nothing()
        }
        "clearInt32Signal" => {
            sim.int_signals.remove(a.text(0)?);
            nothing()
        }
        "getInt32Param" => {
            let p = a.int(0)?;
            if p == INTPARAM_PROGRAM_VERSION && protocol == Protocol::V2 {
                return ret(vec![int(PROGRAM_VERSION_V2.into())]);
            }
            match sim.int_param(p) {
                Some(v) => ret(vec![int(v.into())]),
                None => Err(format!("in {func}: invalid parameter {p}.")),
            }
        }
        "setInt32Param" => {
            let (p, v) = (a.int(0)?, a.int(1)?);
            if sim.set_int_param(p, v) {
                nothing()
            } else {
                Err(format!("in {func}: invalid parameter {p} or value {v}."))
            }
        }
        "createPrimitiveShape" => {
            let kind = a.int(0)?;
            let size = a.vec3(1)?;
            let base = match kind {
                1 => "Plane",
                2 => "Disc",
                3 => "Cuboid",
                4 => "Sphere",
                5 => "Cylinder",
                _ => return Err(format!("in {func}: invalid primitive type {kind}.")),
            };
            let size = if kind == 1 {
                [size[0], size[1], 0.0]
            } else {
                size
            };
            let h = sim
                .scene
                .create(base, new_object(ObjectType::Shape, size, [204, 204, 204]));
            ret(vec![int(h.into())])
        }
        "createDummy" => {
            let size = a.get(0).and_then(cbor::number).unwrap_or(0.01);
            let h = sim.scene.create(
                "Dummy",
                new_object(ObjectType::Dummy, [size; 3], [255, 255, 0]),
            );
            ret(vec![int(h.into())])
        }
        "setShapeColor" => {
            let h = a.int(0)?;
            let component = a.int(2)?;
            let rgb = a.vec3(3)?;
            let o = sim.scene.get(h).map_err(scene_err)?;
            if o.kind != ObjectType::Shape {
                return Err(format!("in {func}: object is not a shape."));
            }
            if component == 0 {
                let byte = |c: f64| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
                sim.scene
                    .set_colour(h, [byte(rgb[0]), byte(rgb[1]), byte(rgb[2])])
                    .map_err(scene_err)?;
            }
            nothing()
        }
        "getShapeColor" => {
            let h = a.int(0)?;
            let o = sim.scene.get(h).map_err(scene_err)?;
            let c = o.colour.map(|b| f64::from(b) / 255.0);
            ret(vec![int(1), float_array(&c)])
        }
        "setObjectSpecialProperty" => {
            let (h, p) = (a.int(0)?, a.int(1)?);
            sim.scene.get(h).map_err(scene_err)?;
            extras.special.insert(h, p);
            nothing()
        }
        "getObjectSpecialProperty" => {
            let h = a.int(0)?;
            ret(vec![int(extras
                .special(sim, h)
                .ok_or_else(|| no_object(func))?
                .into())])
        }
        "setObjectInt32Param" | "getObjectInt32Param" => {
            let (h, p) = (a.int(0)?, a.int(1)?);
            if sim.scene.get(h).map_err(scene_err)?.kind != ObjectType::Shape
                || extras.shape_param(h, p).is_none()
            {
                return Err(format!("in {func}: invalid parameter {p} for object {h}."));
            }
            if name == "getObjectInt32Param" {
                return ret(vec![int(extras.shape_param(h, p).unwrap_or(0).into())]);
            }
            extras.shape_params.insert((h, p), a.int(2)?);
            nothing()
        }
        "saveScene" => {
            let text = serde_json::to_string_pretty(&sim.scene.to_json()).unwrap_or_default();
            match a.get(0) {
                None => ret(vec![Value::Bytes(text.into_bytes())]),
                Some(_) => {
                    let path = a.text(0)?;
                    std::fs::write(path, text)
                        .map_err(|e| format!("in {func}: cannot write {path}: {e}"))?;
                    nothing()
                }
            }
        }
        _ => nofunc(),
    }
}

fn new_object(kind: ObjectType, size: [f64; 3], colour: [u8; 3]) -> NewObject {
    NewObject {
        kind,
        parent: None,
        position: [0.0; 3],
        orientation: [0.0; 3],
        size,
        colour,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coppelia::DEFAULT_IDLE_FPS;
    use crate::sim::Scene;

    fn run(sim: &mut Simulator, func: &str, args: Vec<Value>) -> Outcome {
        call(sim, &mut Extras::default(), Protocol::V2, func, &args)
    }

    fn ret1(o: Outcome) -> Value {
        match o {
            Outcome::Ret(mut v) if v.len() == 1 => v.remove(0),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn created_objects_are_named_like_coppeliasim_and_aliases_rename_them() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let size = float_array(&[1.0, 1.0, 0.0]);
        let a = cbor::int32(&ret1(run(
            &mut sim,
            "sim.createPrimitiveShape",
            vec![int(1), size.clone(), int(0)],
        )))
        .unwrap();
        let b = cbor::int32(&ret1(run(
            &mut sim,
            "sim.createPrimitiveShape",
            vec![int(1), size, int(0)],
        )))
        .unwrap();
        assert_eq!(
            (
                sim.scene.get(a).unwrap().name.as_str(),
                sim.scene.get(b).unwrap().name.as_str()
            ),
            ("Plane", "Plane0")
        );
        run(
            &mut sim,
            "sim.setObjectAlias",
            vec![int(b.into()), Value::Text("Green line!".into())],
        );
        let o = sim.scene.get(b).unwrap();
        assert_eq!(
            (o.alias.as_str(), o.name.as_str()),
            ("Green_line_", "Green_line_")
        );
        // the old-style name follows the alias, so the legacy API finds it too
        assert_eq!(sim.scene.resolve("Green_line_").unwrap(), b);
        let alias0 = ret1(run(
            &mut sim,
            "sim.getObjectAlias",
            vec![int(b.into()), int(0)],
        ));
        assert_eq!(cbor::text(&alias0), Some("Green_line_[0]"));
    }

    #[test]
    fn objects_in_tree_options_and_pose_argument_orders() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let maze = sim.scene.resolve("Maze").unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_parent(line, Some(maze), true).unwrap();
        let tree = |sim: &mut Simulator, base: i32, opt: i32| {
            cbor::handles(&ret1(run(
                sim,
                "sim.getObjectsInTree",
                vec![int(base.into()), int(-2), int(opt.into())],
            )))
            .unwrap()
        };
        assert_eq!(tree(&mut sim, maze, 0), vec![maze, line]);
        assert_eq!(tree(&mut sim, maze, 1), vec![line]);
        assert_eq!(tree(&mut sim, maze, 3), vec![line]);
        let roots = tree(&mut sim, HANDLE_SCENE, 2);
        assert!(!roots.contains(&line) && roots.contains(&maze));
        assert_eq!(tree(&mut sim, HANDLE_SCENE, 0).len(), 5);
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let pose = float_array(&[1.0, 2.0, 0.001, 0.0, 0.0, s, s]);
        for args in [
            vec![int(line.into()), pose.clone(), int(-1)],
            vec![int(line.into()), int(-1), pose.clone()],
        ] {
            sim.scene.set_position(line, -1, [0.0; 3]).unwrap();
            assert_eq!(
                run(&mut sim, "sim.setObjectPose", args),
                Outcome::Ret(vec![])
            );
            let (p, e) = sim.scene.pose(line, -1).unwrap();
            assert!(
                (p[1] - 2.0).abs() < 1e-12 && (e[2] - std::f64::consts::FRAC_PI_2).abs() < 1e-12
            );
        }
        match run(
            &mut sim,
            "sim.setObjectPose",
            vec![int(line.into()), int(-1)],
        ) {
            Outcome::Err(e) => assert!(e.contains("argument 3"), "{e}"),
            other => panic!("{other:?}"),
        }
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
    fn protocol_1_has_no_require_and_reports_4_5_1() {
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
        let v1 = call(
            &mut sim,
            &mut x,
            Protocol::V1,
            "sim.getInt32Param",
            &[int(1)],
        );
        let v2 = call(
            &mut sim,
            &mut x,
            Protocol::V2,
            "sim.getInt32Param",
            &[int(1)],
        );
        assert_eq!(
            (v1, v2),
            (
                Outcome::Ret(vec![int(40501)]),
                Outcome::Ret(vec![int(41000)])
            )
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
