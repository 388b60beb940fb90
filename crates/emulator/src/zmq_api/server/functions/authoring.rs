//! Authoring the scene: creating shapes and dummies, naming them, their colour, special
//! properties and shape parameters (kept in [`Extras`](super::Extras)), and saving the scene.

use ciborium::Value;

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::sim::{NewObject, ObjectType};
use crate::zmq_api::cbor::{self, float_array, int};
use vrep_maze_core::coppelia::{
    OBJINTPARAM_VISIBILITY_LAYER, PRIMITIVESHAPE_CUBOID, PRIMITIVESHAPE_CYLINDER,
    PRIMITIVESHAPE_DISC, PRIMITIVESHAPE_PLANE, PRIMITIVESHAPE_SPHEROID,
};

/// A new root object at the origin.
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

/// `sim.createPrimitiveShape(type, size, options)`: a grey shape named after its type
/// (`Plane`, `Plane0`, ...); a plane's third size is 0.
pub(super) fn create_primitive_shape(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let kind = a.int(0)?;
    let size = a.vec3(1)?;
    let base = match kind {
        PRIMITIVESHAPE_PLANE => "Plane",
        PRIMITIVESHAPE_DISC => "Disc",
        PRIMITIVESHAPE_CUBOID => "Cuboid",
        PRIMITIVESHAPE_SPHEROID => "Sphere",
        PRIMITIVESHAPE_CYLINDER => "Cylinder",
        _ => return Err(format!("in {}: invalid primitive type {kind}.", a.func)),
    };
    let size = if kind == PRIMITIVESHAPE_PLANE {
        [size[0], size[1], 0.0]
    } else {
        size
    };
    let h = ctx
        .sim
        .scene
        .create(base, new_object(ObjectType::Shape, size, [204, 204, 204]));
    ret(vec![int(h.into())])
}

/// `sim.createDummy(size = 0.01)`: a yellow dummy named `Dummy`, `Dummy0`, ...
pub(super) fn create_dummy(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let size = a.get(0).and_then(cbor::number).unwrap_or(0.01);
    let h = ctx.sim.scene.create(
        "Dummy",
        new_object(ObjectType::Dummy, [size; 3], [255, 255, 0]),
    );
    ret(vec![int(h.into())])
}

/// `sim.setObjectAlias(h, alias)`: characters an alias cannot hold become `_`; the old-style
/// name follows.
pub(super) fn set_object_alias(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (h, alias) = (a.int(0)?, a.text(1)?);
    ctx.sim
        .scene
        .set_alias(h, alias)
        .map_err(|_| a.no_object())?;
    nothing()
}

/// `sim.setShapeColor(h, colorName, component, rgb)`: only the ambient-diffuse component (0)
/// is modelled; the others are accepted and ignored.
pub(super) fn set_shape_color(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let component = a.int(2)?;
    let rgb = a.vec3(3)?;
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    if o.kind != ObjectType::Shape {
        return Err(format!("in {}: object is not a shape.", a.func));
    }
    if component == 0 {
        let byte = |c: f64| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
        ctx.sim
            .scene
            .set_colour(h, [byte(rgb[0]), byte(rgb[1]), byte(rgb[2])])
            .map_err(|_| a.no_object())?;
    }
    nothing()
}

/// `sim.getShapeColor(h, colorName, component)`: `(1, rgb)`, the ambient-diffuse colour
/// whatever the component.
pub(super) fn get_shape_color(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    let c = o.colour.map(|b| f64::from(b) / 255.0);
    ret(vec![int(1), float_array(&c)])
}

/// `sim.setObjectSpecialProperty(h, bits)`.
pub(super) fn set_object_special_property(
    ctx: &mut Ctx<'_>,
    a: &Args<'_>,
) -> Result<Outcome, String> {
    let (h, p) = (a.int(0)?, a.int(1)?);
    ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    ctx.extras.special.insert(h, p);
    nothing()
}

/// `sim.getObjectSpecialProperty(h)`: the bits set, or the object type's default.
pub(super) fn get_object_special_property(
    ctx: &mut Ctx<'_>,
    a: &Args<'_>,
) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let bits = ctx
        .extras
        .special(ctx.sim, h)
        .ok_or_else(|| a.no_object())?;
    ret(vec![int(bits.into())])
}

