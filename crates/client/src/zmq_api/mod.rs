//! CoppeliaSim's ZeroMQ remote API (port 23000, CoppeliaSim 4.3 and later), the client's
//! side: CBOR codec and request/reply maps of both protocol generations
//! (`vrep_maze_wire::zmq_api`, re-exported here), a client, the drawing backend and the robot
//! follower. The emulated server is in the emulator crate (`vrep_maze_emulator::zmq_api`).
//!
//! Layers: [`cbor`] (values) → [`message`] (request and reply maps) → [`client`] (then
//! [`backend`], the [`crate::draw::backend::Backend`] implementation) / the emulator's `server` (with
//! its `sim.*` function registry). The client side never imports from the server side.

pub mod backend;
pub mod client;
pub mod follow;
pub mod robot;

pub use backend::ZmqBackend;
pub use client::{Client, ClientOptions, ClientStats, MAX_PROGRAM_CALLS, Outcome, ZmqError};
pub use vrep_maze_wire::zmq_api::{Protocol, cbor, message};
