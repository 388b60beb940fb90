//! The emulated robot (`serve --robot PATH.csv`): an object that, while the simulation runs,
//! follows timed waypoints in the `Floor` frame, so a run can be graded without CoppeliaSim.

use super::object::ObjectType;
use super::scene::{NewObject, Scene, SimError};
use vrep_maze_core::coppelia::HANDLE_WORLD;
use vrep_maze_core::score::Sample;
use vrep_maze_core::score::trajectory::interpolate;

/// Height of the emulated robot's centre above the floor, metres.
pub const ROBOT_Z: f64 = 0.05;

/// A scene object driven along a path of timed waypoints (simulation time, `Floor` frame).
#[derive(Debug, Clone, PartialEq)]
pub struct RobotPath {
    /// The object moved.
    pub handle: i32,
    /// The waypoints, by non-decreasing time; the pose between two is linear.
    pub waypoints: Vec<Sample>,
}

impl RobotPath {
    /// Adds an object named `name` (a 0.2 m x 0.2 m x 0.1 m white shape) to `scene` at the
    /// first waypoint and returns the path that drives it. `waypoints` must not be empty.
    pub fn add_to(scene: &mut Scene, name: &str, waypoints: Vec<Sample>) -> Result<Self, SimError> {
        let handle = scene.add(
            name,
            NewObject {
                kind: ObjectType::Shape,
                parent: None,
                position: [0.0, 0.0, ROBOT_Z],
                orientation: [0.0; 3],
                size: [0.2, 0.2, 0.1],
                colour: [255, 255, 255],
            },
        );
        let path = RobotPath { handle, waypoints };
        path.place(scene, 0.0)?;
        Ok(path)
    }

    /// Puts the object where the path is at simulation time `t` (seconds), relative to
    /// `Floor` (the world if the scene has none). A removed object is left alone.
    pub fn place(&self, scene: &mut Scene, t: f64) -> Result<(), SimError> {
        let Some(pose) = interpolate(&self.waypoints, t) else {
            return Ok(());
        };
        if scene.get(self.handle).is_err() {
            return Ok(());
        }
        let floor = scene.resolve("Floor").unwrap_or(HANDLE_WORLD);
        scene.set_position(self.handle, floor, [pose.x, pose.y, ROBOT_Z])?;
        scene.set_orientation(self.handle, floor, [0.0, 0.0, pose.yaw])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_robot_is_where_its_path_is_relative_to_the_floor() {
        let mut scene = Scene::course();
        let floor = scene.resolve("Floor").unwrap();
        scene
            .set_position(floor, HANDLE_WORLD, [1.0, 2.0, 0.0])
            .unwrap();
        let waypoints = vec![
            Sample {
                t: 0.0,
                x: 0.0,
                y: 0.0,
                yaw: 0.0,
            },
            Sample {
                t: 2.0,
                x: 1.0,
                y: 0.0,
                yaw: 1.0,
            },
        ];
        let path = RobotPath::add_to(&mut scene, "Robot", waypoints).unwrap();
        assert_eq!(scene.resolve("Robot"), Ok(path.handle));
        path.place(&mut scene, 1.0).unwrap();
        let (p, e) = scene.pose(path.handle, floor).unwrap();
        assert!((p[0] - 0.5).abs() < 1e-12 && p[1].abs() < 1e-12, "{p:?}");
        assert!((p[2] - ROBOT_Z).abs() < 1e-12);
        assert!((e[2] - 0.5).abs() < 1e-12, "{e:?}");
        let (world, _) = scene.pose(path.handle, HANDLE_WORLD).unwrap();
        assert!((world[0] - 1.5).abs() < 1e-12 && (world[1] - 2.0).abs() < 1e-12);
    }
}
