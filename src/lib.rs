#![warn(missing_docs)]
//! vrep-maze: seeded, reproducible grid mazes for CoppeliaSim (formerly V-REP).
//!
//! The library behind the `vrep-maze` command: [`maze`] holds the model and its analysis,
//! [`generate`] the algorithms, [`rng`] the only source of randomness. [`sim`] is an
//! in-memory CoppeliaSim scene, [`legacy`] the legacy remote API (client and server) and
//! [`draw`] draws a layout into a scene through any backend.

pub mod atomic_file;
pub mod batch;
pub mod cli;
pub mod coppelia;
pub mod draw;
pub mod generate;
pub mod layout;
pub mod legacy;
pub mod maze;
pub mod render;
pub mod rng;
pub mod sim;
pub mod validate;
pub mod zmq_api;
