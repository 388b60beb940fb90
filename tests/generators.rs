//! Property tests over every algorithm and option: perfect (one connected component and
//! cells - 1 passages: a spanning tree) and deterministic (the same seed twice gives the
//! same maze), on grids up to 64 x 64.

use proptest::prelude::*;
use vrep_maze::generate::{Algorithm, Bias, GrowingMode, MixRatio, generate};
use vrep_maze::maze::Grid;
use vrep_maze::maze::analysis::component_count;

fn any_algorithm() -> impl Strategy<Value = Algorithm> {
    let mode = prop_oneof![
        Just(GrowingMode::Newest),
        Just(GrowingMode::Oldest),
        Just(GrowingMode::Random),
        Just(GrowingMode::Middle),
        (0..=MixRatio::SCALE).prop_map(|p| GrowingMode::Mix(MixRatio::from_millionths(p).unwrap())),
    ];
    prop_oneof![
        proptest::sample::select(Algorithm::ALL.to_vec()),
        mode.prop_map(Algorithm::GrowingTree),
        proptest::sample::select(Bias::ALL.to_vec()).prop_map(Algorithm::BinaryTree),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, ..ProptestConfig::default() })]

    #[test]
    fn every_algorithm_is_perfect_and_deterministic(
        algorithm in any_algorithm(),
        seed in any::<u64>(),
        width in 1u64..=64,
        height in 1u64..=64,
    ) {
        let grid = Grid::new(width, height).unwrap();
        let maze = generate(grid, algorithm, seed);
        let options = algorithm.option_pairs();
        prop_assert_eq!(component_count(&maze), 1, "{} {:?} not connected", algorithm, options);
        prop_assert_eq!(maze.passage_count(), grid.cell_count() - 1, "{} {:?}", algorithm, options);
        prop_assert_eq!(&generate(grid, algorithm, seed), &maze, "{} {:?} not deterministic", algorithm, options);
        let parsed = Algorithm::from_parts(algorithm.name(), &algorithm.options());
        prop_assert_eq!(parsed, Ok(algorithm));
    }
}
