//! Whether the line template lies on an earlier line maze, as its first line, or stands
//! where the user put it. Without a record of its home ([`super::home`]) a drawing must tell
//! them apart before it records the template's pose as its home: only a pose that is its own
//! is recorded, and only a template that lies on a maze is hidden below the floor.

use super::backend::ObjectInfo;
use super::pose::relative_pose;
use vrep_maze_core::coppelia::frame::{Frame, wrap_angle};

/// How far apart (metres, radians) two lines of one maze may be from touching exactly:
/// single precision and a scene saved and loaded again stay far below it.
const SLACK: f64 = 1e-3;

/// `true` if `template` (of `length` metres along its x) lies on a line maze whose other
/// lines are `copies`: one of them touches it as the lines of a maze do, at its height, in
/// line with it (the next line of its passage, overlapping or end to end) or across it (a
/// corner), within its length of its centre. A copy at the template's very pose (pasted
/// from it, never moved) or off its line is no such neighbour: a user's copy of `Line` is
/// no maze.
pub fn lies_on_a_maze(
    template: &ObjectInfo,
    copies: &[&ObjectInfo],
    floor: &Frame,
    length: f64,
) -> bool {
    let (p, e) = relative_pose(floor, template);
    let along = [e[2].cos(), e[2].sin()];
    copies.iter().any(|c| {
        let (q, f) = relative_pose(floor, c);
        let d = [q[0] - p[0], q[1] - p[1]];
        let distance = d[0].hypot(d[1]);
        let turn = wrap_angle(f[2] - e[2]);
        let quarter = std::f64::consts::FRAC_PI_2;
        let parallel = (turn.abs() < SLACK) || (turn.abs() - 2.0 * quarter).abs() < SLACK;
        let across = (turn.abs() - quarter).abs() < SLACK;
        let off_line = (d[0] * along[1] - d[1] * along[0]).abs();
        (q[2] - p[2]).abs() < SLACK
            && distance > SLACK
            && distance <= length + SLACK
            && ((parallel && off_line < SLACK) || across)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(handle: i32, x: f64, y: f64, yaw: f64) -> ObjectInfo {
        ObjectInfo {
            handle,
            name: format!("Line{handle}"),
            parent: Some(1),
            position: [x, y, 0.001],
            orientation: [0.0, 0.0, yaw],
        }
    }

    #[test]
    fn a_maze_line_touches_the_template_and_a_pasted_copy_does_not() {
        let floor = Frame::identity();
        let template = line(2, 0.25, 0.0, 0.0);
        let next = line(3, 0.75, 0.0, 0.0);
        let corner = line(4, 0.0, 0.25, std::f64::consts::FRAC_PI_2);
        let pasted = line(5, 0.25, 0.0, 0.0);
        let aside = line(6, 0.25, 0.5, 0.0);
        let far = line(7, 3.0, 0.0, 0.0);
        let on = |copies: &[&ObjectInfo]| lies_on_a_maze(&template, copies, &floor, 0.6);
        assert!(on(&[&next]));
        assert!(on(&[&corner]));
        assert!(
            !on(&[&pasted]),
            "a copy pasted from the template is no maze"
        );
        assert!(!on(&[&aside, &far]));
        let lifted = ObjectInfo {
            position: [0.75, 0.0, 0.3],
            ..next.clone()
        };
        assert!(!on(&[&lifted]), "another height");
    }
}
