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

/// No generator recurses: each carves a 256 x 256 maze (65,536 cells) on a thread with a
/// 128 KiB stack, where one stack frame per cell (what knossos's recursive backtracker
/// needs) would overflow many times over. 4096 x 4096 runs in the benchmark.
#[test]
fn generators_need_no_stack_proportional_to_the_maze() {
    let grid = Grid::new(256, 256).unwrap();
    let mut algorithms = Algorithm::ALL.to_vec();
    for mode in ["oldest", "random", "middle", "mix:0.5"] {
        algorithms.push(Algorithm::GrowingTree(GrowingMode::parse(mode).unwrap()));
    }
    for algorithm in algorithms {
        let maze = std::thread::Builder::new()
            .stack_size(128 * 1024)
            .spawn(move || generate(grid, algorithm, 3))
            .unwrap()
            .join()
            .unwrap_or_else(|_| panic!("{algorithm} {:?} crashed", algorithm.option_pairs()));
        assert_eq!(maze.passage_count(), grid.cell_count() - 1, "{algorithm}");
    }
}
