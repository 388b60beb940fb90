#![warn(missing_docs)]
//! vrep-maze: seeded, reproducible grid mazes for CoppeliaSim (formerly V-REP).
//!
//! The library behind the `vrep-maze` command; `ARCHITECTURE.md` maps it. From the bottom up:
//!
//! - Pure maze logic: [`maze`] (the compact grid maze and its analysis), [`rng`] (the only
//!   source of randomness), [`generate`] (one file per algorithm), [`layout`] (the JSON layout:
//!   geometry, segments, reading and writing), [`validate`] (every check a layout must pass),
//!   [`render`] (ASCII, SVG, PNG), [`batch`] (many seeds at once) and [`atomic_file`] (files
//!   written whole or not at all).
//! - [`score`]: grading a robot's run (a trajectory) against a layout.
//! - [`coppelia`]: CoppeliaSim's constants and Euler convention, shared by clients and emulator.
//! - [`draw`]: the [`draw::Backend`] port and the backend-neutral `apply`, `clear`, `verify`.
//! - [`export`]: a layout as a CoppeliaSim, MuJoCo, Gazebo (SDF), URDF or Webots file.
//! - The protocols, each a codec, a client, a drawing backend and an emulated server:
//!   [`legacy`] (port 19997) and [`zmq_api`] (ZeroMQ, port 23000).
//! - [`sim`]: the emulated simulator's scene, state and clock, under both servers.
//! - [`cli`]: the command line, the only user of clap; it makes the progress bars (indicatif) that renderers advance.

pub mod atomic_file;
pub mod batch;
pub mod cli;
pub mod coppelia;
pub mod draw;
pub mod export;
pub mod generate;
pub mod layout;
pub mod legacy;
pub mod maze;
pub mod render;
pub mod rng;
pub mod score;
pub mod sim;
pub mod validate;
pub mod zmq_api;
