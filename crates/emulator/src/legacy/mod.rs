//! The emulated legacy remote-API server (port 19997) over [`crate::sim`], speaking the codec
//! of `vrep_maze_wire::legacy` (re-exported here as [`wire`] and [`command`]).

pub mod server;

pub use server::{ServerConfig, ServerHandle, spawn};
pub use vrep_maze_wire::legacy::{command, wire};
