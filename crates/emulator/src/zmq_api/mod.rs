//! The emulated ZeroMQ remote-API server (port 23000) over [`crate::sim`], with its `sim.*`
//! function registry, speaking the codec of `vrep_maze_wire::zmq_api` (re-exported here as
//! [`cbor`] and [`message`]).

pub mod server;

pub use server::{ServerConfig, ServerHandle, SimHost, spawn, spawn_shared};
pub use vrep_maze_wire::zmq_api::{Protocol, cbor, message};
