//! Maze generators: one file per algorithm, all behind the [`Generator`] trait, all
//! driven only by a [`MazeRng`] so the same seed always gives the same maze.

mod aldous_broder;
mod binary_tree;
mod braid;
mod dfs;
mod eller;
mod growing_tree;
mod hunt_and_kill;
mod kruskal;
mod options;
mod padded;
mod prim;
mod recursive_division;
mod sidewinder;
mod wilson;

use std::fmt;
use std::str::FromStr;

use crate::maze::{Grid, Maze};
use crate::rng::MazeRng;
use crate::wording::{Message, Opt, Value};

pub use aldous_broder::AldousBroder;
pub use binary_tree::BinaryTree;
pub use braid::braid;
pub use dfs::Dfs;
pub use eller::Eller;
pub use growing_tree::GrowingTree;
pub use hunt_and_kill::HuntAndKill;
pub use kruskal::Kruskal;
pub use options::{AlgorithmOptions, Bias, GrowingMode, MixRatio};
pub use prim::Prim;
pub use recursive_division::RecursiveDivision;
pub use sidewinder::Sidewinder;
pub use wilson::Wilson;

/// Something that carves a perfect maze (a spanning tree of the grid).
pub trait Generator {
    /// Opens passages in `maze`, which starts with every wall standing, until every cell
    /// is reachable from every other by exactly one path. Every random choice comes from
    /// `rng`; no recursion (4096 x 4096 must fit a default stack).
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng);
}

/// The algorithms `--algo` accepts, with their options (`--growing`, `--bias`).
///
/// [`name`](Self::name) is the `--algo` value; `Display` prints it and `FromStr` parses it
/// back, giving parameterised algorithms their default option ([`GrowingMode::Newest`],
/// [`Bias::NorthEast`]). The options themselves go through [`with_options`](Self::with_options)
/// (command line) or [`from_parts`](Self::from_parts) (layout), and come out through
/// [`options`](Self::options), so `from_parts(a.name(), &a.options()) == a` for every `a`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Algorithm {
    /// Depth-first search (recursive backtracker, run with an explicit stack): long,
    /// winding corridors, few dead ends (about 10%).
    Dfs,
    /// Randomized Prim (random frontier cell): many short dead ends (about 36%).
    Prim,
    /// Randomized Kruskal (shuffled walls, union-find): an even texture (about 30% dead ends).
    Kruskal,
    /// Aldous-Broder random walk: a uniform spanning tree (about 29% dead ends), slow
    /// (the walk's cover time, about n (ln n)^2 steps; see [`AldousBroder`]).
    AldousBroder,
    /// Wilson's loop-erased random walks: a uniform spanning tree (about 29% dead ends),
    /// the fast way to get one.
    Wilson,
    /// Hunt-and-kill: random walks restarted from the first unvisited cell; long corridors
    /// like DFS (about 9% dead ends).
    HuntAndKill,
    /// Growing tree: which active cell grows next decides the texture (`--growing`): from
    /// about 2.5% dead ends (oldest, middle) through 10% (newest, as DFS) to 28% (random).
    GrowingTree(GrowingMode),
    /// Eller: row by row with set labels, in memory proportional to one row (about 29%
    /// dead ends).
    Eller,
    /// Sidewinder: runs east closed by a passage north; the north row is one corridor
    /// (about 28% dead ends).
    Sidewinder,
    /// Binary tree: every cell opens one of two directions (`--bias`); two sides are one
    /// corridor each, exactly 25% dead ends on large grids.
    BinaryTree(Bias),
    /// Recursive division: chambers split by walls with one gap, with an explicit stack;
    /// long straight walls (about 27% dead ends).
    RecursiveDivision,
}

impl Algorithm {
    /// Every algorithm (parameterised ones with their default option), in the order help
    /// texts list them.
    pub const ALL: [Algorithm; 11] = [
        Algorithm::Dfs,
        Algorithm::Prim,
        Algorithm::Kruskal,
        Algorithm::AldousBroder,
        Algorithm::Wilson,
        Algorithm::HuntAndKill,
        Algorithm::GrowingTree(GrowingMode::Newest),
        Algorithm::Eller,
        Algorithm::Sidewinder,
        Algorithm::BinaryTree(Bias::NorthEast),
        Algorithm::RecursiveDivision,
    ];

