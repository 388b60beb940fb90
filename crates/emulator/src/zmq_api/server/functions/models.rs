//! Models: `sim.setModelProperty` / `sim.getModelProperty` (the model base flag),
//! `sim.saveModel` (a model base and everything under it as a CoppeliaSim XML model) and
//! `sim.loadModel` (an XML model into the scene, [`crate::sim::model`]). As CoppeliaSim 4.5.1
//! (`../shared/spec/real-coppeliasim-4.5.1.md`, "One object instead of thousands"): a model is
//! saved after `sim.setModelProperty(h, 0)` makes `h` a model base, and loaded by its
//! `.simmodel.xml` path. The emulator reads and writes XML models only (a `.ttm` is refused).

use ciborium::Value;

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::sim::ObjectType;
use crate::zmq_api::cbor::int;
use vrep_maze_core::coppelia::xml::{
    self, Body, Document, Dummy, FileKind, Primitive, Shape, XmlObject,
};
use vrep_maze_core::coppelia::{SHAPEINTPARAM_RESPONDABLE, SHAPEINTPARAM_STATIC};

/// `sim.modelproperty_not_model`: the object is no model base.
pub(super) const MODELPROPERTY_NOT_MODEL: i32 = 0xf000;

/// `sim.setModelProperty(h, property)`: `0` (or any value without all of
/// [`MODELPROPERTY_NOT_MODEL`]) makes `h` a model base.
pub(super) fn set_model_property(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (h, p) = (a.int(0)?, a.int(1)?);
    ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    ctx.extras.model_property.insert(h, p);
    nothing()
}

/// `sim.getModelProperty(h)`: what was set, [`MODELPROPERTY_NOT_MODEL`] by default.
pub(super) fn get_model_property(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    ret(vec![int(model_property(ctx, h).into())])
}

fn model_property(ctx: &Ctx<'_>, h: i32) -> i32 {
    *ctx.extras
        .model_property
        .get(&h)
        .unwrap_or(&MODELPROPERTY_NOT_MODEL)
}

fn is_model_base(ctx: &Ctx<'_>, h: i32) -> bool {
    model_property(ctx, h) & MODELPROPERTY_NOT_MODEL != MODELPROPERTY_NOT_MODEL
}

/// A path the emulator reads or writes models at: it must end in `.simmodel.xml`.
fn xml_model_path<'s>(a: &Args<'s>, i: usize) -> Result<&'s str, String> {
    let path = a.text(i)?;
    if !path.ends_with(FileKind::Model.extension()) {
        return Err(format!(
            "in {}: the emulator reads and writes XML models only (*.simmodel.xml): {path}",
            a.func
        ));
    }
    Ok(path)
}

/// `sim.saveModel(h, path)`: the model base `h` (at its world pose) and its subtree (at their
/// local poses), shapes with their triangles, colour, special properties and dynamics.
pub(super) fn save_model(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let path = xml_model_path(a, 1)?;
    ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    if !is_model_base(ctx, h) {
        return Err(format!("in {}: object is not a model base.", a.func));
    }
    let doc = model_document(ctx, h).map_err(|e| format!("in {}: {e}", a.func))?;
    std::fs::write(path, xml::write(&doc))
        .map_err(|e| format!("in {}: cannot write {path}: {e}", a.func))?;
    nothing()
}

/// The document of the model based at `base`.
fn model_document(ctx: &Ctx<'_>, base: i32) -> Result<Document, crate::sim::SimError> {
    let scene = &ctx.sim.scene;
    let mut objects = Vec::new();
    for h in scene.subtree(base) {
        let o = scene.get(h)?;
        let (position, euler) = if h == base {
            scene.pose(h, vrep_maze_core::coppelia::HANDLE_WORLD)?
        } else {
            (o.position, o.orientation)
        };
        let q = vrep_maze_core::coppelia::frame::rotation_from_euler(euler);
        let colour = o.colour.map(|c| f32::from(c) / 255.0);
        let body = match o.kind {
            ObjectType::Dummy => Body::Dummy(Dummy {
                size: o.size[0],
                colour,
            }),
            ObjectType::Shape => {
                let mesh = o
                    .shape_mesh()
                    .and_then(|m| xml::Mesh::from_flat(&m.vertices, &m.indices))
                    .unwrap_or_default();
                let param = |p: i32| ctx.extras.shape_param(h, p).unwrap_or(0) != 0;
                Body::Shape(Shape {
                    mesh,
                    colour,
                    primitive: match (&o.mesh, o.size[2]) {
                        (Some(_), _) => Primitive::None,
                        (None, 0.0) => Primitive::Plane([o.size[0], o.size[1], 0.0001]),
                        (None, _) => Primitive::Cuboid(o.size),
                    },
                    is_static: param(SHAPEINTPARAM_STATIC),
                    respondable: param(SHAPEINTPARAM_RESPONDABLE),
                })
            }
        };
        objects.push(XmlObject {
            handle: h,
            parent: if h == base { None } else { o.parent },
            alias: o.alias.clone(),
            position,
            quaternion: [q.w, q.i, q.j, q.k],
            model_base: is_model_base(ctx, h),
            special: ctx.extras.special(ctx.sim, h).unwrap_or(0),
            body,
        });
    }
    Ok(Document {
        kind: FileKind::Model,
        objects,
    })
}

