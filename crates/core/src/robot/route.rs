//! The solution as a robot drives it: straight legs from cell centre to cell centre, joined
//! where the path turns, and [`Follower`], which drives the legs one by one from a pose:
//! along a leg it steers back onto the leg's centre line, at its end it turns on the spot to
//! the next leg. On the spot, so a line robot stays on the lines and a wall robot clear of
//! the corners.

use super::wheels::{DiffDrive, Wheels};
use super::{Pose, wrap};
use crate::layout::solution::Waypoint;

/// One straight leg of the route, floor frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// Where the leg starts.
    pub from: [f64; 2],
    /// Where it ends.
    pub to: [f64; 2],
}

impl Leg {
    /// Length, metres.
    pub fn length(&self) -> f64 {
        (self.to[0] - self.from[0]).hypot(self.to[1] - self.from[1])
    }

    /// The heading along the leg, radians.
    pub fn heading(&self) -> f64 {
        (self.to[1] - self.from[1]).atan2(self.to[0] - self.from[0])
    }

    /// Metres along the leg from its start, and metres to its left, of the point `(x, y)`.
    pub fn along_and_left(&self, x: f64, y: f64) -> (f64, f64) {
        let length = self.length().max(f64::EPSILON);
        let (ux, uy) = (
            (self.to[0] - self.from[0]) / length,
            (self.to[1] - self.from[1]) / length,
        );
        let (dx, dy) = (x - self.from[0], y - self.from[1]);
        (dx * ux + dy * uy, dy * ux - dx * uy)
    }
}

/// The legs of a path of waypoints: repeated points dropped, straight runs made one leg.
/// Empty when the waypoints do not move (start and end in one cell).
pub fn legs(waypoints: &[Waypoint]) -> Vec<Leg> {
    let mut points: Vec<[f64; 2]> = Vec::new();
    for w in waypoints {
        if points
            .last()
            .is_none_or(|p| (p[0] - w.x).hypot(p[1] - w.y) > 1e-9)
        {
            points.push([w.x, w.y]);
        }
    }
    let mut legs: Vec<Leg> = Vec::new();
    for pair in points.windows(2) {
        let leg = Leg {
            from: pair[0],
            to: pair[1],
        };
        match legs.last_mut() {
            Some(last) if wrap(last.heading() - leg.heading()).abs() < 1e-6 => last.to = leg.to,
            _ => legs.push(leg),
        }
    }
    legs
}

/// How the follower drives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gains {
    /// Top forward speed, m/s.
    pub speed: f64,
    /// Top turn rate, rad/s.
    pub turn_rate: f64,
    /// Top wheel speed, rad/s (both wheels scaled together below it).
    pub wheel_max: f64,
    /// Deceleration allowed before a turn, m/s^2 (how early it slows down).
    pub braking: f64,
    /// Heading error, radians, below which a turn on the spot ends.
    pub aligned: f64,
}

impl Default for Gains {
    fn default() -> Self {
        Self {
            speed: 0.5,
            turn_rate: 2.5,
            wheel_max: 16.0,
            braking: 1.0,
            aligned: 0.03,
        }
    }
}

/// What the follower is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Turning on the spot to face leg `usize`.
    Turn(usize),
    /// Driving along leg `usize`.
    Drive(usize),
    /// At the end of the last leg.
    Arrived,
}

/// Drives a route's legs from pose readings: one [`Follower::wheels`] call a control step.
#[derive(Debug, Clone)]
pub struct Follower {
    legs: Vec<Leg>,
    drive: DiffDrive,
    gains: Gains,
    phase: Phase,
}

impl Follower {
    /// A follower at the start of `legs`: it first turns to face the first leg.
    pub fn new(legs: Vec<Leg>, drive: DiffDrive, gains: Gains) -> Self {
        let phase = if legs.is_empty() {
            Phase::Arrived
        } else {
            Phase::Turn(0)
        };
        Self {
            legs,
            drive,
            gains,
            phase,
        }
    }

    /// The legs it drives.
    pub fn legs(&self) -> &[Leg] {
        &self.legs
    }

    /// The leg being turned to or driven, if any.
    pub fn current_leg(&self) -> Option<usize> {
        match self.phase {
            Phase::Turn(i) | Phase::Drive(i) => Some(i),
            Phase::Arrived => None,
        }
    }

