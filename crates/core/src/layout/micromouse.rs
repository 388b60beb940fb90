//! Micromouse presets: the classic 16x16 maze of 18 cm cells and the half-size 32x32 of
//! 9 cm, walls all round, the start in the south-west corner cell opening one way (north
//! when it can), and the goal the 2x2 centre region with a single entrance.
//!
//! The maze is carved by the chosen algorithm, then shaped: the goal's four cells are
//! joined (one loop, declared in the metrics), every side of the goal but one entrance
//! is closed, the start keeps one passage, and the pieces this leaves are joined again
//! through walls chosen by the seed's stream, so every cell can still be reached.

use super::FloorSize;
use super::build::{GenerateSpec, Planned, plan_maze};
use super::endpoints::EndpointSpec;
use super::geometry::{Geometry, round_um};
use super::walls::{Openings, WallOptions, into_walls, length_between_posts};
use crate::generate::generate;
use crate::maze::{Cell, Direction, Grid, Maze};
use crate::rng::MazeRng;
use crate::wording::Message;

/// A micromouse competition format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// Classic: 16x16 cells of 0.18 m, walls 0.012 m thick and 0.05 m high.
    Micromouse,
    /// Half size: 32x32 cells of 0.09 m, walls 0.006 m thick and 0.025 m high.
    MicromouseHalf,
}

impl Preset {
    /// Both presets, classic first.
    pub const ALL: [Preset; 2] = [Preset::Micromouse, Preset::MicromouseHalf];

    /// The name on the command line and in `generator.options.preset`.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Micromouse => "micromouse",
            Preset::MicromouseHalf => "micromouse-half",
        }
    }

    /// The preset a name stands for.
    pub fn from_name(name: &str) -> Option<Preset> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Cells per side.
    pub fn side(self) -> u32 {
        match self {
            Preset::Micromouse => 16,
            Preset::MicromouseHalf => 32,
        }
    }

    /// Cell side, metres.
    pub fn cell_size(self) -> f64 {
        match self {
            Preset::Micromouse => 0.18,
            Preset::MicromouseHalf => 0.09,
        }
    }

    /// The wall template, no openings. Without `posts`, walls are one cell long; with
    /// posts of side `Some(size)` at every lattice corner (a competition maze's: 0.012 m
    /// posts and 0.168 m walls in the classic), walls fill the space between two posts.
    pub fn walls(self, posts: Option<f64>) -> WallOptions {
        let (thickness, height) = match self {
            Preset::Micromouse => (0.012, 0.05),
            Preset::MicromouseHalf => (0.006, 0.025),
        };
        WallOptions {
            length: posts.map_or(self.cell_size(), |size| {
                length_between_posts(self.cell_size(), size)
            }),
            thickness,
            height,
            openings: Openings::default(),
            posts,
        }
    }

    /// `spec` made this preset's: its grid, cell size, a line template scaled to the cell
    /// (0.6 x 0.1 cells, as the course's), the maze centred on the floor origin unless
    /// `origin` is given.
    pub fn spec(self, mut spec: GenerateSpec, origin: Option<[f64; 2]>) -> GenerateSpec {
        let side = u64::from(self.side());
        spec.grid = Grid::new(side, side).expect("a preset's grid is valid");
        let cell = self.cell_size();
        spec.geometry.cell_size = cell;
        spec.geometry.line_length = round_um(0.6 * cell);
        spec.geometry.line_width = round_um(0.1 * cell);
        spec.geometry.origin = origin.unwrap_or_else(|| Geometry::centred_origin(spec.grid, cell));
        spec.braid = 0.0;
        spec
    }

    /// The four cells of the goal, south-west first.
    pub fn goal(self) -> [Cell; 4] {
        let h = self.side() / 2;
        [
            Cell::new(h - 1, h - 1),
            Cell::new(h, h - 1),
            Cell::new(h - 1, h),
            Cell::new(h, h),
        ]
    }
}

/// The wall layout of `preset` for `spec` (already made the preset's with
/// [`Preset::spec`]): shaped maze, start in the south-west corner, end at the goal's
/// entrance cell with the goal as `end.region`; posts of side `posts` at every lattice
/// corner if asked for (see [`Preset::walls`]).
pub fn plan(preset: Preset, spec: &GenerateSpec, posts: Option<f64>) -> Result<Planned, Message> {
    spec.check()?;
    let carved = generate(spec.grid, spec.algorithm, spec.seed);
    let (maze, entrance) = shape(&carved, preset.goal(), spec.seed);
    let shaped = GenerateSpec {
        start: EndpointSpec::Cell(Cell::new(0, 0)),
        end: EndpointSpec::Cell(entrance),
        ..spec.clone()
    };
    let mut planned = plan_maze(maze, &shaped)?;
    let head = &mut planned.head;
    head.generator
        .options
        .insert("preset".to_string(), preset.name().to_string());
    head.end.region = preset.goal().iter().map(|c| [c.x, c.y]).collect();
    let auto_floor = spec.floor == FloorSize::Auto;
    let walls = preset.walls(posts);
    planned.with_walls(|head, maze| into_walls(head, maze, &walls, auto_floor))
}

