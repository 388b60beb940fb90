//! A differential drive: two wheels of one radius on one axle, the track apart. Odometry from
//! the wheels' joint angles, and the wheel speeds that give a wanted forward speed and turn rate.

use super::{Pose, wrap};

/// The geometry of a differential drive, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffDrive {
    /// Wheel radius.
    pub wheel_radius: f64,
    /// Distance between the two wheels' contact points.
    pub track: f64,
}

/// Target velocities of the two wheel joints, radians a second (positive drives forward).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wheels {
    /// The left wheel.
    pub left: f64,
    /// The right wheel.
    pub right: f64,
}

impl DiffDrive {
    /// Checks that both lengths are finite and positive; the error names the bad one.
    pub fn new(wheel_radius: f64, track: f64) -> Result<Self, String> {
        for (name, v) in [("wheel radius", wheel_radius), ("track", track)] {
            if !(v.is_finite() && v > 0.0 && v < 10.0) {
                return Err(format!(
                    "the {name} must be more than 0 and less than 10 m, got {v}"
                ));
            }
        }
        Ok(Self {
            wheel_radius,
            track,
        })
    }

    /// The wheel speeds for `forward` m/s and `turn` rad/s (counter-clockwise), scaled down
    /// together so that neither wheel exceeds `max` rad/s (the path's curvature is kept).
    pub fn wheels(&self, forward: f64, turn: f64, max: f64) -> Wheels {
        let half = turn * self.track / 2.0;
        let (left, right) = (
            (forward - half) / self.wheel_radius,
            (forward + half) / self.wheel_radius,
        );
        let top = left.abs().max(right.abs());
        let scale = if top > max && top > 0.0 {
            max / top
        } else {
            1.0
        };
        Wheels {
            left: left * scale,
            right: right * scale,
        }
    }

    /// The pose after the wheels turned by `left` and `right` radians from `pose` (the
    /// midpoint rule: exact for an arc's chord direction).
    pub fn odometry(&self, pose: Pose, left: f64, right: f64) -> Pose {
        let (dl, dr) = (left * self.wheel_radius, right * self.wheel_radius);
        let ds = (dl + dr) / 2.0;
        let dyaw = (dr - dl) / self.track;
        let mid = pose.yaw + dyaw / 2.0;
        Pose {
            x: pose.x + ds * mid.cos(),
            y: pose.y + ds * mid.sin(),
            yaw: wrap(pose.yaw + dyaw),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const COURSE: DiffDrive = DiffDrive {
        wheel_radius: 0.04,
        track: 0.18,
    };

    #[test]
    fn equal_wheels_drive_straight_and_opposite_wheels_turn_on_the_spot() {
        let p = COURSE.odometry(Pose::default(), 10.0, 10.0);
        assert!((p.x - 0.4).abs() < 1e-12 && p.y.abs() < 1e-12 && p.yaw == 0.0);
        let q = COURSE.odometry(Pose::default(), -1.0, 1.0);
        assert!(q.x.abs() < 1e-12 && q.y.abs() < 1e-12);
        assert!((q.yaw - 2.0 * 0.04 / 0.18).abs() < 1e-12);
    }

    #[test]
    fn a_quarter_circle_in_small_steps_ends_where_geometry_says() {
        // radius 1 m about (0, 1): the outer (right) wheel runs faster
        let mut p = Pose::default();
        let (inner, outer) = (1.0 - 0.09, 1.0 + 0.09);
        let steps = 1000;
        let arc = std::f64::consts::FRAC_PI_2 / f64::from(steps);
        for _ in 0..steps {
            p = COURSE.odometry(p, inner * arc / 0.04, outer * arc / 0.04);
        }
        assert!((p.x - 1.0).abs() < 1e-6, "{p:?}");
        assert!((p.y - 1.0).abs() < 1e-6, "{p:?}");
        assert!((p.yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    }

    #[test]
    fn wheel_speeds_are_capped_together() {
        let w = COURSE.wheels(1.0, 2.0, 10.0);
        assert!(w.right.abs() <= 10.0 + 1e-12 && w.left.abs() <= 10.0);
        // the ratio (the curvature) is kept
        let free = COURSE.wheels(1.0, 2.0, f64::INFINITY);
        assert!((w.left / w.right - free.left / free.right).abs() < 1e-12);
        assert!(
            DiffDrive::new(0.0, 0.18)
                .unwrap_err()
                .contains("wheel radius")
        );
        assert!(
            DiffDrive::new(0.04, f64::NAN)
                .unwrap_err()
                .contains("track")
        );
    }
}