    /// The name used on the command line (`--algo`) and in layouts.
    pub const fn name(self) -> &'static str {
        match self {
            Algorithm::Dfs => "dfs",
            Algorithm::Prim => "prim",
            Algorithm::Kruskal => "kruskal",
            Algorithm::AldousBroder => "aldous-broder",
            Algorithm::Wilson => "wilson",
            Algorithm::HuntAndKill => "hunt-and-kill",
            Algorithm::GrowingTree(_) => "growing-tree",
            Algorithm::Eller => "eller",
            Algorithm::Sidewinder => "sidewinder",
            Algorithm::BinaryTree(_) => "binary-tree",
            Algorithm::RecursiveDivision => "recursive-division",
        }
    }

    /// The generator that implements this algorithm.
    pub fn generator(self) -> Box<dyn Generator> {
        match self {
            Algorithm::Dfs => Box::new(Dfs),
            Algorithm::Prim => Box::new(Prim),
            Algorithm::Kruskal => Box::new(Kruskal),
            Algorithm::AldousBroder => Box::new(AldousBroder),
            Algorithm::Wilson => Box::new(Wilson),
            Algorithm::HuntAndKill => Box::new(HuntAndKill),
            Algorithm::GrowingTree(mode) => Box::new(GrowingTree { mode }),
            Algorithm::Eller => Box::new(Eller),
            Algorithm::Sidewinder => Box::new(Sidewinder),
            Algorithm::BinaryTree(bias) => Box::new(BinaryTree { bias }),
            Algorithm::RecursiveDivision => Box::new(RecursiveDivision),
        }
    }

    /// All names, comma-separated, for error messages.
    pub fn names() -> String {
        Self::ALL.map(Algorithm::name).join(", ")
    }

    /// This algorithm with the options given on the command line (`--growing`, `--bias`);
    /// `None` keeps the current one. An option the algorithm does not take is an error
    /// that says which algorithm takes it.
    pub fn with_options(
        self,
        growing: Option<GrowingMode>,
        bias: Option<Bias>,
    ) -> Result<Self, Message> {
        let mut algorithm = self;
        // "--growing oldest applies to --algo growing-tree, not prim"
        let refused = |opt, value: &dyn fmt::Display, takes: &str, other: &Algorithm| {
            Message::setting(opt, Value::word(value))
                .and(" applies to ")
                .and_setting(Opt::Algo, Value::word(takes))
                .and(format!(", not {other}"))
        };
        if let Some(mode) = growing {
            match &mut algorithm {
                Algorithm::GrowingTree(current) => *current = mode,
                other => return Err(refused(Opt::Growing, &mode, "growing-tree", other)),
            }
        }
        if let Some(new_bias) = bias {
            match &mut algorithm {
                Algorithm::BinaryTree(current) => *current = new_bias,
                other => return Err(refused(Opt::Bias, &new_bias, "binary-tree", other)),
            }
        }
        Ok(algorithm)
    }

    /// The options this algorithm runs with, for the layout's `generator.options`
    /// (empty for algorithms without options).
    pub fn options(self) -> AlgorithmOptions {
        match self {
            Algorithm::GrowingTree(mode) => AlgorithmOptions {
                growing: Some(mode.to_string()),
                ..AlgorithmOptions::default()
            },
            Algorithm::BinaryTree(bias) => AlgorithmOptions {
                bias: Some(bias.to_string()),
                ..AlgorithmOptions::default()
            },
            _ => AlgorithmOptions::default(),
        }
    }

    /// The options as `(name, value)` pairs in a fixed order, e.g. `[("bias", "ne")]`.
    pub fn option_pairs(self) -> Vec<(&'static str, String)> {
        self.options().pairs()
    }

    /// The algorithm a layout names, with its recorded options (the inverse of
    /// [`name`](Self::name) and [`options`](Self::options)).
    pub fn from_parts(name: &str, options: &AlgorithmOptions) -> Result<Self, Message> {
        let growing = options
            .growing
            .as_deref()
            .map(GrowingMode::parse)
            .transpose()?;
        let bias = options.bias.as_deref().map(Bias::parse).transpose()?;
        name.parse::<Algorithm>()?.with_options(growing, bias)
    }
}

