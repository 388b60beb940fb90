//! Helpers shared by the integration tests.

use assert_cmd::Command;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, Layout, build_layout};
use vrep_maze::maze::Grid;

/// The `vrep-maze` binary under test.
pub fn bin() -> Command {
    Command::cargo_bin("vrep-maze").expect("binary built")
}

/// The course layout for `algorithm` and `seed` on a `w` x `h` grid.
pub fn course_layout(algorithm: Algorithm, w: u64, h: u64, seed: u64) -> Layout {
    build_layout(&GenerateSpec::course(
        Grid::new(w, h).unwrap(),
        algorithm,
        seed,
    ))
    .unwrap()
}
