//! Property tests over algorithms, seeds and grid sizes: every layout is a perfect,
//! solvable maze whose segments cover every passage gap-free, and the same inputs always
//! give the same layout.

use crate::support::course_layout;
use proptest::prelude::*;
use vrep_maze::generate::{Algorithm, generate};
use vrep_maze::layout::json::to_string;
use vrep_maze::maze::Grid;
use vrep_maze::maze::analysis::component_count;
use vrep_maze::validate::validate;

fn algorithm() -> impl Strategy<Value = Algorithm> {
    proptest::sample::select(Algorithm::ALL.to_vec())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn every_maze_is_perfect_solvable_and_gap_free(
        algo in algorithm(), seed in any::<u64>(), w in 1u64..=64, h in 1u64..=64
    ) {
        let maze = generate(Grid::new(w, h).unwrap(), algo, seed);
        prop_assert_eq!(component_count(&maze), 1);
        prop_assert_eq!(maze.passage_count(), (w * h - 1) as usize);
        let layout = course_layout(algo, w, h, seed);
        let report = validate(&layout);
        prop_assert!(report.is_ok(), "{:?}", report.problems);
        prop_assert_eq!(layout.metrics.loops, 0);
    }

    #[test]
    fn the_same_inputs_give_the_same_bytes(
        algo in algorithm(), seed in any::<u64>(), w in 1u64..=24, h in 1u64..=24
    ) {
        let first = to_string(&course_layout(algo, w, h, seed));
        let second = to_string(&course_layout(algo, w, h, seed));
        prop_assert_eq!(first, second);
    }
}