/// `sim.loadModel(path)`: the model's objects enter the scene; returns the model base's handle.
pub(super) fn load_model(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let path = xml_model_path(a, 0)?;
    let text = xml::read_file(std::path::Path::new(path))
        .map_err(|e| format!("in {}: cannot read {path}: {e}", a.func))?;
    let doc = xml::read(&text).map_err(|e| format!("in {}: {path}: {e}", a.func))?;
    let loaded = crate::sim::model::load(&mut ctx.sim.scene, &doc)
        .map_err(|e| format!("in {}: {path}: {e}", a.func))?;
    for (o, &h) in doc.objects.iter().zip(&loaded.handles) {
        ctx.extras.special.insert(h, o.special);
        if o.model_base {
            ctx.extras.model_property.insert(h, 0);
        }
        if let Body::Shape(s) = &o.body {
            ctx.extras
                .shape_params
                .insert((h, SHAPEINTPARAM_STATIC), i32::from(s.is_static));
            ctx.extras
                .shape_params
                .insert((h, SHAPEINTPARAM_RESPONDABLE), i32::from(s.respondable));
        }
    }
    ret(vec![Value::Integer(loaded.base.into())])
}

#[cfg(test)]
mod tests {
    use super::super::testing::ret1;
    use super::super::{Extras, call};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use crate::zmq_api::cbor;
    use crate::zmq_api::message::Protocol;

    #[test]
    fn a_model_base_saves_as_xml_and_loads_back_as_a_copy() {
        let mut sim = Simulator::new(Scene::course(), 0);
        // one server's properties across the calls
        let mut extras = Extras::default();
        let mut run = |sim: &mut Simulator, func: &str, args: Vec<Value>| {
            call(sim, &mut extras, Protocol::V2, func, &args)
        };
        let line = sim.scene.resolve("Line").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("line.simmodel.xml").display().to_string();
        let save = vec![int(line.into()), Value::Text(path.clone())];
        let saved = run(&mut sim, "sim.saveModel", save.clone());
        assert!(matches!(saved, Outcome::Err(e) if e.contains("not a model base")));
        let got = ret1(run(
            &mut sim,
            "sim.getModelProperty",
            vec![int(line.into())],
        ));
        assert_eq!(cbor::int32(&got), Some(MODELPROPERTY_NOT_MODEL));
        run(
            &mut sim,
            "sim.setModelProperty",
            vec![int(line.into()), int(0)],
        );
        assert_eq!(run(&mut sim, "sim.saveModel", save), Outcome::Ret(vec![]));
        let doc = xml::read(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert_eq!(doc.objects[0].alias, "Line");
        assert!(doc.objects[0].model_base);
        assert_eq!(doc.objects[0].position, [0.0, 0.0, 0.001]);
        let loaded = ret1(run(
            &mut sim,
            "sim.loadModel",
            vec![Value::Text(path.clone())],
        ));
        let copy = cbor::int32(&loaded).unwrap();
        let o = sim.scene.get(copy).unwrap();
        assert_eq!((o.name.as_str(), o.alias.as_str()), ("Line0", "Line"));
        assert_eq!(o.colour, [0, 255, 0]);
        assert_eq!(o.mesh.as_ref().unwrap().triangles(), 2);
        let ttm = Value::Text(dir.path().join("m.ttm").display().to_string());
        assert!(
            matches!(run(&mut sim, "sim.loadModel", vec![ttm]), Outcome::Err(e) if e.contains("XML models only"))
        );
        let missing = Value::Text(dir.path().join("none.simmodel.xml").display().to_string());
        assert!(matches!(
            run(&mut sim, "sim.loadModel", vec![missing]),
            Outcome::Err(_)
        ));
    }
}
