//! The same user scenarios (apply, re-apply, replace, copies and meshes, walls, clear,
//! inspect, dry runs, Ctrl-C, runs back to back) against every simulator: `vrep-maze serve`
//! as 4.5.1 (legacy and ZeroMQ protocol 1 on one scene) and as 4.10 (ZeroMQ protocol 2), and,
//! when asked, the real CoppeliaSim 4.5.1 and 4.10.0 of `../shared/coppeliasim/`:
//!
//! ```sh
//! VREP_MAZE_REAL_SIMS=../shared/coppeliasim cargo test --test it on_real -- --ignored
//! ```
//!
//! Each test starts its own simulator on free ports and stops it. What a scenario checks is
//! read back from the scene by [`observer`], independently of the code under test, and the
//! maze is compared with its layout point by point ([`footprint`]).

mod cases;
mod footprint;
mod observer;
mod target;
