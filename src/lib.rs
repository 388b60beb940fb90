//! vrep-maze: seeded, reproducible grid mazes for CoppeliaSim (formerly V-REP).
//!
//! The library behind the `vrep-maze` command: [`maze`] holds the model and its analysis,
//! [`generate`] the algorithms, [`rng`] the only source of randomness.

pub mod draw;
pub mod generate;
pub mod legacy;
pub mod zmq_api;
pub mod maze;
pub mod rng;
pub mod sim;