/// `maze` shaped for micromouse around `goal` (a 2x2 block): the goal joined inside with
/// one entrance, the south-west corner cell with one passage, everything connected again.
/// Returns the maze and the goal cell at the entrance.
pub fn shape(maze: &Maze, goal: [Cell; 4], seed: u64) -> (Maze, Cell) {
    let grid = maze.grid();
    let mut masks = maze.masks().to_vec();
    let goal_index: Vec<usize> = goal.iter().map(|&c| grid.index(c)).collect();
    let in_goal = |i: usize| goal_index.contains(&i);
    let set = |masks: &mut Vec<u8>, a: usize, dir: Direction, open: bool| {
        let b = grid.step_index(a, dir).expect("a neighbour on the grid");
        if open {
            masks[a] |= dir.bit();
            masks[b] |= dir.opposite().bit();
        } else {
            masks[a] &= !dir.bit();
            masks[b] &= !dir.opposite().bit();
        }
    };
    // the entrance: the first passage out of the goal the carving made (there is one)
    let mut entrance = None;
    for &g in &goal_index {
        for dir in Direction::ALL {
            let Some(n) = grid.step_index(g, dir) else {
                continue;
            };
            if in_goal(n) {
                set(&mut masks, g, dir, true);
            } else if masks[g] & dir.bit() != 0 {
                if entrance.is_none() {
                    entrance = Some((g, dir));
                } else {
                    set(&mut masks, g, dir, false);
                }
            }
        }
    }
    let (entrance_cell, _) = entrance.expect("a carved maze leaves the goal somewhere");
    // the start opens one way: north when it can
    let start = grid.index(Cell::new(0, 0));
    let both = Direction::North.bit() | Direction::East.bit();
    if masks[start] & both == both {
        set(&mut masks, start, Direction::East, false);
    }
    // join the pieces again, through walls between ordinary cells in the seed's order
    let mut parent: Vec<usize> = (0..grid.cell_count()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut candidates = Vec::new();
    for (i, &mask) in masks.iter().enumerate() {
        for dir in [Direction::East, Direction::North] {
            let Some(n) = grid.step_index(i, dir) else {
                continue;
            };
            if mask & dir.bit() != 0 {
                let (a, b) = (root(&mut parent, i), root(&mut parent, n));
                parent[a] = b;
            } else if !in_goal(i) && !in_goal(n) && i != start && n != start {
                candidates.push((i, dir, n));
            }
        }
    }
    let mut rng = MazeRng::from_seed(seed);
    rng.shuffle(&mut candidates);
    for (i, dir, n) in candidates {
        let (a, b) = (root(&mut parent, i), root(&mut parent, n));
        if a != b {
            parent[a] = b;
            set(&mut masks, i, dir, true);
        }
    }
    let shaped = Maze::from_masks(grid, masks).expect("passages set on both cells");
    (shaped, grid.cell(entrance_cell))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::maze::analysis::component_count;

    #[test]
    fn the_goal_has_one_entrance_and_the_maze_one_loop() {
        for seed in 0..20 {
            let preset = Preset::Micromouse;
            let spec = preset.spec(
                GenerateSpec::course(Grid::new(9, 9).unwrap(), Algorithm::Dfs, seed),
                None,
            );
            let posts = (seed % 2 == 1).then_some(0.012);
            let layout = plan(preset, &spec, posts).unwrap().into_layout();
            assert_eq!(layout.posts.is_empty(), posts.is_none());
            let maze = crate::layout::passages::decode(spec.grid, &layout.passages).unwrap();
            assert_eq!(component_count(&maze), 1);
            assert_eq!(layout.metrics.loops, 1);
            let goal: Vec<usize> = preset.goal().iter().map(|&c| spec.grid.index(c)).collect();
            let exits: usize = goal
                .iter()
                .map(|&g| {
                    maze.open_neighbours(g)
                        .filter(|n| !goal.contains(n))
                        .count()
                })
                .sum();
            assert_eq!(exits, 1, "seed {seed}");
            assert_eq!(maze.degree(0), 1, "seed {seed}: the start opens one way");
            let report = crate::validate::validate(&layout);
            assert!(report.is_ok(), "seed {seed}: {:?}", report.problems);
        }
    }
}
