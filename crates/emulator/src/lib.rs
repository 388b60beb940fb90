#![warn(missing_docs)]
//! The emulated CoppeliaSim behind `vrep-maze serve`: [`sim`] (the scene, its state, clock and
//! cost model) and the two servers over it, [`legacy`] and [`zmq_api`], protocol-faithful to
//! the real 4.5.1 and 4.10.0 (`../shared/spec/`, `docs/measurements.md`). It knows our clients
//! only through the wire (`vrep-maze-wire`).

pub mod legacy;
pub mod sim;
pub mod zmq_api;
