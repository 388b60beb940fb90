//! The object tree: finding objects by path, their aliases, types and parents, copying and
//! removing them.

use std::collections::HashMap;

use ciborium::Value;

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::zmq_api::cbor::{self, int};
use vrep_maze_core::coppelia::{HANDLE_ALL, HANDLE_SCENE, HANDLE_WORLD};

/// `sim.getObject(path, {noError, index})`: the handle at a path; with `noError`, -1 instead of
/// an error when nothing is there.
pub(super) fn get_object(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
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
    match ctx.sim.scene.resolve(&full) {
        Ok(h) => ret(vec![int(h.into())]),
        Err(_) if no_error => ret(vec![int(-1)]),
        Err(_) => Err(format!("in {}: object does not exist: {full}", a.func)),
    }
}

/// `sim.getObjectAlias(h, options = -1)`: the bare alias (-1), the alias with its index
/// (`Line[0]`, 0), or the full path (`/Maze/Line[1]`, anything else).
pub(super) fn get_object_alias(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let opt = a.int_or(1, -1)?;
    let scene = &ctx.sim.scene;
    let o = scene.get(h).map_err(|_| a.no_object())?;
    let s = match opt {
        -1 => o.alias.clone(),
        0 => {
            let path = scene.path(h).map_err(|_| a.no_object())?;
            let idx = path
                .rsplit_once('[')
                .map(|(_, n)| n.trim_end_matches(']').to_string());
            format!("{}[{}]", o.alias, idx.unwrap_or_else(|| "0".into()))
        }
        _ => scene.path(h).map_err(|_| a.no_object())?,
    };
    ret(vec![Value::Text(s)])
}

/// `sim.getObjectType(h)`: `sim.object_shape_type` or `sim.object_dummy_type`.
pub(super) fn get_object_type(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    ret(vec![int(o.kind.code().into())])
}

/// `sim.getObjectFloatParam(h, param)`: parameters 15..20 are the bounding box in the
/// object's frame (`../shared/spec/real-coppeliasim-4.5.1.md`: the course `Line` gives -0.3,
/// -0.05, 0, 0.3, 0.05, 0). Other parameters are not modelled and fail.
pub(super) fn get_object_float_param(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (h, param) = (a.int(0)?, a.int(1)?);
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    match o.float_param(param) {
        Some(v) => ret(vec![Value::Float(v)]),
        None => Err(format!("in {}: unknown parameter {param}", a.func)),
    }
}

/// `sim.copyPasteObjects(handles, options)`: the handles of the copies.
/// `sim.copyPasteObjects(handles, options)`: one handle per handle given. Each distinct
/// handle is pasted once; a repetition answers the handle of the first object in the scene
/// that is neither a copy nor an original still to be answered, as CoppeliaSim 4.5.1 does: it
/// finds each copy by the copy string it carries, and clears the original's after answering
/// it, so a repetition matches the first object with an empty copy string
/// (coppeliaSimLib@coppeliasim-v4.5.1-rev4 `simInternal.cpp:6450-6460, 6508-6523`; spec "Costs
/// that grow with the scene": `copyPasteObjects([Line, Line, Line, Line])` gave `[5, 0, 0, 0]`,
/// 0 being `Floor`'s handle). If no such object exists the handle given is answered.
pub(super) fn copy_paste_objects(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let hs = a.handles(0)?;
    let scene = &mut ctx.sim.scene;
    // objects in the scene's order, before the copies (which come after them all)
    let before: Vec<i32> = scene.objects().map(|o| o.handle).collect();
    let new = scene.copy_paste(&hs).map_err(|_| a.no_object())?;
    let first_at: HashMap<i32, usize> = hs.iter().enumerate().rev().map(|(i, &h)| (h, i)).collect();
    let mut copies = new.into_iter();
    let answers = hs.iter().enumerate().map(|(i, &h)| {
        if first_at[&h] == i {
            copies.next().unwrap_or(h)
        } else {
            // originals first given after `i` still carry their copy string
            let cleared = |o: &i32| first_at.get(o).is_none_or(|&j| j <= i);
            before.iter().copied().find(cleared).unwrap_or(h)
        }
    });
    ret(vec![Value::Array(answers.map(|h| int(h.into())).collect())])
}

/// `sim.removeObjects(handles)`: removes those that exist. A handle already removed (or
/// listed twice) is no error: CoppeliaSim 4.5.1 skips objects it does not find
/// (coppeliaSimLib `simInternal.cpp:1290-1316`, `sceneObjectContainer.cpp:250-268`;
/// `../shared/spec/real-coppeliasim-4.5.1.md`, "ZeroMQ API details": "`sim.removeObjects`
/// with a handle that was already removed succeeds").
pub(super) fn remove_objects(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    for h in a.handles(0)? {
        if ctx.sim.scene.remove(h).is_ok() {
            ctx.extras.special.remove(&h);
            ctx.extras.shape_params.retain(|(o, _), _| *o != h);
        }
    }
    nothing()
}

/// `sim.removeObject(h)`, the pre-4.6 single-object form.
pub(super) fn remove_object(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    ctx.sim.scene.remove(h).map_err(|_| a.no_object())?;
    nothing()
}

