//! vrep-maze: seeded, reproducible grid mazes for CoppeliaSim (formerly V-REP).
//!
//! The library behind the `vrep-maze` command: [`maze`] holds the model and its analysis,
//! [`generate`] the algorithms, [`rng`] the only source of randomness.

pub mod atomic_file;
pub mod batch;
pub mod cli;
pub mod generate;
pub mod layout;
pub mod maze;
pub mod render;
pub mod rng;
pub mod validate;
