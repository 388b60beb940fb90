//! Driving a wheeled robot through a maze, decided from what it observes: the pure half of
//! `vrep-maze drive --wheels` (the client moves the joints and reads the sensors; this module
//! decides the wheel velocities). Nothing here knows a simulator.
//!
//! - [`wheels`]: a differential drive's geometry, its odometry and the wheel speeds for a
//!   wanted motion.
//! - [`route`]: the solution as straight legs, and [`route::Follower`], which drives them one by
//!   one (turning on the spot between legs) from a pose.
//! - [`camera`]: a forward camera's pinhole model, from pixels to points on the floor, and
//!   [`camera::LineColour`], which tells line pixels from the rest.
//! - [`localize`]: a pose estimate corrected by the drawn lines the camera sees (the layout's
//!   lines as a map).
//! - [`steer`]: the two ways of steering, [`steer::PoseSteer`] (ground truth) and
//!   [`steer::CameraSteer`] (camera and odometry only), behind [`steer::Steer`].

pub mod camera;
pub mod localize;
pub mod route;
pub mod steer;
pub mod wheels;

/// A robot's pose on the floor: metres in the floor's frame and the heading about its z axis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// Metres along the floor's x.
    pub x: f64,
    /// Metres along the floor's y.
    pub y: f64,
    /// Heading, radians about the floor's z (0 along +x).
    pub yaw: f64,
}

/// Wrap an angle into (-pi, pi].
pub fn wrap(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let a = angle.rem_euclid(TAU);
    if a > PI { a - TAU } else { a }
}