/// `sim.getObjectsInTree(base, type = sim.handle_all, options = 0)`: the objects under `base`
/// (or the whole scene), in tree order. Options bit 0 leaves out the base, bit 1 keeps only
/// its direct children (the roots, for the scene).
pub(super) fn get_objects_in_tree(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let base = a.int(0)?;
    let kind = a.int_or(1, HANDLE_ALL)?;
    let options = a.int_or(2, 0)?;
    let scene = &ctx.sim.scene;
    // only the tree asked for is walked, through the scene's parent index
    let order: Vec<i32> = if base == HANDLE_SCENE {
        if options & 2 != 0 {
            scene.children(None).collect()
        } else {
            scene.tree_order()
        }
    } else {
        scene.get(base).map_err(|_| a.no_object())?;
        let mut order = if options & 2 != 0 {
            std::iter::once(base)
                .chain(scene.children(Some(base)))
                .collect()
        } else {
            scene.subtree(base)
        };
        if options & 1 != 0 {
            order.remove(0);
        }
        order
    };
    let hs: Vec<Value> = order
        .into_iter()
        .filter(|&h| kind == HANDLE_ALL || scene.get(h).is_ok_and(|o| o.kind.code() == kind))
        .map(|h| int(h.into()))
        .collect();
    ret(vec![Value::Array(hs)])
}

/// `sim.getObjectParent(h)`: the parent's handle, `sim.handle_world` for a root.
pub(super) fn get_object_parent(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let o = ctx.sim.scene.get(h).map_err(|_| a.no_object())?;
    ret(vec![int(o.parent.unwrap_or(HANDLE_WORLD).into())])
}

/// `sim.setObjectParent(h, parent, keepInPlace = true)`; `sim.handle_world` makes `h` a root.
pub(super) fn set_object_parent(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (h, p) = (a.int(0)?, a.int(1)?);
    let keep = a.get(2).and_then(cbor::boolean).unwrap_or(true);
    let parent = (p != HANDLE_WORLD).then_some(p);
    ctx.sim
        .scene
        .set_parent(h, parent, keep)
        .map_err(|e| format!("in {}: {e}", a.func))?;
    nothing()
}

#[cfg(test)]
mod tests {
    use super::super::testing::{ret1, run};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    #[test]
    fn objects_in_tree_options() {
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
        assert_eq!(tree(&mut sim, maze, 2), vec![maze, line]);
    }

    #[test]
    fn float_params_15_to_20_are_the_bounding_box() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let line = sim.scene.resolve("Line").unwrap();
        let got: Vec<Value> = (15..=20)
            .map(|p| {
                ret1(run(
                    &mut sim,
                    "sim.getObjectFloatParam",
                    vec![int(line.into()), int(p.into())],
                ))
            })
            .collect();
        let want: Vec<Value> = [-0.3, -0.05, 0.0, 0.3, 0.05, 0.0]
            .into_iter()
            .map(Value::Float)
            .collect();
        assert_eq!(got, want);
        for (h, p) in [(line, 21), (9999, 15)] {
            assert!(matches!(
                run(
                    &mut sim,
                    "sim.getObjectFloatParam",
                    vec![int(h.into()), int(p.into())]
                ),
                Outcome::Err(_)
            ));
        }
    }

    #[test]
    fn a_repeated_handle_is_pasted_once_and_answered_by_the_first_object() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let (floor, line) = (
            sim.scene.resolve("Floor").unwrap(),
            sim.scene.resolve("Line").unwrap(),
        );
        let paste = |sim: &mut Simulator, hs: &[i32]| {
            let list = Value::Array(hs.iter().map(|h| int((*h).into())).collect());
            cbor::handles(&ret1(run(sim, "sim.copyPasteObjects", vec![list, int(0)]))).unwrap()
        };
        // spec: copyPasteObjects([Line, Line, Line, Line]) gave [5, 0, 0, 0] (0: Floor)
        let got = paste(&mut sim, &[line; 4]);
        assert_eq!(got[1..], [floor; 3]);
        assert_eq!(sim.scene.len(), 6, "one copy");
        assert_eq!(sim.scene.get(got[0]).unwrap().name, "Line0");
        // Floor repeated after Line: Floor's copy string is cleared once it is answered,
        // Line's too, so the repetitions answer Floor itself
        let got = paste(&mut sim, &[floor, line, floor]);
        assert_eq!(got.len(), 3);
        assert_eq!(got[2], floor);
        assert_eq!(sim.scene.len(), 8, "two copies");
        // Floor given again after a repetition of Line: Floor still carries its copy
        // string when Line's repetition is answered, so the next object (Maze) is
        let maze = sim.scene.resolve("Maze").unwrap();
        let got = paste(&mut sim, &[line, line, floor]);
        assert_eq!(got[1], maze);
    }

    #[test]
    fn removing_a_removed_object_succeeds() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let line = sim.scene.resolve("Line").unwrap();
        let list = Value::Array(vec![int(line.into()), int(line.into())]);
        assert_eq!(
            run(&mut sim, "sim.removeObjects", vec![list.clone()]),
            Outcome::Ret(vec![])
        );
        assert!(sim.scene.get(line).is_err());
        assert_eq!(
            run(&mut sim, "sim.removeObjects", vec![list]),
            Outcome::Ret(vec![])
        );
        assert_eq!(sim.scene.len(), 4);
    }
}
