//! Mazes to draw.

use vrep_maze::draw::Drawing;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, Layout, build_layout};
use vrep_maze::maze::Grid;

/// The course layout for `algorithm` and `seed` on a `w` x `h` grid.
pub fn course_layout(algorithm: Algorithm, w: u64, h: u64, seed: u64) -> Layout {
    build_layout(&GenerateSpec::course(
        Grid::new(w, h).unwrap(),
        algorithm,
        seed,
    ))
    .unwrap()
}

/// The lines of the `n` x `n` Prim course for `seed` (9 x 9 seed 42 has 160 lines).
pub fn drawing(n: u64, seed: u64) -> Drawing {
    drawing_with(Algorithm::Prim, n, seed)
}

/// The lines of the `n` x `n` course of `algorithm` for `seed`.
pub fn drawing_with(algorithm: Algorithm, n: u64, seed: u64) -> Drawing {
    Drawing::try_from(&course_layout(algorithm, n, n, seed)).unwrap()
}
