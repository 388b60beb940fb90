//! Positions, Euler orientations and poses (position + quaternion x, y, z, w), relative to
//! another object or the world. Setters take both argument orders: `(h, rel, v)` as up to
//! CoppeliaSim 4.5, `(h, v, rel = world)` as from 4.6, told apart by where the table is.

use nalgebra::{Quaternion, UnitQuaternion};

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::sim::{Scene, SimError};
use crate::zmq_api::cbor::{self, float_array};
use vrep_maze_core::coppelia::HANDLE_WORLD;
use vrep_maze_core::coppelia::frame::{euler_from_rotation, rotation_from_euler};

/// Sets a position or orientation (`set`) from either argument order.
fn set_vector(
    ctx: &mut Ctx<'_>,
    a: &Args<'_>,
    set: fn(&mut Scene, i32, i32, [f64; 3]) -> Result<(), SimError>,
) -> Result<Outcome, String> {
    let h = a.int(0)?;
    let (rel, v) = if a.is_table(1) {
        (a.int_or(2, HANDLE_WORLD)?, a.vec3(1)?)
    } else {
        (a.int(1)?, a.vec3(2)?)
    };
    set(&mut ctx.sim.scene, h, rel, v).map_err(|_| a.no_object())?;
    nothing()
}

/// `(h, rel = world)`: the position and Euler angles of `h` relative to `rel`.
fn pose(ctx: &Ctx<'_>, a: &Args<'_>) -> Result<([f64; 3], [f64; 3]), String> {
    let (h, rel) = (a.int(0)?, a.int_or(1, HANDLE_WORLD)?);
    ctx.sim.scene.pose(h, rel).map_err(|_| a.no_object())
}

/// `sim.setObjectPosition`: moves `h`, keeping its orientation.
pub(super) fn set_object_position(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    set_vector(ctx, a, Scene::set_position)
}

/// `sim.setObjectOrientation` (Euler angles): turns `h`, keeping its position.
pub(super) fn set_object_orientation(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    set_vector(ctx, a, Scene::set_orientation)
}

/// `sim.getObjectPosition(h, rel = world)`.
pub(super) fn get_object_position(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (p, _) = pose(ctx, a)?;
    ret(vec![float_array(&p)])
}

/// `sim.getObjectOrientation(h, rel = world)`: Euler angles.
pub(super) fn get_object_orientation(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (_, e) = pose(ctx, a)?;
    ret(vec![float_array(&e)])
}

/// `sim.setObjectPose`: position and quaternion `[x, y, z, qx, qy, qz, qw]` at once.
pub(super) fn set_object_pose(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
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
    let scene = &mut ctx.sim.scene;
    scene
        .set_orientation(h, rel, euler_from_rotation(&q))
        .map_err(|_| a.no_object())?;
    scene
        .set_position(h, rel, [p[0], p[1], p[2]])
        .map_err(|_| a.no_object())?;
    nothing()
}

/// `sim.getObjectPose(h, rel = world)`: `[x, y, z, qx, qy, qz, qw]`.
pub(super) fn get_object_pose(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (p, e) = pose(ctx, a)?;
    let q = rotation_from_euler(e);
    ret(vec![float_array(&[p[0], p[1], p[2], q.i, q.j, q.k, q.w])])
}

#[cfg(test)]
mod tests {
    use ciborium::Value;

    use super::super::testing::run;
    use super::*;
    use crate::sim::Simulator;
    use crate::zmq_api::cbor::int;
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    #[test]
    fn pose_argument_orders() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let maze = sim.scene.resolve("Maze").unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        sim.scene.set_parent(line, Some(maze), true).unwrap();
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
        let v: Vec<Value> = vec![int(line.into()), float_array(&[3.0, 4.0, 0.0])];
        assert_eq!(
            run(&mut sim, "sim.setObjectPosition", v),
            Outcome::Ret(vec![])
        );
        let (p, _) = sim.scene.pose(line, -1).unwrap();
        assert!(
            (p[0] - 3.0).abs() < 1e-12 && (p[1] - 4.0).abs() < 1e-12,
            "{p:?}"
        );
    }
}