    /// `true` once the end of the last leg is reached.
    pub fn arrived(&self) -> bool {
        self.phase == Phase::Arrived
    }

    /// The wheel speeds for the robot at `pose`; zero once arrived.
    pub fn wheels(&mut self, pose: Pose) -> Wheels {
        loop {
            match self.phase {
                Phase::Arrived => return Wheels::default(),
                Phase::Turn(i) => {
                    let error = wrap(self.legs[i].heading() - pose.yaw);
                    if error.abs() <= self.gains.aligned {
                        self.phase = Phase::Drive(i);
                        continue;
                    }
                    // proportional, with a floor so the last degrees do not crawl
                    let rate = (3.0 * error)
                        .clamp(-self.gains.turn_rate, self.gains.turn_rate)
                        .abs()
                        .max(0.3)
                        * error.signum();
                    return self.drive.wheels(0.0, rate, self.gains.wheel_max);
                }
                Phase::Drive(i) => {
                    let leg = self.legs[i];
                    let (along, left) = leg.along_and_left(pose.x, pose.y);
                    let remaining = leg.length() - along;
                    if remaining <= 0.01 {
                        self.phase = if i + 1 < self.legs.len() {
                            Phase::Turn(i + 1)
                        } else {
                            Phase::Arrived
                        };
                        continue;
                    }
                    let heading_error = wrap(leg.heading() - pose.yaw);
                    if heading_error.abs() > 0.6 {
                        // pushed far off course: face the leg again first
                        self.phase = Phase::Turn(i);
                        continue;
                    }
                    // slow down in time to stop at the leg's end (every leg ends in a turn or
                    // the goal), never below a crawl
                    let speed = self
                        .gains
                        .speed
                        .min((2.0 * self.gains.braking * remaining).sqrt())
                        .max(0.05);
                    // Stanley's rule: aim back onto the centre line, more sharply when slow
                    let wanted = leg.heading() - (2.0 * left).atan2(speed + 0.1);
                    let turn = (4.0 * wrap(wanted - pose.yaw))
                        .clamp(-self.gains.turn_rate, self.gains.turn_rate);
                    return self.drive.wheels(speed, turn, self.gains.wheel_max);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::wheels::DiffDrive;

    fn at(x: f64, y: f64) -> Waypoint {
        Waypoint {
            x,
            y,
            yaw: 0.0,
            distance: 0.0,
        }
    }

    const COURSE: DiffDrive = DiffDrive {
        wheel_radius: 0.04,
        track: 0.18,
    };

    #[test]
    fn straight_runs_become_one_leg_and_repeats_vanish() {
        let w = [
            at(0.0, 0.0),
            at(1.0, 0.0),
            at(1.0, 0.0),
            at(2.0, 0.0),
            at(2.0, 1.0),
        ];
        let l = legs(&w);
        assert_eq!(l.len(), 2);
        assert_eq!(l[0].to, [2.0, 0.0]);
        assert_eq!(l[1].to, [2.0, 1.0]);
        assert!(legs(&[at(1.0, 1.0), at(1.0, 1.0)]).is_empty());
    }

    /// Integrates the follower with perfect wheels: it must reach the end, stay near the
    /// legs and never cut a corner.
    #[test]
    fn a_perfect_robot_follows_an_l_shaped_route_to_its_end() {
        let route = legs(&[at(0.0, 0.0), at(2.0, 0.0), at(2.0, 0.0), at(2.0, 3.0)]);
        let mut follower = Follower::new(route.clone(), COURSE, Gains::default());
        let mut pose = Pose {
            x: 0.02,
            y: -0.05,
            yaw: 0.4,
        };
        let dt = 0.05;
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            let w = follower.wheels(pose);
            pose = COURSE.odometry(pose, w.left * dt, w.right * dt);
            let off = route
                .iter()
                .map(|l| {
                    let (a, left) = l.along_and_left(pose.x, pose.y);
                    if (-0.1..=l.length() + 0.1).contains(&a) {
                        left.abs()
                    } else {
                        f64::INFINITY
                    }
                })
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(off);
            if follower.arrived() {
                break;
            }
        }
        assert!(follower.arrived(), "stopped at {pose:?}");
        assert!(
            (pose.x - 2.0).abs() < 0.05 && (pose.y - 3.0).abs() < 0.05,
            "{pose:?}"
        );
        assert!(worst < 0.06, "strayed {worst} m from the legs");
    }
}
