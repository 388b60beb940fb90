#![warn(missing_docs)]
//! Drawing a maze into a running CoppeliaSim: [`draw`] (the `Backend` port and the
//! backend-neutral apply, clear, verify and inspect) and the two clients with their drawing
//! backends, [`legacy`] (port 19997) and [`zmq_api`] (ZeroMQ). It knows the emulator only
//! through the wire (`vrep-maze-wire`).

pub mod draw;
pub mod held;
pub mod legacy;
pub mod robot;
pub mod zmq_api;
