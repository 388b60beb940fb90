#![warn(missing_docs)]
//! vrep-maze's core: seeded, reproducible grid mazes and everything done with them without a
//! simulator. It builds with no ZeroMQ and no C++ compiler.
//!
//! - [`maze`] (the compact grid maze and its analysis), [`rng`] (the only source of
//!   randomness), [`generate`] (one file per algorithm), [`layout`] (the JSON layout:
//!   geometry, segments, reading and writing), [`validate`] (every check a layout must pass),
//!   [`render`] (ASCII, SVG, PNG), [`batch`] (many seeds at once) and [`atomic_file`] (files
//!   written whole or not at all); [`progress`] is how a long step tells how far it got,
//!   for an adapter to show.
//! - [`score`]: grading a robot's run (a trajectory) against a layout, and the `Follower`
//!   port a simulator connection implements to watch a robot.
//! - [`coppelia`]: CoppeliaSim's vocabulary: constants, Euler convention, XML format, what
//!   its operations cost, the one Lua program our client sends.
//! - [`mesh`]: a layout as a few mesh shapes (pure geometry), which the drawing and the
//!   exports share.
//! - [`export`]: a layout as a CoppeliaSim, MuJoCo, Gazebo (SDF), URDF or Webots file, a ROS
//!   occupancy map, or the arguments of a Gymnasium-Robotics PointMaze.

pub mod atomic_file;
pub mod batch;
pub mod condition;
pub mod coppelia;
pub mod export;
pub mod generate;
pub mod layout;
pub mod maze;
pub mod mesh;
pub mod progress;
pub mod render;
pub mod rng;
pub mod score;
pub mod validate;
pub mod wording;