impl Algorithm {
    /// Like [`from_parts`](Self::from_parts), from `(key, value)` pairs such as a layout's
    /// `generator.options` map: the `growing` and `bias` keys are read, other keys (for
    /// instance `braid`, which is not an algorithm option) are left to their owners.
    pub fn from_name_and_pairs<'a>(
        name: &str,
        pairs: impl IntoIterator<Item = (&'a str, &'a str)>,
    ) -> Result<Self, Message> {
        let mut options = AlgorithmOptions::default();
        for (key, value) in pairs {
            match key {
                "growing" => options.growing = Some(value.to_string()),
                "bias" => options.bias = Some(value.to_string()),
                _ => {}
            }
        }
        Self::from_parts(name, &options)
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Algorithm {
    type Err = String;

    /// An `--algo` value; parameterised algorithms get their default option.
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown algorithm '{s}' (known: {})", Self::names()))
    }
}

/// A perfect maze on `grid`, carved by `algorithm` from the stream of `seed`.
pub fn generate(grid: Grid, algorithm: Algorithm, seed: u64) -> Maze {
    generate_braided(grid, algorithm, seed, 0.0)
}

/// A maze carved by `algorithm` from the stream of `seed`, then braided: `braid_share`
/// of its dead ends opened (0 keeps it perfect) with the same stream, so seed and share
/// decide the result.
pub fn generate_braided(grid: Grid, algorithm: Algorithm, seed: u64, braid_share: f64) -> Maze {
    let mut maze = Maze::closed(grid);
    let mut rng = MazeRng::from_seed(seed);
    algorithm.generator().carve(&mut maze, &mut rng);
    if braid_share > 0.0 {
        braid::braid(&mut maze, &mut rng, braid_share);
    }
    maze
}

/// A grid's shape as the walkers need it: a cell's column without a division.
///
/// `index % width` is a hardware division (tens of cycles) and the walkers ask for it at
/// every step; Lemire's "fastmod" gets the same remainder from two multiplications with a
/// constant computed once: `magic = 2^64 / width` rounded up (wrapping to 0 for width 1),
/// `column = ((magic * index mod 2^64) * width) >> 64`, exact for 32-bit operands.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Lattice {
    width: usize,
    cells: usize,
    magic: u64,
}

impl Lattice {
    pub fn new(grid: Grid) -> Self {
        Self {
            width: grid.width() as usize,
            cells: grid.cell_count(),
            magic: (u64::MAX / u64::from(grid.width())).wrapping_add(1),
        }
    }

    /// `index % width`.
    #[inline]
    pub fn column(&self, index: usize) -> usize {
        let low = self.magic.wrapping_mul(index as u64);
        ((u128::from(low) * self.width as u128) >> 64) as usize
    }
}

