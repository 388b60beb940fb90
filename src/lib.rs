#![warn(missing_docs)]
//! vrep-maze: seeded, reproducible grid mazes for CoppeliaSim (formerly V-REP).
//!
//! The command line ([`cli`]) over the workspace's crates, which this crate re-exports under
//! one name (`ARCHITECTURE.md` maps them):
//!
//! - `vrep-maze-core`: mazes, layouts, validation, pictures, scores, exports ([`maze`],
//!   [`rng`], [`generate`], [`layout`], [`validate`], [`render`], [`batch`],
//!   [`atomic_file`], [`score`], [`coppelia`], [`mesh`], [`export`]); no ZeroMQ;
//! - `vrep-maze-wire`: the two remote-API protocols as codecs;
//! - `vrep-maze-client`: [`draw`] and the two clients ([`legacy`], [`zmq_api`] client side);
//! - `vrep-maze-emulator`: [`sim`] and the two emulated servers ([`legacy::server`],
//!   [`zmq_api::server`]).
//!
//! A Rust program that only makes mazes depends on `vrep-maze-core` alone.

pub mod cli;

pub use vrep_maze_client::draw;
pub use vrep_maze_core::{
    atomic_file, batch, condition, coppelia, export, generate, layout, maze, mesh, progress,
    render, rng, score, validate, wording,
};
pub use vrep_maze_emulator::sim;

/// The legacy remote API (port 19997): the codec, our client and drawing backend, and the
/// emulated server, under one path.
pub mod legacy {
    pub use vrep_maze_client::legacy::*;
    pub use vrep_maze_emulator::legacy::*;
}

/// The ZeroMQ remote API (port 23000): the codec, our client and drawing backend, and the
/// emulated server, under one path.
pub mod zmq_api {
    pub use vrep_maze_client::zmq_api::*;
    pub use vrep_maze_emulator::zmq_api::*;
}
