//! CoppeliaSim's ZeroMQ remote API (port 23000, CoppeliaSim 4.3 and later): CBOR codec,
//! request/reply maps of both protocol generations, a client, an emulated server over
//! [`crate::sim`], and the drawing backend.
//!
//! Layers: [`cbor`] (values) → [`message`] (request and reply maps) → [`client`] (then
//! [`backend`], the [`crate::draw::Backend`] implementation) / [`server`] (the emulator, with
//! its `sim.*` function registry). The client side never imports from the server side.

pub mod backend;
pub mod client;
pub mod follow;

pub use backend::ZmqBackend;
pub use client::{Client, ClientOptions, ClientStats, Outcome, ZmqError};
pub use vrep_maze_wire::zmq_api::{Protocol, cbor, message};