/// The neighbours of cell `index` (up to four) that are `wanted`, in [`Direction::ALL`]
/// order (callers' random choices index into this order). Shared by the walkers (DFS,
/// Prim, hunt-and-kill, growing tree).
///
/// [`Direction::ALL`]: crate::maze::Direction::ALL
#[inline]
fn neighbours_where(
    lattice: &Lattice,
    index: usize,
    mut wanted: impl FnMut(usize) -> bool,
) -> ([(crate::maze::Direction, usize); 4], usize) {
    use crate::maze::Direction;
    // The same checks as `Grid::step_index`, with the column from `Lattice::column`.
    let width = lattice.width;
    let x = lattice.column(index);
    let steps = [
        (Direction::East, x + 1 < width, index + 1),
        (
            Direction::North,
            index + width < lattice.cells,
            index + width,
        ),
        (Direction::West, x > 0, index.wrapping_sub(1)),
        (Direction::South, index >= width, index.wrapping_sub(width)),
    ];
    let mut found = [(Direction::East, 0); 4];
    let mut count = 0;
    for (dir, inside, next) in steps {
        if inside && wanted(next) {
            found[count] = (dir, next);
            count += 1;
        }
    }
    (found, count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maze::analysis::component_count;

    #[test]
    fn every_algorithm_carves_a_spanning_tree() {
        for algorithm in Algorithm::ALL {
            for (w, h) in [(1, 1), (1, 7), (7, 1), (2, 2), (9, 9), (31, 17)] {
                let maze = generate(Grid::new(w, h).unwrap(), algorithm, 42);
                assert_eq!(component_count(&maze), 1, "{algorithm} {w}x{h}");
                assert_eq!(
                    maze.passage_count(),
                    maze.grid().tree_edge_count(),
                    "{algorithm} {w}x{h}"
                );
            }
        }
    }

    #[test]
    fn seeds_decide_the_maze() {
        let grid = Grid::new(12, 12).unwrap();
        for algorithm in Algorithm::ALL {
            assert_eq!(
                generate(grid, algorithm, 5),
                generate(grid, algorithm, 5),
                "{algorithm}"
            );
            assert_ne!(
                generate(grid, algorithm, 5),
                generate(grid, algorithm, 6),
                "{algorithm}"
            );
        }
    }

    /// Every algorithm and every option value worth testing.
    pub(crate) fn every_variant() -> Vec<Algorithm> {
        let mut all = Algorithm::ALL.to_vec();
        for mode in ["oldest", "random", "middle", "mix:0.5", "mix:0", "mix:1"] {
            all.push(Algorithm::GrowingTree(GrowingMode::parse(mode).unwrap()));
        }
        for bias in [Bias::NorthWest, Bias::SouthEast, Bias::SouthWest] {
            all.push(Algorithm::BinaryTree(bias));
        }
        all
    }

    #[test]
    fn every_variant_carves_a_spanning_tree() {
        for algorithm in every_variant() {
            for (w, h) in [(1, 1), (1, 7), (7, 1), (2, 2), (2, 5), (9, 9), (31, 17)] {
                let maze = generate(Grid::new(w, h).unwrap(), algorithm, 42);
                let opts = algorithm.option_pairs();
                assert_eq!(component_count(&maze), 1, "{algorithm} {opts:?} {w}x{h}");
                assert_eq!(
                    maze.passage_count(),
                    maze.grid().tree_edge_count(),
                    "{algorithm} {opts:?} {w}x{h}"
                );
            }
        }
    }

    #[test]
    fn options_round_trip_through_the_layout_parts() {
        for algorithm in every_variant() {
            let options = algorithm.options();
            assert_eq!(
                Algorithm::from_parts(algorithm.name(), &options),
                Ok(algorithm)
            );
            let json = serde_json::to_string(&options).unwrap();
            let back: AlgorithmOptions = serde_json::from_str(&json).unwrap();
            assert_eq!(back, options);
        }
        let tree = Algorithm::GrowingTree(GrowingMode::parse("mix:0.25").unwrap());
        assert_eq!(
            serde_json::to_string(&tree.options()).unwrap(),
            r#"{"growing":"mix:0.25"}"#
        );
        assert_eq!(
            Algorithm::BinaryTree(Bias::SouthWest).option_pairs(),
            vec![("bias", "sw".to_string())]
        );
        assert_eq!(
            serde_json::to_string(&Algorithm::Dfs.options()).unwrap(),
            "{}"
        );
    }

    #[test]
    fn options_only_fit_their_algorithm() {
        let err = Algorithm::Dfs
            .with_options(Some(GrowingMode::Oldest), None)
            .unwrap_err();
        assert!(err.to_string().contains("growing-tree"), "{err}");
        let err = Algorithm::Prim
            .with_options(None, Some(Bias::NorthWest))
            .unwrap_err();
        assert!(err.to_string().contains("binary-tree"), "{err}");
        assert_eq!(
            "binary-tree"
                .parse::<Algorithm>()
                .unwrap()
                .with_options(None, Some(Bias::SouthEast)),
            Ok(Algorithm::BinaryTree(Bias::SouthEast))
        );
        let bad = AlgorithmOptions {
            bias: Some("up".into()),
            ..AlgorithmOptions::default()
        };
        assert!(Algorithm::from_parts("binary-tree", &bad).is_err());
    }

    #[test]
    fn lattice_columns_match_division() {
        for width in [1u64, 2, 3, 7, 100, 1000, 4095, 4096] {
            let grid = Grid::new(width, (1 << 24) / width).unwrap();
            let lattice = Lattice::new(grid);
            let last = grid.cell_count() - 1;
            let samples = (0..5000)
                .chain((0..5000).map(|k| last - k))
                .chain([last / 2]);
            for index in samples {
                assert_eq!(
                    lattice.column(index),
                    index % width as usize,
                    "{width} {index}"
                );
            }
        }
    }

    #[test]
    fn names_parse_back() {
        for algorithm in Algorithm::ALL {
            assert_eq!(algorithm.name().parse::<Algorithm>(), Ok(algorithm));
        }
        let err = "wilsonx".parse::<Algorithm>().unwrap_err();
        assert!(err.contains("dfs, prim, kruskal, aldous-broder"), "{err}");
        assert!(err.contains("recursive-division"), "{err}");
        assert_eq!(
            "Growing-Tree".parse::<Algorithm>(),
            Ok(Algorithm::GrowingTree(GrowingMode::Newest))
        );
    }
}
