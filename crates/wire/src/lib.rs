#![warn(missing_docs)]
//! The two CoppeliaSim remote-API protocols as codecs, bytes to values and back, with no
//! socket: [`legacy`] (port 19997) and [`zmq_api`] (ZeroMQ, CBOR). The client crate
//! (`vrep-maze-client`) and the emulator crate (`vrep-maze-emulator`) both stand on it and
//! never on each other.

pub mod legacy;
pub mod zmq_api;
