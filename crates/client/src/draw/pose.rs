//! Poses on the floor: an object's frame, its pose in the floor's frame, how far it is from
//! the pose a drawing wants, and templates standing where a maze is drawn.

use super::backend::ObjectInfo;
use super::drawing::Drawing;
use super::tolerance::{ANGLE_TOLERANCE, POSITION_TOLERANCE};
use vrep_maze_core::coppelia::frame::{Frame, frame, position_euler, wrap_angle};
use vrep_maze_core::layout::Pose;

/// Position of a pose as an array.
pub fn position(p: &Pose) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// CoppeliaSim Euler angles of a pose (roll = pitch = 0).
pub fn euler(p: &Pose) -> [f64; 3] {
    [0.0, 0.0, p.yaw]
}

/// Frame of an object from its world position and Euler angles.
pub fn world_frame(o: &ObjectInfo) -> Frame {
    frame(o.position, o.orientation)
}

/// The frame of the floor (handle `floor`) among `objects`, `None` when they do not list it.
pub fn floor_frame(objects: &[ObjectInfo], floor: i32) -> Option<Frame> {
    objects.iter().find(|o| o.handle == floor).map(world_frame)
}

/// Pose of `object` in the frame `floor` as (position, Euler).
pub fn relative_pose(floor: &Frame, object: &ObjectInfo) -> ([f64; 3], [f64; 3]) {
    position_euler(&(floor.inverse() * world_frame(object)))
}

/// Differences between an object's pose in the floor frame and the wanted pose (`None` if
/// within tolerance; a flipped line (yaw + pi) is not accepted: Start/End and lines are
/// compared exactly up to 2 pi). A non-finite number anywhere (object, floor or wanted pose)
/// is always a difference: every comparison with NaN fails.
pub fn pose_differences(floor: &Frame, object: &ObjectInfo, want: &Pose) -> Option<String> {
    let (p, e) = relative_pose(floor, object);
    let position_ok = p
        .iter()
        .zip(position(want))
        .all(|(a, b)| (a - b).abs() <= POSITION_TOLERANCE);
    let angles_ok = [
        wrap_angle(e[0]),
        wrap_angle(e[1]),
        wrap_angle(e[2] - want.yaw),
    ]
    .iter()
    .all(|a| a.abs() <= ANGLE_TOLERANCE);
    if position_ok && angles_ok {
        None
    } else {
        Some(format!(
            "at ({:.4}, {:.4}, {:.4}) yaw {:.4} (roll {:.4}, pitch {:.4}), expected ({:.4}, {:.4}, {:.4}) yaw {:.4}",
            p[0], p[1], p[2], e[2], e[0], e[1], want.x, want.y, want.z, want.yaw
        ))
    }
}

/// Warnings for the templates a wall maze copies (`templates`: name and handle) that stand
/// on the maze: within half a cell of the area its walls and posts cover, at or above the
/// floor. They stay where the scene has them, so there they show as walls the layout does
/// not have.
pub fn templates_on_the_maze(
    drawing: &Drawing,
    objects: &[ObjectInfo],
    floor: &Frame,
    templates: &[(&str, i32)],
) -> Vec<String> {
    let poses = drawing.pieces.iter().chain(&drawing.posts);
    let margin = drawing.sizes.cell / 2.0;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in poses {
        lo = [lo[0].min(p.x - margin), lo[1].min(p.y - margin)];
        hi = [hi[0].max(p.x + margin), hi[1].max(p.y + margin)];
    }
    templates
        .iter()
        .filter_map(|(name, handle)| {
            let o = objects.iter().find(|o| o.handle == *handle)?;
            let (p, _) = relative_pose(floor, o);
            let inside = (lo[0]..=hi[0]).contains(&p[0])
                && (lo[1]..=hi[1]).contains(&p[1])
                && p[2] >= 0.0;
            inside.then(|| {
                format!(
                    "the template `{name}` stands on the maze at ({:.3}, {:.3}): it shows as a wall the layout does not have; move it off the maze (e.g. beside the floor)",
                    p[0], p[1]
                )
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::backend::object_at_origin as obj;

    #[test]
    fn pose_compare_in_a_rotated_floor() {
        let floor_info = ObjectInfo {
            position: [1.0, 2.0, 0.0],
            orientation: [0.0, 0.0, 1.0],
            ..obj(1, "Floor", None)
        };
        let floor = world_frame(&floor_info);
        let want = Pose {
            x: 0.25,
            y: 1.0,
            z: 0.001,
            yaw: std::f64::consts::FRAC_PI_2,
        };
        let world = floor * frame(position(&want), euler(&want));
        let (p, e) = position_euler(&world);
        let o = ObjectInfo {
            position: p,
            orientation: e,
            ..obj(5, "Line0", Some(2))
        };
        assert_eq!(pose_differences(&floor, &o, &want), None);
        let moved = Pose { x: 0.2502, ..want };
        assert!(pose_differences(&floor, &o, &moved).is_some());
    }

    #[test]
    fn a_non_finite_pose_is_never_in_place() {
        let floor = world_frame(&obj(1, "Floor", None));
        let want = Pose {
            x: 0.25,
            y: 0.0,
            z: 0.001,
            yaw: 0.0,
        };
        let placed = ObjectInfo {
            position: [0.25, 0.0, 0.001],
            ..obj(5, "Line0", Some(2))
        };
        assert_eq!(pose_differences(&floor, &placed, &want), None);
        for (i, bad) in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY]
            .into_iter()
            .enumerate()
        {
            for k in 0..3 {
                let mut o = placed.clone();
                o.position[k] = bad;
                assert!(
                    pose_differences(&floor, &o, &want).is_some(),
                    "position[{k}] #{i}"
                );
                let mut o = placed.clone();
                o.orientation[k] = bad;
                assert!(
                    pose_differences(&floor, &o, &want).is_some(),
                    "orientation[{k}] #{i}"
                );
            }
            let wanted = Pose { yaw: bad, ..want };
            assert!(
                pose_differences(&floor, &placed, &wanted).is_some(),
                "wanted yaw #{i}"
            );
            let nan_floor = world_frame(&ObjectInfo {
                position: [bad, 0.0, 0.0],
                ..obj(1, "Floor", None)
            });
            assert!(
                pose_differences(&nan_floor, &placed, &want).is_some(),
                "floor #{i}"
            );
        }
    }
}