/// The `(h, param)` of a shape-parameter call, if `h` is a shape and `param` one we model
/// (static, respondable).
fn shape_param_of(ctx: &Ctx<'_>, a: &Args<'_>) -> Result<(i32, i32), String> {
    let (h, p) = (a.int(0)?, a.int(1)?);
    if ctx.sim.scene.get(h).map_err(|_| a.no_object())?.kind != ObjectType::Shape
        || ctx.extras.shape_param(h, p).is_none()
    {
        return Err(format!(
            "in {}: invalid parameter {p} for object {h}.",
            a.func
        ));
    }
    Ok((h, p))
}

/// `sim.setObjectInt32Param(h, param, value)`, for any object's visibility layer and shapes'
/// static and respondable flags.
pub(super) fn set_object_int32_param(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    if a.int(1)? == OBJINTPARAM_VISIBILITY_LAYER {
        let (h, bits) = (a.int(0)?, a.int(2)?);
        ctx.sim
            .scene
            .set_layer(h, bits)
            .map_err(|_| a.no_object())?;
        return nothing();
    }
    let (h, p) = shape_param_of(ctx, a)?;
    ctx.extras.shape_params.insert((h, p), a.int(2)?);
    nothing()
}

/// `sim.getObjectInt32Param(h, param)`, for any object's visibility layer and shapes' static
/// and respondable flags.
pub(super) fn get_object_int32_param(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    if a.int(1)? == OBJINTPARAM_VISIBILITY_LAYER {
        let h = a.int(0)?;
        let layer = ctx.sim.scene.get(h).map_err(|_| a.no_object())?.layer();
        return ret(vec![int(layer.into())]);
    }
    let (h, p) = shape_param_of(ctx, a)?;
    ret(vec![int(ctx.extras.shape_param(h, p).unwrap_or(0).into())])
}

/// `sim.saveScene(path)`: writes the scene as JSON (our stand-in for a `.ttt`); without a
/// path, returns the bytes.
pub(super) fn save_scene(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let text = serde_json::to_string_pretty(&ctx.sim.scene.to_json()).unwrap_or_default();
    match a.get(0) {
        None => ret(vec![Value::Bytes(text.into_bytes())]),
        Some(_) => {
            let path = a.text(0)?;
            std::fs::write(path, text)
                .map_err(|e| format!("in {}: cannot write {path}: {e}", a.func))?;
            nothing()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::{ret1, run};
    use super::super::{Extras, call};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use crate::zmq_api::message::Protocol;
    use vrep_maze_core::coppelia::{
        DEFAULT_IDLE_FPS, SHAPEINTPARAM_RESPONDABLE, SPECIAL_COLLIDABLE, SPECIAL_DETECTABLE,
        SPECIAL_MEASURABLE, SPECIAL_RENDERABLE,
    };

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
    fn special_properties_and_shape_params_default_then_stick() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut x = Extras::default();
        let mut go =
            |func: &str, args: Vec<Value>| call(&mut sim, &mut x, Protocol::V2, func, &args);
        let cube = vec![int(3), float_array(&[0.1; 3]), int(0)];
        let shape = ret1(go("sim.createPrimitiveShape", cube));
        let dummy = ret1(go("sim.createDummy", vec![]));
        let all = SPECIAL_COLLIDABLE | SPECIAL_MEASURABLE | SPECIAL_DETECTABLE | SPECIAL_RENDERABLE;
        for (h, bits) in [(&shape, all), (&dummy, 0)] {
            assert_eq!(
                go("sim.getObjectSpecialProperty", vec![h.clone()]),
                Outcome::Ret(vec![int(bits.into())])
            );
        }
        let renderable = int(SPECIAL_RENDERABLE.into());
        go(
            "sim.setObjectSpecialProperty",
            vec![dummy.clone(), renderable.clone()],
        );
        assert_eq!(
            go("sim.getObjectSpecialProperty", vec![dummy.clone()]),
            Outcome::Ret(vec![renderable])
        );
        let respondable = int(SHAPEINTPARAM_RESPONDABLE.into());
        let get = vec![shape.clone(), respondable.clone()];
        assert_eq!(
            go("sim.getObjectInt32Param", get.clone()),
            Outcome::Ret(vec![int(1)])
        );
        go(
            "sim.setObjectInt32Param",
            vec![shape.clone(), respondable.clone(), int(0)],
        );
        assert_eq!(
            go("sim.getObjectInt32Param", get),
            Outcome::Ret(vec![int(0)])
        );
        let d = cbor::int32(&dummy).unwrap();
        assert_eq!(
            go("sim.getObjectInt32Param", vec![dummy, respondable]),
            Outcome::Err(format!(
                "in sim.getObjectInt32Param: invalid parameter {SHAPEINTPARAM_RESPONDABLE} for object {d}."
            ))
        );
    }
}
