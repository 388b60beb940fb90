//! Whether a run was sampled densely enough to be graded.
//!
//! Between two samples the grade draws a straight line, so it only knows where the robot
//! went if consecutive samples are close. The rule: no move between two consecutive
//! samples longer than half a cell. Within that, the two samples lie in the same cell or
//! in neighbouring ones (the cell index of each coordinate changes by at most one), so the
//! cells visited, the path and the distances from the lines or walls are those of the run
//! to within the cell's own geometry. A longer move can skip a cell and its chord can cut
//! across walls or lines the robot never crossed: the kinematic `drive` on a headless
//! simulator, which runs faster than remote calls move the robot, was graded perfect from
//! samples 7 m apart that cut straight through a 9 x 9 maze.

use nalgebra::Point2;
use schemars::JsonSchema;
use serde::Serialize;

/// How densely a run was sampled, and whether that is enough to grade it.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Sampling {
    /// The longest move of the robot's centre between two consecutive samples; 0 with
    /// fewer than two samples.
    pub largest_jump_m: f64,
    /// Simulation time of the sample that ends the longest move; `null` with fewer than
    /// two samples.
    pub largest_jump_at_s: Option<f64>,
    /// The longest move between two samples that lets a run be graded: half the cell size.
    pub max_jump_m: f64,
    /// Moves between consecutive samples longer than `max_jump_m`: with any, the run is
    /// not `complete` and has no SPL.
    pub jumps_over_max: usize,
}

impl Sampling {
    /// Measures the moves between consecutive `points` (maze frame) stamped at `times`,
    /// against half of `cell_size`.
    pub fn of(points: &[Point2<f64>], times: &[f64], cell_size: f64) -> Sampling {
        let max_jump = cell_size / 2.0;
        let mut sampling = Sampling {
            largest_jump_m: 0.0,
            largest_jump_at_s: None,
            max_jump_m: max_jump,
            jumps_over_max: 0,
        };
        for (pair, &t) in points.windows(2).zip(times.iter().skip(1)) {
            let jump = (pair[1] - pair[0]).norm();
            if jump > max_jump {
                sampling.jumps_over_max += 1;
            }
            if sampling.largest_jump_at_s.is_none() || jump > sampling.largest_jump_m {
                sampling.largest_jump_m = jump;
                sampling.largest_jump_at_s = Some(t);
            }
        }
        sampling
    }

    /// `true` when no move between samples was longer than `max_jump_m`.
    pub fn is_dense(&self) -> bool {
        self.jumps_over_max == 0
    }

    /// Why a sparse run cannot be graded; `None` for a dense one.
    pub fn too_sparse(&self) -> Option<String> {
        let at = self
            .largest_jump_at_s
            .map_or(String::new(), |t| format!(" at {t:.2} s"));
        (!self.is_dense()).then(|| {
            format!(
                "sampled too sparsely to grade: {} move(s) between two samples longer than half a cell ({:.3} m), the longest {:.3} m{at}, so where the robot went between them is unknown",
                self.jumps_over_max, self.max_jump_m, self.largest_jump_m
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(xs: &[f64]) -> Vec<Point2<f64>> {
        xs.iter().map(|&x| Point2::new(x, 0.0)).collect()
    }

    #[test]
    fn moves_of_half_a_cell_are_dense_and_longer_ones_are_counted() {
        let times = [0.0, 0.05, 0.1, 0.15];
        let dense = Sampling::of(&points(&[0.0, 0.5, 1.0, 1.25]), &times, 1.0);
        assert!(
            dense.is_dense() && dense.too_sparse().is_none(),
            "{dense:?}"
        );
        assert_eq!(
            (dense.largest_jump_m, dense.largest_jump_at_s),
            (0.5, Some(0.05))
        );
        let sparse = Sampling::of(&points(&[0.0, 0.6, 7.6, 7.7]), &times, 1.0);
        assert_eq!(sparse.jumps_over_max, 2);
        assert_eq!(
            (sparse.largest_jump_m, sparse.largest_jump_at_s),
            (7.0, Some(0.1))
        );
        let why = sparse.too_sparse().unwrap();
        assert!(
            why.contains("2 move(s)")
                && why.contains("(0.500 m)")
                && why.contains("7.000 m at 0.10 s"),
            "{why}"
        );
    }

    #[test]
    fn one_sample_or_none_is_dense() {
        for xs in [&[][..], &[3.0]] {
            let s = Sampling::of(&points(xs), &[0.0; 1][..xs.len()], 1.0);
            assert!(s.is_dense());
            assert_eq!((s.largest_jump_m, s.largest_jump_at_s), (0.0, None));
        }
    }
}
